/* error.c — filling tetrafoil's tf_error, and small string helpers. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analytic.h"

/* Length of the valid UTF-8 sequence starting at s, or 0 when it is not one. */
static size_t utf8_sequence(const unsigned char *s) {
    size_t n, i;
    unsigned int c = s[0];
    if (c < 0x80)
        return 1;
    if (c >= 0xc2 && c <= 0xdf)
        n = 2;
    else if (c >= 0xe0 && c <= 0xef)
        n = 3;
    else if (c >= 0xf0 && c <= 0xf4)
        n = 4;
    else
        return 0;
    for (i = 1; i < n; i++)
        if ((s[i] & 0xc0) != 0x80)
            return 0;
    /* overlong forms, UTF-16 surrogates and code points above U+10FFFF */
    if (n == 3 && c == 0xe0 && s[1] < 0xa0)
        return 0;
    if (n == 3 && c == 0xed && s[1] >= 0xa0)
        return 0;
    if (n == 4 && c == 0xf0 && s[1] < 0x90)
        return 0;
    if (n == 4 && c == 0xf4 && s[1] >= 0x90)
        return 0;
    return n;
}

/* Messages quote the offending text of the file, which may hold any bytes (or be cut in the
   middle of a character by the length limit); tetrafoil wants UTF-8, so anything else, and
   control characters, become '?'. */
static void sanitise(char *msg) {
    unsigned char *s = (unsigned char *)msg;
    while (*s) {
        size_t n = utf8_sequence(s);
        if (n == 0 || (n == 1 && (*s < 0x20 || *s == 0x7f))) {
            *s++ = '?';
            continue;
        }
        s += n;
    }
}

tf_status an_error(tf_error *err, tf_status status, int32_t kind, int32_t entity,
                   const char *fmt, ...) {
    va_list ap;
    if (!err)
        return status;
    err->entity_kind = kind;
    err->entity = entity;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
    err->message[sizeof err->message - 1] = '\0';
    sanitise(err->message);
    return status;
}

char *an_strdup(const char *s) {
    size_t n = strlen(s) + 1;
    char *copy = malloc(n);
    if (copy)
        memcpy(copy, s, n);
    return copy;
}

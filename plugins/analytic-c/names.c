/* names.c — the names of a file's entities, one table per kind, while it is parsed. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "analytic.h"

static uint64_t hash(const char *s, size_t len) {
    uint64_t h = 1469598103934665603u; /* FNV-1a */
    size_t i;
    for (i = 0; i < len; i++) {
        h ^= (unsigned char)s[i];
        h *= 1099511628211u;
    }
    return h;
}

/* The slot holding s, or the empty slot where it would go. */
static an_name *find_slot(const an_names *m, const char *s, size_t len) {
    size_t i = (size_t)(hash(s, len) & (m->cap - 1));
    for (;;) {
        an_name *e = &m->slots[i];
        if (!e->name || (strncmp(e->name, s, len) == 0 && e->name[len] == '\0'))
            return e;
        i = (i + 1) & (m->cap - 1);
    }
}

const an_name *an_names_get(const an_names *m, const char *s, size_t len) {
    const an_name *e;
    if (m->cap == 0)
        return NULL;
    e = find_slot(m, s, len);
    return e->name ? e : NULL;
}

int an_names_put(an_names *m, const char *name, int index, int line) {
    an_name *e;
    /* at most half full, so that probes stay short */
    if (2 * (m->count + 1) > m->cap) {
        size_t cap = m->cap ? 2 * m->cap : 64, i;
        an_names bigger;
        bigger.slots = calloc(cap, sizeof *bigger.slots);
        if (!bigger.slots)
            return 0;
        bigger.cap = cap;
        bigger.count = m->count;
        for (i = 0; i < m->cap; i++)
            if (m->slots[i].name)
                *find_slot(&bigger, m->slots[i].name, strlen(m->slots[i].name)) = m->slots[i];
        free(m->slots);
        *m = bigger;
    }
    e = find_slot(m, name, strlen(name));
    e->name = name;
    e->index = index;
    e->line = line;
    m->count++;
    return 1;
}

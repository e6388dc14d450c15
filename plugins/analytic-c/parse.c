/*
 * parse.c — the reader of .analytic files.
 *
 * The format
 * ----------
 * Line based. '#' starts a comment that runs to the end of the line; blank lines are
 * ignored; tokens are separated by white space. Every entity is defined before it is
 * referenced. Names are identifiers (a letter or '_', then letters, digits, '_', '.' or '-');
 * each kind (vertex, curve, surface, edge, face, solid) has its own namespace.
 *
 *   vertex  <name> x y z
 *   curve   <name> line   x0 y0 z0  x1 y1 z1
 *             C(t) = P0 + t (P1 - P0) / |P1 - P0|: t is the arc length from P0
 *   curve   <name> circle cx cy cz  r  ax ay az  xx xy xz
 *             C(t) = c + r (cos t X + sin t Y), Y = A x X; A is normalised, X made square
 *             to A and normalised
 *   surface <name> plane    ox oy oz  ux uy uz  vx vy vz
 *             S = O + u U + v V (U normalised, V made square to U and normalised)
 *   surface <name> cylinder cx cy cz  r  ax ay az  xx xy xz
 *             S = C + r (cos u X + sin u Y) + v A                       u period 2 pi
 *   surface <name> cone     cx cy cz  r  alpha  ax ay az  xx xy xz
 *             S = C + (r + v sin alpha)(cos u X + sin u Y) + v cos alpha A
 *             alpha: the half angle in radians, |alpha| < pi/2;         u period 2 pi
 *   surface <name> sphere   cx cy cz  r  ax ay az  xx xy xz
 *             S = C + r cos v (cos u X + sin u Y) + r sin v A
 *             u period 2 pi, v in [-pi/2, pi/2] (the poles are C -/+ r A)
 *   surface <name> torus    cx cy cz  R r  ax ay az  xx xy xz
 *             S = C + (R + r cos v)(cos u X + sin u Y) + r sin v A;     u, v period 2 pi
 *   edge    <name> <curve> <v0> <v1> [t0 t1]
 *             from v0 at t0 to v1 at t1, t0 < t1; default range: a line [0, length], a
 *             circle [0, 2 pi]. curve(t0) must lie within 1e-6 x model size of v0, and
 *             curve(t1) of v1 (the model size is the diagonal of the vertices' box).
 *   edge    <name> degenerate <v>
 *             a pole: no 3-D curve, t in [0, 1], both ends at v
 *   face    <name> <surface> [u0 u1 v0 v1]
 *             the face's parameter ranges; when omitted, the box of its loops' pcurves
 *   loop    <use> <use> ...
 *             a loop of the face defined last (a face has one or more loop lines). The uses
 *             must chain: each one ends at the vertex where the next one starts.
 *   solid   <name> <face> <face> ...     a solid and its outer shell
 *   shell   <face> <face> ...            one more (cavity) shell of the solid defined last
 *
 * A use is [-]<edge>[@u0|@u1|@v0|@v1]. '-' runs the edge from t1 to t0. The tag puts the
 * use's pcurve on that side of the face's range in a periodic direction: an edge used twice
 * by one face is a seam of it, and on a periodic surface its two uses must be tagged with
 * the two sides of one direction (e.g. "seam@u0 ... -seam@u1"). An untagged pcurve is
 * placed with its midpoint in [lo, lo + 2 pi), lo being the face's u0 (or v0) when the
 * face gives its range, else 0; so one lying on the seam line itself needs a tag.
 *
 * On a plane any line or circle lying in it may bound a face. On the other surfaces an edge
 * must be an iso-parameter line: a line along a cylinder's or cone's generator, a circle
 * around the axis (a parallel), or a meridian circle of a sphere or torus.
 *
 * A number is a decimal (or C hexadecimal) floating-point literal, or a multiple of pi
 * written [-][k*]pi[/d], e.g. pi, -pi/2, 2*pi, 3*pi/4.
 */
#include <errno.h>
#include <locale.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analytic.h"

/* ---- the parser --------------------------------------------------------------------------- */

typedef struct parser {
    tf_model *m;
    tf_error *err;
    int line;
    char **tok;
    int n_tok, cap_tok;
    an_names vertices, curves, surfaces, edges, faces, solids;
} parser;

static tf_status fail(parser *p, tf_status status, const char *fmt, ...) AN_PRINTF(3, 4);
static tf_status fail(parser *p, tf_status status, const char *fmt, ...) {
    char text[TF_MESSAGE_LEN];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    return an_error(p->err, status, TF_ENTITY_LINE, p->line, "line %d: %s", p->line, text);
}

static tf_status out_of_memory(parser *p) {
    return fail(p, TF_ERR_INTERNAL, "out of memory");
}

/* arr itself when it has room for element n, else a bigger copy; NULL when out of memory
   (arr is then untouched). */
static void *grow(void *arr, int *cap, int n, size_t size) {
    int new_cap;
    void *bigger;
    if (n < *cap)
        return arr;
    if (*cap > INT32_MAX / 4)
        return NULL;
    new_cap = *cap ? 2 * *cap : 16;
    bigger = realloc(arr, (size_t)new_cap * size);
    if (bigger)
        *cap = new_cap;
    return bigger;
}

/* out = a new zeroed element at the end of arr. */
#define PUSH(p, arr, n, cap, out)                                                             \
    do {                                                                                      \
        void *grown_ = grow((arr), &(cap), (n), sizeof *(arr));                               \
        if (!grown_)                                                                          \
            return out_of_memory(p);                                                          \
        (arr) = grown_;                                                                       \
        (out) = &(arr)[(n)++];                                                                \
        memset((out), 0, sizeof *(out));                                                      \
    } while (0)

/* ---- tokens ------------------------------------------------------------------------------- */

/* strtod reads the decimal point of the process's locale, which the host may have changed:
   put that one in place of '.'. */
static int parse_plain(const char *tok, double *out) {
    const char *point = localeconv()->decimal_point;
    char buf[256], *end;
    const char *s = tok;
    if (!*tok)
        return 0;
    if (point && strcmp(point, ".") != 0 && strchr(tok, '.')) {
        size_t i, j = 0, lp = strlen(point);
        for (i = 0; tok[i]; i++) {
            if (j + lp + 1 >= sizeof buf)
                return 0;
            if (tok[i] == '.') {
                memcpy(buf + j, point, lp);
                j += lp;
            } else {
                buf[j++] = tok[i];
            }
        }
        buf[j] = '\0';
        s = buf;
    }
    *out = strtod(s, &end);
    return end != s && *end == '\0' && isfinite(*out);
}

/* A plain number, or [-][k*]pi[/d]. */
static int parse_number(const char *tok, double *out) {
    double sign = 1.0, k = 1.0, d = 1.0;
    const char *s = tok, *pi;
    if (parse_plain(tok, out))
        return 1;
    if (*s == '-' || *s == '+')
        sign = *s++ == '-' ? -1.0 : 1.0;
    pi = strstr(s, "pi");
    if (!pi)
        return 0;
    if (pi > s) {
        char buf[64];
        size_t n = (size_t)(pi - s);
        if (pi[-1] != '*' || n < 2 || n > sizeof buf)
            return 0;
        memcpy(buf, s, n - 1);
        buf[n - 1] = '\0';
        if (!parse_plain(buf, &k))
            return 0;
    }
    if (pi[2] != '\0' && (pi[2] != '/' || !parse_plain(pi + 3, &d) || d == 0.0))
        return 0;
    *out = sign * k * AN_PI / d;
    return isfinite(*out);
}

/* Tokens first .. first + n as numbers. */
static tf_status numbers(parser *p, int first, int n, double *out) {
    int i;
    for (i = 0; i < n; i++)
        if (!parse_number(p->tok[first + i], &out[i]))
            return fail(p, TF_ERR_FORMAT, "'%.60s' is not a finite number", p->tok[first + i]);
    return TF_OK;
}

static tf_status count(parser *p, int want, const char *usage) {
    if (p->n_tok < want)
        return fail(p, TF_ERR_FORMAT, "too few values for %s: expected '%s'", p->tok[0], usage);
    if (p->n_tok > want)
        return fail(p, TF_ERR_FORMAT, "unexpected '%.60s' at the end: expected '%s'",
                    p->tok[want], usage);
    return TF_OK;
}

static int valid_name(const char *s) {
    const char *c;
    if (!((*s >= 'a' && *s <= 'z') || (*s >= 'A' && *s <= 'Z') || *s == '_'))
        return 0;
    for (c = s + 1; *c; c++)
        if (!((*c >= 'a' && *c <= 'z') || (*c >= 'A' && *c <= 'Z') || (*c >= '0' && *c <= '9') ||
              *c == '_' || *c == '.' || *c == '-'))
            return 0;
    return 1;
}

/* A new name of the given kind: valid and not taken. */
static tf_status check_new_name(parser *p, an_names *map, const char *kind, const char *name) {
    const an_name *e;
    if (!valid_name(name))
        return fail(p, TF_ERR_FORMAT,
                    "'%.60s' is not a valid %s name (a letter or '_', then letters, digits, "
                    "'_', '.' or '-')",
                    name, kind);
    e = an_names_get(map, name, strlen(name));
    if (e)
        return fail(p, TF_ERR_ENTITY, "%s '%.60s' is already defined at line %d", kind, name,
                    e->line);
    return TF_OK;
}

/* Copy name into *out and register it as entity index of map. */
static tf_status add_name(parser *p, an_names *map, const char *name, int index, char **out) {
    *out = an_strdup(name);
    if (!*out || !an_names_put(map, *out, index, p->line))
        return out_of_memory(p);
    return TF_OK;
}

/* The index of a defined entity, or an error naming the token. */
static tf_status lookup(parser *p, const an_names *map, const char *kind, const char *s,
                        size_t len, int *index) {
    const an_name *e = an_names_get(map, s, len);
    if (!e)
        return fail(p, TF_ERR_ENTITY, "unknown %s '%.*s'", kind, (int)(len > 60 ? 60 : len), s);
    *index = e->index;
    return TF_OK;
}

/* ---- directions --------------------------------------------------------------------------- */

static tf_status unit(parser *p, const double v[3], double out[3], const char *what) {
    double n = an_norm(v);
    if (!(n > 0.0) || !isfinite(n))
        return fail(p, TF_ERR_ENTITY, "the %s (%g, %g, %g) has no length", what, v[0], v[1],
                    v[2]);
    out[0] = v[0] / n;
    out[1] = v[1] / n;
    out[2] = v[2] / n;
    return TF_OK;
}

/* The unit vector of v made square to the unit vector a. */
static tf_status square_to(parser *p, const double a[3], const double v[3], double out[3],
                           const char *what, const char *to) {
    double w[3];
    double n = an_norm(v);
    an_axpy(v, -an_dot(v, a), a, w);
    if (!(an_norm(w) > 1e-9 * n))
        return fail(p, TF_ERR_ENTITY, "the %s (%g, %g, %g) is parallel to the %s", what, v[0],
                    v[1], v[2], to);
    return unit(p, w, out, what);
}

/* Axis and x direction to the unit frame a, x, y = a x x. */
static tf_status frame(parser *p, const double axis[3], const double xdir[3], double a[3],
                       double x[3], double y[3]) {
    TRY(unit(p, axis, a, "axis"));
    TRY(square_to(p, a, xdir, x, "x direction", "axis"));
    an_cross(a, x, y);
    return TF_OK;
}

/* ---- one handler per keyword -------------------------------------------------------------- */

static tf_status do_vertex(parser *p) {
    tf_model *m = p->m;
    an_vertex *v;
    double xyz[3];
    TRY(count(p, 5, "vertex <name> x y z"));
    TRY(check_new_name(p, &p->vertices, "vertex", p->tok[1]));
    TRY(numbers(p, 2, 3, xyz));
    PUSH(p, m->vertices, m->n_vertices, m->cap_vertices, v);
    v->line = p->line;
    memcpy(v->p, xyz, sizeof xyz);
    return add_name(p, &p->vertices, p->tok[1], m->n_vertices - 1, &v->name);
}

static tf_status do_curve(parser *p) {
    tf_model *m = p->m;
    an_curve c, *out;
    double x[10];
    memset(&c, 0, sizeof c);
    if (p->n_tok < 3)
        return fail(p, TF_ERR_FORMAT, "too few values for curve: expected 'curve <name> "
                                      "line|circle ...'");
    if (strcmp(p->tok[1], "degenerate") == 0)
        return fail(p, TF_ERR_FORMAT, "'degenerate' is reserved (edge <name> degenerate <v>) "
                                      "and cannot name a curve");
    TRY(check_new_name(p, &p->curves, "curve", p->tok[1]));
    if (strcmp(p->tok[2], "line") == 0) {
        double d[3];
        TRY(count(p, 9, "curve <name> line x0 y0 z0 x1 y1 z1"));
        TRY(numbers(p, 3, 6, x));
        c.kind = AN_LINE;
        memcpy(c.c, x, 3 * sizeof *x);
        an_sub(x + 3, x, d);
        c.length = an_norm(d);
        if (!(c.length > 1e-12 * (an_norm(x) + an_norm(x + 3))))
            return fail(p, TF_ERR_ENTITY, "line '%.60s' has its two points equal",
                        p->tok[1]);
        TRY(unit(p, d, c.a, "direction"));
    } else if (strcmp(p->tok[2], "circle") == 0) {
        TRY(count(p, 13, "curve <name> circle cx cy cz r ax ay az xx xy xz"));
        TRY(numbers(p, 3, 10, x));
        c.kind = AN_CIRCLE;
        memcpy(c.c, x, 3 * sizeof *x);
        c.r = x[3];
        if (!(c.r > 0.0))
            return fail(p, TF_ERR_ENTITY, "circle '%.60s' has radius %g", p->tok[1], c.r);
        TRY(frame(p, x + 4, x + 7, c.a, c.x, c.y));
    } else {
        return fail(p, TF_ERR_FORMAT, "unknown curve kind '%.60s' (expected line or circle)",
                    p->tok[2]);
    }
    PUSH(p, m->curves, m->n_curves, m->cap_curves, out);
    *out = c;
    out->line = p->line;
    return add_name(p, &p->curves, p->tok[1], m->n_curves - 1, &out->name);
}

static tf_status do_surface(parser *p) {
    tf_model *m = p->m;
    an_surface s, *out;
    double x[11];
    const char *kind;
    int at; /* where the axis and x direction start in x[] */
    memset(&s, 0, sizeof s);
    if (p->n_tok < 3)
        return fail(p, TF_ERR_FORMAT, "too few values for surface: expected 'surface <name> "
                                      "plane|cylinder|cone|sphere|torus ...'");
    TRY(check_new_name(p, &p->surfaces, "surface", p->tok[1]));
    kind = p->tok[2];
    if (strcmp(kind, "plane") == 0) {
        TRY(count(p, 12, "surface <name> plane ox oy oz ux uy uz vx vy vz"));
        TRY(numbers(p, 3, 9, x));
        s.kind = AN_PLANE;
        memcpy(s.c, x, 3 * sizeof *x);
        TRY(unit(p, x + 3, s.x, "u direction"));
        TRY(square_to(p, s.x, x + 6, s.y, "v direction", "u direction"));
        an_cross(s.x, s.y, s.a);
    } else {
        if (strcmp(kind, "cylinder") == 0) {
            TRY(count(p, 13, "surface <name> cylinder cx cy cz r ax ay az xx xy xz"));
            s.kind = AN_CYLINDER;
            at = 4;
        } else if (strcmp(kind, "cone") == 0) {
            TRY(count(p, 14, "surface <name> cone cx cy cz r alpha ax ay az xx xy xz"));
            s.kind = AN_CONE;
            at = 5;
        } else if (strcmp(kind, "sphere") == 0) {
            TRY(count(p, 13, "surface <name> sphere cx cy cz r ax ay az xx xy xz"));
            s.kind = AN_SPHERE;
            at = 4;
        } else if (strcmp(kind, "torus") == 0) {
            TRY(count(p, 14, "surface <name> torus cx cy cz R r ax ay az xx xy xz"));
            s.kind = AN_TORUS;
            at = 5;
        } else {
            return fail(p, TF_ERR_FORMAT,
                        "unknown surface kind '%.60s' (expected plane, cylinder, cone, sphere "
                        "or torus)",
                        kind);
        }
        TRY(numbers(p, 3, at + 6, x));
        memcpy(s.c, x, 3 * sizeof *x);
        if (s.kind == AN_TORUS) {
            s.big_r = x[3];
            s.r = x[4];
            if (!(s.big_r > 0.0) || !(s.r > 0.0))
                return fail(p, TF_ERR_ENTITY, "torus '%.60s' has radii R = %g, r = %g (both "
                                              "must be positive)",
                            p->tok[1], s.big_r, s.r);
        } else {
            s.r = x[3];
            if (s.kind == AN_CONE ? !(s.r >= 0.0) : !(s.r > 0.0))
                return fail(p, TF_ERR_ENTITY, "%s '%.60s' has radius %g", kind, p->tok[1], s.r);
        }
        if (s.kind == AN_CONE) {
            if (!(fabs(x[4]) < 0.5 * AN_PI))
                return fail(p, TF_ERR_ENTITY, "cone '%.60s' has half angle %g: it must lie "
                                              "strictly between -pi/2 and pi/2 (radians)",
                            p->tok[1], x[4]);
            s.sin_a = sin(x[4]);
            s.cos_a = cos(x[4]);
        }
        TRY(frame(p, x + at, x + at + 3, s.a, s.x, s.y));
    }
    PUSH(p, m->surfaces, m->n_surfaces, m->cap_surfaces, out);
    *out = s;
    out->line = p->line;
    return add_name(p, &p->surfaces, p->tok[1], m->n_surfaces - 1, &out->name);
}

static tf_status do_edge(parser *p) {
    tf_model *m = p->m;
    an_edge e, *out;
    memset(&e, 0, sizeof e);
    if (p->n_tok < 4)
        return fail(p, TF_ERR_FORMAT, "too few values for edge: expected 'edge <name> <curve> "
                                      "<v0> <v1> [t0 t1]' or 'edge <name> degenerate <v>'");
    TRY(check_new_name(p, &p->edges, "edge", p->tok[1]));
    if (strcmp(p->tok[2], "degenerate") == 0) {
        TRY(count(p, 4, "edge <name> degenerate <v>"));
        TRY(lookup(p, &p->vertices, "vertex", p->tok[3], strlen(p->tok[3]), &e.v0));
        e.v1 = e.v0;
        e.curve = -1;
        e.has_range = 1;
        e.t[0] = 0.0;
        e.t[1] = 1.0;
    } else {
        const an_curve *c;
        if (p->n_tok != 5 && p->n_tok != 7)
            return count(p, p->n_tok < 5 ? 5 : 7, "edge <name> <curve> <v0> <v1> [t0 t1]");
        TRY(lookup(p, &p->curves, "curve", p->tok[2], strlen(p->tok[2]), &e.curve));
        TRY(lookup(p, &p->vertices, "vertex", p->tok[3], strlen(p->tok[3]), &e.v0));
        TRY(lookup(p, &p->vertices, "vertex", p->tok[4], strlen(p->tok[4]), &e.v1));
        c = &m->curves[e.curve];
        if (p->n_tok == 7) {
            TRY(numbers(p, 5, 2, e.t));
            if (!(e.t[1] > e.t[0]))
                return fail(p, TF_ERR_ENTITY, "edge '%.60s' has t range [%g, %g]: t1 must "
                                              "exceed t0",
                            p->tok[1], e.t[0], e.t[1]);
            if (c->kind == AN_CIRCLE && e.t[1] - e.t[0] > AN_TWO_PI * (1.0 + 1e-12))
                return fail(p, TF_ERR_ENTITY, "edge '%.60s' has t range [%g, %g], longer "
                                              "than a turn of its circle",
                            p->tok[1], e.t[0], e.t[1]);
            e.has_range = 1;
        } else {
            e.t[0] = 0.0;
            e.t[1] = c->kind == AN_LINE ? c->length : AN_TWO_PI;
        }
    }
    PUSH(p, m->edges, m->n_edges, m->cap_edges, out);
    *out = e;
    out->line = p->line;
    return add_name(p, &p->edges, p->tok[1], m->n_edges - 1, &out->name);
}

static tf_status do_face(parser *p) {
    tf_model *m = p->m;
    an_face f, *out;
    memset(&f, 0, sizeof f);
    if (p->n_tok != 3 && p->n_tok != 7)
        return count(p, p->n_tok < 3 ? 3 : 7, "face <name> <surface> [u0 u1 v0 v1]");
    TRY(check_new_name(p, &p->faces, "face", p->tok[1]));
    TRY(lookup(p, &p->surfaces, "surface", p->tok[2], strlen(p->tok[2]), &f.surface));
    if (p->n_tok == 7) {
        double r[4];
        TRY(numbers(p, 3, 4, r));
        if (!(r[1] > r[0]) || !(r[3] > r[2]))
            return fail(p, TF_ERR_ENTITY, "face '%.60s' has range u [%g, %g], v [%g, %g]: "
                                          "each must be increasing",
                        p->tok[1], r[0], r[1], r[2], r[3]);
        f.has_range = 1;
        f.range[0][0] = r[0];
        f.range[0][1] = r[1];
        f.range[1][0] = r[2];
        f.range[1][1] = r[3];
    }
    f.first_loop = m->n_loops;
    PUSH(p, m->faces, m->n_faces, m->cap_faces, out);
    *out = f;
    out->line = p->line;
    return add_name(p, &p->faces, p->tok[1], m->n_faces - 1, &out->name);
}

static tf_status parse_use(parser *p, const char *tok, an_use *u) {
    const char *s = tok, *at;
    size_t len;
    if (*s == '-') {
        u->reversed = 1;
        s++;
    }
    at = strchr(s, '@');
    len = at ? (size_t)(at - s) : strlen(s);
    if (len == 0)
        return fail(p, TF_ERR_FORMAT, "'%.60s' is not an edge use ([-]edge[@u0|@u1|@v0|@v1])",
                    tok);
    if (at) {
        static const char *const tags[] = {"u0", "u1", "v0", "v1"};
        int k;
        for (k = 0; k < 4; k++)
            if (strcmp(at + 1, tags[k]) == 0)
                u->tag = AN_TAG_U0 + k;
        if (!u->tag)
            return fail(p, TF_ERR_FORMAT, "unknown tag '%.60s' in '%.60s' (expected @u0, @u1, "
                                          "@v0 or @v1)",
                        at, tok);
    }
    return lookup(p, &p->edges, "edge", s, len, &u->edge);
}

static tf_status do_loop(parser *p) {
    tf_model *m = p->m;
    an_loop *lp;
    an_face *f;
    int i;
    if (m->n_faces == 0)
        return fail(p, TF_ERR_FORMAT, "loop before any face (a loop belongs to the face "
                                      "defined above it)");
    if (p->n_tok < 2)
        return fail(p, TF_ERR_FORMAT, "empty loop: expected 'loop <use> <use> ...'");
    PUSH(p, m->loops, m->n_loops, m->cap_loops, lp);
    lp->line = p->line;
    lp->face = m->n_faces - 1;
    lp->first_use = m->n_uses;
    lp->n_uses = p->n_tok - 1;
    f = &m->faces[m->n_faces - 1];
    f->n_loops++;
    for (i = 1; i < p->n_tok; i++) {
        an_use *u;
        PUSH(p, m->uses, m->n_uses, m->cap_uses, u);
        u->line = p->line;
        u->face = m->n_faces - 1;
        TRY(parse_use(p, p->tok[i], u));
    }
    return TF_OK;
}

/* A new shell of the last solid holding the faces named from token first on. */
static tf_status add_shell(parser *p, int first) {
    tf_model *m = p->m;
    an_shell *sh;
    int i;
    PUSH(p, m->shells, m->n_shells, m->cap_shells, sh);
    sh->line = p->line;
    sh->first_ref = m->n_refs;
    sh->n_refs = p->n_tok - first;
    m->solids[m->n_solids - 1].n_shells++;
    for (i = first; i < p->n_tok; i++) {
        int *ref;
        PUSH(p, m->refs, m->n_refs, m->cap_refs, ref);
        TRY(lookup(p, &p->faces, "face", p->tok[i], strlen(p->tok[i]), ref));
    }
    return TF_OK;
}

static tf_status do_solid(parser *p) {
    tf_model *m = p->m;
    an_solid *s;
    if (p->n_tok < 3)
        return fail(p, TF_ERR_FORMAT, "too few values for solid: expected 'solid <name> <face> "
                                      "<face> ...'");
    TRY(check_new_name(p, &p->solids, "solid", p->tok[1]));
    PUSH(p, m->solids, m->n_solids, m->cap_solids, s);
    s->line = p->line;
    s->first_shell = m->n_shells;
    TRY(add_name(p, &p->solids, p->tok[1], m->n_solids - 1, &s->name));
    return add_shell(p, 2);
}

static tf_status do_shell(parser *p) {
    if (p->m->n_solids == 0)
        return fail(p, TF_ERR_FORMAT, "shell before any solid (a shell belongs to the solid "
                                      "defined above it)");
    if (p->n_tok < 2)
        return fail(p, TF_ERR_FORMAT, "empty shell: expected 'shell <face> <face> ...'");
    return add_shell(p, 1);
}

/* ---- lines and files ---------------------------------------------------------------------- */

/* Split line (modified in place) into p->tok, dropping its comment. */
static tf_status tokenize(parser *p, char *line) {
    char *s = line, *hash = strchr(line, '#');
    if (hash)
        *hash = '\0';
    p->n_tok = 0;
    for (;;) {
        char **slot;
        while (*s == ' ' || *s == '\t' || *s == '\r' || *s == '\v' || *s == '\f')
            s++;
        if (!*s)
            return TF_OK;
        PUSH(p, p->tok, p->n_tok, p->cap_tok, slot);
        *slot = s;
        while (*s && !(*s == ' ' || *s == '\t' || *s == '\r' || *s == '\v' || *s == '\f'))
            s++;
        if (*s)
            *s++ = '\0';
    }
}

static tf_status dispatch(parser *p) {
    static const struct {
        const char *word;
        tf_status (*run)(parser *);
    } keywords[] = {{"vertex", do_vertex}, {"curve", do_curve}, {"surface", do_surface},
                    {"edge", do_edge},     {"face", do_face},   {"loop", do_loop},
                    {"solid", do_solid},   {"shell", do_shell}};
    size_t k;
    for (k = 0; k < sizeof keywords / sizeof keywords[0]; k++)
        if (strcmp(p->tok[0], keywords[k].word) == 0)
            return keywords[k].run(p);
    return fail(p, TF_ERR_FORMAT, "unknown keyword '%.60s' (expected vertex, curve, surface, "
                                  "edge, face, loop, solid or shell)",
                p->tok[0]);
}

/* The whole file, NUL-terminated, in *text (*len bytes before the NUL). */
static tf_status read_file(const char *path, char **text, size_t *len, tf_error *err) {
    FILE *f = fopen(path, "rb");
    size_t cap = 1 << 16, n = 0;
    char *buf;
    if (!f)
        return an_error(err, TF_ERR_IO, TF_ENTITY_NONE, -1, "cannot open '%s': %s", path,
                        strerror(errno));
    buf = malloc(cap);
    for (;;) {
        size_t got;
        if (!buf) {
            fclose(f);
            return an_error(err, TF_ERR_INTERNAL, TF_ENTITY_NONE, -1, "out of memory reading '%s'",
                            path);
        }
        if (cap - n < 2) {
            char *bigger = cap < ((size_t)-1) / 2 ? realloc(buf, cap * 2) : NULL;
            if (!bigger)
                free(buf);
            buf = bigger;
            cap *= 2;
            continue;
        }
        errno = 0;
        got = fread(buf + n, 1, cap - n - 1, f);
        n += got;
        if (got == 0)
            break;
    }
    if (ferror(f)) {
        int e = errno;
        fclose(f);
        free(buf);
        return an_error(err, TF_ERR_IO, TF_ENTITY_NONE, -1, "cannot read '%s': %s", path,
                        e ? strerror(e) : "read error");
    }
    fclose(f);
    buf[n] = '\0';
    *text = buf;
    *len = n;
    return TF_OK;
}

static void free_parser(parser *p) {
    free(p->tok);
    free(p->vertices.slots);
    free(p->curves.slots);
    free(p->surfaces.slots);
    free(p->edges.slots);
    free(p->faces.slots);
    free(p->solids.slots);
}

tf_status an_parse_file(const char *path, tf_model *m, tf_error *err) {
    parser p;
    char *text = NULL, *s, *end, *nul;
    size_t len = 0;
    tf_status st = read_file(path, &text, &len, err);
    if (st != TF_OK)
        return st;
    memset(&p, 0, sizeof p);
    p.m = m;
    p.err = err;
    nul = memchr(text, '\0', len);
    if (nul) {
        char *c;
        p.line = 1;
        for (c = text; c < nul; c++)
            p.line += *c == '\n';
        free(text);
        return fail(&p, TF_ERR_FORMAT, "the file holds a NUL byte: it is not a text file");
    }
    for (s = text; st == TF_OK && s; s = end ? end + 1 : NULL) {
        p.line++;
        end = strchr(s, '\n');
        if (end)
            *end = '\0';
        st = tokenize(&p, s);
        if (st == TF_OK && p.n_tok > 0)
            st = dispatch(&p);
    }
    free_parser(&p);
    free(text);
    return st;
}

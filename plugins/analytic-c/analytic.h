/*
 * analytic.h — shared declarations of the analytic geometry kernel (a tetrafoil plugin).
 *
 * The model is built in two steps: parse.c turns the text into records (names resolved to
 * indices, numbers checked), then model.c checks the geometry, builds the pcurves
 * (pcurves.c) and lays out the flat arrays tetrafoil reads. After open_file returns, nothing
 * in a model changes until close, which is what makes the queries thread-safe.
 */
#ifndef TETRAFOIL_ANALYTIC_H
#define TETRAFOIL_ANALYTIC_H

#include <math.h>
#include <stddef.h>

#include "tetrafoil_geometry.h"

/* Internal functions stay out of the shared library's dynamic symbol table, so only the
   entry point is exported and two plugins cannot clash on a helper's name. */
#if defined(__GNUC__)
#define AN_HIDDEN __attribute__((visibility("hidden")))
#define AN_PRINTF(f, a) __attribute__((format(printf, f, a)))
#else
#define AN_HIDDEN
#define AN_PRINTF(f, a)
#endif

/* M_PI is not part of C99. */
#define AN_PI 3.14159265358979323846
#define AN_TWO_PI (2.0 * AN_PI)

/* Points sampled along an edge to build and check its pcurves. */
#define AN_SAMPLES 17

/* Tolerances, relative to the model size (vertex bounding-box diagonal). */
#define AN_REL_ON 1e-6   /* a point lies on a curve or surface */
#define AN_REL_TOL 1e-7  /* tolerance reported for vertices, edges and faces */
#define AN_REL_ISO 1e-9  /* a sampled pcurve is a straight line in (u,v) */

enum an_curve_kind { AN_LINE = 1, AN_CIRCLE };
enum an_surface_kind { AN_PLANE = 1, AN_CYLINDER, AN_CONE, AN_SPHERE, AN_TORUS };
enum an_tag { AN_TAG_NONE = 0, AN_TAG_U0, AN_TAG_U1, AN_TAG_V0, AN_TAG_V1 };
enum an_pcurve_kind { AN_PC_LINEAR = 1, AN_PC_PROJECT };

typedef struct an_vertex {
    char *name;
    int line;
    double p[3];
    double tol; /* grows to the largest gap to the ends of its edges */
} an_vertex;

typedef struct an_curve {
    char *name;
    int line;
    int kind;
    double c[3];       /* line: start point; circle: centre */
    double a[3];       /* line: unit direction; circle: unit axis */
    double x[3], y[3]; /* circle: unit frame of its plane, y = a x x */
    double r;          /* circle radius */
    double length;     /* line: distance between its two points */
} an_curve;

/* Every surface but the plane is a surface of revolution
   S(u,v) = c + rho(v) (cos u x + sin u y) + h(v) a; surfaces.c keeps rho and h per kind. */
typedef struct an_surface {
    char *name;
    int line;
    int kind;
    double c[3];       /* plane origin, or centre */
    double a[3];       /* unit axis; the plane's unit normal x cross y */
    double x[3], y[3]; /* plane: unit U and V; else the frame square to a, y = a x x */
    double r;          /* radius (torus: tube radius) */
    double big_r;      /* torus: distance from the centre to the tube's centre circle */
    double sin_a, cos_a; /* cone half angle */
} an_surface;

typedef struct an_edge {
    char *name;
    int line;
    int curve; /* -1: degenerate (a pole) */
    int v0, v1;
    int has_range;
    double t[2];
    double tol; /* grows to the largest distance between its curve and pcurves */
} an_edge;

typedef struct an_face {
    char *name;
    int line;
    int surface;
    int has_range;
    double range[2][2]; /* [u or v][low, high] */
    int first_loop, n_loops;
} an_face;

typedef struct an_loop {
    int line;
    int face;
    int first_use, n_uses;
} an_loop;

/* Linear: p(t) = p0 + d (t - t0). Project: the edge's curve projected on a plane face. */
typedef struct an_pcurve {
    int kind;
    double t0;
    double p0[2], d[2];
} an_pcurve;

typedef struct an_use {
    int line;
    int face;
    int edge;
    int reversed;
    int tag; /* enum an_tag */
    int seam;
    an_pcurve pc;
} an_use;

typedef struct an_solid {
    char *name;
    int line;
    int first_shell, n_shells;
} an_solid;

typedef struct an_shell {
    int line;
    int first_ref, n_refs;
} an_shell;

struct tf_model {
    double size; /* bounding-box diagonal of the vertices */

    /* records, in file order */
    an_vertex *vertices;
    an_curve *curves;
    an_surface *surfaces;
    an_edge *edges;
    an_face *faces;
    an_loop *loops;
    an_use *uses;
    an_solid *solids;
    an_shell *shells;
    int *refs; /* the shells' faces */
    int n_vertices, n_curves, n_surfaces, n_edges, n_faces, n_loops, n_uses, n_solids,
        n_shells, n_refs;
    int cap_vertices, cap_curves, cap_surfaces, cap_edges, cap_faces, cap_loops, cap_uses,
        cap_solids, cap_shells, cap_refs;

    /* what tetrafoil reads */
    tf_topology topo;
    tf_vertex *tf_vertices;
    tf_edge *tf_edges;
    tf_face *tf_faces;
    tf_loop *tf_loops;
    tf_edge_use *tf_uses;
    tf_shell *tf_shells;
    tf_face_ref *tf_face_refs;
    tf_solid *tf_solids;
    int32_t *tf_solid_shells;
};

/* ---- small vector helpers ---------------------------------------------------------------- */

static inline double an_dot(const double a[3], const double b[3]) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static inline void an_cross(const double a[3], const double b[3], double out[3]) {
    double x = a[1] * b[2] - a[2] * b[1];
    double y = a[2] * b[0] - a[0] * b[2];
    double z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}

static inline void an_sub(const double a[3], const double b[3], double out[3]) {
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}

static inline double an_norm(const double a[3]) {
    return sqrt(an_dot(a, a));
}

static inline double an_dist(const double a[3], const double b[3]) {
    double d[3];
    an_sub(a, b, d);
    return an_norm(d);
}

/* out = a + s b (out may alias a). */
static inline void an_axpy(const double a[3], double s, const double b[3], double out[3]) {
    out[0] = a[0] + s * b[0];
    out[1] = a[1] + s * b[1];
    out[2] = a[2] + s * b[2];
}

/* The angle a shifted by whole turns to lie nearest target. */
static inline double an_wrap_near(double a, double target) {
    return a + AN_TWO_PI * round((target - a) / AN_TWO_PI);
}

/* ---- error.c ----------------------------------------------------------------------------- */

/* Fill err (when not NULL) and return status; the message is forced to valid UTF-8. */
AN_HIDDEN tf_status an_error(tf_error *err, tf_status status, int32_t kind, int32_t entity,
                             const char *fmt, ...) AN_PRINTF(5, 6);
/* A copy of s, or NULL when out of memory (strdup is not C99). */
AN_HIDDEN char *an_strdup(const char *s);

/* ---- curves.c ---------------------------------------------------------------------------- */

AN_HIDDEN void an_curve_eval(const an_curve *c, double t, double out[9]);
AN_HIDDEN void an_curve_point(const an_curve *c, double t, double out[3]);
/* The parameter in [t0, t1] of the curve point closest to p, near *hint when given. */
AN_HIDDEN double an_curve_closest(const an_curve *c, const double p[3], const double *hint,
                                  double t0, double t1);
AN_HIDDEN const char *an_curve_kind_name(int kind);

/* ---- surfaces.c -------------------------------------------------------------------------- */

AN_HIDDEN void an_surface_eval(const an_surface *s, double u, double v, double out[18]);
AN_HIDDEN void an_surface_point(const an_surface *s, double u, double v, double out[3]);
/* (u,v) of the surface point closest to p, unclamped; u from atan2 in (-pi, pi]. Returns 0
   when p is within axis_tol of the axis, where u is undefined (uv[0] is then 0). */
AN_HIDDEN int an_surface_invert(const an_surface *s, const double p[3], double axis_tol,
                                double uv[2]);
/* 1 when the surface closes in direction dir (0: u, 1: v); the period is then 2 pi. */
AN_HIDDEN int an_surface_periodic(const an_surface *s, int dir);
/* A length in (u,v) direction dir against which parameter tolerances are measured. */
AN_HIDDEN double an_surface_scale(const an_surface *s, int dir, double model_size);
AN_HIDDEN const char *an_surface_kind_name(int kind);

/* ---- pcurves.c --------------------------------------------------------------------------- */

/* Build the pcurves of every use of one face and, when the file gives none, its range.
   scratch holds n_edges zeros, and holds them again on return. */
AN_HIDDEN tf_status an_build_face_pcurves(tf_model *m, int face, int *scratch, tf_error *err);
/* out[6] = c, c', c'' in (u,v) at the edge's parameter t. */
AN_HIDDEN void an_pcurve_eval(const tf_model *m, int use, double t, double out[6]);
/* "-name@u1": the use as the file wrote it. */
AN_HIDDEN void an_use_label(const tf_model *m, int use, char *buf, size_t size);

/* ---- names.c ----------------------------------------------------------------------------- */

typedef struct an_name {
    const char *name; /* owned by the entity's record; NULL: an empty slot */
    int index;
    int line;
} an_name;

/* A hash table of one kind's names (open addressing): lookups stay O(1) on large files. */
typedef struct an_names {
    an_name *slots;
    size_t cap, count;
} an_names;

/* The entry of the name s[0 .. len), or NULL. */
AN_HIDDEN const an_name *an_names_get(const an_names *m, const char *s, size_t len);
/* Add name (not copied); 0 when out of memory. */
AN_HIDDEN int an_names_put(an_names *m, const char *name, int index, int line);

/* ---- parse.c ----------------------------------------------------------------------------- */

/* Read path into m's records; names resolved, numbers and counts checked. */
AN_HIDDEN tf_status an_parse_file(const char *path, tf_model *m, tf_error *err);

/* ---- model.c ----------------------------------------------------------------------------- */

/* Check the parsed records, build the pcurves and the arrays tetrafoil reads. */
AN_HIDDEN tf_status an_build_model(tf_model *m, tf_error *err);
AN_HIDDEN void an_free_model(tf_model *m);

/* Return the status of x when it is not TF_OK. */
#define TRY(x)                                                                                \
    do {                                                                                      \
        tf_status st_ = (x);                                                                  \
        if (st_ != TF_OK)                                                                     \
            return st_;                                                                       \
    } while (0)

#endif /* TETRAFOIL_ANALYTIC_H */

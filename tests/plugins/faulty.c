/*
 * faulty.c — deliberately broken tetrafoil geometry plugins, for tetrafoil's tests of how it
 * loads plugins and reports their failures. One file, built five ways (from the repository
 * root; FAULT is one of the names below or its number):
 *
 *   cc -std=c99 -Wall -Wextra -Werror -O2 -fPIC -shared -Iinclude -DFAULT=FAULT_ABI \
 *      tests/plugins/faulty.c -o libtetrafoil_faulty_abi.so -lm
 *
 * FAULT_NO_ENTRY  exports no tetrafoil_geometry_plugin (only another function)
 * FAULT_ABI       a table with abi_version 99
 * FAULT_MISSING   a table without the required topology function
 * FAULT_ERROR     the unit cube, whose face 3 (ymax) fails surface_derivs and surface_points
 *                 with TF_ERR_EVAL and "the kernel lost face 3"
 * FAULT_NAN       the unit cube, whose face 3 answers NaN for every coordinate (with TF_OK)
 *
 * The cube [0,1]^3: vertex c = x + 2y + 4z at (x, y, z); edge 4a + k runs along axis a from
 * the k-th corner (in index order) whose bit a is 0, t in [0, 1]; face 2a + s is the side
 * at coordinate a = s (xmin, xmax, ymin, ymax, zmin, zmax), with u and v along the next two
 * axes. Whatever path open_file is given (it must not be NULL), it opens this cube.
 */
#define FAULT_NO_ENTRY 1
#define FAULT_ABI 2
#define FAULT_MISSING 3
#define FAULT_ERROR 4
#define FAULT_NAN 5

#ifndef FAULT
#error "build with -DFAULT=FAULT_NO_ENTRY (or FAULT_ABI, FAULT_MISSING, FAULT_ERROR, FAULT_NAN)"
#endif

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "tetrafoil_geometry.h"

#if FAULT == FAULT_NO_ENTRY

/* A library that is no plugin: the entry point is missing. */
int tetrafoil_not_a_plugin(void);
int tetrafoil_not_a_plugin(void) {
    return 0;
}

#else

struct tf_model {
    tf_vertex vertices[8];
    tf_edge edges[12];
    tf_face faces[6];
    tf_loop loops[6];
    tf_edge_use uses[24];
    tf_shell shell;
    tf_face_ref refs[6];
    tf_solid solid;
    int32_t solid_shell;
    tf_topology topo;
};

static const char *const face_names[6] = {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"};

/* The edge along axis a starting at corner c (whose bit a is 0). */
static int edge_from(int c, int a) {
    int k = 0, d;
    for (d = 0; d < c; d++)
        k += !(d & (1 << a));
    return 4 * a + k;
}

static tf_status fail(tf_error *err, tf_status st, int32_t kind, int32_t entity, const char *what) {
    if (err) {
        err->entity_kind = kind;
        err->entity = entity;
        snprintf(err->message, sizeof err->message, "%s", what);
    }
    return st;
}

static tf_status open_file(const char *path, tf_model **model, tf_error *err) {
    tf_model *m;
    int c, a, f, k;
    if (!path || !model)
        return fail(err, TF_ERR_IO, TF_ENTITY_NONE, -1, "no path");
    m = calloc(1, sizeof *m);
    if (!m)
        return fail(err, TF_ERR_INTERNAL, TF_ENTITY_NONE, -1, "out of memory");
    for (c = 0; c < 8; c++) {
        for (a = 0; a < 3; a++)
            m->vertices[c].point[a] = (c >> a) & 1;
        m->vertices[c].tolerance = 1e-7;
    }
    for (a = 0; a < 3; a++)
        for (c = 0; c < 8; c++)
            if (!(c & (1 << a))) {
                tf_edge *e = &m->edges[edge_from(c, a)];
                e->v0 = c;
                e->v1 = c | (1 << a);
                e->t_range[1] = 1.0;
                e->tolerance = 1e-7;
            }
    for (f = 0; f < 6; f++) {
        static const int corner_uv[5][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0, 0}};
        int ax = f / 2, ua = (ax + 1) % 3, va = (ax + 2) % 3;
        tf_face *face = &m->faces[f];
        face->name = face_names[f];
        face->first_loop = f;
        face->n_loops = 1;
        face->u_range[1] = face->v_range[1] = 1.0;
        face->tolerance = 1e-7;
        m->loops[f].first_use = 4 * f;
        m->loops[f].n_uses = 4;
        for (k = 0; k < 4; k++) {
            int c0 = (f % 2) << ax | corner_uv[k][0] << ua | corner_uv[k][1] << va;
            int c1 = (f % 2) << ax | corner_uv[k + 1][0] << ua | corner_uv[k + 1][1] << va;
            int lo = c0 < c1 ? c0 : c1, along = (c0 ^ c1) == 1 ? 0 : (c0 ^ c1) == 2 ? 1 : 2;
            m->uses[4 * f + k].edge = edge_from(lo, along);
            m->uses[4 * f + k].flags = TF_USE_PCURVE | (c0 > c1 ? TF_USE_REVERSED : 0u);
        }
        m->refs[f].face = f;
    }
    m->shell.n_faces = 6;
    m->solid.name = "cube";
    m->solid.n_shells = 1;
    m->topo.n_vertices = 8;
    m->topo.n_edges = 12;
    m->topo.n_faces = 6;
    m->topo.n_loops = 6;
    m->topo.n_uses = 24;
    m->topo.n_shells = 1;
    m->topo.n_face_refs = 6;
    m->topo.n_solids = 1;
    m->topo.n_solid_shells = 1;
    m->topo.vertices = m->vertices;
    m->topo.edges = m->edges;
    m->topo.faces = m->faces;
    m->topo.loops = m->loops;
    m->topo.uses = m->uses;
    m->topo.shells = &m->shell;
    m->topo.face_refs = m->refs;
    m->topo.solids = &m->solid;
    m->topo.solid_shells = &m->solid_shell;
    *model = m;
    return TF_OK;
}

static void close_model(tf_model *m) {
    free(m);
}

#if FAULT != FAULT_MISSING
static tf_status topology(const tf_model *m, tf_topology *out, tf_error *err) {
    (void)err;
    *out = m->topo;
    return TF_OK;
}
#endif

static tf_status curve_derivs(const tf_model *m, int32_t edge, size_t n, const double *t,
                              double *out, tf_error *err) {
    size_t k;
    int a;
    if (edge < 0 || edge >= 12)
        return fail(err, TF_ERR_EVAL, TF_ENTITY_EDGE, edge, "no such edge");
    for (k = 0; k < n; k++)
        for (a = 0; a < 3; a++) {
            double along = edge / 4 == a;
            out[9 * k + a] = m->vertices[m->edges[edge].v0].point[a] + t[k] * along;
            out[9 * k + 3 + a] = along;
            out[9 * k + 6 + a] = 0.0;
        }
    return TF_OK;
}

/* The edge's line projected on the face's axes: exact, as the edge lies in the face. */
static tf_status pcurve_derivs(const tf_model *m, int32_t use, size_t n, const double *t,
                               double *out, tf_error *err) {
    size_t k;
    int ua, va;
    if (use < 0 || use >= 24)
        return fail(err, TF_ERR_EVAL, TF_ENTITY_USE, use, "no such edge use");
    ua = (use / 8 + 1) % 3; /* use / 4 is the face, face / 2 its axis */
    va = (use / 8 + 2) % 3;
    for (k = 0; k < n; k++) {
        double c[9];
        curve_derivs(m, m->uses[use].edge, 1, &t[k], c, err);
        out[6 * k] = c[ua];
        out[6 * k + 1] = c[va];
        out[6 * k + 2] = c[3 + ua];
        out[6 * k + 3] = c[3 + va];
        out[6 * k + 4] = out[6 * k + 5] = 0.0;
    }
    return TF_OK;
}

/* Face 3 is where the cube breaks: 1 when *st (and out) hold the answer for it. */
static int broken(int32_t face, size_t n, size_t stride, double *out, tf_error *err,
                  tf_status *st) {
    size_t k;
    if (face != 3 || (FAULT != FAULT_ERROR && FAULT != FAULT_NAN))
        return 0;
    if (FAULT == FAULT_ERROR) {
        *st = fail(err, TF_ERR_EVAL, TF_ENTITY_FACE, 3, "the kernel lost face 3");
        return 1;
    }
    for (k = 0; k < n * stride; k++)
        out[k] = NAN;
    *st = TF_OK;
    return 1;
}

static tf_status surface_derivs(const tf_model *m, int32_t face, size_t n, const double *uv,
                                double *out, tf_error *err) {
    size_t k;
    int a, ax = face / 2, ua = (ax + 1) % 3, va = (ax + 2) % 3;
    tf_status st;
    (void)m;
    if (face < 0 || face >= 6)
        return fail(err, TF_ERR_EVAL, TF_ENTITY_FACE, face, "no such face");
    if (broken(face, n, 18, out, err, &st))
        return st;
    for (k = 0; k < n; k++) {
        double *o = out + 18 * k;
        for (a = 0; a < 18; a++)
            o[a] = 0.0;
        o[ax] = face % 2;
        o[ua] = uv[2 * k];
        o[va] = uv[2 * k + 1];
        o[3 + ua] = 1.0;
        o[6 + va] = 1.0;
    }
    return TF_OK;
}

static tf_status surface_points(const tf_model *m, int32_t face, size_t n, const double *uv,
                                double *out, tf_error *err) {
    size_t k;
    tf_status st;
    if (face < 0 || face >= 6)
        return fail(err, TF_ERR_EVAL, TF_ENTITY_FACE, face, "no such face");
    if (broken(face, n, 3, out, err, &st))
        return st;
    for (k = 0; k < n; k++) {
        double d[18];
        surface_derivs(m, face, 1, uv + 2 * k, d, err);
        out[3 * k] = d[0];
        out[3 * k + 1] = d[1];
        out[3 * k + 2] = d[2];
    }
    return TF_OK;
}

static const char *const extensions[] = {"faulty", NULL};

static const tf_plugin table = {
#if FAULT == FAULT_ABI
    .abi_version = 99u,
#else
    .abi_version = TF_GEOMETRY_ABI_VERSION,
#endif
    .struct_size = sizeof(tf_plugin),
    .name = "faulty",
    .version = "1.0.0",
    .extensions = extensions,
    .flags = 0u,
    .open_file = open_file,
    .close = close_model,
#if FAULT == FAULT_MISSING
    .topology = NULL,
#else
    .topology = topology,
#endif
    .curve_derivs = curve_derivs,
    .pcurve_derivs = pcurve_derivs,
    .surface_derivs = surface_derivs,
    .surface_points = surface_points,
};

const tf_plugin *tetrafoil_geometry_plugin(void);
const tf_plugin *tetrafoil_geometry_plugin(void) {
    return &table;
}

#endif

/*
 * plugin.c — the tetrafoil plugin table of the analytic kernel and its ABI functions.
 *
 * Build: see README.md (every .c file of this directory, C99, -lm).
 *
 * Every query only reads the model, which does not change after open_file, and writes
 * nothing but its caller's buffers: the plugin is safe to call from several threads at
 * once (flags 0).
 */
#include <stdlib.h>

#include "analytic.h"

/* ---- argument checks ---------------------------------------------------------------------- */

static tf_status check_call(const tf_model *m, int32_t index, int32_t n_entities, int32_t kind,
                            const char *what, size_t n, const void *in, const void *out,
                            tf_error *err) {
    if (!m)
        return an_error(err, TF_ERR_INTERNAL, TF_ENTITY_NONE, -1, "no model given");
    if (index < 0 || index >= n_entities)
        return an_error(err, TF_ERR_EVAL, kind, index, "there is no %s %d (the model has %d)",
                        what, (int)index, (int)n_entities);
    if (n > 0 && (!in || !out))
        return an_error(err, TF_ERR_INTERNAL, kind, index, "NULL array passed for %zu values", n);
    return TF_OK;
}

static tf_status not_finite(tf_error *err, int32_t kind, int32_t index, const char *what,
                            size_t k, double x) {
    return an_error(err, TF_ERR_EVAL, kind, index, "%s[%zu] = %g is not finite", what, k, x);
}

/* ---- topology ----------------------------------------------------------------------------- */

static tf_status open_file(const char *path, tf_model **model, tf_error *err) {
    tf_model *m;
    tf_status st;
    if (!model)
        return an_error(err, TF_ERR_INTERNAL, TF_ENTITY_NONE, -1, "no place for the model");
    *model = NULL;
    if (!path)
        return an_error(err, TF_ERR_IO, TF_ENTITY_NONE, -1, "no path given");
    m = calloc(1, sizeof *m);
    if (!m)
        return an_error(err, TF_ERR_INTERNAL, TF_ENTITY_NONE, -1, "out of memory");
    st = an_parse_file(path, m, err);
    if (st == TF_OK)
        st = an_build_model(m, err);
    if (st != TF_OK) {
        an_free_model(m);
        return st;
    }
    *model = m;
    return TF_OK;
}

static void close_model(tf_model *m) {
    an_free_model(m);
}

static tf_status topology(const tf_model *m, tf_topology *out, tf_error *err) {
    if (!m || !out)
        return an_error(err, TF_ERR_INTERNAL, TF_ENTITY_NONE, -1, "no model or no output");
    *out = m->topo;
    return TF_OK;
}

/* ---- curves ------------------------------------------------------------------------------- */

/* A degenerate edge has no curve; should it be asked, it is its vertex standing still. */
static void edge_eval(const tf_model *m, int32_t edge, double t, double out[9]) {
    const an_edge *e = &m->edges[edge];
    int i;
    if (e->curve >= 0) {
        an_curve_eval(&m->curves[e->curve], t, out);
        return;
    }
    for (i = 0; i < 3; i++) {
        out[i] = m->vertices[e->v0].p[i];
        out[3 + i] = out[6 + i] = 0.0;
    }
}

static tf_status curve_derivs(const tf_model *m, int32_t edge, size_t n, const double *t,
                              double *out, tf_error *err) {
    size_t k;
    tf_status st = check_call(m, edge, m ? m->n_edges : 0, TF_ENTITY_EDGE, "edge", n, t, out, err);
    if (st != TF_OK)
        return st;
    for (k = 0; k < n; k++) {
        if (!isfinite(t[k]))
            return not_finite(err, TF_ENTITY_EDGE, edge, "t", k, t[k]);
        edge_eval(m, edge, t[k], out + 9 * k);
    }
    return TF_OK;
}

static tf_status curve_points(const tf_model *m, int32_t edge, size_t n, const double *t,
                              double *out, tf_error *err) {
    size_t k;
    tf_status st = check_call(m, edge, m ? m->n_edges : 0, TF_ENTITY_EDGE, "edge", n, t, out, err);
    if (st != TF_OK)
        return st;
    for (k = 0; k < n; k++) {
        double d[9];
        if (!isfinite(t[k]))
            return not_finite(err, TF_ENTITY_EDGE, edge, "t", k, t[k]);
        edge_eval(m, edge, t[k], d);
        out[3 * k] = d[0];
        out[3 * k + 1] = d[1];
        out[3 * k + 2] = d[2];
    }
    return TF_OK;
}

static tf_status curve_closest(const tf_model *m, int32_t edge, const double *p,
                               const double *hint, double *t, tf_error *err) {
    const an_edge *e;
    tf_status st = check_call(m, edge, m ? m->n_edges : 0, TF_ENTITY_EDGE, "edge", 1, p, t, err);
    if (st != TF_OK)
        return st;
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
        return an_error(err, TF_ERR_EVAL, TF_ENTITY_EDGE, edge, "the point is not finite");
    e = &m->edges[edge];
    if (e->curve < 0)
        *t = hint && isfinite(*hint) ? fmin(fmax(*hint, e->t[0]), e->t[1]) : e->t[0];
    else
        *t = an_curve_closest(&m->curves[e->curve], p, hint, e->t[0], e->t[1]);
    return TF_OK;
}

/* ---- pcurves ------------------------------------------------------------------------------ */

static tf_status pcurve_derivs(const tf_model *m, int32_t use, size_t n, const double *t,
                               double *out, tf_error *err) {
    size_t k;
    tf_status st = check_call(m, use, m ? m->n_uses : 0, TF_ENTITY_USE, "edge use", n, t, out, err);
    if (st != TF_OK)
        return st;
    for (k = 0; k < n; k++) {
        if (!isfinite(t[k]))
            return not_finite(err, TF_ENTITY_USE, use, "t", k, t[k]);
        an_pcurve_eval(m, use, t[k], out + 6 * k);
    }
    return TF_OK;
}

/* ---- surfaces ----------------------------------------------------------------------------- */

static tf_status check_uv(tf_error *err, int32_t face, size_t k, const double *uv) {
    if (!isfinite(uv[2 * k]))
        return not_finite(err, TF_ENTITY_FACE, face, "uv", 2 * k, uv[2 * k]);
    if (!isfinite(uv[2 * k + 1]))
        return not_finite(err, TF_ENTITY_FACE, face, "uv", 2 * k + 1, uv[2 * k + 1]);
    return TF_OK;
}

static tf_status surface_derivs(const tf_model *m, int32_t face, size_t n, const double *uv,
                                double *out, tf_error *err) {
    size_t k;
    tf_status st = check_call(m, face, m ? m->n_faces : 0, TF_ENTITY_FACE, "face", n, uv, out, err);
    for (k = 0; st == TF_OK && k < n; k++) {
        st = check_uv(err, face, k, uv);
        if (st == TF_OK)
            an_surface_eval(&m->surfaces[m->faces[face].surface], uv[2 * k], uv[2 * k + 1],
                            out + 18 * k);
    }
    return st;
}

static tf_status surface_points(const tf_model *m, int32_t face, size_t n, const double *uv,
                                double *out, tf_error *err) {
    size_t k;
    tf_status st = check_call(m, face, m ? m->n_faces : 0, TF_ENTITY_FACE, "face", n, uv, out, err);
    for (k = 0; st == TF_OK && k < n; k++) {
        st = check_uv(err, face, k, uv);
        if (st == TF_OK)
            an_surface_point(&m->surfaces[m->faces[face].surface], uv[2 * k], uv[2 * k + 1],
                             out + 3 * k);
    }
    return st;
}

/* An angle shifted by whole turns into [lo, hi], or nearest to it when the range is less
   than a turn and the angle falls outside. */
static double into_range(double x, double lo, double hi) {
    double eps = 1e-12 * AN_TWO_PI;
    x -= AN_TWO_PI * floor((x - lo + eps) / AN_TWO_PI);
    if (x > hi && lo - (x - AN_TWO_PI) < x - hi)
        x -= AN_TWO_PI;
    return x;
}

static tf_status surface_closest(const tf_model *m, int32_t face, const double *p,
                                 const double *hint, double *uv, tf_error *err) {
    const an_face *f;
    const an_surface *s;
    double raw[2];
    int dir, u_defined;
    tf_status st = check_call(m, face, m ? m->n_faces : 0, TF_ENTITY_FACE, "face", 1, p, uv, err);
    if (st != TF_OK)
        return st;
    if (!isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]))
        return an_error(err, TF_ERR_EVAL, TF_ENTITY_FACE, face, "the point is not finite");
    if (hint && (!isfinite(hint[0]) || !isfinite(hint[1])))
        hint = NULL;
    f = &m->faces[face];
    s = &m->surfaces[f->surface];
    u_defined = an_surface_invert(s, p, 1e-14 * (an_dist(p, s->c) + m->size), raw);
    for (dir = 0; dir < 2; dir++) {
        double lo = f->range[dir][0], hi = f->range[dir][1];
        if (!an_surface_periodic(s, dir)) {
            uv[dir] = fmin(fmax(raw[dir], lo), hi);
        } else if (dir == 0 && !u_defined) {
            /* on the axis (a pole, the apex) every u is the same point */
            uv[dir] = hint ? hint[0] : 0.5 * (lo + hi);
        } else if (hint) {
            uv[dir] = an_wrap_near(raw[dir], hint[dir]);
        } else {
            uv[dir] = into_range(raw[dir], lo, hi);
        }
    }
    return TF_OK;
}

/* ---- the table ---------------------------------------------------------------------------- */

static const char *const extensions[] = {"analytic", NULL};

static const tf_plugin table = {
    .abi_version = TF_GEOMETRY_ABI_VERSION,
    .struct_size = sizeof(tf_plugin),
    .name = "analytic",
    .version = "1.0.0",
    .extensions = extensions,
    .flags = 0u,
    .reserved = 0u,
    .open_file = open_file,
    .close = close_model,
    .topology = topology,
    .curve_derivs = curve_derivs,
    .pcurve_derivs = pcurve_derivs,
    .surface_derivs = surface_derivs,
    .open_buffer = NULL,
    .curve_points = curve_points,
    .surface_points = surface_points,
    .curve_closest = curve_closest,
    .surface_closest = surface_closest,
    .surface_circle = NULL,
    .sew = NULL,
    .fuse = NULL,
};

#if defined(__GNUC__)
__attribute__((visibility("default")))
#endif
const tf_plugin *tetrafoil_geometry_plugin(void);

const tf_plugin *tetrafoil_geometry_plugin(void) {
    return &table;
}

/*
 * pcurves.c — the (u,v) image of every edge use on its face: the core of the kernel.
 *
 * tetrafoil meshes a face in its parameter plane and needs surface(pcurve(t)) == curve(t)
 * to rounding. On a plane that is an exact projection. On the surfaces of revolution the
 * kernel accepts only iso-parameter edges, whose pcurves are straight lines in t: sampled,
 * inverted in closed form, unwrapped, and fitted exactly by the first and last samples.
 * Periodic directions leave each such line free up to whole periods; the tags of the file
 * and the face's range pick the period, so that a seam's two uses land on both sides.
 */
#include <stdio.h>
#include <string.h>

#include "analytic.h"

void an_pcurve_eval(const tf_model *m, int use, double t, double out[6]) {
    const an_use *u = &m->uses[use];
    const an_pcurve *pc = &u->pc;
    if (pc->kind == AN_PC_LINEAR) {
        out[0] = pc->p0[0] + pc->d[0] * (t - pc->t0);
        out[1] = pc->p0[1] + pc->d[1] * (t - pc->t0);
        out[2] = pc->d[0];
        out[3] = pc->d[1];
        out[4] = out[5] = 0.0;
    } else {
        const an_surface *s = &m->surfaces[m->faces[u->face].surface];
        double c[9], rel[3];
        an_curve_eval(&m->curves[m->edges[u->edge].curve], t, c);
        an_sub(c, s->c, rel);
        out[0] = an_dot(rel, s->x);
        out[1] = an_dot(rel, s->y);
        out[2] = an_dot(c + 3, s->x);
        out[3] = an_dot(c + 3, s->y);
        out[4] = an_dot(c + 6, s->x);
        out[5] = an_dot(c + 6, s->y);
    }
}

void an_use_label(const tf_model *m, int use, char *buf, size_t size) {
    static const char *const tags[] = {"", "@u0", "@u1", "@v0", "@v1"};
    const an_use *u = &m->uses[use];
    snprintf(buf, size, "%s%.60s%s", u->reversed ? "-" : "", m->edges[u->edge].name,
             tags[u->tag]);
}

/* ---- helpers on one use ------------------------------------------------------------------- */

static int is_degenerate(const tf_model *m, int use) {
    return m->edges[m->uses[use].edge].curve < 0;
}

static void pc_at(const tf_model *m, int use, double t, double uv[2]) {
    double o[6];
    an_pcurve_eval(m, use, t, o);
    uv[0] = o[0];
    uv[1] = o[1];
}

/* Where the loop enters and leaves the use, in (u,v). */
static void use_ends(const tf_model *m, int use, double start[2], double end[2]) {
    const an_edge *e = &m->edges[m->uses[use].edge];
    int rev = m->uses[use].reversed;
    pc_at(m, use, e->t[rev ? 1 : 0], start);
    pc_at(m, use, e->t[rev ? 0 : 1], end);
}

static double pc_mid(const tf_model *m, int use, int dir) {
    const an_edge *e = &m->edges[m->uses[use].edge];
    double uv[2];
    pc_at(m, use, 0.5 * (e->t[0] + e->t[1]), uv);
    return uv[dir];
}

/* The pcurve's extent in direction dir over its edge's range. */
static void pc_extent(const tf_model *m, int use, int dir, double *lo, double *hi) {
    const an_use *u = &m->uses[use];
    const an_edge *e = &m->edges[u->edge];
    double a[2], b[2];
    pc_at(m, use, e->t[0], a);
    pc_at(m, use, e->t[1], b);
    *lo = fmin(a[dir], b[dir]);
    *hi = fmax(a[dir], b[dir]);
    /* a circle projected on a plane also peaks inside its range */
    if (u->pc.kind == AN_PC_PROJECT && m->curves[e->curve].kind == AN_CIRCLE) {
        const an_curve *c = &m->curves[e->curve];
        const double *axis = dir == 0 ? m->surfaces[m->faces[u->face].surface].x
                                      : m->surfaces[m->faces[u->face].surface].y;
        double base = atan2(an_dot(c->y, axis), an_dot(c->x, axis));
        double t = base + AN_PI * ceil((e->t[0] - base) / AN_PI);
        int k;
        for (k = 0; k < 4 && t <= e->t[1]; k++, t += AN_PI) {
            double uv[2];
            pc_at(m, use, t, uv);
            *lo = fmin(*lo, uv[dir]);
            *hi = fmax(*hi, uv[dir]);
        }
    }
}

/* Which side of direction dir the use is tagged to: 0, 1, or -1 when it is not. */
static int tag_side(int tag, int dir) {
    if (dir == 0)
        return tag == AN_TAG_U0 ? 0 : tag == AN_TAG_U1 ? 1 : -1;
    return tag == AN_TAG_V0 ? 0 : tag == AN_TAG_V1 ? 1 : -1;
}

static const char *const dir_name[2] = {"u", "v"};

/* ---- building one use's pcurve ------------------------------------------------------------ */

typedef struct face_ctx {
    tf_model *m;
    int face;
    an_face *f;
    const an_surface *s;
    tf_error *err;
} face_ctx;

static void sample_ts(const an_edge *e, double t[AN_SAMPLES]) {
    int k;
    for (k = 0; k < AN_SAMPLES; k++)
        t[k] = e->t[0] + (e->t[1] - e->t[0]) * k / (AN_SAMPLES - 1);
    t[AN_SAMPLES - 1] = e->t[1];
}

static tf_status project_on_plane(face_ctx *fc, int ui) {
    tf_model *m = fc->m;
    an_use *u = &m->uses[ui];
    an_edge *e = &m->edges[u->edge];
    double t[AN_SAMPLES], worst = 0.0;
    int k;
    sample_ts(e, t);
    for (k = 0; k < AN_SAMPLES; k++) {
        double p[3], rel[3];
        an_curve_point(&m->curves[e->curve], t[k], p);
        an_sub(p, fc->s->c, rel);
        worst = fmax(worst, fabs(an_dot(rel, fc->s->a)));
    }
    if (!(worst <= AN_REL_ON * m->size))
        return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                        "line %d: face '%s' (plane): edge '%s' is %g from the plane", u->line,
                        fc->f->name, e->name, worst);
    e->tol = fmax(e->tol, worst);
    u->pc.kind = AN_PC_PROJECT;
    return TF_OK;
}

/* The straight line in (u,v) through the inverted samples of an iso-parameter edge. */
static tf_status fit_iso_line(face_ctx *fc, int ui) {
    tf_model *m = fc->m;
    const an_surface *s = fc->s;
    an_use *u = &m->uses[ui];
    an_edge *e = &m->edges[u->edge];
    const an_curve *c = &m->curves[e->curve];
    double t[AN_SAMPLES], p[AN_SAMPLES][3], uv[AN_SAMPLES][2], worst = 0.0;
    int defined[AN_SAMPLES], k, dir, any = 0;

    sample_ts(e, t);
    for (k = 0; k < AN_SAMPLES; k++) {
        an_curve_point(c, t[k], p[k]);
        defined[k] = an_surface_invert(s, p[k], 1e-9 * m->size, uv[k]);
        any |= defined[k];
    }
    if (!any)
        return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                        "line %d: face '%s' (%s): edge '%s' runs along the surface's axis",
                        u->line, fc->f->name, an_surface_kind_name(s->kind), e->name);
    /* at a pole or apex u is undefined: any u maps to the point, so take the neighbour's */
    for (k = 0; k < AN_SAMPLES; k++) {
        int j;
        if (defined[k])
            continue;
        if (k > 0) {
            uv[k][0] = uv[k - 1][0];
            continue;
        }
        for (j = 1; !defined[j]; j++)
            ;
        uv[k][0] = uv[j][0];
    }
    for (k = 0; k < AN_SAMPLES; k++) {
        double q[3];
        an_surface_point(s, uv[k][0], uv[k][1], q);
        worst = fmax(worst, an_dist(q, p[k]));
    }
    if (!(worst <= AN_REL_ON * m->size))
        return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                        "line %d: face '%s' (%s): edge '%s' is %g from the surface", u->line,
                        fc->f->name, an_surface_kind_name(s->kind), e->name, worst);
    for (dir = 0; dir < 2; dir++) {
        double slope, stray = 0.0, tol = AN_REL_ISO * an_surface_scale(s, dir, m->size);
        if (an_surface_periodic(s, dir))
            for (k = 1; k < AN_SAMPLES; k++)
                uv[k][dir] = an_wrap_near(uv[k][dir], uv[k - 1][dir]);
        slope = (uv[AN_SAMPLES - 1][dir] - uv[0][dir]) / (t[AN_SAMPLES - 1] - t[0]);
        for (k = 1; k < AN_SAMPLES - 1; k++)
            stray = fmax(stray, fabs(uv[k][dir] - (uv[0][dir] + slope * (t[k] - t[0]))));
        if (!(stray <= tol))
            return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                            "line %d: face '%s' (%s): edge '%s' is not an iso-parameter line "
                            "of the surface; the analytic kernel meshes only lines and circles "
                            "that are (its %s strays %g from a straight line in t)",
                            u->line, fc->f->name, an_surface_kind_name(s->kind), e->name,
                            dir_name[dir], stray);
        u->pc.p0[dir] = uv[0][dir];
        u->pc.d[dir] = slope;
    }
    u->pc.kind = AN_PC_LINEAR;
    u->pc.t0 = t[0];
    e->tol = fmax(e->tol, worst);
    return TF_OK;
}

/* A pole's pcurve: the straight line from where the previous use leaves to where the next
   one enters, over the edge's [0, 1]. */
static tf_status join_degenerate(face_ctx *fc, const an_loop *lp, int k) {
    tf_model *m = fc->m;
    int ui = lp->first_use + k;
    int prev = lp->first_use + (k + lp->n_uses - 1) % lp->n_uses;
    int next = lp->first_use + (k + 1) % lp->n_uses;
    an_use *u = &m->uses[ui];
    const an_edge *e = &m->edges[u->edge];
    double from[2], to[2], unused[2];
    int dir;
    if (is_degenerate(m, prev) || is_degenerate(m, next))
        return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                        "line %d: face '%s': degenerate edge '%s' must lie between two "
                        "ordinary edge uses in its loop",
                        u->line, fc->f->name, e->name);
    use_ends(m, prev, unused, from);
    use_ends(m, next, to, unused);
    u->pc.kind = AN_PC_LINEAR;
    u->pc.t0 = e->t[0];
    for (dir = 0; dir < 2; dir++) {
        double a = u->reversed ? to[dir] : from[dir];
        double b = u->reversed ? from[dir] : to[dir];
        u->pc.p0[dir] = a;
        u->pc.d[dir] = (b - a) / (e->t[1] - e->t[0]);
    }
    return TF_OK;
}

/* ---- one face ----------------------------------------------------------------------------- */

/* Seams (an edge used twice by the face) and the tags' sense. */
static tf_status check_seams_and_tags(face_ctx *fc, int first, int last, int *scratch) {
    tf_model *m = fc->m;
    const an_surface *s = fc->s;
    char a[128], b[128];
    tf_status st = TF_OK;
    int ui;
    /* a pole visited twice is no seam: only ordinary edges are counted */
    for (ui = first; ui < last; ui++)
        scratch[m->uses[ui].edge] += !is_degenerate(m, ui);
    for (ui = first; ui < last && st == TF_OK; ui++) {
        an_use *u = &m->uses[ui];
        int *slot = &scratch[u->edge];
        if (u->tag && !an_surface_periodic(s, u->tag <= AN_TAG_U1 ? 0 : 1)) {
            an_use_label(m, ui, a, sizeof a);
            st = an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                          "line %d: face '%s' (%s) is not periodic in %s: the tag of '%s' has "
                          "no meaning there",
                          u->line, fc->f->name, an_surface_kind_name(s->kind),
                          u->tag <= AN_TAG_U1 ? "u" : "v", a);
        } else if (*slot > 2) {
            st = an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                          "line %d: face '%s' uses edge '%s' %d times (a seam is used twice)",
                          u->line, fc->f->name, m->edges[u->edge].name, *slot);
        } else if (*slot == 2) {
            *slot = -(ui + 1); /* the first of the pair, until its partner comes */
            u->seam = 1;
        } else if (*slot < 0) {
            an_use *v = &m->uses[-*slot - 1];
            int pair_ok = v->tag && u->tag && (v->tag - 1) / 2 == (u->tag - 1) / 2 &&
                          v->tag != u->tag;
            u->seam = 1;
            if (v->reversed == u->reversed) {
                an_use_label(m, -*slot - 1, a, sizeof a);
                an_use_label(m, ui, b, sizeof b);
                st = an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                              "line %d: face '%s' uses edge '%s' twice in the same direction "
                              "('%s' and '%s'); a seam's two uses run opposite ways",
                              u->line, fc->f->name, m->edges[u->edge].name, a, b);
            } else if (s->kind != AN_PLANE && !pair_ok) {
                an_use_label(m, -*slot - 1, a, sizeof a);
                an_use_label(m, ui, b, sizeof b);
                st = an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                              "line %d: face '%s' (%s): edge '%s' is a seam (used twice by the "
                              "face, as '%s' and '%s'): tag its uses with both sides of one "
                              "direction, @u0 and @u1 (or @v0 and @v1)",
                              u->line, fc->f->name, an_surface_kind_name(s->kind),
                              m->edges[u->edge].name, a, b);
            }
        }
    }
    for (ui = first; ui < last; ui++)
        scratch[m->uses[ui].edge] = 0;
    return st;
}

/* Shift the pcurves by whole periods in a periodic direction: the rules are in the format
   comment of parse.c (untagged: midpoint in [lo, lo + 2 pi); tagged: nearest their side). */
static void place_periodic(face_ctx *fc, int first, int last, int dir) {
    tf_model *m = fc->m;
    const an_face *f = fc->f;
    const double period = AN_TWO_PI, eps = 1e-9 * AN_TWO_PI;
    double lo = f->has_range ? f->range[dir][0] : 0.0, ref[2];
    int ui, have_ref = 0;

    for (ui = first; ui < last; ui++) {
        if (is_degenerate(m, ui) || tag_side(m->uses[ui].tag, dir) >= 0)
            continue;
        m->uses[ui].pc.p0[dir] -=
            period * floor((pc_mid(m, ui, dir) - lo + eps) / period);
    }

    if (f->has_range) {
        ref[0] = f->range[dir][0];
        ref[1] = f->range[dir][1];
    } else {
        /* the untagged pcurves span the face: the tagged ones go to their sides */
        for (ui = first; ui < last; ui++) {
            double a, b;
            if (is_degenerate(m, ui) || tag_side(m->uses[ui].tag, dir) >= 0)
                continue;
            pc_extent(m, ui, dir, &a, &b);
            ref[0] = have_ref ? fmin(ref[0], a) : a;
            ref[1] = have_ref ? fmax(ref[1], b) : b;
            have_ref = 1;
        }
        if (!have_ref) {
            /* nothing untagged (a whole sphere: a seam and two poles): the first tagged
               use fixes its side */
            ref[0] = 0.0;
            ref[1] = period;
            for (ui = first; ui < last; ui++) {
                int side = tag_side(m->uses[ui].tag, dir);
                double mid;
                if (is_degenerate(m, ui) || side < 0)
                    continue;
                mid = pc_mid(m, ui, dir);
                mid -= period * floor((mid + eps) / period);
                ref[0] = side == 0 ? mid : mid - period;
                ref[1] = ref[0] + period;
                break;
            }
        }
    }

    for (ui = first; ui < last; ui++) {
        int side = tag_side(m->uses[ui].tag, dir);
        if (is_degenerate(m, ui) || side < 0)
            continue;
        m->uses[ui].pc.p0[dir] +=
            period * round((ref[side] - pc_mid(m, ui, dir)) / period);
    }
}

/* The face's range from its pcurves, or a check of the given one against them. */
static tf_status settle_range(face_ctx *fc, int first, int last) {
    tf_model *m = fc->m;
    an_face *f = fc->f;
    const an_surface *s = fc->s;
    char a[128];
    int dir, ui;
    for (dir = 0; dir < 2; dir++) {
        double lo = 0.0, hi = 0.0, scale = an_surface_scale(s, dir, m->size);
        for (ui = first; ui < last; ui++) {
            double x, y;
            pc_extent(m, ui, dir, &x, &y);
            lo = ui == first ? x : fmin(lo, x);
            hi = ui == first ? y : fmax(hi, y);
        }
        if (f->has_range) {
            double tol = AN_REL_ON * scale;
            for (ui = first; ui < last; ui++) {
                double x, y;
                pc_extent(m, ui, dir, &x, &y);
                if (x >= f->range[dir][0] - tol && y <= f->range[dir][1] + tol)
                    continue;
                an_use_label(m, ui, a, sizeof a);
                return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                                "line %d: face '%s' (%s): the pcurve of '%s' spans %s [%g, %g], "
                                "outside the face's range [%g, %g]; check the tags "
                                "(@%s0/@%s1) or the range",
                                m->uses[ui].line, f->name, an_surface_kind_name(s->kind), a,
                                dir_name[dir], x, y, f->range[dir][0], f->range[dir][1],
                                dir_name[dir], dir_name[dir]);
            }
            continue;
        }
        if (an_surface_periodic(s, dir) && hi - lo > AN_TWO_PI * (1.0 + 1e-9))
            return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                            "line %d: face '%s' (%s): its pcurves span %s [%g, %g], more than "
                            "the period 2 pi; check the tags (@%s0/@%s1)",
                            f->line, f->name, an_surface_kind_name(s->kind), dir_name[dir], lo,
                            hi, dir_name[dir], dir_name[dir]);
        if (!(hi - lo > 1e-12 * scale))
            return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                            "line %d: face '%s' (%s): its loops have no extent in %s", f->line,
                            f->name, an_surface_kind_name(s->kind), dir_name[dir]);
        f->range[dir][0] = lo;
        f->range[dir][1] = hi;
    }
    if (s->kind == AN_SPHERE &&
        (f->range[1][0] < -0.5 * AN_PI * (1 + 1e-12) || f->range[1][1] > 0.5 * AN_PI * (1 + 1e-12)))
        return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                        "line %d: face '%s' (sphere): v range [%g, %g] reaches past the poles "
                        "(v in [-pi/2, pi/2])",
                        f->line, f->name, f->range[1][0], f->range[1][1]);
    return TF_OK;
}

/* Each use must start in (u,v) where the previous one ends: exactly when the loop holds a
   seam or a pole (the face is cut open there), else up to whole periods. */
static tf_status check_uv_chain(face_ctx *fc, const an_loop *lp) {
    tf_model *m = fc->m;
    const an_surface *s = fc->s;
    char a[128], b[128];
    int k, dir, strict = 0;
    for (k = 0; k < lp->n_uses; k++)
        strict |= m->uses[lp->first_use + k].seam || is_degenerate(m, lp->first_use + k);
    for (k = 0; k < lp->n_uses; k++) {
        int ui = lp->first_use + k, next = lp->first_use + (k + 1) % lp->n_uses;
        double start[2], end[2], next_start[2], next_end[2];
        use_ends(m, ui, start, end);
        use_ends(m, next, next_start, next_end);
        for (dir = 0; dir < 2; dir++) {
            double gap = next_start[dir] - end[dir];
            if (!strict && an_surface_periodic(s, dir))
                gap -= AN_TWO_PI * round(gap / AN_TWO_PI);
            if (fabs(gap) > 1e-3 * an_surface_scale(s, dir, m->size)) {
                an_use_label(m, ui, a, sizeof a);
                an_use_label(m, next, b, sizeof b);
                return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                                "line %d: face '%s' (%s): the pcurve of '%s' ends at (u, v) = "
                                "(%g, %g) but that of the next use '%s' starts at (%g, %g); "
                                "check the tags (@u0/@u1/@v0/@v1), or put a degenerate edge "
                                "where the loop passes a pole",
                                lp->line, fc->f->name, an_surface_kind_name(s->kind), a, end[0],
                                end[1], b, next_start[0], next_start[1]);
            }
        }
    }
    return TF_OK;
}

/* A pole's pcurve must map to its vertex all along. */
static tf_status check_pole(face_ctx *fc, int ui) {
    tf_model *m = fc->m;
    const an_use *u = &m->uses[ui];
    an_edge *e = &m->edges[u->edge];
    const an_vertex *v = &m->vertices[e->v0];
    double worst = 0.0;
    int k;
    for (k = 0; k <= 4; k++) {
        double uv[2], q[3];
        pc_at(m, ui, e->t[0] + 0.25 * k * (e->t[1] - e->t[0]), uv);
        an_surface_point(fc->s, uv[0], uv[1], q);
        worst = fmax(worst, an_dist(q, v->p));
    }
    if (!(worst <= AN_REL_ON * m->size))
        return an_error(fc->err, TF_ERR_ENTITY, TF_ENTITY_FACE, fc->face,
                        "line %d: face '%s' (%s): degenerate edge '%s' is not at a pole of the "
                        "surface: its pcurve runs %g from vertex '%s'",
                        u->line, fc->f->name, an_surface_kind_name(fc->s->kind), e->name,
                        worst, v->name);
    e->tol = fmax(e->tol, worst);
    return TF_OK;
}

tf_status an_build_face_pcurves(tf_model *m, int face, int *scratch, tf_error *err) {
    face_ctx fc;
    const an_loop *first_loop, *last_loop;
    int first, last, ui, l, dir;
    fc.m = m;
    fc.face = face;
    fc.f = &m->faces[face];
    fc.s = &m->surfaces[fc.f->surface];
    fc.err = err;
    /* a face's loops, and their uses, are contiguous */
    first_loop = &m->loops[fc.f->first_loop];
    last_loop = &m->loops[fc.f->first_loop + fc.f->n_loops - 1];
    first = first_loop->first_use;
    last = last_loop->first_use + last_loop->n_uses;

    TRY(check_seams_and_tags(&fc, first, last, scratch));
    for (ui = first; ui < last; ui++) {
        if (is_degenerate(m, ui))
            continue;
        TRY(fc.s->kind == AN_PLANE ? project_on_plane(&fc, ui) : fit_iso_line(&fc, ui));
    }
    for (dir = 0; dir < 2; dir++)
        if (an_surface_periodic(fc.s, dir))
            place_periodic(&fc, first, last, dir);
    for (l = 0; l < fc.f->n_loops; l++) {
        const an_loop *lp = &m->loops[fc.f->first_loop + l];
        int k;
        for (k = 0; k < lp->n_uses; k++)
            if (is_degenerate(m, lp->first_use + k))
                TRY(join_degenerate(&fc, lp, k));
    }
    for (ui = first; ui < last; ui++)
        if (is_degenerate(m, ui))
            TRY(check_pole(&fc, ui));
    TRY(settle_range(&fc, first, last));
    for (l = 0; l < fc.f->n_loops; l++)
        TRY(check_uv_chain(&fc, &m->loops[fc.f->first_loop + l]));
    return TF_OK;
}

/* model.c — from parsed records to a checked model and the arrays tetrafoil reads. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analytic.h"

/* The diagonal of the vertices' box; for a model without two distinct vertices, the size of
   its curves and surfaces, so that tolerances keep a scale. */
static double model_size(const tf_model *m) {
    double lo[3] = {0.0, 0.0, 0.0}, hi[3] = {0.0, 0.0, 0.0}, size = 0.0;
    int i, k;
    for (i = 0; i < m->n_vertices; i++)
        for (k = 0; k < 3; k++) {
            lo[k] = i ? fmin(lo[k], m->vertices[i].p[k]) : m->vertices[i].p[k];
            hi[k] = i ? fmax(hi[k], m->vertices[i].p[k]) : m->vertices[i].p[k];
        }
    if (m->n_vertices > 0)
        size = sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                    (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (size > 0.0)
        return size;
    for (i = 0; i < m->n_curves; i++)
        size = fmax(size, m->curves[i].kind == AN_LINE ? m->curves[i].length : 2 * m->curves[i].r);
    for (i = 0; i < m->n_surfaces; i++)
        size = fmax(size, 2 * (m->surfaces[i].r + m->surfaces[i].big_r));
    return size > 0.0 ? size : 1.0;
}

/* The curve must pass through the edge's vertices at the ends of its range. */
static tf_status check_edge_ends(tf_model *m, int ei, tf_error *err) {
    an_edge *e = &m->edges[ei];
    const an_curve *c = &m->curves[e->curve];
    int end;
    for (end = 0; end < 2; end++) {
        an_vertex *v = &m->vertices[end ? e->v1 : e->v0];
        double p[3], gap;
        an_curve_point(c, e->t[end], p);
        gap = an_dist(p, v->p);
        if (!(gap <= AN_REL_ON * m->size))
            return an_error(err, TF_ERR_ENTITY, TF_ENTITY_EDGE, ei,
                            "line %d: edge '%s': curve '%s' at t=%.10g is %g from vertex '%s' "
                            "(%g, %g, %g)",
                            e->line, e->name, c->name, e->t[end], gap, v->name, v->p[0], v->p[1],
                            v->p[2]);
        v->tol = fmax(v->tol, gap);
        e->tol = fmax(e->tol, gap);
    }
    return TF_OK;
}

/* Each use must end at the vertex where the next one starts. */
static tf_status check_chain(const tf_model *m, int li, tf_error *err) {
    const an_loop *lp = &m->loops[li];
    int k;
    for (k = 0; k < lp->n_uses; k++) {
        int ui = lp->first_use + k, next = lp->first_use + (k + 1) % lp->n_uses;
        const an_use *u = &m->uses[ui], *n = &m->uses[next];
        const an_edge *e = &m->edges[u->edge], *f = &m->edges[n->edge];
        int end = u->reversed ? e->v0 : e->v1, start = n->reversed ? f->v1 : f->v0;
        if (end != start) {
            char a[128], b[128];
            an_use_label(m, ui, a, sizeof a);
            an_use_label(m, next, b, sizeof b);
            return an_error(err, TF_ERR_ENTITY, TF_ENTITY_FACE, lp->face,
                            "line %d: face '%s': the loop does not chain: '%s' ends at vertex "
                            "'%s' but the next use '%s' starts at vertex '%s'",
                            lp->line, m->faces[lp->face].name, a, m->vertices[end].name, b,
                            m->vertices[start].name);
        }
    }
    return TF_OK;
}

/* At least one element, so that no array tetrafoil reads is NULL. */
static void *table(int n, size_t size) {
    return calloc(n > 0 ? (size_t)n : 1, size);
}

static tf_status lay_out(tf_model *m, tf_error *err) {
    tf_topology *t = &m->topo;
    double tol = AN_REL_TOL * m->size;
    int i;
    m->tf_vertices = table(m->n_vertices, sizeof *m->tf_vertices);
    m->tf_edges = table(m->n_edges, sizeof *m->tf_edges);
    m->tf_faces = table(m->n_faces, sizeof *m->tf_faces);
    m->tf_loops = table(m->n_loops, sizeof *m->tf_loops);
    m->tf_uses = table(m->n_uses, sizeof *m->tf_uses);
    m->tf_shells = table(m->n_shells, sizeof *m->tf_shells);
    m->tf_face_refs = table(m->n_refs, sizeof *m->tf_face_refs);
    m->tf_solids = table(m->n_solids, sizeof *m->tf_solids);
    m->tf_solid_shells = table(m->n_shells, sizeof *m->tf_solid_shells);
    if (!m->tf_vertices || !m->tf_edges || !m->tf_faces || !m->tf_loops || !m->tf_uses ||
        !m->tf_shells || !m->tf_face_refs || !m->tf_solids || !m->tf_solid_shells)
        return an_error(err, TF_ERR_INTERNAL, TF_ENTITY_NONE, -1, "out of memory");

    for (i = 0; i < m->n_vertices; i++) {
        memcpy(m->tf_vertices[i].point, m->vertices[i].p, sizeof m->vertices[i].p);
        m->tf_vertices[i].tolerance = m->vertices[i].tol;
    }
    for (i = 0; i < m->n_edges; i++) {
        const an_edge *e = &m->edges[i];
        tf_edge *o = &m->tf_edges[i];
        o->v0 = e->v0;
        o->v1 = e->v1;
        o->flags = e->curve < 0 ? TF_EDGE_DEGENERATE : 0u;
        o->t_range[0] = e->t[0];
        o->t_range[1] = e->t[1];
        o->tolerance = e->tol;
    }
    for (i = 0; i < m->n_faces; i++) {
        const an_face *f = &m->faces[i];
        const an_surface *s = &m->surfaces[f->surface];
        tf_face *o = &m->tf_faces[i];
        o->name = f->name;
        o->first_loop = f->first_loop;
        o->n_loops = f->n_loops;
        o->u_range[0] = f->range[0][0];
        o->u_range[1] = f->range[0][1];
        o->v_range[0] = f->range[1][0];
        o->v_range[1] = f->range[1][1];
        o->u_period = an_surface_periodic(s, 0) ? AN_TWO_PI : 0.0;
        o->v_period = an_surface_periodic(s, 1) ? AN_TWO_PI : 0.0;
        o->tolerance = tol;
    }
    for (i = 0; i < m->n_loops; i++) {
        m->tf_loops[i].first_use = m->loops[i].first_use;
        m->tf_loops[i].n_uses = m->loops[i].n_uses;
    }
    for (i = 0; i < m->n_uses; i++) {
        const an_use *u = &m->uses[i];
        m->tf_uses[i].edge = u->edge;
        m->tf_uses[i].flags = TF_USE_PCURVE | (u->reversed ? TF_USE_REVERSED : 0u) |
                              (u->seam ? TF_USE_SEAM : 0u);
    }
    for (i = 0; i < m->n_shells; i++) {
        m->tf_shells[i].first_face = m->shells[i].first_ref;
        m->tf_shells[i].n_faces = m->shells[i].n_refs;
        m->tf_solid_shells[i] = i; /* a solid's shells follow it in the file */
    }
    for (i = 0; i < m->n_refs; i++)
        m->tf_face_refs[i].face = m->refs[i];
    for (i = 0; i < m->n_solids; i++) {
        m->tf_solids[i].name = m->solids[i].name;
        m->tf_solids[i].first_shell = m->solids[i].first_shell;
        m->tf_solids[i].n_shells = m->solids[i].n_shells;
    }

    t->n_vertices = m->n_vertices;
    t->n_edges = m->n_edges;
    t->n_faces = m->n_faces;
    t->n_loops = m->n_loops;
    t->n_uses = m->n_uses;
    t->n_shells = m->n_shells;
    t->n_face_refs = m->n_refs;
    t->n_solids = m->n_solids;
    t->n_solid_shells = m->n_shells;
    t->vertices = m->tf_vertices;
    t->edges = m->tf_edges;
    t->faces = m->tf_faces;
    t->loops = m->tf_loops;
    t->uses = m->tf_uses;
    t->shells = m->tf_shells;
    t->face_refs = m->tf_face_refs;
    t->solids = m->tf_solids;
    t->solid_shells = m->tf_solid_shells;
    return TF_OK;
}

tf_status an_build_model(tf_model *m, tf_error *err) {
    int i, *scratch;
    tf_status st = TF_OK;
    m->size = model_size(m);
    for (i = 0; i < m->n_vertices; i++)
        m->vertices[i].tol = AN_REL_TOL * m->size;
    for (i = 0; i < m->n_edges; i++) {
        m->edges[i].tol = AN_REL_TOL * m->size;
        if (m->edges[i].curve >= 0)
            TRY(check_edge_ends(m, i, err));
    }
    if (m->n_faces == 0)
        return an_error(err, TF_ERR_FORMAT, TF_ENTITY_NONE, -1, "the file defines no faces");
    for (i = 0; i < m->n_faces; i++)
        if (m->faces[i].n_loops == 0)
            return an_error(err, TF_ERR_FORMAT, TF_ENTITY_FACE, i,
                            "line %d: face '%s' has no loop (put 'loop' lines after it)",
                            m->faces[i].line, m->faces[i].name);
    for (i = 0; i < m->n_loops; i++)
        TRY(check_chain(m, i, err));

    scratch = calloc(m->n_edges > 0 ? (size_t)m->n_edges : 1, sizeof *scratch);
    if (!scratch)
        return an_error(err, TF_ERR_INTERNAL, TF_ENTITY_NONE, -1, "out of memory");
    for (i = 0; i < m->n_faces && st == TF_OK; i++)
        st = an_build_face_pcurves(m, i, scratch, err);
    free(scratch);
    TRY(st);
    return lay_out(m, err);
}

void an_free_model(tf_model *m) {
    int i;
    if (!m)
        return;
    for (i = 0; i < m->n_vertices; i++)
        free(m->vertices[i].name);
    for (i = 0; i < m->n_curves; i++)
        free(m->curves[i].name);
    for (i = 0; i < m->n_surfaces; i++)
        free(m->surfaces[i].name);
    for (i = 0; i < m->n_edges; i++)
        free(m->edges[i].name);
    for (i = 0; i < m->n_faces; i++)
        free(m->faces[i].name);
    for (i = 0; i < m->n_solids; i++)
        free(m->solids[i].name);
    free(m->vertices);
    free(m->curves);
    free(m->surfaces);
    free(m->edges);
    free(m->faces);
    free(m->loops);
    free(m->uses);
    free(m->solids);
    free(m->shells);
    free(m->refs);
    free(m->tf_vertices);
    free(m->tf_edges);
    free(m->tf_faces);
    free(m->tf_loops);
    free(m->tf_uses);
    free(m->tf_shells);
    free(m->tf_face_refs);
    free(m->tf_solids);
    free(m->tf_solid_shells);
    free(m);
}

/*
 * tetrafoil_geometry.h — the foreign-geometry plugin interface of tetrafoil, ABI version 1.
 *
 * A plugin is a shared library (libtetrafoil_<name>.so) that exports one C function,
 *
 *     const tf_plugin *tetrafoil_geometry_plugin(void);
 *
 * returning a table that lives as long as the process. Through it tetrafoil opens a file,
 * reads its topology as plain arrays, and asks geometric questions of its curves, pcurves and
 * surfaces. docs/plugins.md is the full contract; the rules that matter most:
 *
 * - Every function returns a tf_status. On anything but TF_OK it fills the caller's tf_error
 *   (the entity concerned and a NUL-terminated message). Nothing may unwind across the
 *   boundary: a C++ plugin catches its exceptions.
 * - Entities are 0-based indices into the topology's arrays. Edge uses are numbered across
 *   the whole model (tf_topology.uses); a pcurve is asked for by its use.
 * - A pcurve is parametrised like its edge: t in the edge's t_range.
 * - Queries (the *_derivs, *_points, *_closest and surface_circle functions) must answer on
 *   the whole parameter range of their entity; an error or a non-finite value there stops the
 *   run with a message naming the plugin and the entity. The optional queries may answer
 *   TF_NOT_FOUND instead ("no such point"), which is not an error.
 * - Threads: unless the table sets TF_PLUGIN_SERIAL, queries on one open model may run on
 *   several threads at once. open_*, topology, sew, fuse and close never run concurrently
 *   with any other call on the same model. With TF_PLUGIN_SERIAL tetrafoil makes every call
 *   to the plugin one at a time.
 * - Memory: the topology's arrays and names belong to the model and stay valid until close.
 *   An array whose count is 0 may be NULL. The table and its strings stay valid for the life
 *   of the process. Reserved fields are written 0.
 * - Lengths (tolerances, coordinates) are absolute, in the model's units.
 *
 * Versioning: abi_version changes when anything here changes meaning. New optional entries
 * may be appended to tf_plugin within one version; struct_size tells tetrafoil how far the
 * table reaches, so an older plugin (a shorter table) still loads.
 */
#ifndef TETRAFOIL_GEOMETRY_H
#define TETRAFOIL_GEOMETRY_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TF_GEOMETRY_ABI_VERSION 1u
#define TF_ENTRY_POINT "tetrafoil_geometry_plugin"

/* ---- status and errors ------------------------------------------------------------------ */

typedef int32_t tf_status;
#define TF_OK 0
#define TF_NOT_FOUND 1       /* optional queries only: there is no such point */
#define TF_ERR_IO 2          /* the file cannot be read */
#define TF_ERR_FORMAT 3      /* the file is not valid for this kernel */
#define TF_ERR_ENTITY 4      /* an entity is wrong (unknown id, bad geometry) */
#define TF_ERR_EVAL 5        /* a query failed */
#define TF_ERR_UNSUPPORTED 6 /* the plugin does not do this */
#define TF_ERR_INTERNAL 7

/* Which entity an error is about. */
#define TF_ENTITY_NONE 0
#define TF_ENTITY_VERTEX 1
#define TF_ENTITY_EDGE 2
#define TF_ENTITY_FACE 3
#define TF_ENTITY_USE 4
#define TF_ENTITY_SHELL 5
#define TF_ENTITY_SOLID 6
#define TF_ENTITY_LINE 7 /* a line of the input file (1-based) */

#define TF_MESSAGE_LEN 512

/* Filled by the plugin when a call fails; tetrafoil zeroes it before each call. */
typedef struct tf_error {
    int32_t entity_kind; /* TF_ENTITY_* */
    int32_t entity;      /* index (or line number) of that entity; -1 when none */
    char message[TF_MESSAGE_LEN]; /* NUL-terminated, UTF-8 */
} tf_error;

/* ---- topology ------------------------------------------------------------------------- */

/* An open model: the plugin's own object. */
typedef struct tf_model tf_model;

typedef struct tf_vertex {
    double point[3];
    double tolerance;
} tf_vertex;

/* The edge collapses to a point (a sphere's pole): it has pcurves but no 3-D curve, and
   tetrafoil never asks curve_* about it. */
#define TF_EDGE_DEGENERATE 1u

/* An edge from vertex v0 (at t_range[0]) to v1 (at t_range[1]). */
typedef struct tf_edge {
    int32_t v0, v1;
    uint32_t flags; /* TF_EDGE_* */
    uint32_t reserved;
    double t_range[2];
    double tolerance;
} tf_edge;

/* The loop runs the edge from t_range[1] to t_range[0]. */
#define TF_USE_REVERSED 1u
/* The edge is a seam of this face: it occurs twice in the face's loops, once per side. */
#define TF_USE_SEAM 2u
/* pcurve_derivs answers for this use. Without it tetrafoil projects the edge's curve onto
   the surface; a seam's uses and a degenerate edge's uses must have pcurves. */
#define TF_USE_PCURVE 4u

/* One traversal of an edge by a face loop. */
typedef struct tf_edge_use {
    int32_t edge;
    uint32_t flags; /* TF_USE_* */
} tf_edge_use;

/* uses[first_use .. first_use + n_uses], in loop order. */
typedef struct tf_loop {
    int32_t first_use, n_uses;
} tf_loop;

/* The face's outward side is opposite to its surface's du x dv (informative: tetrafoil
   works out orientation itself). */
#define TF_FACE_REVERSED 1u

/* A trimmed piece of one surface. Periods are 0 in a direction that does not close; the
   ranges bound the face's pcurves (a face that closes in u spans one period there). */
typedef struct tf_face {
    const char *name; /* NULL when the file gives none */
    uint32_t flags;   /* TF_FACE_* */
    int32_t first_loop, n_loops; /* loops[first_loop ..]; any order, any direction */
    uint32_t reserved;
    double u_range[2], v_range[2];
    double u_period, v_period;
    double tolerance;
} tf_face;

typedef struct tf_face_ref {
    int32_t face;
    uint32_t reversed;
} tf_face_ref;

/* face_refs[first_face .. first_face + n_faces]: a connected set of faces. */
typedef struct tf_shell {
    int32_t first_face, n_faces;
} tf_shell;

/* solid_shells[first_shell ..]: shell indices in any order (tetrafoil finds the outer one). */
typedef struct tf_solid {
    const char *name; /* NULL when the file gives none */
    int32_t first_shell, n_shells;
} tf_solid;

/* The whole model as flat arrays owned by the model. */
typedef struct tf_topology {
    int32_t n_vertices, n_edges, n_faces, n_loops, n_uses;
    int32_t n_shells, n_face_refs, n_solids, n_solid_shells;
    const tf_vertex *vertices;
    const tf_edge *edges;
    const tf_face *faces;
    const tf_loop *loops;
    const tf_edge_use *uses;
    const tf_shell *shells;
    const tf_face_ref *face_refs;
    const tf_solid *solids;
    const int32_t *solid_shells;
} tf_topology;

/* ---- far fields ----------------------------------------------------------------------- */

#define TF_FARFIELD_BOX 0
#define TF_FARFIELD_SPHERE 1

/* A flow domain around a body: the far-field solid (a box about centre with half extents
   half[], or a sphere of radius half[0]); for a half model, only the side symmetry_side (+1 or
   -1) of the plane coordinate[symmetry_axis] = symmetry_at (symmetry_axis -1: the whole
   solid); the body's solids cut out, gaps up to fuzzy taken as contact. */
typedef struct tf_farfield {
    int32_t shape; /* TF_FARFIELD_* */
    int32_t symmetry_axis;
    int32_t symmetry_side;
    uint32_t reserved;
    double centre[3];
    double half[3];
    double symmetry_at;
    double fuzzy;
} tf_farfield;

/* ---- the table ------------------------------------------------------------------------ */

/* Every call to this plugin must be made one at a time (a kernel that is not thread-safe). */
#define TF_PLUGIN_SERIAL 1u

typedef struct tf_plugin {
    uint32_t abi_version; /* TF_GEOMETRY_ABI_VERSION */
    uint32_t struct_size; /* sizeof(tf_plugin) as the plugin was built */
    const char *name;     /* short, e.g. "occt", "analytic" */
    const char *version;  /* the plugin's own version, free text */
    /* File extensions claimed, lower case without the dot, NULL-terminated. */
    const char *const *extensions;
    uint32_t flags; /* TF_PLUGIN_* */
    uint32_t reserved;

    /* -- required ------------------------------------------------------------------------ */

    tf_status (*open_file)(const char *path, tf_model **model, tf_error *err);
    void (*close)(tf_model *model);
    tf_status (*topology)(const tf_model *model, tf_topology *out, tf_error *err);

    /* n points at once: out[9k..9k+9] = C, C', C'' at t[k]. */
    tf_status (*curve_derivs)(const tf_model *model, int32_t edge, size_t n, const double *t,
                              double *out, tf_error *err);
    /* out[6k..6k+6] = c, c', c'' in (u,v) at t[k] (the edge's parameter). */
    tf_status (*pcurve_derivs)(const tf_model *model, int32_t use, size_t n, const double *t,
                               double *out, tf_error *err);
    /* uv[2k..2k+2] in, out[18k..18k+18] = S, Su, Sv, Suu, Suv, Svv. */
    tf_status (*surface_derivs)(const tf_model *model, int32_t face, size_t n, const double *uv,
                                double *out, tf_error *err);

    /* -- optional (NULL: tetrafoil's own default) ------------------------------------------ */

    /* Open from memory; extension says the format ("step"). */
    tf_status (*open_buffer)(const void *data, size_t len, const char *extension,
                             tf_model **model, tf_error *err);
    /* Points only: out[3k..3k+3]. Default: the derivs functions. */
    tf_status (*curve_points)(const tf_model *model, int32_t edge, size_t n, const double *t,
                              double *out, tf_error *err);
    tf_status (*surface_points)(const tf_model *model, int32_t face, size_t n, const double *uv,
                                double *out, tf_error *err);
    /* The parameter of the curve's point closest to p, within the edge's t_range; hint (a
       nearby t) may be NULL. Default: Newton iteration on curve_derivs. */
    tf_status (*curve_closest)(const tf_model *model, int32_t edge, const double *p,
                               const double *hint, double *t, tf_error *err);
    /* The (u,v) of the surface's point closest to p; hint may be NULL. Non-periodic
       directions within the face's range, periodic ones near the hint (tetrafoil folds them
       into the range). Default: Newton. */
    tf_status (*surface_closest)(const tf_model *model, int32_t face, const double *p,
                                 const double *hint, double *uv, tf_error *err);
    /* Points where the surface meets the circle (centre, unit axis, unit x_axis square to it,
       radius), at most max_hits, each hits[6k..6k+6] = theta (from x_axis towards
       axis x x_axis), u, v, x, y, z; *n_hits is how many. Default: Newton from tetrafoil's
       hint. */
    tf_status (*surface_circle)(const tf_model *model, int32_t face, const double *centre,
                                const double *axis, const double *x_axis, double radius,
                                size_t max_hits, double *hits, size_t *n_hits, tf_error *err);
    /* Healing: a new model with faces sewn into shells and solids at tolerance. tetrafoil
       calls it on a model that has faces but no solid; the result is closed separately. */
    tf_status (*sew)(const tf_model *model, double tolerance, tf_model **out, tf_error *err);
    /* Booleans: a new model whose touching solids share their contact faces. */
    tf_status (*fuse)(const tf_model *model, double tolerance, tf_model **out, tf_error *err);
    /* The model's bounding box, out[0..3] the low corner, out[3..6] the high one (the default
       spacing is 1/20 of its diagonal). Default: the vertices and a grid on each face. */
    tf_status (*bounding_box)(const tf_model *model, double *out, tf_error *err);
    /* Healing: a new model with the kernel's repairs (gaps in wires, small edges, tolerances)
       at tolerance; tetrafoil sews the result once more when sewing alone closed no solid. */
    tf_status (*heal)(const tf_model *model, double tolerance, tf_model **out, tf_error *err);
    /* Booleans: a new model, the flow domain of spec around this model's solids, as one
       solid whose faces are named "farfield" (the outer solid's), "symmetry" (on the plane) or
       as the body's were ("body" for a face without a name). */
    tf_status (*farfield)(const tf_model *model, const tf_farfield *spec, tf_model **out,
                          tf_error *err);
    /* Healing: a new model holding only the solids, the faces in no solid's shells (open
       construction shells beside a solid) left out. tetrafoil calls it when a model has solids
       and faces outside them; without it, those faces are meshed too. */
    tf_status (*solids_only)(const tf_model *model, tf_model **out, tf_error *err);
} tf_plugin;

/* The one symbol a plugin exports. */
typedef const tf_plugin *(*tf_entry_point)(void);

#ifdef __cplusplus
}
#endif

#endif /* TETRAFOIL_GEOMETRY_H */

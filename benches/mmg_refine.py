#!/usr/bin/env python3
"""MMG3D 5.8 (through mmgpy) as the peer of tetrafoil's directional refinement: it remeshes an
isotropic tet mesh to the anisotropic metric of the same layer distribution.

At each vertex, with d its distance to the wall and n the unit vector from the nearest wall
point to it (the area-weighted wall normal at wall nodes),
    M = n nᵀ / h_n² + (I − n nᵀ) / h_t²,
h_t = δ the local isotropic spacing of the input (mean length of the vertex's edges; a global δ
would refine the far field as well), h_n = the spacing of the 1-D distribution at d (first for
the `constant` layers, then × growth), up to δ: the isotropic I/δ² where it reaches the local δ
(as tetrafoil's layers stop there) or --size (the distribution's largest spacing), past which
nothing is refined.

MMG remeshes the wall too (--wall free, the default), within its default Hausdorff distance
(0.01), which on the wing keeps the isotropic wall spacing. Freezing it instead (--wall
required: required triangles, with nosizreq so MMG keeps the metric at their vertices rather
than an isotropic size from their edges, as `nosurf` alone does, MMG issue #178) makes MMG 5.8
churn for minutes even on a 10k-tet cube at aspect 10. opnbdy keeps the embedded (wake)
triangles. Only the remesh call is timed (MMG is serial).

Usage: mmg_refine.py ISO.mesh --wall-names a,b | --wall-ref 9,10  --first F --growth G
                     --constant C --size DELTA -o OUT.mesh
Prints one JSON line: seconds, tets, vertices, options.
"""
import argparse
import json
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scripts"))
import refine_stats as rs  # noqa: E402


def read_medit(path):
    import meshio

    m = meshio.read(path)
    get = lambda kind: np.concatenate([c.data for c in m.cells if c.type == kind])  # noqa: E731
    ref = lambda kind: np.concatenate(  # noqa: E731
        [r for c, r in zip(m.cells, m.cell_data["medit:ref"]) if c.type == kind]
    )
    return m.points[:, :3].astype(float), get("tetra"), ref("tetra"), get("triangle"), ref("triangle")


def local_size(points, tets):
    """Mean length of each vertex's edges: the spacing the isotropic mesh has there."""
    e = np.unique(np.sort(rs.tet_edges(tets), axis=1), axis=0)
    ln = np.linalg.norm(points[e[:, 0]] - points[e[:, 1]], axis=1)
    total, count = np.zeros(len(points)), np.zeros(len(points))
    for k in (0, 1):
        np.add.at(total, e[:, k], ln)
        np.add.at(count, e[:, k], 1)
    return total / np.maximum(count, 1)


def wall_metric(points, tets, wall_tri, first, growth, constant, size):
    """Per-vertex metric (xx, xy, xz, yy, yz, zz) of the layers away from the wall triangles."""
    wall = rs.Wall(points[wall_tri])
    d, q = wall.nearest(points)
    n = points - q
    on_wall = np.zeros(len(points), bool)
    on_wall[wall_tri.ravel()] = True
    # the area-weighted normal where the direction to the nearest point is undefined
    a, b, c = (points[wall_tri[:, k]] for k in range(3))
    fn = np.cross(b - a, c - a)  # length = twice the area
    vn = np.zeros_like(points)
    for k in range(3):
        np.add.at(vn, wall_tri[:, k], fn)
    n[on_wall] = vn[on_wall]
    norm = np.linalg.norm(n, axis=1)
    n /= np.where(norm > 0, norm, 1.0)[:, None]
    delta = local_size(points, tets)
    h_n = rs.spacing_at(np.where(on_wall, 0.0, d), first, growth, constant, size)
    # past the layers (spacing reaching the cap) nothing is refined: the isotropic input size
    h_n = np.minimum(np.where(h_n >= size, np.inf, h_n), delta)
    h_n[norm == 0] = delta[norm == 0]  # no direction (e.g. normals cancelling at a sharp edge): isotropic
    lam_n, lam_t = 1.0 / h_n**2, 1.0 / delta**2
    m = (lam_n - lam_t)[:, None, None] * n[:, :, None] * n[:, None, :] + lam_t[:, None, None] * np.eye(3)
    return m[:, [0, 0, 0, 1, 1, 2], [0, 1, 2, 1, 2, 2]], delta


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh")
    ap.add_argument("--wall-ref")
    ap.add_argument("--wall-names")
    ap.add_argument("--first", type=float, required=True)
    ap.add_argument("--growth", type=float, required=True)
    ap.add_argument("--constant", type=int, default=1)
    ap.add_argument("--size", type=float, required=True, help="the distribution's largest spacing")
    ap.add_argument("--wall", choices=("free", "required", "nosurf"), default="free",
                    help="free: MMG remeshes the wall too, within its default hausd (the default); "
                    "required: the wall triangles are frozen, with nosizreq; nosurf: MMG's nosurf alone")
    ap.add_argument("--mmg", default="", help="extra MMG options, e.g. hgrad=1.3,hausd=0.001")
    ap.add_argument("-v", "--verbose", type=int, default=-1)
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()

    from mmgpy._mmgpy import MmgMesh3D

    points, tets, tet_ref, tri, tri_ref = read_medit(a.mesh)
    refs = [int(r) for r in a.wall_ref.split(",")] if a.wall_ref else rs.refs_of_names(a.mesh, a.wall_names.split(","))
    is_wall = np.isin(tri_ref, refs)
    metric, delta = wall_metric(points, tets, tri[is_wall], a.first, a.growth, a.constant, a.size)

    mesh = MmgMesh3D()
    mesh.set_mesh_size(vertices=len(points), tetrahedra=len(tets), triangles=len(tri))
    mesh.set_vertices(points)
    mesh.set_tetrahedra(tets.astype(np.int32), tet_ref.astype(np.int64))
    mesh.set_triangles(tri.astype(np.int32), tri_ref.astype(np.int64))
    # Sizes from the metric alone: hmin/hmax only keep MMG's own bounds from clipping it, and
    # hgrad=-1 leaves the distribution's growth as it is (MMG's gradation refines the wall far
    # below δ from the ridges on, e.g. 218 -> 1819 triangles on a cube face).
    opts = dict(hmin=0.5 * a.first, hmax=2.0 * float(delta.max()), hgrad=-1, opnbdy=1, verbose=a.verbose)
    if a.wall == "required":
        # frozen wall; nosizreq/hgradreq keep the metric at its vertices. Very slow: MMG churns
        # (collapses as many points as it splits) and its cost explodes with the aspect ratio.
        mesh.set_required_triangles(np.flatnonzero(is_wall).astype(np.int32))
        opts.update(nosizreq=1, hgradreq=-1)
    elif a.wall == "nosurf":
        opts["nosurf"] = 1
    for kv in filter(None, a.mmg.split(",")):
        k, v = kv.split("=")
        opts[k] = float(v) if "." in v or "e" in v else int(v)
    mesh.set_field("tensor", np.ascontiguousarray(metric))

    start = time.perf_counter()
    mesh.remesh(**opts)
    seconds = time.perf_counter() - start

    # written by meshio: MMG's own writer adds sections (RequiredTriangles, Ridges…) that
    # meshio's MEDIT reader, hence refine_stats.py, cannot read
    import meshio

    pts = mesh.get_vertices()
    out, out_ref = mesh.get_tetrahedra_with_refs()
    ot, ot_ref = mesh.get_triangles_with_refs()
    meshio.write(a.output, meshio.Mesh(pts, [("triangle", ot), ("tetra", out)],
                                       cell_data={"medit:ref": [np.asarray(ot_ref), np.asarray(out_ref)]}))
    print(json.dumps({"seconds": seconds, "tets": int(len(out)), "vertices": int(len(pts)),
                      "input_tets": int(len(tets)), "options": opts}))


if __name__ == "__main__":
    main()

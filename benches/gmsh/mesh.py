"""Mesh one CAD file with Gmsh (OCC kernel, one thread, size h and 12 elements per 2π of
curvature, as tetrafoil's CAD defaults) and print a JSON line:
seconds for the meshing calls (1-D, 2-D and, unless --surface, 3-D with Gmsh's default
optimisation), element counts, and the same quality measures tetrafoil reports (minimum and
maximum dihedral angle, mean radius ratio 3·r_in/r_circ), computed here with numpy.

With --sew, a file that has no solid is read again with its faces sewn and solids made from
the closed shells (`Geometry.OCCSewFaces`, `Geometry.OCCMakeSolids`), as a user of a
surface-only file would (sewing a file that has solids can break them).

Usage: python3 mesh.py FILE.step H|auto [CURVATURE_SEGMENTS] [--surface] [--sew]
(auto: 1/20 of the model's bounding-box diagonal, tetrafoil's default size)
"""
import json
import sys
import time

import gmsh
import numpy as np


def tet_quality(xyz, tets):
    p = [xyz[tets[:, i]] for i in range(4)]
    pairs = [(0, 1, 2, 3), (0, 2, 1, 3), (0, 3, 1, 2), (1, 2, 0, 3), (1, 3, 0, 2), (2, 3, 0, 1)]
    dmin = np.full(len(tets), np.inf)
    dmax = np.zeros(len(tets))
    for i, j, k, l in pairs:
        e = p[j] - p[i]
        n1 = np.cross(e, p[k] - p[i])
        n2 = np.cross(e, p[l] - p[i])
        c = np.einsum("ij,ij->i", n1, n2) / (
            np.linalg.norm(n1, axis=1) * np.linalg.norm(n2, axis=1)
        )
        ang = np.degrees(np.arccos(np.clip(c, -1.0, 1.0)))
        dmin = np.minimum(dmin, ang)
        dmax = np.maximum(dmax, ang)
    a, b, c = p[1] - p[0], p[2] - p[0], p[3] - p[0]
    vol6 = np.abs(np.einsum("ij,ij->i", a, np.cross(b, c)))

    def area(u, v, w):
        return 0.5 * np.linalg.norm(np.cross(v - u, w - u), axis=1)

    s = area(p[0], p[1], p[2]) + area(p[0], p[1], p[3]) + area(p[0], p[2], p[3]) + area(p[1], p[2], p[3])
    r_in = 0.5 * vol6 / s
    num = (
        (a * a).sum(1)[:, None] * np.cross(b, c)
        + (b * b).sum(1)[:, None] * np.cross(c, a)
        + (c * c).sum(1)[:, None] * np.cross(a, b)
    )
    r_circ = np.linalg.norm(num, axis=1) / (2.0 * vol6)
    rr = 3.0 * r_in / r_circ
    edges = sum(
        np.linalg.norm(p[j] - p[i], axis=1) for i in range(4) for j in range(i + 1, 4)
    ) / 6.0
    return {
        "mean_edge": float(edges.mean()),
        "min_dihedral": float(dmin.min()),
        "max_dihedral": float(dmax.max()),
        "mean_radius_ratio": float(rr.mean()),
        "volume": float(vol6.sum() / 6.0),
    }


def main():
    path, h = sys.argv[1], sys.argv[2]
    surface = "--surface" in sys.argv
    sew = "--sew" in sys.argv
    curvature = float(sys.argv[3]) if len(sys.argv) > 3 and not sys.argv[3].startswith("--") else 12
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    gmsh.option.setNumber("General.NumThreads", 1)
    gmsh.option.setNumber("Mesh.MaxNumThreads1D", 1)
    gmsh.option.setNumber("Mesh.MaxNumThreads2D", 1)
    gmsh.option.setNumber("Mesh.MaxNumThreads3D", 1)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)
    gmsh.option.setNumber("Mesh.MeshSizeFromPoints", 0)
    # The curvature limit δ ≤ 2πR/N (tetrafoil's CAD default N = 12; 0 = off).
    gmsh.option.setNumber("Mesh.MeshSizeFromCurvature", curvature)
    t0 = time.perf_counter()
    gmsh.open(path)
    if sew and not gmsh.model.getEntities(3):
        gmsh.clear()
        gmsh.option.setNumber("Geometry.OCCSewFaces", 1)
        gmsh.option.setNumber("Geometry.OCCMakeSolids", 1)
        gmsh.open(path)
    if h == "auto":  # 1/20 of the bounding-box diagonal, tetrafoil's default
        b = gmsh.model.getBoundingBox(-1, -1)
        h = ((b[3] - b[0]) ** 2 + (b[4] - b[1]) ** 2 + (b[5] - b[2]) ** 2) ** 0.5 / 20
    h = float(h)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h)
    t1 = time.perf_counter()
    out = {"file": path, "size": h, "load_seconds": t1 - t0}
    try:
        gmsh.model.mesh.generate(2 if surface else 3)
        out["seconds"] = time.perf_counter() - t1
        tags, coords, _ = gmsh.model.mesh.getNodes()
        xyz = np.zeros((int(tags.max()) + 1, 3))
        xyz[tags.astype(int)] = coords.reshape(-1, 3)
        _, tri = gmsh.model.mesh.getElementsByType(2)
        out["triangles"] = len(tri) // 3
        if not surface:
            _, tet = gmsh.model.mesh.getElementsByType(4)
            tets = tet.astype(int).reshape(-1, 4)
            out["tets"] = len(tets)
            if len(tets) == 0:
                out["error"] = "no tets (Gmsh found no volume in the model)"
            else:
                out.update(tet_quality(xyz, tets))
    except Exception as e:  # Gmsh raises on meshing failures
        out["error"] = str(e)
        out["seconds"] = time.perf_counter() - t1
    gmsh.finalize()
    print(json.dumps(out))


if __name__ == "__main__":
    main()

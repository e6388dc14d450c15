#!/usr/bin/env python3
"""Near-wall statistics of a tetrahedral mesh, for comparing directional refinement between
meshers (benches/refine-peers.sh): tets, stretched tets (centroid within --thickness of the
wall), their largest dihedral angles, and the first-layer height at the wall nodes over the
requested first spacing. Prints one JSON object.

The wall is given as triangles of the mesh itself (--wall-ref: MEDIT triangle refs;
--wall-names: names from the `# triangle ref N: name` comments tetrafoil's MEDIT writer puts in
the header) or as an ASCII STL (--wall-stl, optionally only some solids with --wall-names).

Usage: refine_stats.py MESH (--wall-ref 9,10 | --wall-names a,b | --wall-stl W.stl)
                       --thickness T --first F
       refine_stats.py --self-test
"""
import argparse
import json
import re
import sys

import numpy as np

# ---------------------------------------------------------------- reading


def read_volume(path):
    """points (n,3), tets (m,4), triangles (k,3), triangle refs (k,) of any meshio file."""
    import meshio

    m = meshio.read(path)
    tets = [c.data for c in m.cells if c.type == "tetra"]
    tris = [(i, c.data) for i, c in enumerate(m.cells) if c.type == "triangle"]
    refs = []
    for i, t in tris:
        # MEDIT refs, else Gmsh physical tags; 0 when the file names none
        arr = None
        for key in ("medit:ref", "gmsh:physical"):
            if key in m.cell_data:
                arr = m.cell_data[key][i]
                break
        refs.append(np.zeros(len(t), int) if arr is None else np.asarray(arr, int))
    tri = np.concatenate([t for _, t in tris]) if tris else np.zeros((0, 3), int)
    ref = np.concatenate(refs) if refs else np.zeros(0, int)
    return np.asarray(m.points[:, :3], float), np.concatenate(tets).astype(np.int64), tri, ref


def medit_ref_names(path):
    """{name: ref} from the `# triangle ref N: name` header comments of tetrafoil's MEDIT files."""
    out = {}
    with open(path) as f:
        for line in f:
            if not line.startswith("#") and line.strip() and not line.startswith(("MeshVersion", "Dimension")):
                break  # the comments are all before the first section
            g = re.match(r"# triangle ref (\d+): (.*)$", line.rstrip("\n"))
            if g:
                out.setdefault(g.group(2), []).append(int(g.group(1)))
    return out


def refs_of_names(path, names):
    known = medit_ref_names(path)
    missing = [n for n in names if n not in known]
    if missing:
        sys.exit(f"{path}: no triangle ref named {', '.join(missing)} (has {', '.join(known)})")
    return sorted(r for n in names for r in known[n])


def read_stl(path, solids=None):
    """Triangles (k,3,3) of an ASCII STL, only of the named solids when `solids` is given."""
    out, keep = [], True
    with open(path) as f:
        for line in f:
            w = line.split()
            if not w:
                continue
            if w[0] == "solid":
                keep = solids is None or (len(w) > 1 and w[1] in solids)
            elif w[0] == "vertex" and keep:
                out.append([float(x) for x in w[1:4]])
    if len(out) == 0 or len(out) % 3:
        sys.exit(f"{path}: no triangles (or not ASCII STL) for solids {solids}")
    return np.array(out).reshape(-1, 3, 3)


# ---------------------------------------------------------------- geometry


def _dot(a, b):
    return np.einsum("...i,...i->...", a, b)


def _closest_on_segment(p, a, b):
    ab = b - a
    ll = _dot(ab, ab)
    t = np.clip(_dot(p - a, ab) / np.where(ll > 0, ll, 1.0), 0.0, 1.0)
    return a + t[..., None] * ab


def closest_on_triangles(p, a, b, c):
    """Closest points on triangles (a,b,c) to points p (broadcast): the plane projection when it
    falls inside, else the nearest of the three edges (exact for any triangle)."""
    v0, v1, v2 = b - a, c - a, p - a
    d00, d01, d11 = _dot(v0, v0), _dot(v0, v1), _dot(v1, v1)
    d20, d21 = _dot(v2, v0), _dot(v2, v1)
    den = d00 * d11 - d01 * d01
    ok = den > 1e-300
    den = np.where(ok, den, 1.0)
    beta = (d11 * d20 - d01 * d21) / den
    gamma = (d00 * d21 - d01 * d20) / den
    inside = ok & (beta >= 0) & (gamma >= 0) & (beta + gamma <= 1)
    best = a + beta[..., None] * v0 + gamma[..., None] * v1
    edges = [_closest_on_segment(p, a, b), _closest_on_segment(p, b, c), _closest_on_segment(p, c, a)]
    dist = [_dot(p - q, p - q) for q in edges]
    k = np.argmin(np.stack(dist), axis=0)
    on_edge = np.choose(k[..., None], edges)  # k broadcasts over xyz
    return np.where(inside[..., None], best, on_edge)


class Wall:
    """Exact distance to a triangle set: the k triangles with the nearest centroids are
    candidates (a KD-tree from scipy, else a brute-force search), the exact point-triangle
    distance picks among them."""

    def __init__(self, tri_xyz, k=16):
        self.t = np.asarray(tri_xyz, float)
        self.cent = self.t.mean(axis=1)
        self.k = min(k, len(self.t))
        try:
            from scipy.spatial import cKDTree

            self.tree = cKDTree(self.cent)
        except ImportError:
            self.tree = None

    def _candidates(self, p):
        if self.tree is not None:
            _, idx = self.tree.query(p, k=self.k)
            return idx.reshape(len(p), self.k)
        d = ((p[:, None, :] - self.cent[None, :, :]) ** 2).sum(-1)
        return np.argpartition(d, self.k - 1, axis=1)[:, : self.k]

    def nearest(self, p, cap=None, chunk=None):
        """Distance and closest wall point of each point; with `cap`, points surely farther than
        cap (nearest centroid farther than cap + the largest centroid-corner distance) get
        inf and nan instead, which saves the exact search for most of a volume mesh."""
        p = np.asarray(p, float)
        dist, q = np.full(len(p), np.inf), np.full((len(p), 3), np.nan)
        todo = np.arange(len(p))
        if cap is not None and self.tree is not None:
            radius = np.sqrt(((self.t - self.cent[:, None, :]) ** 2).sum(-1)).max()
            todo = todo[self.tree.query(p, k=1)[0] < cap + radius]
        chunk = chunk or (50000 if self.tree is not None else max(1, 2_000_000 // len(self.t)))
        for s in range(0, len(todo), chunk):
            pp = p[todo[s : s + chunk]]
            idx = self._candidates(pp)
            tri = self.t[idx]  # (n,k,3,3)
            cq = closest_on_triangles(pp[:, None, :], tri[..., 0, :], tri[..., 1, :], tri[..., 2, :])
            d2 = ((cq - pp[:, None, :]) ** 2).sum(-1)
            j = np.argmin(d2, axis=1)
            r = np.arange(len(pp))
            dist[todo[s : s + chunk]] = np.sqrt(d2[r, j])
            q[todo[s : s + chunk]] = cq[r, j]
        return dist, q


def max_dihedral(p4):
    """Largest interior dihedral angle (degrees) of each tet, corners p4 (n,4,3)."""
    faces = ((1, 2, 3), (0, 2, 3), (0, 1, 3), (0, 1, 2))  # face i is opposite corner i
    normals = []
    for i, (a, b, c) in enumerate(faces):
        n = np.cross(p4[:, b] - p4[:, a], p4[:, c] - p4[:, a])
        # outward: away from the opposite corner, whatever the tet's orientation
        n *= np.where(_dot(n, p4[:, a] - p4[:, i]) < 0, -1.0, 1.0)[:, None]
        normals.append(n / np.maximum(np.linalg.norm(n, axis=1), 1e-300)[:, None])
    out = np.zeros(len(p4))
    for f in range(4):
        for g in range(f + 1, 4):
            cos = np.clip(_dot(normals[f], normals[g]), -1.0, 1.0)
            out = np.maximum(out, 180.0 - np.degrees(np.arccos(cos)))
    return out


def tet_edges(tets):
    pairs = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]
    return np.concatenate([tets[:, [i, j]] for i, j in pairs])


# ---------------------------------------------------------------- the distribution


def layer_spacing(k, first, growth, constant):
    """Spacing of layer k: `constant` layers of `first`, then geometric growth (as tetrafoil's
    refine::Distribution)."""
    return first * growth ** np.maximum(np.asarray(k) + 1 - max(constant, 1), 0)


def sites(first, growth, constant, delta, limit=4000):
    """Distances 0 = φ0 < φ1 < … of the layers whose spacing is below `delta`."""
    phi, out = 0.0, [0.0]
    for k in range(limit):
        s = float(layer_spacing(k, first, growth, constant))
        if s >= delta:
            break
        phi += s
        out.append(phi)
    return np.array(out)


def spacing_at(d, first, growth, constant, delta):
    """Spacing asked for at distance d: that of the layer holding d (≥ delta past the last)."""
    s = sites(first, growth, constant, delta)
    k = np.searchsorted(s, d, side="right") - 1
    return layer_spacing(np.maximum(k, 0), first, growth, constant)


def thickness(first, growth, constant, delta):
    """Distance at which the distribution reaches delta."""
    return float(sites(first, growth, constant, delta)[-1])


# ---------------------------------------------------------------- the statistics


def pct(x, qs):
    if len(x) == 0:
        return {name: None for name in qs}
    return {name: float(np.percentile(x, q)) for name, q in qs.items()}


def stats(points, tets, wall_tri_xyz, wall_nodes, thick, first):
    """The JSON-ready statistics; wall_nodes is a boolean mask over the points."""
    wall = Wall(wall_tri_xyz)
    dcent, _ = wall.nearest(points[tets].mean(axis=1), cap=thick)
    near = dcent < thick
    dih = max_dihedral(points[tets[near]])
    # first layer: per wall node, the nearest (to the wall) non-wall node one tet edge away
    e = tet_edges(tets)
    e = e[wall_nodes[e[:, 0]] != wall_nodes[e[:, 1]]]
    w = np.where(wall_nodes[e[:, 0]], e[:, 0], e[:, 1])
    v = np.where(wall_nodes[e[:, 0]], e[:, 1], e[:, 0])
    uv, inv = np.unique(v, return_inverse=True)
    dv, _ = wall.nearest(points[uv])
    h = np.full(len(points), np.inf)
    np.minimum.at(h, w, dv[inv])
    h = h[wall_nodes & np.isfinite(h)] / first
    return {
        "tets": int(len(tets)),
        "wall_triangles": int(len(wall_tri_xyz)),
        "thickness": thick,
        "stretched": int(near.sum()),
        "max_dihedral": pct(dih, {"p50": 50, "p90": 90, "p99": 99, "max": 100}),
        "first_layer": {**pct(h, {"median": 50, "p10": 10, "p90": 90}), "nodes": int(len(h))},
    }


def stats_of_file(path, thick, first, wall_ref=None, wall_names=None, wall_stl=None):
    points, tets, tri, ref = read_volume(path)
    if wall_stl:
        txyz = read_stl(wall_stl, wall_names)
        # mesh nodes lying on the wall (to round-off of the bounding box)
        tol = 1e-9 * np.linalg.norm(points.max(0) - points.min(0))
        wall_nodes = Wall(txyz).nearest(points, cap=tol)[0] <= tol
    else:
        refs = wall_ref if wall_ref else refs_of_names(path, wall_names)
        t = tri[np.isin(ref, refs)]
        if len(t) == 0:
            sys.exit(f"{path}: no triangles with refs {refs}")
        txyz = points[t]
        wall_nodes = np.zeros(len(points), bool)
        wall_nodes[t.ravel()] = True
    return stats(points, tets, txyz, wall_nodes, thick, first)


# ---------------------------------------------------------------- self-test


def layered_mesh(n=10, first=0.01, layers=5):
    """A unit square wall at z=0 (n×n squares, 2 right triangles each) under `layers` layers of
    spacing `first`, each prism split into 3 tets. Each triangle's corners are ordered
    45°-corner, right-angle corner, 45°-corner (key j−i does it for both triangles of a square),
    and every prism is split by diagonals from its lowest corner: then each of the 3 tets is
    trirectangular or has its right dihedral angles on the base and vertical faces, so the
    largest dihedral angle is exactly 90°. The key orders the two ends of a shared edge the
    same way in both prisms, so the diagonals match and the mesh is conforming."""
    i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1), indexing="ij")
    node = lambda a, b: a * (n + 1) + b  # noqa: E731
    key = (j - i).ravel()
    tris = []
    for a in range(n):
        for b in range(n):
            p00, p10, p01, p11 = node(a, b), node(a + 1, b), node(a, b + 1), node(a + 1, b + 1)
            tris += [(p00, p10, p01), (p11, p01, p10)]
    tris = np.array(tris)
    tris = np.take_along_axis(tris, np.argsort(key[tris], axis=1), axis=1)
    base = np.c_[i.ravel(), j.ravel()] / n
    nb = len(base)
    points = np.concatenate([np.c_[base, np.full(nb, first * k)] for k in range(layers + 1)])
    tets = []
    for k in range(layers):
        lo, hi = tris + k * nb, tris + (k + 1) * nb
        a0, b0, c0, a1, b1, c1 = lo[:, 0], lo[:, 1], lo[:, 2], hi[:, 0], hi[:, 1], hi[:, 2]
        tets += [np.c_[a0, b0, c0, c1], np.c_[a0, b0, b1, c1], np.c_[a0, a1, b1, c1]]
    return points, np.concatenate(tets), tris


def self_test():
    import os
    import tempfile

    first, layers = 0.01, 5
    points, tets, tris = layered_mesh(first=first, layers=layers)
    # conformity: every interior face shared by exactly two tets, boundary faces by one
    f = np.sort(np.concatenate([tets[:, [1, 2, 3]], tets[:, [0, 2, 3]], tets[:, [0, 1, 3]], tets[:, [0, 1, 2]]]), 1)
    _, count = np.unique(f, axis=0, return_counts=True)
    assert count.max() == 2, "layered mesh not conforming"
    vol = np.abs(np.einsum("ij,ij->i", np.cross(points[tets[:, 1]] - points[tets[:, 0]], points[tets[:, 2]] - points[tets[:, 0]]), points[tets[:, 3]] - points[tets[:, 0]])).sum() / 6
    assert abs(vol - first * layers) < 1e-12, vol

    # the exact distance against brute force over all triangles, points inside and outside the square
    rng = np.random.default_rng(1)
    q = rng.uniform([-0.5, -0.5, -0.3], [1.5, 1.5, 0.3], (2000, 3))
    txyz = points[tris]
    d, _ = Wall(txyz).nearest(q)
    brute = np.sqrt(((closest_on_triangles(q[:, None], txyz[None, :, 0], txyz[None, :, 1], txyz[None, :, 2]) - q[:, None]) ** 2).sum(-1)).min(1)
    clamp = np.clip(q[:, :2], 0, 1)  # the square's own distance
    exact = np.sqrt(((q[:, :2] - clamp) ** 2).sum(1) + q[:, 2] ** 2)
    assert np.allclose(d, exact, atol=1e-12) and np.allclose(brute, exact, atol=1e-12)
    dc, _ = Wall(txyz).nearest(q, cap=0.1)
    assert np.array_equal(dc < 0.1, exact < 0.1) and np.allclose(dc[dc < 0.1], exact[exact < 0.1], atol=1e-12)

    wall_nodes = np.zeros(len(points), bool)
    wall_nodes[tris.ravel()] = True
    s = stats(points, tets, txyz, wall_nodes, thick=first * layers, first=first)
    _check(s, len(tets))

    # the same through files: a MEDIT mesh with named refs (the top as a second, non-wall ref), and an STL
    import meshio

    top = tris + layers * len(points) // (layers + 1)
    with tempfile.TemporaryDirectory() as tmp:
        mp = os.path.join(tmp, "layers.mesh")
        meshio.write(mp, meshio.Mesh(points, [("triangle", np.r_[tris, top]), ("tetra", tets)],
                                     cell_data={"medit:ref": [np.r_[np.full(len(tris), 1), np.full(len(top), 2)], np.ones(len(tets), int)]}))
        with open(mp) as fh:
            body = fh.read()
        with open(mp, "w") as fh:
            fh.write("MeshVersionFormatted 2\n# triangle ref 1: floor\n# triangle ref 2: lid\n" + body.split("\n", 1)[1])
        _check(stats_of_file(mp, first * layers, first, wall_ref=[1]), len(tets))
        _check(stats_of_file(mp, first * layers, first, wall_names=["floor"]), len(tets))
        sp = os.path.join(tmp, "wall.stl")
        with open(sp, "w") as fh:
            for name, tt in (("floor", tris), ("lid", top)):
                fh.write(f"solid {name}\n")
                for t in points[tt]:
                    fh.write("facet normal 0 0 0\nouter loop\n" + "".join(f"vertex {x:.17e} {y:.17e} {z:.17e}\n" for x, y, z in t) + "endloop\nendfacet\n")
                fh.write(f"endsolid {name}\n")
        _check(stats_of_file(mp, first * layers, first, wall_names=["floor"], wall_stl=sp), len(tets))

    # the distribution as tetrafoil's (refine::distribution's test): 3 layers of 0.01, then ×1.5
    sp = [0.01, 0.01, 0.01, 0.015, 0.0225, 0.03375, 0.050625, 0.0759375]
    assert np.allclose(sites(0.01, 1.5, 3, 0.1), np.r_[0, np.cumsum(sp)])
    assert np.allclose(spacing_at(np.array([0.005, 0.031, 0.2, 0.3]), 0.01, 1.5, 3, 0.1), [0.01, 0.015, 0.0759375, 0.11390625])
    assert abs(thickness(0.01, 1.5, 3, 0.04) - (0.03 + 0.015 + 0.0225 + 0.03375)) < 1e-12
    print("refine_stats self-test: ok")


def _check(s, ntets):
    assert s["tets"] == ntets and s["stretched"] == ntets, s
    fl, md = s["first_layer"], s["max_dihedral"]
    assert all(abs(fl[k] - 1.0) < 1e-9 for k in ("median", "p10", "p90")), fl
    assert abs(md["max"] - 90.0) < 1e-6, md


# ---------------------------------------------------------------- command line


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mesh", nargs="?")
    ap.add_argument("--wall-ref", help="comma-separated MEDIT triangle refs of the wall")
    ap.add_argument("--wall-names", help="comma-separated wall names (MEDIT header comments, or STL solids)")
    ap.add_argument("--wall-stl", help="ASCII STL of the wall triangles")
    ap.add_argument("--thickness", type=float, help="distance from the wall of the stretched region")
    ap.add_argument("--first", type=float, help="requested first-layer spacing")
    ap.add_argument("--self-test", action="store_true")
    a = ap.parse_args()
    if a.self_test:
        self_test()
        return
    if not (a.mesh and a.thickness and a.first and (a.wall_ref or a.wall_names or a.wall_stl)):
        ap.error("MESH, --thickness, --first and one of --wall-ref/--wall-names/--wall-stl are needed")
    refs = [int(r) for r in a.wall_ref.split(",")] if a.wall_ref else None
    names = a.wall_names.split(",") if a.wall_names else None
    print(json.dumps(stats_of_file(a.mesh, a.thickness, a.first, refs, names, a.wall_stl)))


if __name__ == "__main__":
    main()

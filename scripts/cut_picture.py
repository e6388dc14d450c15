#!/usr/bin/env python3
"""Draw a planar cut through a tetrahedral or hybrid mesh as a PNG.

Every cell (tet, prism, pyramid) that the plane crosses is cut in a polygon; the picture draws
all of them as thin black outlines over a light fill (blue for tets, orange for prisms, green
for pyramids), with equal aspect, over a window given by the user -- the usual picture of a
viscous mesh. With --inset a second panel, side by side,
zooms into a smaller window (the leading edge, say) so the thin layers at the wall show.

Usage:
    cut_picture.py MESH.vtu OUT.png --plane y=0.5 --window xmin,xmax,zmin,zmax
                   [--inset xmin,xmax,zmin,zmax] [--title TEXT] [--dpi 150]

The plane is AXIS=VALUE with AXIS one of x, y, z; the window is in the two other axes, in
order (x=: y,z; y=: x,z; z=: x,y). Any mesh meshio reads works; its tets, wedges and pyramids
are drawn.
Needs numpy, meshio and matplotlib. For pictures only: no test depends on it.
"""
import argparse
import sys

import matplotlib
import meshio
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.patches import Rectangle  # noqa: E402

AXES = "xyz"
# The edges of each cell kind (meshio's node order), as pairs of local vertex indices.
EDGES = {
    "tetra": np.array([(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)]),
    "wedge": np.array([(0, 1), (1, 2), (2, 0), (3, 4), (4, 5), (5, 3), (0, 3), (1, 4), (2, 5)]),
    "pyramid": np.array([(0, 1), (1, 2), (2, 3), (3, 0), (0, 4), (1, 4), (2, 4), (3, 4)]),
}
FILL = {"tetra": "#dde6f0", "wedge": "#f6dcb8", "pyramid": "#cfe8cf"}
# A plane cuts a tet in at most 4 points, a prism or a pyramid in at most 5.
SLOTS = 5


def read_cells(path):
    """Points (n, 3) and, per cell kind present, its cells (m, k) of a mesh file."""
    mesh = meshio.read(path)
    cells = {}
    for c in mesh.cells:
        if c.type in EDGES:
            cells.setdefault(c.type, []).append(c.data)
    if not cells:
        raise SystemExit("%s: no tetrahedra, prisms or pyramids" % path)
    cells = {k: np.concatenate(v).astype(np.int64) for k, v in cells.items()}
    return np.asarray(mesh.points, float), cells


def cut_polygons(points, tets, axis, value, edges=EDGES["tetra"]):
    """Cut every cell crossing the plane points[:, axis] == value.

    Returns (m, 5, 2) polygon corners in the plane's two other coordinates, ordered around
    the polygon; a polygon of fewer corners repeats its last one. A vertex on the plane counts
    as being on the positive side, so a cell that only touches the plane is not cut (its
    neighbour is).
    """
    others = [k for k in range(3) if k != axis]
    s = points[:, axis] - value  # signed distance of every vertex
    below = s[tets] < 0  # (m, corners)
    n_below = below.sum(axis=1)
    crossing = (n_below > 0) & (n_below < tets.shape[1])
    t = tets[crossing]
    below = below[crossing]

    # Edge-plane intersections, for all edges at once; `hit` marks the edges that cross.
    a, b = t[:, edges[:, 0]], t[:, edges[:, 1]]  # (m, edges) vertex ids
    hit = below[:, edges[:, 0]] != below[:, edges[:, 1]]
    sa, sb = s[a], s[b]
    with np.errstate(divide="ignore", invalid="ignore"):
        w = np.where(hit, sa / (sa - sb), 0.0)
    pa, pb = points[a][..., others], points[b][..., others]  # (m, edges, 2)
    q = pa + w[..., None] * (pb - pa)

    # Order each polygon's points by angle around their centroid; the edges that do not
    # cross sort last. Then keep SLOTS slots and fill the empty ones with the last point.
    count = hit.sum(axis=1)
    centre = (q * hit[..., None]).sum(axis=1) / count[:, None]
    d = q - centre[:, None, :]
    angle = np.where(hit, np.arctan2(d[..., 1], d[..., 0]), np.inf)
    slots = min(SLOTS, q.shape[1])
    order = np.argsort(angle, axis=1)[:, :slots]
    poly = np.take_along_axis(q, order[..., None], axis=1)
    for k in range(1, slots):
        short = count <= k
        poly[short, k] = poly[short, k - 1]
    return poly


def in_window(poly, window, margin=0.05):
    """Mask of the polygons whose bounding box meets the window grown by margin·size."""
    u0, u1, v0, v1 = window
    du, dv = margin * (u1 - u0), margin * (v1 - v0)
    lo, hi = poly.min(axis=1), poly.max(axis=1)
    return (hi[:, 0] >= u0 - du) & (lo[:, 0] <= u1 + du) & (hi[:, 1] >= v0 - dv) & (lo[:, 1] <= v1 + dv)


def draw(ax, polys, window, linewidth):
    """Draw each kind's polygons in the window on ax; returns how many were drawn."""
    drawn = 0
    for kind, poly in polys.items():
        keep = poly[in_window(poly, window)]
        ax.add_collection(PolyCollection(keep, facecolors=FILL[kind], edgecolors="black",
                                         linewidths=linewidth, antialiased=True))
        drawn += len(keep)
    ax.set_xlim(window[0], window[1])
    ax.set_ylim(window[2], window[3])
    ax.set_aspect("equal")
    ax.set_facecolor("white")
    return drawn


def parse_window(text):
    w = [float(v) for v in text.split(",")]
    if len(w) != 4 or w[0] >= w[1] or w[2] >= w[3]:
        raise argparse.ArgumentTypeError("window must be umin,umax,vmin,vmax: %r" % text)
    return w


def parse_plane(text):
    axis, _, value = text.partition("=")
    if axis.strip() not in AXES or not value:
        raise argparse.ArgumentTypeError("plane must be x=V, y=V or z=V: %r" % text)
    return AXES.index(axis.strip()), float(value)


def join_values(argv):
    """Turn `--window -0.5,2,-1,1` into `--window=-0.5,2,-1,1`: argparse takes a value that
    starts with '-' (and is not a plain number) for an option."""
    out = []
    for arg in argv:
        if out and out[-1] in ("--window", "--inset", "--plane"):
            out[-1] += "=" + arg
        else:
            out.append(arg)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("mesh", help="tetrahedral or hybrid mesh (VTU or anything meshio reads)")
    ap.add_argument("out", help="PNG to write")
    ap.add_argument("--plane", type=parse_plane, required=True, help="cut plane, e.g. y=0.5")
    ap.add_argument("--window", type=parse_window, required=True,
                    help="umin,umax,vmin,vmax in the plane's other two axes")
    ap.add_argument("--inset", type=parse_window, help="second, zoomed window")
    ap.add_argument("--title", help="figure title (default: plane and counts)")
    ap.add_argument("--dpi", type=int, default=150)
    ap.add_argument("--linewidth", type=float, default=0.25, help="outline width in points")
    a = ap.parse_args(join_values(sys.argv[1:]))

    axis, value = a.plane
    u, v = [AXES[k] for k in range(3) if k != axis]
    points, cells = read_cells(a.mesh)
    poly = {k: cut_polygons(points, c, axis, value, EDGES[k]) for k, c in cells.items()}

    windows = [a.window] + ([a.inset] if a.inset else [])
    # Panel widths in proportion to the windows' aspect ratios, so both have the same height.
    ratios = [(w[1] - w[0]) / (w[3] - w[2]) for w in windows]
    height = 5.0
    fig, axes = plt.subplots(1, len(windows), figsize=(height * sum(ratios) + 0.6 * len(windows), height + 0.8),
                             gridspec_kw={"width_ratios": ratios}, squeeze=False)
    for k, (ax, w) in enumerate(zip(axes[0], windows)):
        n = draw(ax, poly, w, a.linewidth)
        ax.set_xlabel(u)
        ax.set_ylabel(v)
        ax.set_title("%s window, %d cut polygons" % ("inset" if k else "whole", n), fontsize=9)
    if a.inset:
        x0, x1, z0, z1 = a.inset
        axes[0][0].add_patch(Rectangle((x0, z0), x1 - x0, z1 - z0, fill=False,
                                       edgecolor="red", linewidth=1.0, zorder=3))
        for spine in axes[0][1].spines.values():
            spine.set_edgecolor("red")
    counts = ", ".join("%d %s" % (len(c), k) for k, c in cells.items())
    fig.suptitle(a.title or "cut %s = %g through %s (%s; %d cut)"
                 % (AXES[axis], value, a.mesh.split("/")[-1], counts,
                    sum(len(p) for p in poly.values())))
    fig.tight_layout()
    fig.savefig(a.out, dpi=a.dpi)


if __name__ == "__main__":
    main()

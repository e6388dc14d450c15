#!/usr/bin/env python3
"""Draw the cut of a tetrafoil volume mesh (.vtu with tets, as tetrafoil writes it) by the
plane y = Y: every tet crossing the plane gives a triangle or quadrilateral in (x, z).

Usage: docs/section.py MESH.vtu OUT.png [--y 0.6] [--window -0.6,2.4,-0.9,0.9]
Needs numpy and matplotlib. Only for pictures: no test depends on it.
"""
import argparse
import re

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402


def array(text, name):
    m = re.search(r'Name="%s"[^>]*>(.*?)</DataArray>' % name, text, re.S)
    return np.array(m.group(1).split(), float) if m else np.array([])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh")
    ap.add_argument("out")
    ap.add_argument("--y", type=float, default=0.6)
    ap.add_argument("--window", default="-0.6,2.4,-0.9,0.9")
    a = ap.parse_args()
    text = open(a.mesh).read()
    pts = np.array(
        re.search(r"<Points>.*?>(.*?)</DataArray>", text, re.S).group(1).split(), float
    ).reshape(-1, 3)
    tets = array(text, "connectivity").astype(int).reshape(-1, 4)
    quality = array(text, "min_dihedral")
    x0, x1, z0, z1 = map(float, a.window.split(","))
    d = pts[:, 1] - a.y
    polys, colours = [], []
    for k, t in enumerate(tets):
        s = d[t]
        if s.min() >= 0 or s.max() <= 0:
            continue
        p = pts[t]
        if p[:, 0].max() < x0 or p[:, 0].min() > x1 or p[:, 2].max() < z0 or p[:, 2].min() > z1:
            continue
        cut = []
        for i in range(4):
            for j in range(i + 1, 4):
                if (s[i] < 0) != (s[j] < 0):
                    w = s[i] / (s[i] - s[j])
                    q = p[i] + w * (p[j] - p[i])
                    cut.append((q[0], q[2]))
        c = np.array(cut)
        centre = c.mean(axis=0)
        order = np.argsort(np.arctan2(c[:, 1] - centre[1], c[:, 0] - centre[0]))
        polys.append(c[order])
        colours.append(quality[k] if len(quality) else 0.0)
    fig, ax = plt.subplots(figsize=(9, 5.4), dpi=110)
    coll = PolyCollection(polys, array=np.array(colours), cmap="viridis", edgecolors="k",
                          linewidths=0.25)
    coll.set_clim(10, 70)
    ax.add_collection(coll)
    ax.set_xlim(x0, x1)
    ax.set_ylim(z0, z1)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("z")
    fig.colorbar(coll, ax=ax, label="smallest dihedral angle of the tet (degrees)", shrink=0.8)
    ax.set_title("cut y = %g through the volume mesh (%d tets in all)" % (a.y, len(tets)))
    fig.tight_layout()
    fig.savefig(a.out)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Render a tetrafoil surface mesh (.vtu as tetrafoil writes it) to a PNG for the docs.

Usage: docs/render.py MESH.vtu OUT.png [--faces 6,7,8] [--elev 25] [--azim -60]
Needs matplotlib (pip install matplotlib). Only for pictures: no test depends on it.
"""
import argparse
import re

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402


def array(text, name):
    m = re.search(r'Name="%s"[^>]*>(.*?)</DataArray>' % name, text, re.S)
    return m.group(1).split() if m else []


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh")
    ap.add_argument("out")
    ap.add_argument("--faces", default="")
    ap.add_argument("--elev", type=float, default=25)
    ap.add_argument("--azim", type=float, default=-60)
    a = ap.parse_args()
    text = open(a.mesh).read()
    pts_block = re.search(r"<Points>.*?>(.*?)</DataArray>", text, re.S).group(1).split()
    pts = [tuple(map(float, pts_block[i : i + 3])) for i in range(0, len(pts_block), 3)]
    conn = list(map(int, array(text, "connectivity")))
    offsets = list(map(int, array(text, "offsets")))
    face = list(map(int, array(text, "face")))
    keep = set(int(f) for f in a.faces.split(",") if f)
    tris, colours, prev = [], [], 0
    palette = ["#9ecae1", "#fdae6b", "#a1d99b", "#bcbddc", "#fc9272", "#d9d9d9"]
    for k, off in enumerate(offsets):
        cell = conn[prev:off]
        prev = off
        if len(cell) != 3 or (keep and face[k] not in keep):
            continue
        tris.append([pts[i] for i in cell])
        colours.append(palette[face[k] % len(palette)])
    fig = plt.figure(figsize=(10, 6), dpi=110)
    ax = fig.add_subplot(projection="3d")
    ax.add_collection3d(Poly3DCollection(tris, facecolors=colours, edgecolors="#333333", linewidths=0.15))
    xs = [p[0] for t in tris for p in t]
    ys = [p[1] for t in tris for p in t]
    zs = [p[2] for t in tris for p in t]
    ax.set_xlim(min(xs), max(xs))
    ax.set_ylim(min(ys), max(ys))
    ax.set_zlim(min(zs), max(zs))
    ax.set_box_aspect((max(xs) - min(xs), max(ys) - min(ys), max(zs) - min(zs)))
    ax.view_init(a.elev, a.azim)
    ax.set_axis_off()
    plt.tight_layout()
    plt.savefig(a.out, bbox_inches="tight")


if __name__ == "__main__":
    main()

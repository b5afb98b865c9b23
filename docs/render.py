#!/usr/bin/env python3
"""Render meshes written by `meshbool` (OBJ) to PNG pictures for the README.

Usage: python3 docs/render.py [--zscale F] [--view ELEV,AZIM] OUT.png TITLE MESH.obj[:COLOR] [MESH.obj[:COLOR] ...]
--zscale F draws heights F times larger (a terrain's relief is small beside its extent);
--view: the camera's elevation and azimuth in degrees (default 30,-55).
Needs numpy and matplotlib: pip install -r docs/requirements.txt. Reads only `v` and `f` lines.
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from mpl_toolkits.mplot3d.art3d import Poly3DCollection


def read_obj(path):
    V, F = [], []
    for line in open(path):
        p = line.split()
        if not p:
            continue
        if p[0] == "v":
            V.append([float(x) for x in p[1:4]])
        elif p[0] == "f":
            F.append([int(x.split("/")[0]) - 1 for x in p[1:4]])
    return np.array(V), np.array(F)


def main():
    args = sys.argv[1:]
    zscale, elev, azim = 1.0, 30.0, -55.0
    while args[:1] in (["--zscale"], ["--view"]):
        if args[0] == "--zscale":
            zscale = float(args[1])
        else:
            elev, azim = (float(x) for x in args[1].split(","))
        args = args[2:]
    out, title, specs = args[0], args[1], args[2:]
    fig = plt.figure(figsize=(6, 5), dpi=110)
    ax = fig.add_subplot(projection="3d")
    light = np.array([0.4, -0.5, 0.8])
    light /= np.linalg.norm(light)
    lo, hi = np.full(3, np.inf), np.full(3, -np.inf)
    # One collection for everything, so that faces of all meshes are depth-sorted together.
    all_tri, all_col = [], []
    for spec in specs:
        path, _, color = spec.partition(":")
        V, F = read_obj(path)
        tri = V[F]
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        n /= np.maximum(np.linalg.norm(n, axis=1, keepdims=True), 1e-300)
        shade = 0.35 + 0.65 * np.abs(n @ light)
        base = np.array(matplotlib.colors.to_rgb(color or "#7a9cc6"))
        all_tri.append(tri)
        all_col.append(np.clip(shade[:, None] * base, 0, 1))
        lo, hi = np.minimum(lo, V.min(0)), np.maximum(hi, V.max(0))
    ax.add_collection3d(Poly3DCollection(
        np.concatenate(all_tri), facecolors=np.concatenate(all_col), edgecolor="none",
        linewidth=0, antialiased=False))
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_zlim(lo[2], hi[2])
    ax.set_box_aspect((hi - lo) * [1, 1, zscale], zoom=1.25)
    ax.view_init(elev=elev, azim=azim)
    ax.set_axis_off()
    ax.set_title(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(out)


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""The soil's height map of a run on a mesh of layers, at each output time, with its obstacles.

Usage: plot_height_map.py RUN [--beyond X] [--png FILE]

RUN is a run of a case on a mesh of layers (3D), which writes column_height_NNNNN.csv at each output
time: x, z and the soil height h = sum c dy of each (x, z) column (and, with obstacles, each
column's blocked height, obstacle_height). Printed per output time: the soil volume sum h dx dz, the
highest column and, with --beyond X, the share of the soil in the columns beyond x = X (what passed
a barrier there); the run-out is the history's (toe_one_cell, toe_contour). With --png, one panel per
output time: h over (x, z) in colour (blank below a thousandth of the highest column), the obstacles
with no soil on them in grey (darker where higher). Volumes take each column's width from the
midpoints between the centres: exact on uniform cells, approximate on graded ones.
"""
import argparse

import numpy as np

from granflow_files import InputError, column_heights, finite, main_with_errors, picture_file, require_columns


def grid_of(table, path):
    """The columns' centres along x and z, and the table's heights as arrays [z, x]."""
    require_columns(table, path, ["x", "z", "height"])
    xs, zs = np.unique(table["x"]), np.unique(table["z"])
    if len(xs) * len(zs) != len(table["height"]) or len(xs) < 2 or len(zs) < 2:
        raise InputError(f"{path}: not one row per (x, z) column of a mesh of layers")
    ix, iz = np.searchsorted(xs, table["x"]), np.searchsorted(zs, table["z"])
    def as_map(values):
        m = np.zeros((len(zs), len(xs)))
        m[iz, ix] = values
        return m
    blocked = as_map(table["obstacle_height"]) if "obstacle_height" in table else np.zeros((len(zs), len(xs)))
    return xs, zs, as_map(table["height"]), blocked


def faces_of(centres):
    """Cell faces from cell centres (uniform or graded), the outer ones mirrored about the end centres."""
    inner = 0.5 * (centres[1:] + centres[:-1])
    return np.concatenate(([2 * centres[0] - inner[0]], inner, [2 * centres[-1] - inner[-1]]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run")
    ap.add_argument("--beyond", type=finite, help="report the share of the soil in the columns beyond this x (m)")
    ap.add_argument("--png", type=picture_file)
    a = ap.parse_args()
    maps = []
    for index, (time, table) in sorted(column_heights(a.run).items()):
        path = f"{a.run}/column_height_{index:05d}.csv"
        xs, zs, h, blocked = grid_of(table, path)
        xf, zf = faces_of(xs), faces_of(zs)
        area = np.outer(np.diff(zf), np.diff(xf))
        volume = (h * area).sum()
        line = f"t = {time:.3g} s: soil volume {volume:.6g} m^3, highest column {h.max():.4f} m"
        if a.beyond is not None:
            share = (h * area)[:, xs > a.beyond].sum() / volume if volume > 0 else float("nan")
            line += f", {100 * share:.2f} % of it beyond x = {a.beyond:g} m"
        print(line)
        maps.append((time, xf, zf, h, blocked))
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        top = max(m[3].max() for m in maps) or 1.0
        fig, axes = plt.subplots(len(maps), 1, figsize=(7.5, 1.2 + 1.6 * len(maps)), squeeze=False, sharex=True)
        for ax, (time, xf, zf, h, blocked) in zip(axes[:, 0], maps):
            # Columns of less than a thousandth of the highest: blank (traces of soil the air carried).
            image = ax.pcolormesh(xf, zf, np.ma.masked_where(h < 1e-3 * top, h), vmin=0.0, vmax=top, cmap="viridis")
            exposed = (blocked > 0.0) & (h < 1e-3 * top)  # obstacles with no soil on them
            if exposed.any():
                ax.pcolormesh(xf, zf, np.ma.masked_where(~exposed, blocked), cmap="Greys", vmin=0.0,
                              vmax=2.0 * blocked.max())
            ax.set_aspect("equal")
            ax.set_ylabel("z (m)")
            ax.set_title(f"t = {time:.3g} s", fontsize=9)
            fig.colorbar(image, ax=ax, label="soil height (m)", shrink=0.8)
        axes[-1, 0].set_xlabel("x (m)")
        fig.tight_layout()
        fig.savefig(a.png, dpi=130)
        print(f"wrote {a.png}")
    return 0


if __name__ == "__main__":
    main_with_errors(main)

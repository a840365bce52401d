#!/usr/bin/python3
"""A granular column collapsing in 3D against its axisymmetric twin on the same cells.

Usage: compare_column_3d.py RUN_3D RUN_AXI [--png FILE]

RUN_3D is a run of a quarter column about the corner of the symmetry planes x = 0 and z = 0 on a
mesh of layers (cases/lube2004_a05_3d.toml), RUN_AXI the same column on an axisymmetric mesh of the
same cells along r and y (scripts/run_column_3d.sh runs both). At each output time both wrote their
column heights h = sum c dy: the 3D run per (x, z) column, the axisymmetric one per radius. Printed per
output time:
- the 3D footprint's radius, sqrt(4 A / pi) of the area A of the columns holding at least one cell of
  soil, against the axisymmetric run-out at one cell (the outer face of its outermost such column);
- the 3D toes along x (the columns next to z = 0) and along z (next to x = 0);
- the heights at the axis, and the RMS and largest difference of the 3D columns' heights from the
  axisymmetric profile at their radius (interpolated), over the 3D columns inside the footprint.
With --png, h against r at each output time: every 3D column as a dot, the axisymmetric profile as a
line.
"""
import argparse
import math
import os

import numpy as np

from granflow_files import InputError, column_heights, main_with_errors, picture_file, require_columns


def compare(time, layered, axi, path3, patha):
    require_columns(layered, path3, ["x", "z", "height"])
    require_columns(axi, patha, ["x", "height", "x_east", "floor_cell_height"])
    x, z, h = layered["x"], layered["z"], layered["height"]
    xs, zs = np.unique(x), np.unique(z)
    if len(xs) * len(zs) != len(h):
        raise InputError(f"{path3}: not one row per (x, z) column")
    dx, dz = (xs[1] - xs[0]) if len(xs) > 1 else 1.0, (zs[1] - zs[0]) if len(zs) > 1 else 1.0
    floor = axi["floor_cell_height"][0]
    soil = h >= floor
    footprint = math.sqrt(4.0 * soil.sum() * dx * dz / math.pi)
    held = axi["height"] >= floor
    axi_toe = axi["x_east"][held].max() if held.any() else 0.0
    along_x = x[(z == zs[0]) & soil]
    along_z = z[(x == xs[0]) & soil]
    toe_x = along_x.max() + 0.5 * dx if along_x.size else 0.0
    toe_z = along_z.max() + 0.5 * dz if along_z.size else 0.0
    r = np.hypot(x, z)
    profile = np.interp(r, axi["x"], axi["height"])
    inside = soil & (r < footprint)
    diff = h[inside] - profile[inside]
    rms = math.sqrt(np.mean(diff ** 2)) if diff.size else float("nan")
    largest = np.abs(diff).max() if diff.size else float("nan")
    axis_3d = h[(x == xs[0]) & (z == zs[0])][0]
    print(f"t = {time:.3g} s: footprint radius {footprint:.4f} m (toe along x {toe_x:.3f}, along z {toe_z:.3f}); "
          f"axisymmetric run-out {axi_toe:.3f} m; height at the axis {axis_3d:.4f} m against {axi['height'][0]:.4f} m; "
          f"heights within the footprint differ by {1e3 * rms:.2f} mm RMS, {1e3 * largest:.2f} mm at most "
          f"({diff.size} columns)")
    return r, h, axi


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run_3d")
    ap.add_argument("run_axi")
    ap.add_argument("--png", type=picture_file)
    a = ap.parse_args()
    layered, axi = column_heights(a.run_3d), column_heights(a.run_axi)
    common = sorted(set(layered) & set(axi))
    if not common:
        raise InputError("the two runs have no output in common")
    drawn = []
    for k in common:
        (t3, c3), (ta, ca) = layered[k], axi[k]
        if abs(t3 - ta) > 1e-9 * max(1.0, t3):
            raise InputError(f"output {k} is at t = {t3} s in {a.run_3d} and t = {ta} s in {a.run_axi}")
        p3 = os.path.join(a.run_3d, f"column_height_{k:05d}.csv")
        pa = os.path.join(a.run_axi, f"column_height_{k:05d}.csv")
        drawn.append((t3,) + compare(t3, c3, ca, p3, pa))
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7.5, 3.6))
        for n, (t, r, h, axi_table) in enumerate(drawn):
            colour = f"C{n}"
            ax.plot(r, h, ".", color=colour, ms=2, alpha=0.35)
            ax.plot(axi_table["x"], axi_table["height"], "-", color=colour, lw=1.4, label=f"t = {t:.3g} s")
        ax.set_xlabel("r (m)")
        ax.set_ylabel("soil height h (m)")
        ax.set_title("3D quarter column (dots: each (x, z) column) and the axisymmetric run (lines)", fontsize=9)
        ax.legend(fontsize=8)
        ax.set_xlim(left=0.0)
        ax.set_ylim(bottom=0.0)
        fig.tight_layout()
        fig.savefig(a.png, dpi=130)
        print(f"wrote {a.png}")
    return 0


if __name__ == "__main__":
    main_with_errors(main)

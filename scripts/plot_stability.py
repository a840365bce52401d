#!/usr/bin/python3
"""The mechanism of a strength-reduction analysis (`granflow stability`): the displacement of the soil
in the trial at the smallest factor that failed, as it was when the trial saw it fail.

Usage: plot_stability.py OUT [--png FILE] [--line CSV]
Prints the bracket (the largest factor that stood, the smallest that failed) from OUT/stability.csv, or
the smallest factor tried where the soil failed in every trial;
with --png draws the displacement magnitude over the soil (cells with c >= 0.5) of that trial's last
fields file, with the soil's surface (c = 0.5) and, dashed, the contacts of the soil materials (where
a material's share of the soil is a half). The trials must have written fields
(output.fields = true). --line draws a reference line over it, red and dashed: a CSV of columns x, y in
the case's coordinates, a row of nan between pieces (validation/refdata/prandtl1920_strip_footing_mechanism.csv).
"""
import argparse
import csv
import glob
import os

import numpy as np

from granflow_files import InputError, figure_size, main_with_errors, picture_file, read_csv, read_vtr


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--png", type=picture_file)
    ap.add_argument("--line", help="a reference line to draw: CSV of x, y")
    a = ap.parse_args()
    line = read_csv(a.line) if a.line else None
    if line is not None and not ("x" in line and "y" in line and len(line["x"])):
        raise InputError(f"{a.line}: no rows of columns x, y")
    path = os.path.join(a.out, "stability.csv")
    try:
        with open(path) as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        raise InputError(f"cannot read {path}: {e.strerror}")
    try:
        trials = [(float(r["factor"]), r["fails"], r["directory"]) for r in rows]
    except (KeyError, TypeError, ValueError):
        raise InputError(f"{path}: not a table of trials (factor, fails, ..., directory)")
    # A row cut short (a damaged table) must not pass for a trial that stood.
    if not trials:
        raise InputError(f"{path}: no trials (the analysis ended before its first?)")
    if any(f not in ("0", "1") or not d for _, f, d in trials):
        raise InputError(f"{path}: a row without its verdict or directory (the table is damaged)")
    trials = [(factor, fails == "1", d) for factor, fails, d in trials]
    failed = [t for t in trials if t[1]]
    stood = [t for t in trials if not t[1]]
    if not failed:
        raise InputError(f"{path}: the soil stands in every trial: no failure to draw")
    fails_at, _, directory = min(failed)
    if stood:
        stands_at = max(t[0] for t in stood)
        print(f"stands at F = {stands_at:.4f}, fails at F = {fails_at:.4f}: factor of safety "
              f"{0.5 * (stands_at + fails_at):.3f}")
    else:  # no bracket, but the mechanism of the smallest factor tried is still the one to see
        print(f"fails at every factor tried, down to F = {fails_at:.4f}: factor of safety below it")
    if not a.png:
        return 0
    trial = os.path.join(a.out, directory)
    files = sorted(glob.glob(os.path.join(trial, "fields_*.vtr")))
    if not os.path.isdir(trial):
        raise InputError(f"{trial}: the trial's directory is missing")
    if not files:
        raise InputError(f"{trial}: no fields_*.vtr (run the analysis with output.fields = true)")
    x, y, cells = read_vtr(files[-1])
    for name in ("soil_fraction", "displacement"):
        if name not in cells:
            raise InputError(f"{files[-1]}: no field {name}")
    c = cells["soil_fraction"]
    d = np.hypot(cells["displacement"][..., 0], cells["displacement"][..., 1])
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    xc, yc = 0.5 * (x[1:] + x[:-1]), 0.5 * (y[1:] + y[:-1])
    soil = c > 0.5
    top = yc[np.any(soil, axis=1)].max() if soil.any() else y[-1]
    right = xc[np.any(soil, axis=0)].max() if soil.any() else x[-1]
    # The frame shows the soil and a little above and beyond it; the figure takes its proportions.
    y1 = min(y[-1], y[0] + 1.6 * (top - y[0]))
    x1 = min(x[-1], x[0] + 1.2 * (right - x[0]))
    fig, ax = plt.subplots(figsize=figure_size(x1 - x[0], y1 - y[0]))
    shown = np.ma.masked_where(c < 0.5, d)
    m = ax.pcolormesh(x, y, shown, cmap="viridis", shading="flat")
    fig.colorbar(m, ax=ax, label="displacement (m)")
    ax.contour(xc, yc, c, levels=[0.5], colors="k", linewidths=1.0)
    # Soil materials: where each one's share of the soil is a half, dashed.
    for name in sorted(k for k in cells if k.startswith("soil_fraction_")):
        share = np.where(c > 0.5, cells[name] / np.maximum(c, 1e-300), np.nan)
        if np.nanmin(share) < 0.5 < np.nanmax(share):
            ax.contour(xc, yc, share, levels=[0.5], colors="w", linewidths=1.0, linestyles="--")
    if line is not None:
        ax.plot(line["x"], line["y"], "r--", linewidth=1.2)
    ax.set_ylim(y[0], y1)
    ax.set_xlim(x[0], x1)
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    bracket = f"stands at F = {stands_at:.4f}, fails" if stood else "fails at every factor tried, down"
    ax.set_title(f"strength reduction: {bracket} at F = {fails_at:.4f} (displacement at F = {fails_at:.4f})",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(a.png, dpi=120)
    print(f"wrote {a.png}")
    return 0


if __name__ == "__main__":
    main_with_errors(main)

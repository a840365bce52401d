#!/usr/bin/python3
"""Draw a granflow run of a bui2008_sph_* case at the times of the SPH comparison of [VoF] Figs. 4-7.

Usage: compare_bui2008_sph.py RUN_DIR [--png FILE] [--json FILE] [--times 0.8,1.1,1.4,2.5]

No SPH data of Bui et al. (2008) is shipped, so this does not score the run: it draws the soil
surface (c = 0.5) and the failure line (strain norm 0.3) at the paper's times, with the initial block,
for a visual comparison with the paper's figures, and prints per time:
- run-out: the toe of the c = 0.5 contour, and the toe of the soil at least one cell thick (a film
  thinner than a cell runs ahead of the bulk, so both are given);
- the soil height at the wall (column height sum c dy of the first column), and the mean slope of
  the surface between 3/4 and 1/4 of that height (where the column heights cross them, linearly
  between column centres);
- the failure line: its bounding box, and the lowest and highest points and the length of its connected
  piece through the lowest point (the diagonal line from the floor shown in the paper's figures; the
  paper leaves out short pieces parallel to the surface).
"""
import argparse
import glob
import json
import os

import numpy as np

from granflow_files import (InputError, json_file, main_with_errors, one_cell_toe, picture_file, read_csv,
                            require_initial_volume, sample_time)

# Which figure of [VoF] a case is drawn for, from the run directory's name.
FIGURES = {"bui2008_sph_phi25_c5": "Fig. 7", "bui2008_sph_phi25": "Fig. 4", "bui2008_sph_phi45": "Fig. 5",
           "bui2008_sph_phi65": "Fig. 6"}
BLOCK_AREA = 4.0 * 2.0  # m^2, the initial block of every bui2008_sph case


def outputs(run_dir):
    """Output index -> time, from the surface files' headers."""
    files = sorted(glob.glob(os.path.join(glob.escape(run_dir), "surface_[0-9][0-9][0-9][0-9][0-9].csv")))
    if not files:
        raise InputError(f"{run_dir}: no surface_NNNNN.csv (not a granflow output directory of a soil case?)")
    return {os.path.basename(f)[8:13]: sample_time(f) for f in files}


def chains(x0, y0, x1, y1, tol):
    """Join contour segments that share end points into pieces; returns a list of index lists."""
    key = lambda x, y: (round(x / tol), round(y / tol))
    ends = {}
    for k in range(len(x0)):
        for p in (key(x0[k], y0[k]), key(x1[k], y1[k])):
            ends.setdefault(p, []).append(k)
    seen, pieces = set(), []
    for start in range(len(x0)):
        if start in seen:
            continue
        piece, todo = [], [start]
        seen.add(start)
        while todo:
            k = todo.pop()
            piece.append(k)
            for p in (key(x0[k], y0[k]), key(x1[k], y1[k])):
                for n in ends[p]:
                    if n not in seen:
                        seen.add(n)
                        todo.append(n)
        pieces.append(piece)
    return pieces


def failure_extent(fail, dx):
    x0, y0, x1, y1 = fail["x0"], fail["y0"], fail["x1"], fail["y1"]
    if len(x0) == 0:
        return None
    lengths = np.hypot(x1 - x0, y1 - y0)
    pieces = chains(x0, y0, x1, y1, 1e-4 * dx)
    # The diagonal line of the paper's figures starts at the floor: take the piece through the lowest
    # point (the longest among pieces that reach the same lowest cell row), not closed loops above it.
    lowest = lambda p: min(y0[p].min(), y1[p].min())
    main = min(pieces, key=lambda p: (round(lowest(p) / dx), -lengths[p].sum()))
    px = np.concatenate([x0[main], x1[main]])
    py = np.concatenate([y0[main], y1[main]])
    lo, hi = int(np.argmin(py)), int(np.argmax(py))
    allx, ally = np.concatenate([x0, x1]), np.concatenate([y0, y1])
    return {
        "x_min_m": float(allx.min()), "x_max_m": float(allx.max()),
        "y_min_m": float(ally.min()), "y_max_m": float(ally.max()),
        "length_m": float(lengths.sum()), "pieces": len(pieces),
        "main_length_m": float(lengths[main].sum()),
        "main_lower_end_m": [float(px[lo]), float(py[lo])],
        "main_upper_end_m": [float(px[hi]), float(py[hi])],
    }


def history_at(run_dir, t):
    path = os.path.join(run_dir, "history.csv")
    if not os.path.exists(path):
        return None
    h = read_csv(path)
    if "time" not in h or len(h["time"]) == 0:
        return None
    k = int(np.argmin(np.abs(h["time"] - t)))
    if abs(h["time"][k] - t) > 1e-6 * max(1.0, t):
        return None
    return {name: float(h[name][k]) for name in h}


def measure(run_dir, stamp, t):
    def named(name):
        path = os.path.join(run_dir, f"{name}_{stamp}.csv")
        if not os.path.exists(path):
            raise InputError(f"{path}: missing (the surface of output {stamp} has no {name} file)")
        return read_csv(path)

    surf, fail, cols = named("surface"), named("failure_line"), named("column_height")
    x, h = cols["x"], cols["height"]
    if len(x) < 2:
        raise InputError(f"{run_dir}/column_height_{stamp}.csv: fewer than two columns")
    dx = x[1] - x[0]
    toe_contour = float(max(surf["x0"].max(), surf["x1"].max())) if len(surf["x0"]) else 0.0
    toe_cell = one_cell_toe(cols, os.path.join(run_dir, f"column_height_{stamp}.csv"))
    # Mean slope of the surface between the points 3/4 and 1/4 as high as the wall, each where the
    # column heights first cross it (linear between column centres): a cohesionless pile at rest can
    # stand no steeper than its yield surface allows (asin(3 alpha_phi) in plane strain).
    def crossing(f):
        below = np.nonzero(h < f * h[0])[0]
        if not len(below):
            return None
        k = below[0]  # >= 1, as h[0] >= f h[0]
        return x[k - 1] + (h[k - 1] - f * h[0]) / (h[k - 1] - h[k]) * (x[k] - x[k - 1])

    slope = None
    if h[0] > 0:
        hi, lo = crossing(0.75), crossing(0.25)
        if hi is not None and lo is not None and lo > hi:
            slope = float(np.degrees(np.arctan(0.5 * h[0] / (lo - hi))))
    row = {
        "time_s": t,
        "output": stamp,
        "runout_contour_m": toe_contour,
        "runout_one_cell_m": toe_cell,
        "wall_height_m": float(h[0]),
        "mid_slope_deg": slope,
        "failure_line": failure_extent(fail, dx),
    }
    hist = history_at(run_dir, t)
    if hist:
        row["kinetic_energy_J_per_m"] = hist.get("kinetic_energy")
        row["soil_volume_m2"] = hist.get("soil_volume")
    return row, (surf, fail, x, h, dx)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run_dir")
    ap.add_argument("--png", type=picture_file, help="write the figure to this file")
    ap.add_argument("--json", type=json_file, help="write the numbers to this file")
    ap.add_argument("--times", default="0.8,1.1,1.4,2.5",
                    help="comma-separated times in s (default: the paper's 0.8,1.1,1.4 and 2.5)")
    a = ap.parse_args()
    try:
        times = [float(v) for v in a.times.split(",") if v.strip()]
    except ValueError:
        ap.error(f"--times '{a.times}': expected comma-separated numbers, e.g. 0.8,1.1,1.4,2.5")
    if not times:
        ap.error("--times: no time given")

    run_dir = a.run_dir.rstrip("/") or "/"
    if not os.path.isdir(run_dir):
        raise InputError(f"{run_dir}: no such directory")
    history_path = os.path.join(run_dir, "history.csv")
    require_initial_volume(read_csv(history_path), history_path, BLOCK_AREA, "the 4 x 2 m block of the bui2008_sph cases")
    index = outputs(run_dir)
    rows, drawn = [], []
    for t in times:
        match = [s for s, to in index.items() if abs(to - t) <= 1e-6 * max(1.0, abs(t))]
        if not match:
            have = ", ".join(f"{v:g}" for v in sorted(index.values()))
            raise InputError(f"{run_dir}: no output at t = {t:g} s (outputs at t = {have} s)")
        row, geo = measure(run_dir, match[0], index[match[0]])
        rows.append(row)
        drawn.append(geo)

    # Initial block: the c = 0.5 contour of output 0 when there is one.
    initial = None
    first = min(index, key=lambda s: index[s])
    if index[first] == 0.0:
        initial = read_csv(os.path.join(run_dir, f"surface_{first}.csv"))
        init_toe = float(max(initial["x0"].max(), initial["x1"].max())) if len(initial["x0"]) else 0.0
    name = os.path.basename(os.path.abspath(run_dir))
    figure = next((f for case, f in FIGURES.items() if name.startswith(case)), "Figs. 4-7")

    print(f"{run_dir}: soil surface c = 0.5, failure line ||e|| = 0.3"
          + (f"; initial toe {init_toe:.3f} m" if initial is not None else ""))
    print(f"{'t (s)':>6} {'run-out c=0.5':>14} {'run-out 1 cell':>15} {'wall height':>12} {'slope':>6}"
          "   failure line (piece from the floor)")
    for r in rows:
        f = r["failure_line"]
        ftxt = "none"
        sl = f"{r['mid_slope_deg']:.1f}" if r["mid_slope_deg"] is not None else "-"
        if f:
            (lx, ly), (ux, uy) = f["main_lower_end_m"], f["main_upper_end_m"]
            ftxt = (f"({lx:.2f}, {ly:.2f}) to ({ux:.2f}, {uy:.2f}) m, length {f['main_length_m']:.2f} m; "
                    f"all {f['pieces']} pieces in x {f['x_min_m']:.2f}-{f['x_max_m']:.2f} m")
        print(f"{r['time_s']:6.3g} {r['runout_contour_m']:12.3f} m {r['runout_one_cell_m']:13.3f} m "
              f"{r['wall_height_m']:10.3f} m {sl:>6}   {ftxt}")

    if a.json:
        with open(a.json, "w") as out:
            json.dump({"run_dir": run_dir, "compare_with": f"[VoF] {figure} (SPH of Bui et al. 2008), visually",
                       "initial_toe_m": init_toe if initial is not None else None, "times": rows}, out, indent=1)
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        xmax = max(float(x[-1] + 0.5 * dx) for (_, _, x, _, dx) in drawn)
        ytop = 1.15 * max(max(float(h.max()) for (_, _, _, h, _) in drawn), 1e-30)
        fig, axes = plt.subplots(len(rows), 1, figsize=(10, 0.6 + len(rows) * max(1.2, 10 * ytop / xmax + 0.5)),
                                 sharex=True, squeeze=False)
        for ax, r, (surf, fail, x, h, dx) in zip(axes[:, 0], rows, drawn):
            if initial is not None:
                for k in range(len(initial["x0"])):
                    ax.plot([initial["x0"][k], initial["x1"][k]], [initial["y0"][k], initial["y1"][k]], "k:",
                            lw=0.8, label="initial block" if k == 0 else None)
            for k in range(len(surf["x0"])):
                ax.plot([surf["x0"][k], surf["x1"][k]], [surf["y0"][k], surf["y1"][k]], "b-", lw=1.4,
                        label="soil surface (c = 0.5)" if k == 0 else None)
            for k in range(len(fail["x0"])):
                ax.plot([fail["x0"][k], fail["x1"][k]], [fail["y0"][k], fail["y1"][k]], "r-", lw=1.1,
                        label="failure line (||e|| = 0.3)" if k == 0 else None)
            ax.plot([r["runout_one_cell_m"]], [0], "g^", ms=6, label="toe, soil one cell thick")
            ax.set_xlim(0, xmax)
            ax.set_ylim(0, ytop)
            ax.set_aspect("equal")
            ax.set_ylabel("y [m]")
            ax.text(0.99, 0.92, f"t = {r['time_s']:g} s: run-out {r['runout_contour_m']:.2f} m (c = 0.5), "
                    f"{r['runout_one_cell_m']:.2f} m (one cell); wall height {r['wall_height_m']:.2f} m",
                    transform=ax.transAxes, ha="right", va="top", fontsize=8)
        axes[-1, 0].set_xlabel("x [m]")
        axes[0, 0].legend(fontsize=7, loc="center right", framealpha=0.8)  # the run-out side is clear early on
        fig.suptitle(f"{name}: granflow at the times of [VoF] {figure}; no SPH data shipped, "
                     f"compare visually with the paper's figure", fontsize=9)
        fig.tight_layout()
        fig.savefig(a.png, dpi=130)
    return 0


if __name__ == "__main__":
    main_with_errors(main)

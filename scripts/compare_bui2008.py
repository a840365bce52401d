#!/usr/bin/python3
"""Compare a granflow run of bui2008_experiment with the experiment of Bui et al. (2008).

Usage: compare_bui2008.py RUN_DIR [--png FILE] [--json FILE]
Reads the last output of RUN_DIR (column_height_*.csv, surface_*.csv, failure_line_*.csv) and prints:
run-out (toe of the c = 0.5 contour and of a one-cell-thick layer) against 0.442 m, the RMS height
difference at the experiment's surface points, the mean distance of the experiment's failure
points from the computed failure line, and the change of the soil volume (with what left the
domain) and the energy budget (kinetic plus dissipated energy against the potential energy released)
from history.csv. A run with no output after its start, or of another block than the case's (by its
initial soil volume), is refused. A run without failure lines (soil.displacement = false) is compared
without them. Warned of on stderr: a last output before the case's time.end (a run stopped early), a
pile that may still move (the kinetic energy in the soil's mass a root-mean-square speed above
1e-3 m/s: the experiment's surface is the deposit at rest), and soil that left the domain (its run-out and surface are then of what stayed).
"""
import argparse
import glob
import json
import os
import sys
import tomllib

import numpy as np

from granflow_files import (InputError, json_file, main_with_errors, one_cell_toe, picture_file, read_csv,
                            require_columns, require_initial_volume, require_rows, sample_time)

HERE = os.path.dirname(os.path.abspath(__file__))
REFDATA = os.path.join(HERE, "..", "validation", "refdata")
EXPERIMENT_RUNOUT = 0.442
BLOCK_AREA = 0.2 * 0.1  # m^2 per metre of depth: the block of cases/bui2008_experiment.toml
SOIL_DENSITY = 2650.0  # kg/m^3, the case's, where the run's record does not give it
REST_SPEED = 1e-3  # m/s: below it the pile is at rest (the measure, on the largest speed)


def last_output(run_dir):
    """The files of the last output, all of one output index: a run killed while writing one leaves
    its column heights without its surface, and the output before is taken whole. The failure line
    is None where the run wrote none (soil.displacement = false)."""
    if not os.path.isdir(run_dir):
        raise InputError(f"{run_dir}: no such directory")
    with_failure_lines = bool(glob.glob(os.path.join(glob.escape(run_dir), "failure_line_[0-9]*.csv")))
    stamps = sorted(os.path.basename(f)[len("column_height_"):-len(".csv")]
                    for f in glob.glob(os.path.join(glob.escape(run_dir), "column_height_[0-9]*.csv")))
    for stamp in reversed(stamps):
        names = ("column_height", "surface") + (("failure_line",) if with_failure_lines else ())
        files = {name: os.path.join(run_dir, f"{name}_{stamp}.csv") for name in names}
        if all(os.path.exists(f) for f in files.values()):
            files.setdefault("failure_line", None)
            return files
    raise InputError(f"{run_dir}: no output with its column_height_ and surface_ files "
                     "(not the output directory of a run of bui2008_experiment?)")


def case_value(run_dir, table, key):
    """A number of the case as the run took it (granflow_case.toml), or None."""
    path = os.path.join(run_dir, "granflow_case.toml")
    try:
        with open(path, "rb") as f:
            return float(tomllib.load(f)[table][key])
    except (OSError, KeyError, TypeError, ValueError, tomllib.TOMLDecodeError):
        return None


def metrics(run_dir):
    files = last_output(run_dir)
    cols_path = files["column_height"]
    time = sample_time(cols_path)
    if not time > 0:
        raise InputError(f"{cols_path}: the run has no output after its start (t = {time:g} s)")
    history_path = os.path.join(run_dir, "history.csv")
    history = read_csv(history_path)
    require_columns(history, history_path, ["soil_volume", "soil_outflow", "kinetic_energy", "potential_energy",
                                            "dissipated_energy"])
    require_initial_volume(history, history_path, BLOCK_AREA, "the bui2008_experiment block")
    cols = require_rows(read_csv(cols_path), cols_path)
    surf = read_csv(files["surface"])
    fail = read_csv(files["failure_line"]) if files["failure_line"] else {"x0": np.array([]), "y0": np.array([]),
                                                                          "x1": np.array([]), "y1": np.array([])}
    exp_s = read_csv(os.path.join(REFDATA, "bui2008_al_bar_collapse_final_surface.csv"))
    exp_f = read_csv(os.path.join(REFDATA, "bui2008_al_bar_collapse_failure_line.csv"))
    x, h = cols["x"], cols["height"]
    toe_cell = one_cell_toe(cols, cols_path)
    toe_contour = max(surf["x0"].max(), surf["x1"].max()) if len(surf["x0"]) else 0.0
    ex, ey = exp_s["x_m"], exp_s["y_m"]
    # Beyond the columns' centres the surface is the nearest column's (the first point lies within
    # the first cell's half width of the wall).
    heights = np.interp(ex, x, h)
    rms = float(np.sqrt(np.mean((heights - ey) ** 2)))
    fx, fy = exp_f[list(exp_f)[0]], exp_f[list(exp_f)[1]]
    mean_dist = float("nan")
    if len(fail["x0"]):
        p0 = np.stack([fail["x0"], fail["y0"]], 1)
        p1 = np.stack([fail["x1"], fail["y1"]], 1)
        d = []
        for q in np.stack([fx, fy], 1):
            seg = p1 - p0
            t = np.clip(np.einsum("ij,ij->i", q - p0, seg) / np.maximum(np.einsum("ij,ij->i", seg, seg), 1e-30), 0, 1)
            closest = p0 + t[:, None] * seg
            d.append(np.sqrt(((closest - q) ** 2).sum(1)).min())
        mean_dist = float(np.mean(d))
    released = history["potential_energy"][0] - history["potential_energy"][-1]
    accounted = history["kinetic_energy"][-1] + history["dissipated_energy"][-1]
    # The soil's root-mean-square speed were all the kinetic energy in its mass: a bound on it, since the
    # air's share counts too (at rest most of what is left is the air's).
    density = case_value(run_dir, "soil", "density") or SOIL_DENSITY
    speed_bound = np.sqrt(2 * max(history["kinetic_energy"][-1], 0.0) / (density * history["soil_volume"][-1]))
    return {
        "time": time,
        "runout_contour_m": float(toe_contour),
        "runout_one_cell_m": float(toe_cell),
        "runout_experiment_m": EXPERIMENT_RUNOUT,
        "runout_error_contour": float(toe_contour / EXPERIMENT_RUNOUT - 1),
        "runout_error_one_cell": float(toe_cell / EXPERIMENT_RUNOUT - 1),
        "surface_rms_m": rms,
        "failure_line_mean_distance_m": mean_dist,
        "soil_speed_bound_m_s": float(speed_bound),
        # the largest speed over the cells with c >= 0.5 at the last step (NaN from a run before the column)
        "soil_speed_m_s": float(history["soil_speed"][-1]) if "soil_speed" in history else float("nan"),
        # what the domain holds and what left it, against the first step's
        "soil_volume_change": float((history["soil_volume"][-1] + history["soil_outflow"][-1]) / history["soil_volume"][0] - 1),
        # the share of the soil that left through the open sides
        "soil_outflow_fraction": float(history["soil_outflow"][-1] / history["soil_volume"][0]),
        # (kinetic + dissipated) / potential energy released - 1: zero when the budget closes
        "energy_budget_error": float(accounted / released - 1) if released > 0 else float("nan"),
    }, (x, h, surf, fail, exp_s, exp_f)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run_dir")
    ap.add_argument("--png", type=picture_file)
    ap.add_argument("--json", type=json_file)
    a = ap.parse_args()
    m, (x, h, surf, fail, exp_s, exp_f) = metrics(a.run_dir)
    for k, v in m.items():
        if k in ("soil_volume_change", "soil_outflow_fraction", "soil_speed_bound_m_s", "soil_speed_m_s"):
            print(f"{k} = {v:.3g}")
        elif k.endswith("_m") and k.startswith(("surface_rms", "failure_line")):  # to 0.01 mm, as the docs quote them
            print(f"{k} = {v:.5f}")
        else:
            print(f"{k} = {v:.4f}" if isinstance(v, float) else f"{k} = {v}")
    end = case_value(a.run_dir, "time", "end")
    rest_speed = case_value(a.run_dir, "time", "rest_speed") or 0.0
    # A run stopped by time.rest_speed ends before time.end with its soil slower than that: its final pile.
    at_rest = rest_speed > 0 and m["soil_speed_m_s"] < rest_speed  # False for NaN
    if end is not None and m["time"] < end * (1 - 1e-9):
        if at_rest:
            print(f"the run stopped at t = {m['time']:.6g} s with the soil at rest (slower than time.rest_speed = "
                  f"{rest_speed:g} m/s)")
        else:
            print(f"warning: the last output is at t = {m['time']:.6g} s, before the case's time.end = {end:g} s: "
                  "the run stopped early, and this is not its final pile", file=sys.stderr)
    # The experiment's surface is its deposit at rest: the largest soil speed where the history has it,
    # else the bound from the kinetic energy (which the moving air's counts in).
    speed = m["soil_speed_m_s"] if np.isfinite(m["soil_speed_m_s"]) else m["soil_speed_bound_m_s"]
    if speed > REST_SPEED:
        how = ("its largest speed is" if np.isfinite(m["soil_speed_m_s"]) else
               "the kinetic energy in the soil's mass is a root-mean-square speed of")
        print(f"warning: the pile may still move at t = {m['time']:.6g} s ({how} {speed:.3g} m/s): the "
              "experiment's surface is its deposit at rest", file=sys.stderr)
    if m["soil_outflow_fraction"] > 1e-10:
        print(f"warning: {100 * m['soil_outflow_fraction']:.3g} % of the soil left the domain; the run-out and the "
              "surface are of the soil that stayed (a longer domain is needed)", file=sys.stderr)
    if np.isnan(m["failure_line_mean_distance_m"]):
        print("note: no failure line to compare (none written, or no soil strained to 0.3)", file=sys.stderr)
    if a.json:  # a measure that cannot be taken (no failure line) is null, not NaN, which JSON lacks
        json.dump({k: None if isinstance(v, float) and np.isnan(v) else v for k, v in m.items()}, open(a.json, "w"), indent=1)
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(9, 3.6))
        for k in range(len(surf["x0"])):
            ax.plot([surf["x0"][k], surf["x1"][k]], [surf["y0"][k], surf["y1"][k]], "b-", lw=1.5,
                    label="granflow surface (c = 0.5)" if k == 0 else None)
        for k in range(len(fail["x0"])):
            ax.plot([fail["x0"][k], fail["x1"][k]], [fail["y0"][k], fail["y1"][k]], "r-", lw=1.2,
                    label="granflow failure line (||e|| = 0.3)" if k == 0 else None)
        ax.plot(exp_s["x_m"], exp_s["y_m"], "ko", mfc="none", ms=4, label="experiment surface")
        fk = list(exp_f)
        ax.plot(exp_f[fk[0]], exp_f[fk[1]], "ks", mfc="none", ms=4, label="experiment failure line")
        ax.plot([0, 0.2, 0.2], [0.1, 0.1, 0], "k:", lw=0.8, label="initial block")
        ax.set_xlim(0, 0.6); ax.set_ylim(0, 0.12); ax.set_aspect("equal")
        ax.set_xlabel("x [m]"); ax.set_ylabel("y [m]")
        ax.set_title(f"Bui et al. (2008) collapse, t = {m['time']:.2f} s: run-out {m['runout_contour_m']:.3f} m "
                     f"(experiment 0.442), RMS {1000 * m['surface_rms_m']:.1f} mm")
        ax.legend(fontsize=7, loc="upper right")
        fig.tight_layout()
        fig.savefig(a.png, dpi=130)
    return 0


if __name__ == "__main__":
    main_with_errors(main)

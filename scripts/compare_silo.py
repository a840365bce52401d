#!/usr/bin/python3
"""The discharge of a silo through a slot in its floor (cases/silo_discharge.toml and its variants:
another slot, fill, soil, or a liquid): the hour-glass against the clepsydra.

Usage: compare_silo.py RUN_DIR [RUN_DIR ...] [--png FILE]

Each run is half a silo on its axis (the west side a symmetry plane), its floor the first [[obstacle]],
a box from the slot's edge x = L / 2 to the east wall. From RUN_DIR/history.csv and the case as the run
took it (RUN_DIR/granflow_case.toml) it prints, in windows of a twentieth of the initial fill, the fill
height h (the soil's volume over the silo's width, a mean level) and the discharge Q of the whole silo
per metre of slot (twice the half's soil_outflow rate), with Beverloo's coefficient Q / (sqrt(g) L^1.5)
and Torricelli's Q / (L sqrt(2 g h)). Then, over the windows after the first (the start) and while h
is above 2 L, the spread of Q and the exponent a of Q ~ h^a fitted over them: 0 for a granular
hour-glass, whose rate does not depend on the fill, 1/2 for a liquid's clepsydra.
With --png, Q against h for every run.
"""
import argparse
import math
import os

import numpy as np

from granflow_files import (InputError, main_with_errors, picture_file, read_csv, read_run_case, require_columns,
                            require_rows)


def read_silo(run_dir):
    case, path = read_run_case(run_dir)
    try:
        if case["boundary"]["west"]["type"] != "symmetry":
            raise InputError(f"{path}: the west side is not the silo's axis (a symmetry plane)")
        floor = case["obstacle"][0]
        if floor["shape"] != "box":
            raise InputError(f"{path}: the first obstacle (the floor) is not a box")
        lower, upper = case["mesh"]["lower"], case["mesh"]["upper"]
        half_slot = floor["lower"][0] - lower[0]
        if not 0 < half_slot < upper[0] - lower[0]:
            raise InputError(f"{path}: the floor does not leave a slot on the axis")
        gx, gy = case["physics"]["gravity"]
        g = math.hypot(gx, gy)
        if not g > 0:
            raise InputError(f"{path}: no gravity: nothing drains")
        return {"L": 2.0 * half_slot, "width": upper[0] - lower[0], "g": g,
                "title": case.get("title", os.path.basename(os.path.normpath(run_dir)))}
    except (KeyError, IndexError, TypeError, ValueError) as e:
        raise InputError(f"{path}: not a silo with a floor obstacle and a slot on its axis "
                         f"({type(e).__name__}: {e})")


def discharge(run_dir, silo):
    """Windows of the run: (time, mean fill h, Q of the whole silo)."""
    path = os.path.join(run_dir, "history.csv")
    history = require_rows(read_csv(path), path)
    require_columns(history, path, ["time", "soil_volume", "soil_outflow"])
    t, volume, out = history["time"], history["soil_volume"], history["soil_outflow"]
    if not volume[0] > 0:
        raise InputError(f"{path}: no soil in the silo at the start")
    step = volume[0] / 20.0
    rows, k = [], 0
    for j in range(1, len(t)):
        # A window closes when a twentieth of the fill has flowed out; the last, cut short by the run's
        # end, counts if half as much has.
        last = j == len(t) - 1 and out[j] - out[k] >= 0.5 * step
        if out[j] - out[k] >= step or last:
            h = 0.5 * (volume[j] + volume[k]) / silo["width"]
            rows.append((0.5 * (t[j] + t[k]), h, 2.0 * (out[j] - out[k]) / (t[j] - t[k])))
            k = j
    if len(rows) < 3:
        raise InputError(f"{path}: too little has flowed out to measure a rate (fewer than three windows)")
    return np.array(rows)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir", nargs="+")
    ap.add_argument("--png", type=picture_file)
    args = ap.parse_args()
    curves = []
    for run_dir in args.run_dir:
        silo = read_silo(run_dir)
        rows = discharge(run_dir, silo)
        L, g = silo["L"], silo["g"]
        print(f"{run_dir}: {silo['title']}\n  slot L = {L:.4g} m, silo {2 * silo['width']:.4g} m wide")
        print(f"  {'t (s)':>8} {'h (m)':>8} {'Q (m^2/s)':>11} {'Q/(g^.5 L^1.5)':>15} {'Q/(L (2gh)^.5)':>15}")
        for time, h, q in rows:
            print(f"  {time:8.4f} {h:8.4f} {q:11.5g} {q / (math.sqrt(g) * L ** 1.5):15.4f} "
                  f"{q / (L * math.sqrt(2.0 * g * max(h, 1e-300))):15.4f}")
        used = rows[1:][rows[1:, 1] > 2.0 * L]
        if len(used) >= 2:
            spread = used[:, 2].max() / used[:, 2].min() - 1.0
            exponent = np.polyfit(np.log(used[:, 1]), np.log(used[:, 2]), 1)[0]
            print(f"  from h = {used[0, 1]:.4g} to {used[-1, 1]:.4g} m: Q from {used[:, 2].min():.5g} to "
                  f"{used[:, 2].max():.5g} m^2/s (spread {100 * spread:.2f} %), Q ~ h^{exponent:.3f} "
                  f"(hour-glass 0, clepsydra 0.5); Beverloo's coefficient {np.mean(used[:, 2]) / (math.sqrt(g) * L ** 1.5):.4f}")
        else:
            print("  fewer than two windows after the start with h above 2 L: no fit")
        curves.append((run_dir, silo, rows))
    if args.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(6.5, 4.2))
        for run_dir, silo, rows in curves:
            ax.plot(rows[1:, 1], rows[1:, 2], "o-", ms=3,
                    label=f"{os.path.basename(os.path.normpath(run_dir))} (L = {silo['L']:.3g} m)")
        ax.set_xlabel("fill height h (m)")
        ax.set_ylabel("discharge Q (m$^2$/s per metre of slot)")
        ax.set_ylim(bottom=0.0)
        ax.invert_xaxis()
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
        ax.set_title("silo discharge as it empties: hour-glass (flat) and clepsydra (falling)", fontsize=10)
        fig.tight_layout()
        fig.savefig(args.png, dpi=120)
        print(f"wrote {args.png}")
    return 0


if __name__ == "__main__":
    main_with_errors(main)

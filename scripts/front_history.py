#!/usr/bin/python3
"""The toe of the c = 0.5 contour over time, for one or more runs side by side (a mesh study).

Usage: scripts/front_history.py RUN_DIR [RUN_DIR ...] [--times 0.1,0.2,...]

Reads each run's history.csv (column toe_contour, linear between steps) and prints one row per run:
the toe in metres at each time, '-' past the run's end.
"""
import argparse
import math
import os

import numpy as np

from granflow_files import InputError, main_with_errors, read_csv, require_columns


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("runs", nargs="+", help="output directories of granflow runs")
    parser.add_argument("--times", default="0.1,0.2,0.3,0.4,0.5,0.6", help="comma-separated times in s")
    args = parser.parse_args()
    try:
        times = [float(t) for t in args.times.split(",")]
    except ValueError:
        raise InputError(f"--times: not a list of numbers: {args.times}")
    if not all(math.isfinite(t) and t >= 0 for t in times):
        raise InputError(f"--times: not a list of finite times of at least 0 s: {args.times}")
    histories = []
    for run in args.runs:  # all read before anything is printed: a bad run is one error line
        path = os.path.join(run, "history.csv")
        h = read_csv(path)
        require_columns(h, path, ["time", "toe_contour"])
        histories.append((run, h["time"], h["toe_contour"]))
    width = max(len(r) for r in args.runs)
    print("run".ljust(width), " ".join(f"{'t=' + format(t, 'g'):>8}" for t in times))
    for run, t, toe in histories:
        cells = [f"{np.interp(x, t, toe):8.3f}" if t.size and x <= t[-1] + 1e-9 else f"{'-':>8}" for x in times]
        print(run.ljust(width), " ".join(cells))
    return 0


if __name__ == "__main__":
    main_with_errors(main)

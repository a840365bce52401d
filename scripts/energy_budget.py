#!/usr/bin/python3
"""The energy budget of a run over a window of time, from its history.

Usage: scripts/energy_budget.py RUN_DIR [--from T0] [--to T1]

Reads RUN_DIR/history.csv (linear between steps; by default from its first row to its last) and prints
what the run gained over the window: kinetic and potential energy, the energy dissipated, and the
energy brought in through the sides (boundary_work: the kinetic and potential energy carried in less
that carried out, and the work of the sides' pressure and stress). The budget closes when gained +
dissipated = brought in; its residual is printed as a share of the potential energy released (where
some was) and of the energy brought in (where it is not zero). J per metre of depth on a planar mesh (per radian on an
axisymmetric one), J on a mesh of layers.
"""
import argparse
import math
import os

import numpy as np

from granflow_files import InputError, finite, main_with_errors, read_csv, require_columns, require_rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", help="output directory of a granflow run with soil")
    parser.add_argument("--from", dest="start", type=finite, help="start of the window, s (the first row's time)")
    parser.add_argument("--to", dest="end", type=finite, help="end of the window, s (the last row's time)")
    args = parser.parse_args()
    path = os.path.join(args.run, "history.csv")
    h = read_csv(path)
    columns = ["time", "kinetic_energy", "potential_energy", "dissipated_energy", "boundary_work"]
    if "time" in h and "kinetic_energy" in h and "boundary_work" not in h:
        raise InputError(f"{path}: no column boundary_work (written by an earlier granflow; run the case again)")
    require_columns(h, path, columns)
    require_rows(h, path)
    t = h["time"]
    start = t[0] if args.start is None else args.start
    end = t[-1] if args.end is None else args.end
    if not (t[0] <= start < end <= t[-1]):
        raise InputError(f"the window {start:g} to {end:g} s is not within the run's {t[0]:g} to {t[-1]:g} s, "
                         "from an earlier time to a later one")
    work = h["boundary_work"]
    if not np.all(np.isfinite(work[(t >= start) & (t <= end)])):
        raise InputError(f"{path}: boundary_work is empty (nan) in the window: rows of a run restarted from a "
                         "checkpoint of an earlier granflow; take a window after its restart")

    def change(column):
        return float(np.interp(end, t, h[column]) - np.interp(start, t, h[column]))

    kinetic, potential = change("kinetic_energy"), change("potential_energy")
    dissipated, brought_in = change("dissipated_energy"), change("boundary_work")
    surface = change("surface_energy") if "surface_energy" in h else 0.0  # a case with surface tension
    residual = kinetic + potential + surface + dissipated - brought_in
    print(f"{args.run}: t = {start:.6g} to {end:.6g} s")
    print(f"  kinetic energy gained      {kinetic:14.6g}")
    print(f"  potential energy gained    {potential:14.6g}")
    if "surface_energy" in h:
        print(f"  surface energy gained      {surface:14.6g}")
    print(f"  dissipated                 {dissipated:14.6g}")
    print(f"  brought in through sides   {brought_in:14.6g}")
    shares = []
    if potential + surface < 0.0:
        released = "potential and surface energy" if "surface_energy" in h else "potential energy"
        shares.append(f"{residual / -(potential + surface):+.4%} of the {released} released")
    if brought_in != 0.0:
        shares.append(f"{residual / brought_in:+.4%} of the energy brought in")
    print(f"  residual (gained + dissipated - brought in) {residual:.6g}" +
          (": " + ", ".join(shares) if shares else ""))
    return 0


if __name__ == "__main__":
    main_with_errors(main)

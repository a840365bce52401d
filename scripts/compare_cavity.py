#!/usr/bin/python3
"""Compare granflow's cavity centre-line velocities with Ghia, Ghia & Shin (1982).

Usage: compare_cavity.py RUN_DIR RE [--png FILE]
Prints the largest absolute deviation of u (vertical centre line) and v (horizontal centre line)
at Ghia's points (the wall points are the boundary conditions, on which the line samples end) and
exits 0. Ghia's profiles are steady: a sample that the run did not mark as its steady state (the
shipped cases stop there, `time.steady_tolerance`) is compared with a warning.
"""
import argparse
import os
import re
import sys

import numpy as np

from granflow_files import InputError, main_with_errors, picture_file, read_csv, require_rows

HERE = os.path.dirname(os.path.abspath(__file__))
REFDATA = os.path.join(HERE, "..", "validation", "refdata")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("run_dir")
    ap.add_argument("re", type=int)
    ap.add_argument("--png", type=picture_file)
    ap.add_argument("--refdata", default=os.environ.get("GRANFLOW_REFDATA", REFDATA))
    a = ap.parse_args()
    ref_path = os.path.join(a.refdata, f"ghia1982_cavity_re{a.re}.csv")
    if not os.path.exists(ref_path):
        have = sorted(int(m.group(1)) for f in os.listdir(a.refdata)
                      if (m := re.fullmatch(r"ghia1982_cavity_re(\d+)\.csv", f)))
        raise InputError(f"no data of Ghia et al. (1982) for Re = {a.re} in {a.refdata}; it has Re = "
                         + ", ".join(str(r) for r in have))
    ref = read_csv(ref_path)
    ucl_path = os.path.join(a.run_dir, "u_vertical_centreline.csv")
    ucl = require_rows(read_csv(ucl_path), ucl_path)
    # The shipped cavities have a unit lid speed, side and density, so their viscosity is 1 / Re.
    if "viscosity" in ucl and len(ucl["viscosity"]) and not np.allclose(ucl["viscosity"], 1.0 / a.re, rtol=1e-6):
        raise InputError(f"{ucl_path}: the viscosity is {ucl['viscosity'][0]:g} Pa s, not the 1/{a.re} of a cavity "
                         f"at Re {a.re} (unit lid speed, side and density): a run at another Re?")
    vcl = read_csv(os.path.join(a.run_dir, "v_horizontal_centreline.csv"))
    with open(ucl_path) as f:
        when = f.readline().strip().lstrip("# ")
    if not when.endswith("steady state reached"):
        print(f"warning: {ucl_path} is not a steady state ({when}): the run stopped at its time.end, out of "
              f"steps or was stopped, and is compared with Ghia's steady profiles as it stands", file=sys.stderr)
    du = np.abs(np.interp(ref["y"], ucl["y"], ucl["u"]) - ref["u"]).max()
    dv = np.abs(np.interp(ref["x"], vcl["x"], vcl["v"]) - ref["v"]).max()
    print(f"Re {a.re}: max |u - u_Ghia| = {du:.4f}, max |v - v_Ghia| = {dv:.4f}")
    if a.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(1, 2, figsize=(9, 4))
        ax[0].plot(ucl["u"], ucl["y"], "-", label="granflow")
        ax[0].plot(ref["u"], ref["y"], "o", mfc="none", label="Ghia et al. 1982")
        ax[0].set_xlabel("u"); ax[0].set_ylabel("y"); ax[0].set_title(f"x = 0.5, Re {a.re}")
        ax[1].plot(vcl["x"], vcl["v"], "-", label="granflow")
        ax[1].plot(ref["x"], ref["v"], "o", mfc="none", label="Ghia et al. 1982")
        ax[1].set_xlabel("x"); ax[1].set_ylabel("v"); ax[1].set_title(f"y = 0.5, Re {a.re}")
        ax[0].legend()
        fig.tight_layout()
        fig.savefig(a.png, dpi=120)
    return 0


if __name__ == "__main__":
    main_with_errors(main)

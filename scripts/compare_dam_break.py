#!/usr/bin/python3
"""Compare a granflow run of water_dam_break with the water-column collapse of Martin & Moyce (1952), n^2 = 2.

Usage: compare_dam_break.py RUN_DIR [--png FILE] [--also DIR=LABEL ...] [--tmax T] [--a A]
       compare_dam_break.py RUN_DIR --koshizuka [--tmax T]

Reads RUN_DIR/history.csv and converts it to the experiment's non-dimensional variables:
  surge front      T   = t sqrt(2 g / a),  Z = toe_contour / a      (toe of the c = 0.5 contour)
  residual column  tau = t sqrt(g / a),    H = wall_height / (2 a)  (dense-phase height at the left wall)
The two tables use different time scales (see the headers of the refdata files: the residual-height
table is given against tau = t sqrt(g/a), without the factor n = sqrt(2)). The simulation is
interpolated linearly at the experiment's times with T <= --tmax (default 3, i.e. tau <= 3/sqrt(2) for
the residual height), and the script prints, for every point and as the largest value, the relative
front deviation |Z_sim - Z_exp| / Z_exp with the simulation's lead in time (T_exp minus the T at which
the computed front reaches Z_exp), and the residual-height deviation H_sim - H_exp (absolute, in units
of the initial height, and relative to H_exp). The largest front deviation is also given separately for
the early points 0.8 < T < 1.7, where the computed front runs ahead of the experiment (see
tests/verification/test_dam_break.cpp), and for the rest. With --png both are plotted against the
data; --also adds the front and height of further runs (e.g. a finer grid) to the plot.

The model releases the column at t = 0 and its early front runs ahead of the experiment's.
Comparisons of Navier-Stokes/VoF solvers with these data often shift the simulated time by 0.175 in
T, as for a late release in the experiment (e.g. the dam-break example of the Lethe code,
chaos-polymtl/lethe, examples/multiphysics/dam-break). The script
prints the raw comparison first and then both tables again with that shift (--release-shift to change
it; the residual height is read at tau - shift / sqrt(2)). A late release would delay the column's fall
as much as the front, so the shift is a test of that explanation, not a correction the tests use.

With --koshizuka, RUN_DIR is a run of cases/water_dam_break_koshizuka.toml (column width L = 0.146 m)
and its front is compared with the experiment reported by Koshizuka & Oka (1996) instead, a second
experiment of the same geometry; Martin & Moyce's front, read at the same T, is printed beside it so
that the two experiments can be compared with each other.
"""
import argparse
import os
import sys

import numpy as np

from granflow_files import finite, main_with_errors, picture_file, positive, read_csv, require_initial_volume

HERE = os.path.dirname(os.path.abspath(__file__))
REFDATA = os.path.join(HERE, "..", "validation", "refdata")
A = 0.05715  # column width a = 2.25 in
G = 9.81
KOSHIZUKA_L = 0.146  # column width of the Koshizuka & Oka experiment (cases/water_dam_break_koshizuka.toml)
RELEASE_SHIFT = 0.175  # in T: the experiment's late start, as other comparisons take it (docstring)


def front_deviation(T_sim, z_sim, Te, Ze, shift=0.0):
    """The simulated front read at the experiment's times minus shift, and its relative deviation."""
    Zs = np.interp(Te - shift, T_sim, z_sim, left=1.0)
    return Zs, np.abs(Zs - Ze) / Ze


def simulated_front(hist, a, g=G):
    """A run's front from its history as T = t sqrt(2g/a) and Z = toe_contour / a, from the initial column
    (Z = 1) on."""
    t = np.concatenate([[0.0], hist["time"]])
    return t * np.sqrt(2 * g / a), np.concatenate([[1.0], hist["toe_contour"] / a])


def compare_koshizuka(run_dir, tmax):
    """Front of a Koshizuka & Oka scale run against their data and against Martin & Moyce's at the same T."""
    history_path = os.path.join(run_dir, "history.csv")
    history = read_csv(history_path)
    require_initial_volume(history, history_path, 2 * KOSHIZUKA_L ** 2, f"a water column {KOSHIZUKA_L} m wide and twice as high")
    T_sim, z_sim = simulated_front(history, KOSHIZUKA_L)
    ko = read_csv(os.path.join(REFDATA, "koshizuka_oka1996_surge_front_pysph.csv"))
    mm = read_csv(os.path.join(REFDATA, "martin_moyce1952_n2_2_surge_front.csv"))
    if T_sim[-1] < tmax * (1 - 1e-6):
        sys.exit(f"error: {run_dir}: the run ends at T = {T_sim[-1]:.3f}, before T = {tmax} (compare up to where it ends with --tmax)")
    sel = (ko["T"] > 0) & (ko["T"] <= tmax + 1e-12)  # the table's (0, 1) is the initial column
    Te, Ze = ko["T"][sel], ko["Z"][sel]
    Zs, dev = front_deviation(T_sim, z_sim, Te, Ze)
    # Martin & Moyce's table starts at T = 0.41; before it, from their column at rest (T = 0, Z = 1).
    Zmm = np.interp(Te, np.concatenate([[0.0], mm["T"]]), np.concatenate([[1.0], mm["Z"]]), right=np.nan)
    print(f"surge front against Koshizuka & Oka (1996), L = {KOSHIZUKA_L} m, T = t sqrt(2g/L), Z = toe_contour / L,"
          f" points with T <= {tmax:g};")
    print("Z_MM: Martin & Moyce's front at the same T (linear between their points)")
    print("      T    Z_KO   Z_sim  |dZ|/Z_KO    Z_MM  (Z_MM-Z_KO)/Z_KO")
    for k in range(len(Te)):
        print(f"  {Te[k]:5.3f}  {Ze[k]:6.3f}  {Zs[k]:6.3f}  {dev[k]:9.4f}  {Zmm[k]:6.3f}  {(Zmm[k] - Ze[k]) / Ze[k]:+8.4f}")
    kmax = int(np.argmax(dev))
    between = np.abs(Zmm - Ze) / Ze
    print(f"largest relative front deviation from Koshizuka & Oka: {dev[kmax]:.4f} at T = {Te[kmax]:.3f};"
          f" the two experiments differ by up to {np.nanmax(between):.4f}")


def compare(run_dir, a=A, g=G, tmax=3.0, shift=RELEASE_SHIFT):
    history_path = os.path.join(run_dir, "history.csv")
    hist = read_csv(history_path)
    require_initial_volume(hist, history_path, 2 * a * a, f"a water column a = {a} m wide and 2a high (--a)")
    t = np.concatenate([[0.0], hist["time"]])
    # The initial state (t = 0) is not a history row; the column starts at Z = 1, H = 1.
    T_sim, z_sim = simulated_front(hist, a, g)
    h_sim = np.concatenate([[1.0], hist["wall_height"] / (2 * a)])
    tau_sim = t * np.sqrt(g / a)
    front = read_csv(os.path.join(REFDATA, "martin_moyce1952_n2_2_surge_front.csv"))
    resid = read_csv(os.path.join(REFDATA, "martin_moyce1952_n2_2_residual_height.csv"))
    out = {"T_sim": T_sim, "Z_sim": z_sim, "tau_sim": tau_sim, "H_sim": h_sim, "front": front, "resid": resid}
    if T_sim[-1] < tmax * (1 - 1e-6):
        sys.exit(f"error: {run_dir}: the run ends at T = {T_sim[-1]:.3f}, before T = {tmax} (compare up to where it ends with --tmax)")
    sel = front["T"] <= tmax + 1e-12
    Te, Ze = front["T"][sel], front["Z"][sel]
    Zs, dev = front_deviation(T_sim, z_sim, Te, Ze)
    lead = Te - np.interp(Ze, np.maximum.accumulate(z_sim), T_sim)
    out["front_points"] = (Te, Ze, Zs, dev, lead)
    out["shifted_points"] = front_deviation(T_sim, z_sim, Te, Ze, shift)
    out["shift"] = shift
    sel = resid["tau"] * np.sqrt(2.0) <= tmax + 1e-12
    tau_e, He = resid["tau"][sel], resid["H"][sel]
    Hs = np.interp(tau_e, tau_sim, h_sim)
    out["resid_points"] = (tau_e, He, Hs, Hs - He)
    Hs_shifted = np.interp(tau_e - shift / np.sqrt(2.0), tau_sim, h_sim, left=1.0)
    out["shifted_resid"] = (Hs_shifted, Hs_shifted - He)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run_dir")
    ap.add_argument("--png", type=picture_file, help="write the comparison plot to this file")
    ap.add_argument("--also", action="append", default=[], metavar="DIR=LABEL",
                    help="plot a further run (with --png), e.g. a finer grid; repeatable")
    ap.add_argument("--tmax", type=positive, default=3.0, help="compare experiment points with T <= TMAX (default 3)")
    ap.add_argument("--a", type=positive, default=A, help=f"column width a in m (default {A})")
    ap.add_argument("--release-shift", type=finite, default=RELEASE_SHIFT,
                    help=f"shift in T of the second front table (default {RELEASE_SHIFT}, see above)")
    ap.add_argument("--koshizuka", action="store_true",
                    help="RUN_DIR is cases/water_dam_break_koshizuka.toml: compare its front with Koshizuka & Oka (1996)")
    args = ap.parse_args()
    if args.also and not args.png:
        ap.error("--also adds runs to the plot: give --png FILE too")
    if args.koshizuka:
        compare_koshizuka(args.run_dir, args.tmax)
        return
    r = compare(args.run_dir, a=args.a, tmax=args.tmax, shift=args.release_shift)
    # the further runs are read before anything is printed, so that a bad one stops the script at once
    others = []
    for k, spec in enumerate(args.also):
        d, _, label = spec.partition("=")
        others.append((compare(d, a=args.a, tmax=args.tmax), label or d, f"C{k + 1}"))

    Te, Ze, Zs, dz, lead = r["front_points"]
    print(f"surge front, T = t sqrt(2g/a), Z = toe_contour / a, experiment points with T <= {args.tmax:g}:")
    print("      T   Z_exp   Z_sim  |dZ|/Z_exp  lead in T")
    for k in range(len(Te)):
        print(f"  {Te[k]:5.2f}  {Ze[k]:6.3f}  {Zs[k]:6.3f}  {dz[k]:9.4f}  {lead[k]:9.3f}")
    kmax = int(np.argmax(dz))
    early = (Te > 0.8) & (Te < 1.7)
    print(f"largest relative front deviation: {dz[kmax]:.4f} at T = {Te[kmax]:.2f} (mean {np.mean(dz):.4f});"
          f" early points 0.8 < T < 1.7: {dz[early].max() if early.any() else float('nan'):.4f},"
          f" the others: {dz[~early].max() if (~early).any() else float('nan'):.4f}")

    tau_e, He, Hs, dh = r["resid_points"]
    print(f"residual column height, tau = t sqrt(g/a), H = wall_height / (2a), points with T = sqrt(2) tau <= {args.tmax:g}:")
    print("    tau   H_exp   H_sim  H_sim-H_exp  rel")
    for k in range(len(tau_e)):
        print(f"  {tau_e[k]:5.2f}  {He[k]:6.3f}  {Hs[k]:6.3f}  {dh[k]:+10.4f}  {dh[k] / He[k]:+7.4f}")
    kmax = int(np.argmax(np.abs(dh)))
    print(f"largest residual-height deviation: {abs(dh[kmax]):.4f} of the initial height"
          f" ({abs(dh[kmax]) / He[kmax]:.4f} relative) at tau = {tau_e[kmax]:.2f};"
          f" largest relative {np.max(np.abs(dh) / He):.4f}")
    Zsh, dzh = r["shifted_points"]
    print(f"with the release shift, the simulation read at T - {r['shift']:g} (tau - {r['shift'] / np.sqrt(2.0):.3f}):")
    print("      T   Z_exp   Z_sim  |dZ|/Z_exp")
    for k in range(len(Te)):
        print(f"  {Te[k]:5.2f}  {Ze[k]:6.3f}  {Zsh[k]:6.3f}  {dzh[k]:9.4f}")
    print(f"largest relative front deviation with the release shift: {dzh.max():.4f}"
          f" at T = {Te[int(np.argmax(dzh))]:.2f} (mean {np.mean(dzh):.4f})")
    Hsh, dhh = r["shifted_resid"]
    print(f"largest residual-height deviation with the release shift: {np.max(np.abs(dhh)):.4f} of the initial height"
          f" at tau = {tau_e[int(np.argmax(np.abs(dhh)))]:.2f} (without: {np.max(np.abs(dh)):.4f})")

    if args.png:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
        fr, rs = r["front"], r["resid"]
        T_end = r["T_sim"][-1]
        ax1.plot(r["T_sim"], r["Z_sim"], "-", color="C0", label="granflow (c = 0.5 contour)")
        ax1.plot(r["T_sim"] + r["shift"], r["Z_sim"], ":", color="C0",
                 label=f"granflow, T + {r['shift']:g} (release shift)")
        for o, label, color in others:
            ax1.plot(o["T_sim"], o["Z_sim"], "--", color=color, lw=1, label=label)
        ax1.plot(fr["T"], fr["Z"], "o", color="k", mfc="none", label="Martin & Moyce (1952)")
        ax1.fill_between(fr["T"], 0.9 * fr["Z"], 1.1 * fr["Z"], color="0.85", label="experiment $\\pm$10 %")
        ax1.axvline(args.tmax, color="0.6", ls=":", lw=1)
        ax1.set_xlim(0, max(3.6, min(T_end, 4.0)))
        ax1.set_ylim(1, 4.5)
        ax1.set_xlabel("$T = t\\,\\sqrt{2g/a}$")
        ax1.set_ylabel("$Z = x_{front}/a$")
        ax1.set_title("surge front")
        ax1.legend(loc="upper left", fontsize=8)
        ax2.plot(r["tau_sim"], r["H_sim"], "-", color="C0", label="granflow (height at x = 0)")
        ax2.plot(r["tau_sim"] + r["shift"] / np.sqrt(2.0), r["H_sim"], ":", color="C0",
                 label=f"granflow, $\\tau$ + {r['shift'] / np.sqrt(2.0):.3f} (release shift)")
        for o, label, color in others:
            ax2.plot(o["tau_sim"], o["H_sim"], "--", color=color, lw=1, label=label)
        ax2.plot(rs["tau"], rs["H"], "o", color="k", mfc="none", label="Martin & Moyce (1952)")
        ax2.axvline(args.tmax / np.sqrt(2.0), color="0.6", ls=":", lw=1)
        ax2.set_xlim(0, max(2.6, min(r["tau_sim"][-1], 3.0)))
        ax2.set_ylim(0, 1.05)
        ax2.set_xlabel("$\\tau = t\\,\\sqrt{g/a}$")
        ax2.set_ylabel("$H = h/(2a)$")
        ax2.set_title("residual column height")
        ax2.legend(loc="lower left", fontsize=8)
        fig.suptitle("Water column collapse, $n^2 = 2$, $a$ = 2.25 in")
        fig.tight_layout()
        fig.savefig(args.png, dpi=120)
        print(f"wrote {args.png}")


if __name__ == "__main__":
    main_with_errors(main)

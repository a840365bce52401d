#!/usr/bin/python3
"""Compare a granflow run of cases/bagnold_chute.toml (or cases/chute_inlet.toml) with the steady profile
of mu(I) flow down a chute.

Usage: compare_bagnold.py RUN_DIR [--png FILE] [--label LABEL] [--also DIR=LABEL ...]

Reads the latest line sample RUN_DIR/profile.csv and the case as the run took it
(RUN_DIR/granflow_case.toml: the slope from the gravity vector, the densities, the mu(I) constants,
the grain size and the viscosity floor mu_min, the layer's depth from its initial box). A chute fed
through an inlet on its west side and started without soil has no initial box: its steady layer is
the one that carries the inlet's flux q = u soil_fraction soil_depth (over its opening, span_y, where it
has one), each profile at its own depth
for q (Bagnold's h = (q / (0.6 A))^(2/5)), and the depth the run reached is printed beside them
from the sample's soil fraction. It prints, at
each sample point in the layer, the computed velocity against two profiles, each relative to the
model's surface velocity:
  - Bagnold's: tau / p = tan(theta) at every depth, so I = I_0 (tan theta - mu_s) / (mu_2 - tan theta)
    and u(z) = (2/3) (I / d) sqrt(g cos theta) (h^1.5 - (h - z)^1.5);
  - the model's own steady profile: tau = mu(I) p + mu_min gamma_dot (the regularised viscosity in
    simple shear), the shear stress carrying the weight along the slope less the air's (which a mean
    pressure gradient carries on a periodic slope), the pressure the soil's weight plus the air's
    column above the surface.
The steadiness is the largest change of u in the layer between the last two samples (profile_NNNNN.csv),
relative to the last sample's largest u; above 1 % the run is warned of as not yet steady.
With --png the profiles are drawn with the computed one; --also adds the profiles of further runs
(e.g. another mesh).
"""
import argparse
import glob
import math
import os
import sys

import numpy as np

from granflow_files import (InputError, main_with_errors, picture_file, read_csv, read_run_case,
                            require_columns, require_rows, sample_time)


def read_case(run_dir):
    case, path = read_run_case(run_dir)
    try:
        rheology = case["soil"]["rheology"]
        if rheology.get("friction") != "mu_of_I":
            raise InputError(f"{path}: the soil's friction is not mu_of_I (a run of another case?)")
        gx, gy = case["physics"]["gravity"]
        m = {
            "theta": math.atan2(gx, -gy), "g": math.hypot(gx, gy),
            "rho_s": case["soil"]["density"], "rho_a": case["air"]["density"],
            "height": case["mesh"]["upper"][1] - case["mesh"]["lower"][1],
            "d": rheology["grain_diameter"], "mu_s": rheology["mu_s"], "mu_2": rheology["mu_2"],
            "I_0": rheology["I_0"], "mu_min": rheology.get("mu_min", 1e-3), "flux": None,
        }
        west = case["boundary"]["west"]
        if not case.get("initial", {}).get("soil") and west.get("type") == "inlet":
            # the soil enters over the inlet's opening (span_y, heights as the mesh's) below its depth
            bottom = case["mesh"].get("lower", [0.0, 0.0])[1]
            span = west.get("span_y", [bottom, bottom + m["height"]])
            top = min(west.get("soil_depth", m["height"]), span[1] - bottom, m["height"])
            opening = max(top - max(span[0] - bottom, 0.0), 0.0)
            m["flux"] = west["velocity"][0] * west.get("soil_fraction", 0.0) * opening
            m["depth"] = None  # each profile's own, for the flux
        else:
            box = case["initial"]["soil"][0]
            m["depth"] = box["upper"][1] - box["lower"][1]
        return m
    except (KeyError, IndexError, TypeError, ValueError) as e:
        raise InputError(f"{path}: not a chute case of a mu(I) soil layer on a tilted floor ({e!r} missing)")


def steady_profile(m, z, model):
    """u at heights z: Bagnold's (model=False) or the model's own steady profile (model=True)."""
    levels = 20000
    level = np.linspace(0.0, m["depth"], levels + 1)
    below = m["depth"] - level
    buoyancy = m["rho_a"] if model else 0.0
    column = m["rho_a"] * m["g"] * math.cos(m["theta"]) * (m["height"] - m["depth"]) if model else 0.0
    tau = (m["rho_s"] - buoyancy) * m["g"] * math.sin(m["theta"]) * below
    p = m["rho_s"] * m["g"] * math.cos(m["theta"]) * below + column
    floor = m["mu_min"] if model else 0.0
    flowing = (p > 0) & (tau > m["mu_s"] * p)
    p_safe = np.where(p > 0, p, 1.0)
    lo, hi = np.zeros_like(level), np.full_like(level, 1e4)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        inertial = np.maximum(mid * m["d"] * np.sqrt(m["rho_s"] / p_safe), 1e-300)
        stress = (m["mu_s"] + (m["mu_2"] - m["mu_s"]) / (m["I_0"] / inertial + 1.0)) * p + floor * mid
        low = stress < tau
        lo, hi = np.where(low, mid, lo), np.where(low, hi, mid)
    rate = np.where(flowing, 0.5 * (lo + hi), 0.0)
    u = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(level))])
    return np.interp(z, level, u)


def depth_for_flux(m, model):
    """The depth whose steady layer carries m["flux"] (bisection on the depth)."""
    lo, hi = 0.0, m["height"]
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        level = np.linspace(0.0, mid, 401)
        u = steady_profile(dict(m, depth=mid), level, model)
        if np.sum(0.5 * (u[1:] + u[:-1]) * np.diff(level)) < m["flux"]:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def read_profile(run_dir):
    path = os.path.join(run_dir, "profile.csv")
    table = require_rows(read_csv(path), path)
    require_columns(table, path, ["y", "u"])
    with open(path) as f:
        first = f.readline().strip()
    return table, first


def last_change(run_dir, depth):
    """(t_before, t_last, largest |u_last - u_before| in the layer) from the last two numbered samples."""
    samples = sorted(glob.glob(os.path.join(glob.escape(run_dir), "profile_[0-9][0-9][0-9][0-9][0-9].csv")))
    if len(samples) < 2:
        return None
    before, last = read_csv(samples[-2]), read_csv(samples[-1])
    require_columns(before, samples[-2], ["y", "u"])
    if len(before["y"]) != len(last["y"]):
        raise InputError(f"{samples[-2]} and {samples[-1]} sample different points")
    inside = last["y"] < depth
    change = np.max(np.abs(last["u"] - before["u"])[inside]) / max(np.max(np.abs(last["u"][inside])), 1e-300)
    return sample_time(samples[-2]), sample_time(samples[-1]), float(change)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dir")
    ap.add_argument("--png", type=picture_file)
    ap.add_argument("--also", action="append", default=[], metavar="DIR=LABEL")
    ap.add_argument("--label", help="the run's label in the figure (default: its directory's name)")
    args = ap.parse_args()
    m = read_case(args.run_dir)
    # A steady flow needs mu_s < tan(theta) < mu_2: below, the layer stands; above, it accelerates.
    slope = math.tan(m["theta"])
    if not m["mu_s"] < slope < m["mu_2"]:
        low, high = (math.degrees(math.atan(v)) for v in (m["mu_s"], m["mu_2"]))
        raise InputError(f"{args.run_dir}: the chute's slope, {math.degrees(m['theta']):.4g} deg, has no steady mu(I) "
                         f"flow to compare with: that needs a slope between atan(mu_s) = {low:.4g} and atan(mu_2) = "
                         f"{high:.4g} deg")
    table, when = read_profile(args.run_dir)
    inertial = m["I_0"] * (math.tan(m["theta"]) - m["mu_s"]) / (m["mu_2"] - math.tan(m["theta"]))
    m_bagnold, m_own = dict(m), dict(m)
    fed = m["flux"] is not None
    if fed:  # each steady layer at its own depth for the inlet's flux
        m_bagnold["depth"], m_own["depth"] = depth_for_flux(m, False), depth_for_flux(m, True)
        m["depth"] = m_own["depth"]
    inside = table["y"] < m["depth"]
    z, u = table["y"][inside], table["u"][inside]
    surface = float(steady_profile(m_own, np.array([m_own["depth"]]), True)[0])
    bagnold, own = steady_profile(m_bagnold, z, False), steady_profile(m_own, z, True)
    print(f"{when[2:] if when.startswith('#') else when}; slope {math.degrees(m['theta']):.4g} deg, "
          f"I = {inertial:.4f}, layer {m['depth']:.4g} m")
    if fed:
        print(f"flux_m2_s = {m['flux']:.6g}")
        print(f"depth_for_flux_bagnold_m = {m_bagnold['depth']:.6g}")
        print(f"depth_for_flux_model_m = {m_own['depth']:.6g}")
        if "soil_fraction" in table:
            y = table["y"]
            spacing = float(np.mean(np.diff(y))) if len(y) > 1 else 0.0
            print(f"depth_computed_m = {float(np.sum(table['soil_fraction'])) * spacing:.6g} (the sample's soil "
                  f"fraction times its spacing)")
    print("z_m,u_computed,u_model,u_bagnold,diff_model_rel,diff_bagnold_rel")
    for k in range(len(z)):
        print(f"{z[k]:.6g},{u[k]:.6f},{own[k]:.6f},{bagnold[k]:.6f},{(u[k] - own[k]) / surface:+.5f},"
              f"{(u[k] - bagnold[k]) / surface:+.5f}")
    print(f"surface_velocity_model_m_s = {surface:.5f}")
    print(f"largest_difference_from_model = {np.max(np.abs(u - own)) / surface:.5f}")
    print(f"largest_difference_from_bagnold = {np.max(np.abs(u - bagnold)) / surface:.5f}")
    change = last_change(args.run_dir, m["depth"])
    if change is None:
        print("steadiness = null (fewer than two samples)")
        print("warning: one sample only: the run's steadiness is not known", file=sys.stderr)
    else:
        t0, t1, du = change
        print(f"steadiness = {du:.5f} (largest change of u from t = {t0:.6g} to {t1:.6g} s, relative to the "
              f"largest u at {t1:.6g} s)")
        if du > 0.01:
            print(f"warning: u changed by {100 * du:.3g} % of its largest value between the last two "
                  f"samples (t = {t0:.6g} and {t1:.6g} s): the flow is not yet steady", file=sys.stderr)
    if args.png:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fine_b, fine_m = np.linspace(0.0, m_bagnold["depth"], 200), np.linspace(0.0, m_own["depth"], 200)
        fig, ax = plt.subplots(figsize=(5, 4.5))
        ax.plot(steady_profile(m_bagnold, fine_b, False), 1e3 * fine_b, "k-", lw=1,
                label="Bagnold: tau / p = tan(theta)")
        ax.plot(steady_profile(m_own, fine_m, True), 1e3 * fine_m, "k--", lw=1, label="model: + mu_min, air")
        ax.plot(u, 1e3 * z, "o", ms=4, mfc="none", label=args.label or f"computed, {args.run_dir.rstrip('/').split('/')[-1]}")
        for item in args.also:
            run, _, label = item.partition("=")
            t, _ = read_profile(run)
            keep = t["y"] < m["depth"]
            ax.plot(t["u"][keep], 1e3 * t["y"][keep], "x", ms=4, label=label or run)
        ax.set_xlabel("u (m/s)")
        ax.set_ylabel("z (mm)")
        ax.set_title(f"mu(I) flow down a chute at {math.degrees(m['theta']):.0f} deg"
                     + (f",\nfed at q = {m['flux']:.4g} m$^2$/s through an inlet" if fed else ""))
        ax.legend(fontsize=8, loc="upper left")
        ax.grid(alpha=0.3)
        fig.tight_layout()
        fig.savefig(args.png, dpi=120)
        print(f"wrote {args.png}")


if __name__ == "__main__":
    main_with_errors(main)

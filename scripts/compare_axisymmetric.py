#!/usr/bin/python3
"""Draw and compare the axisymmetric collapses of [YS] Sec. 4 (cylinders of Lube et al. 2004 and a ring).

Usage: /usr/bin/python3 scripts/compare_axisymmetric.py OUT [--json FILE]
OUT holds one run per case and yield surface, OUT/<case>_<model>/ (as scripts/run_axisymmetric.sh
writes them); missing runs, and runs whose initial soil volume is not their case's, are skipped
with a note. x is the radius r (axis at r = 0), y the height z.
Writes into OUT (PNG):
- <case>_sections.png: the c = 0.5 surface at t = 0.1 (dotted), 0.2 (dash-dot), 0.5 s (dashed), one
  colour per model, the initial shape in grey; for the cylinders the final run-out r_inf of the law of
  Lube et al. (2004) (and h_inf = h0 for a < 0.74) as black crosses ([YS] Figs. 6, 9, 13);
- <case>_lode_rate.png: Lode angle and log10 ||D|| of the Matsuoka-Nakai run ([YS] Figs. 7, 10, 14);
- <case>_stress_ratio.png: yield stress ratio to Drucker-Prager of the MN and MC runs ([YS] Figs. 8, 11, 15);
- lode_dissipation.png: each run's share of its dissipated energy per 2-degree Lode-angle bin ([YS] Fig. 17).
and the numbers at the last output (t = 0.5 s) to OUT/axisymmetric.json (or --json FILE), with a table
on stdout. Run-out "one cell" is the outer edge of the outermost column holding at least one cell
height of soil (sum c dy >= dy); run-out "contour" is the largest r of the c = 0.5 contour.
"""
import argparse
import glob
import json
import os
import re
import sys

import numpy as np

from granflow_files import (InputError, json_file, main_with_errors, one_cell_columns, one_cell_toe,
                            read_csv, read_vtr, require_initial_volume)

MODELS = {"drucker_prager": ("Drucker-Prager", "C0", "-"), "mohr_coulomb": ("Mohr-Coulomb", "C3", "--"),
          "matsuoka_nakai": ("Matsuoka-Nakai", "C2", ":")}  # label, colour, line style (lode_dissipation.png)
# h0, r0 of the cylinders (a = h0 / r0); the soil's volume per radian (h0 r0^2 / 2; the ring's
# h0 (0.35^2 - 0.25^2) / 2), which a run must start with; the time of the Lode-angle and stress-ratio
# figures.
CASES = {"lube2004_a05": dict(h0=0.1, r0=0.2, volume=0.002, t_field=0.2, label="cylinder a = 0.5", colour="C0"),
         "lube2004_a2": dict(h0=0.2, r0=0.1, volume=0.001, t_field=0.1, label="cylinder a = 2", colour="C3"),
         "ring_collapse": dict(h0=0.1, r0=None, volume=0.003, t_field=0.2, label="ring", colour="C2")}
SECTION_TIMES = {0.1: ":", 0.2: "-.", 0.5: "--"}


def output_times(run):
    """Output stamp ('00003') -> time, from fields.pvd, else from the surface files' comment lines."""
    pvd = os.path.join(run, "fields.pvd")
    if os.path.exists(pvd):
        pairs = re.findall(r'timestep="([^"]+)"\s+file="fields_(\d{5})\.vtr"', open(pvd).read())
        if pairs:
            return {s: float(t) for t, s in pairs}
    times = {}
    for f in sorted(glob.glob(os.path.join(glob.escape(run), "surface_[0-9]*.csv"))):
        m = re.search(r"t = ([-+0-9.eE]+)", open(f).readline())
        if m:
            times[os.path.basename(f)[8:13]] = float(m.group(1))
    return times


def stamp_at(times, t):
    """The output nearest to time t (None if none within 1 ms)."""
    s = min(times, key=lambda k: abs(times[k] - t), default=None)
    return s if s is not None and abs(times[s] - t) < 1e-3 else None


def polylines(seg, tol=1e-7):
    """Join the segments x0,y0,x1,y1 sharing end points into ordered polylines (lists of (x, y))."""
    key = lambda x, y: (round(x / tol), round(y / tol))
    pts = [((seg["x0"][k], seg["y0"][k]), (seg["x1"][k], seg["y1"][k])) for k in range(len(seg["x0"]))]
    at = {}
    for k, (p, q) in enumerate(pts):
        at.setdefault(key(*p), []).append(k)
        at.setdefault(key(*q), []).append(k)
    unused, lines = set(range(len(pts))), []
    # Start at open ends first, so that open lines come out whole; closed loops after.
    starts = [k for k, (p, q) in enumerate(pts) if len(at[key(*p)]) == 1 or len(at[key(*q)]) == 1]
    for k0 in starts + list(range(len(pts))):
        if k0 not in unused:
            continue
        p, q = pts[k0]
        if len(at[key(*q)]) == 1:
            p, q = q, p
        line, k = [p, q], k0
        unused.discard(k)
        while True:
            nxt = [n for n in at[key(*line[-1])] if n in unused]
            if not nxt:
                break
            k = nxt[0]
            unused.discard(k)
            a, b = pts[k]
            line.append(b if key(*a) == key(*line[-1]) else a)
        lines.append(np.array(line))
    return lines


def lube_runout(h0, r0):
    a = h0 / r0
    return r0 * (1 + 1.24 * a) if a < 1.7 else r0 * (1 + 1.6 * a ** 0.5)


def measure(run, case, times):
    """The numbers of one run at its last output."""
    last = max(times, key=times.get)
    cols_path = os.path.join(run, f"column_height_{last}.csv")
    cols = read_csv(cols_path)
    surf = read_csv(os.path.join(run, f"surface_{last}.csv"))
    x, h = cols["x"], cols["height"]
    gx, gy, cells = read_vtr(os.path.join(run, f"fields_{last}.vtr"))
    toe = one_cell_toe(cols, cols_path)
    thick = one_cell_columns(cols, cols_path)
    west = 2 * x - cols["x_east"]  # each column's west face
    m = {"time_s": times[last],
         "runout_one_cell_m": toe,
         "runout_contour_m": float(max(surf["x0"].max(), surf["x1"].max())) if len(surf["x0"]) else 0.0}
    if CASES[case]["r0"] is None:  # ring: the highest column, and the inner front
        k = int(np.argmax(h))
        m.update(max_height_m=float(h[k]), max_height_radius_m=float(x[k]),
                 inner_front_one_cell_m=float(west[thick].min()) if thick.any() else None)
    else:
        m["central_height_m"] = float(h[0])
    hist_path = os.path.join(run, "history.csv")
    hist = read_csv(hist_path)
    require_initial_volume(hist, hist_path, CASES[case]["volume"], f"the {CASES[case]['label']} of {case}.toml")
    m.update(soil_volume_change=float(hist["soil_volume"][-1] / hist["soil_volume"][0] - 1),
             kinetic_energy_end_J_per_rad=float(hist["kinetic_energy"][-1]),
             dissipated_energy_end_J_per_rad=float(hist["dissipated_energy"][-1]))
    c = cells.get("soil_fraction")
    m["soil_fraction_range"] = [float(np.nanmin(c)), float(np.nanmax(c))] if c is not None else None
    m["fields_with_nan"] = sorted(n for n, v in cells.items() if not np.all(np.isfinite(v)))
    lode = os.path.join(run, "lode_dissipation.csv")
    if os.path.exists(lode):
        d = read_csv(lode)
        th, e = d["theta_deg"], d["energy"]
        total = e.sum()
        share = lambda sel: float(e[sel].sum() / total) if total > 0 else None
        m.update(lode_peak_theta_deg=float(th[np.argmax(e)]), lode_share_below_minus5=share(th <= -5),
                 lode_share_within_5=share(np.abs(th) < 5), lode_share_above_plus5=share(th >= 5))
    return m, (x, h)


def compare(results, columns):
    """Differences of MC and MN from DP, and the cylinders' deviations from the law of Lube et al."""
    for case, runs in results.items():
        p = CASES[case]
        if p["r0"] is not None:
            r_inf = lube_runout(p["h0"], p["r0"])
            for m in runs.values():
                m["lube_runout_m"] = r_inf
                m["runout_one_cell_deviation_from_lube"] = m["runout_one_cell_m"] / r_inf - 1
                if p["h0"] / p["r0"] < 0.74:
                    m["lube_central_height_m"] = p["h0"]
                    m["central_height_deviation_from_lube"] = m["central_height_m"] / p["h0"] - 1
        if "drucker_prager" not in runs:
            continue
        dp, (xd, hd) = runs["drucker_prager"], columns[case]["drucker_prager"]
        for model in ("mohr_coulomb", "matsuoka_nakai"):
            if model not in runs:
                continue
            if abs(runs[model]["time_s"] - dp["time_s"]) > 1e-6:
                raise InputError(f"{case}: the {model} run ends at t = {runs[model]['time_s']:g} s and the "
                                 f"drucker_prager run at {dp['time_s']:g} s; runs of one end time are compared")
            m, (x, h) = runs[model], columns[case][model]
            h = np.interp(xd, x, h, right=0.0)
            m["runout_one_cell_diff_from_dp"] = m["runout_one_cell_m"] / dp["runout_one_cell_m"] - 1
            m["runout_contour_diff_from_dp"] = m["runout_contour_m"] / dp["runout_contour_m"] - 1
            m["shape_diff_from_dp"] = float(np.sum(np.abs(h - hd) * xd) / np.sum(hd * xd))


def draw_segments(ax, seg, **kw):
    for line in polylines(seg):
        ax.plot(line[:, 0], line[:, 1], **kw)
        kw.pop("label", None)


def frame(ax, xmax, ymax):
    ax.set_xlim(0, xmax); ax.set_ylim(0, ymax); ax.set_aspect("equal")
    ax.set_xlabel("r [m]"); ax.set_ylabel("z [m]")


def figures(out, runs, times, results):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D

    def save(fig, name):
        fig.savefig(os.path.join(out, name), dpi=110)
        plt.close(fig)
        print(f"wrote {os.path.join(out, name)}")

    for case, p in CASES.items():
        have = {m: runs[(case, m)] for m in MODELS if (case, m) in runs}
        if not have:
            continue
        any_run = next(iter(have.values()))
        gx, gy, _ = read_vtr(os.path.join(any_run, f"fields_{min(times[any_run])}.vtr"))
        # 1. Sections: the whole width of the domain, up to 1.3 h0.
        xmax, ymax = gx[-1], min(gy[-1], 1.3 * p["h0"])
        fig, ax = plt.subplots(figsize=(10, 10 * ymax / xmax + 1.6))
        t0 = stamp_at(times[any_run], 0.0)
        if t0:
            draw_segments(ax, read_csv(os.path.join(any_run, f"surface_{t0}.csv")), color="0.6", lw=0.8)
        for model, run in have.items():
            for t, ls in SECTION_TIMES.items():
                s = stamp_at(times[run], t)
                if s:
                    draw_segments(ax, read_csv(os.path.join(run, f"surface_{s}.csv")), color=MODELS[model][1],
                                  ls=ls, lw=1.3)
        handles = [Line2D([], [], color=MODELS[m][1], label=MODELS[m][0]) for m in have]
        handles += [Line2D([], [], color="k", ls=ls, label=f"t = {t:g} s") for t, ls in SECTION_TIMES.items()]
        handles.append(Line2D([], [], color="0.6", lw=0.8, label="t = 0"))
        if p["r0"] is not None:
            r_inf = lube_runout(p["h0"], p["r0"])
            ax.plot([r_inf], [0], "kx", ms=10, mew=2, clip_on=False)
            label = f"Lube et al. (2004): r_inf = {r_inf:.3f} m"
            if p["h0"] / p["r0"] < 0.74:
                ax.plot([0], [p["h0"]], "kx", ms=10, mew=2, clip_on=False)
                label += f", h_inf = {p['h0']:g} m"
            handles.append(Line2D([], [], color="k", marker="x", ls="", mew=2, label=label))
        frame(ax, xmax, ymax)
        ax.legend(handles=handles, fontsize=8, loc="upper right", ncol=2)
        ax.set_title(f"{case} ({p['label']}): c = 0.5 sections ([YS] Fig. "
                     f"{ {'lube2004_a05': 6, 'lube2004_a2': 9, 'ring_collapse': 13}[case]})", fontsize=10)
        fig.tight_layout()
        save(fig, f"{case}_sections.png")

        # 2. and 3. Fields at t_field, masked to c > 0.5, cropped to the pile.
        def load(run):
            s = stamp_at(times[run], p["t_field"])
            if s is None:
                return None
            fx, fy, cells = read_vtr(os.path.join(run, f"fields_{s}.vtr"))
            return fx, fy, cells, read_csv(os.path.join(run, f"surface_{s}.csv")), times[run][s]

        def field_figure(panels, fname):
            """panels: (data from load, field name, transform, colormap, vmin, vmax, title, colour bar label)."""
            panels = [q for q in panels if q[0] is not None]
            if not panels:
                return
            surf = panels[0][0][3]
            xmax = min(gx[-1], max(surf["x0"].max(), surf["x1"].max()) + 0.03) if len(surf["x0"]) else gx[-1]
            ymax = min(gy[-1], max(surf["y0"].max(), surf["y1"].max()) + 0.02) if len(surf["y0"]) else gy[-1]
            h = min(4.5, 9 * ymax / xmax)  # panel height [in]; tall piles get narrower panels
            fig, axes = plt.subplots(len(panels), 1, squeeze=False,
                                     figsize=(h * xmax / ymax + 3, len(panels) * (h + 0.9) + 0.3))
            for ax, ((fx, fy, cells, sf, t), name, tr, cmap, vmin, vmax, title, cbar) in zip(axes[:, 0], panels):
                v = np.ma.masked_where(~(cells["soil_fraction"] > 0.5), tr(cells[name]))
                im = ax.pcolormesh(fx, fy, v, cmap=cmap, vmin=vmin, vmax=vmax, shading="flat")
                draw_segments(ax, sf, color="k", lw=1.0)
                frame(ax, xmax, ymax)
                fig.colorbar(im, ax=ax, label=cbar, shrink=0.9)
                ax.set_title(f"{case}, {title}, t = {t:g} s", fontsize=10)
            fig.tight_layout()
            save(fig, fname)

        mn, mc = (load(have[m]) if m in have else None for m in ("matsuoka_nakai", "mohr_coulomb"))
        field_figure([(mn, "lode_angle", lambda v: v, "RdBu_r", -30, 30, "Matsuoka-Nakai: Lode angle",
                       "theta [deg]"),
                      (mn, "strain_rate_norm", lambda v: np.log10(np.maximum(v, 1e-6)), "viridis", -2, 2,
                       "Matsuoka-Nakai: strain rate", "log10 ||D|| [1/s]")], f"{case}_lode_rate.png")
        # One colour range for both stress-ratio panels, from the soil cells of both runs.
        vals = np.concatenate([d[2]["stress_ratio_to_drucker_prager"][d[2]["soil_fraction"] > 0.5]
                               for d in (mn, mc) if d is not None] + [np.zeros(0)])
        lo, hi = np.nanpercentile(vals, [0.5, 99.5]) if np.isfinite(vals).any() else (0.8, 1.2)
        field_figure([(d, "stress_ratio_to_drucker_prager", lambda v: v, "viridis", lo, hi,
                       f"{lab} / Drucker-Prager", "yield stress ratio to DP")
                      for d, lab in ((mn, "Matsuoka-Nakai"), (mc, "Mohr-Coulomb"))], f"{case}_stress_ratio.png")

    # 4. Dissipated energy by Lode angle.
    fig, ax = plt.subplots(figsize=(8, 4.5))
    for (case, model), run in runs.items():
        path = os.path.join(run, "lode_dissipation.csv")
        if not os.path.exists(path):
            continue
        d = read_csv(path)
        total = d["energy"].sum()
        if total > 0:
            ax.plot(d["theta_deg"], d["energy"] / total, color=CASES[case]["colour"], ls=MODELS[model][2],
                    marker=".", lw=1.3, label=f"{CASES[case]['label']}, {MODELS[model][0]}")
    ax.set_xlim(-31, 31)
    ax.set_xlabel("Lode angle theta [deg] (2-degree bins)")
    ax.set_ylabel("share of the run's dissipated energy")
    ax.set_title("Dissipated energy up to t = 0.5 s by Lode angle ([YS] Fig. 17)", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    save(fig, "lode_dissipation.png")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out", help="directory holding <case>_<model>/ runs; the PNGs go here")
    ap.add_argument("--json", type=json_file, help="default OUT/axisymmetric.json")
    a = ap.parse_args()
    runs, times, results, columns = {}, {}, {}, {}
    for case in CASES:
        for model in MODELS:
            run = os.path.join(a.out, f"{case}_{model}")
            t = output_times(run) if os.path.isdir(run) else {}
            if not t:
                print(f"note: {run}: missing or no outputs, skipped")
                continue
            try:
                m, cols = measure(run, case, t)
            except (InputError, OSError, ValueError, IndexError, KeyError) as e:
                print(f"note: {run}: skipped ({type(e).__name__}: {e})")
                continue
            runs[(case, model)], times[run] = run, t
            results.setdefault(case, {})[model] = m
            columns.setdefault(case, {})[model] = cols
    if not runs:
        sys.exit(f"error: no runs in {a.out}")
    compare(results, columns)

    print(f"{'case':14} {'model':15} {'t':>4} {'ro 1cell':>8} {'ro c.5':>7} {'height':>7} {'dV/V':>8} "
          f"{'KE end':>8} {'diss':>7} {'dRo1/DP':>8} {'shape':>7} {'vs Lube':>8} {'peak':>5} "
          f"{'<=-5':>5} {'|.|<5':>5} {'>=5':>5}")
    f = lambda v, fmt: format(v, fmt) if isinstance(v, (int, float)) else "-"
    for case, ms in results.items():
        for model, m in ms.items():
            height = m.get("central_height_m", m.get("max_height_m"))
            print(f"{case:14} {model:15} {m['time_s']:4.2g} {m['runout_one_cell_m']:8.4f} "
                  f"{m['runout_contour_m']:7.4f} {height:7.4f} {m['soil_volume_change']:8.1e} "
                  f"{m['kinetic_energy_end_J_per_rad']:8.2e} {m['dissipated_energy_end_J_per_rad']:7.4f} "
                  f"{f(m.get('runout_one_cell_diff_from_dp'), '+8.4f'):>8} {f(m.get('shape_diff_from_dp'), '7.4f'):>7} "
                  f"{f(m.get('runout_one_cell_deviation_from_lube'), '+8.3f'):>8} "
                  f"{f(m.get('lode_peak_theta_deg'), '5.0f'):>5} {f(m.get('lode_share_below_minus5'), '5.2f'):>5} "
                  f"{f(m.get('lode_share_within_5'), '5.2f'):>5} {f(m.get('lode_share_above_plus5'), '5.2f'):>5}")
            if m["fields_with_nan"]:
                print(f"  warning: NaN in {', '.join(m['fields_with_nan'])}")
    over = max(max(-m["soil_fraction_range"][0], m["soil_fraction_range"][1] - 1)
               for ms in results.values() for m in ms.values() if m["soil_fraction_range"])
    if over > 1e-9:
        print(f"note: the soil fraction leaves [0, 1] by up to {over:.1e} at the last outputs")
    print("height: central column (ring: highest column, radius in the JSON); ro = run-out [m]; "
          "dRo1/DP, shape: MC/MN vs DP; vs Lube: one-cell run-out / r_inf - 1; last 4: Lode-angle peak [deg] "
          "and shares of dissipated energy")
    path = a.json or os.path.join(a.out, "axisymmetric.json")
    with open(path, "w") as fh:
        json.dump({"out": a.out, "cases": results}, fh, indent=1)
    print(f"wrote {path}")
    figures(a.out, runs, times, results)
    return 0


if __name__ == "__main__":
    main_with_errors(main)

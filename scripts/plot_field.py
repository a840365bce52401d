#!/usr/bin/python3
"""A field of a run at one output time, to PNG: any cell field of its fields_NNNNN.vtr, with the soil's
surface (c = 0.5) and, where the run wrote one, its failure line (dashed), as the run wrote them.

Usage: plot_field.py OUT [--field NAME] [--time T | --output N] [--component x|y|magnitude]
                         [--soil-only] [--log] [--png FILE]

Without --png it lists the run's output times and the fields of the chosen output. --time takes the
output nearest T (within the outputs' span, half an interval either side), --output N the N-th (from 0, the initial state); the default is the last. A vector
field (velocity, displacement) is drawn as its magnitude unless --component says x or y. --soil-only
leaves out the cells with c < 0.5; --log draws log10 of the absolute value (for the viscosity, which
spans ten decades), from the smallest non-zero magnitude, at most 14 decades below the largest (cells of
0, as air at rest, are drawn at that floor). Blocked cells (obstacles, terrain) and left-out cells are drawn grey. Fields and
units: docs/output.md.
"""
import argparse
import os
import re
import sys

import numpy as np

from granflow_files import InputError, figure_size, finite, main_with_errors, picture_file, read_csv, read_vtr

UNITS = {"velocity": "m/s", "pressure": "Pa", "density": "kg/m^3", "viscosity": "Pa s",
         "displacement": "m", "strain_rate_norm": "1/s", "lode_angle": "degrees"}


def outputs(out):
    """(time, file) of each output of the run, in order, from OUT/fields.pvd."""
    path = os.path.join(out, "fields.pvd")
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        raise InputError(f"cannot read {path}: {e.strerror} (a run with output.fields = true writes it)")
    found = re.findall(r'<DataSet timestep="([^"]+)" file="([^"]+)"', text)
    if not found:
        raise InputError(f"{path}: lists no fields file")
    return [(float(t), name) for t, name in found]


def segments(path):
    """The segments of a line CSV the run wrote (x0, y0, x1, y1), or None if there is no such file."""
    if not os.path.exists(path):
        return None
    table = read_csv(path)
    if not all(k in table for k in ("x0", "y0", "x1", "y1")):
        raise InputError(f"{path}: no columns x0, y0, x1, y1")
    return np.stack([np.column_stack([table["x0"], table["y0"]]),
                     np.column_stack([table["x1"], table["y1"]])], axis=1)


def main():
    ap = argparse.ArgumentParser(description="Draw a cell field of a granflow run at one output time.")
    ap.add_argument("out", help="the run's output directory")
    ap.add_argument("--field", help="the field to draw (listed without --png)")
    when = ap.add_mutually_exclusive_group()
    when.add_argument("--time", type=finite, help="the output nearest this time, s")
    when.add_argument("--output", type=int, help="the output of this number (0 the initial state)")
    ap.add_argument("--component", choices=("x", "y", "magnitude"), default="magnitude",
                    help="of a vector field (default magnitude)")
    ap.add_argument("--soil-only", action="store_true", help="leave out cells with c < 0.5")
    ap.add_argument("--log", action="store_true", help="draw log10 of the absolute value")
    ap.add_argument("--png", type=picture_file, help="the picture to write")
    a = ap.parse_args()

    runs = outputs(a.out)
    if a.output is not None:
        if not 0 <= a.output < len(runs):
            raise InputError(f"{a.out}: no output {a.output}; it has outputs 0 to {len(runs) - 1}")
        index = a.output
    elif a.time is not None:
        # Nearest, within the run's outputs: a time outside them is a slip (a sign, a unit), not a request
        # for the first or last output.
        first, last = runs[0][0], runs[-1][0]
        spacing = (last - first) / max(len(runs) - 1, 1)
        if not first - 0.5 * spacing <= a.time <= last + 0.5 * spacing:
            raise InputError(f"--time {a.time:g}: the run's outputs lie from t = {first:g} to {last:g} s")
        index = int(np.argmin([abs(t - a.time) for t, _ in runs]))
    else:
        index = len(runs) - 1
    time, name = runs[index]
    x, y, cells = read_vtr(os.path.join(a.out, name))

    if not a.png:
        print(f"{len(runs)} output{'' if len(runs) == 1 else 's'}: " + ", ".join(f"{k} (t = {t:g} s)" for k, (t, _) in enumerate(runs)))
        print(f"fields of output {index}: " + ", ".join(
            f"{k} ({v.shape[2]} components)" if v.ndim == 3 else k for k, v in sorted(cells.items())))
        if a.field:
            print("give --png FILE to draw it")
        return 0
    if not a.field:
        raise InputError("--png needs --field NAME (run without --png to list the fields)")
    if a.field not in cells:
        raise InputError(f"{name} has no field {a.field}; it has {', '.join(sorted(cells))}")

    value = cells[a.field]
    label = a.field
    if value.ndim != 3 and a.component != "magnitude":
        raise InputError(f"--component {a.component}: {a.field} is a scalar field; --component is for vector fields")
    if value.ndim == 3:
        if a.component == "magnitude":
            value = np.hypot(value[..., 0], value[..., 1])
            label = f"|{a.field}|"
        else:
            value = value[..., 0 if a.component == "x" else 1]
            label = f"{a.field} {a.component}"
    unit = UNITS.get(a.field, "-")
    if a.log:
        # Cells at exactly 0 (air at rest) would set the scale at 1e-300 and squeeze every other value
        # into one colour: the floor is the smallest non-zero magnitude, but at most 14 decades below
        # the largest (the viscosity spans about 13).
        magnitude = np.abs(value)
        nonzero = magnitude[np.isfinite(magnitude) & (magnitude > 0)]
        if nonzero.size == 0:
            raise InputError(f"--log: every value of {label} is 0 (or not finite); draw it without --log")
        floor = max(nonzero.min(), nonzero.max() * 1e-14)
        if (np.nanmin(value) < 0) and (np.nanmax(value) > 0):
            print(f"note: --log draws log10 of the magnitude; {label} takes both signs", file=sys.stderr)
        value = np.log10(np.maximum(magnitude, floor))
        label = f"log10 {label} ({unit})"
    else:
        label = f"{label} ({unit})"
    c = cells.get("soil_fraction")
    if a.soil_only:
        if c is None:
            raise InputError(f"{name}: no soil_fraction, so --soil-only has no soil to keep")
        if not (c >= 0.5).any():
            raise InputError(f"{name}: no cell holds soil (c >= 0.5), so --soil-only leaves nothing to draw")
        value = np.ma.masked_where(c < 0.5, value)
    # Blocked cells (obstacles, terrain) hold no flow: drawn grey, outside the colour scale.
    blocked = cells.get("obstacle")
    if blocked is not None and a.field != "obstacle" and (blocked > 0.5).any():
        value = np.ma.masked_where(np.asarray(blocked) > 0.5, value)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.collections import LineCollection

    width, height = x[-1] - x[0], y[-1] - y[0]
    fig, ax = plt.subplots(figsize=figure_size(width, height))
    if np.ma.count(value) == 0:
        raise InputError(f"{name}: no cell of {a.field} is left to draw")
    ax.set_facecolor("0.6")  # where cells are left out: grey
    m = ax.pcolormesh(x, y, value, cmap="viridis", shading="flat")
    fig.colorbar(m, ax=ax, label=label)
    stem = os.path.splitext(name)[0].replace("fields_", "")
    for csv, style in ((f"surface_{stem}.csv", "-"), (f"failure_line_{stem}.csv", "--")):
        lines = segments(os.path.join(a.out, csv))
        if lines is not None and len(lines):
            ax.add_collection(LineCollection(lines, colors="w", linewidths=1.2, linestyles=style))
    ax.set_xlim(x[0], x[-1])
    ax.set_ylim(y[0], y[-1])
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(f"{os.path.basename(os.path.normpath(a.out))}: {a.field} at t = {time:g} s", fontsize=10)
    fig.tight_layout()
    fig.savefig(a.png, dpi=120)
    print(f"wrote {a.png} ({label} from {value.min():.4g} to {value.max():.4g})")
    return 0


if __name__ == "__main__":
    main_with_errors(main)

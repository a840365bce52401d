"""Reading granflow's output (CSV tables, VTK fields) and the reference data, for the comparison scripts.

A missing or malformed file is an InputError naming the file; `main_with_errors` turns it (and any
unreadable file) into one line `error: ...` and exit status 1 instead of a traceback.
"""
import argparse
import glob
import math
import os
import re
import sys
import tomllib
import zlib

import numpy as np


class InputError(Exception):
    pass


def read_csv(path):
    """Columns of a CSV file with one header line; lines starting with '#' are comments."""
    try:
        with open(path) as f:
            text = f.read()
    except OSError as e:
        raise InputError(f"cannot read {path}: {e.strerror}")
    except UnicodeDecodeError:
        raise InputError(f"{path}: not a text file")
    # granflow writes whole files, each line ended: a last line without its end was cut short, and its
    # last number may be only the start of one (-8.17 of -8.17e-16).
    if text and not text.endswith("\n"):
        raise InputError(f"{path}: its last line has no line end (the file was cut short?)")
    lines = text.splitlines()
    rows = [l.strip() for l in lines if l.strip() and not l.startswith("#")]
    if not rows:
        raise InputError(f"{path}: no header line")
    header = rows[0].split(",")
    for r in rows[1:]:
        if r.count(",") != len(header) - 1:  # a short row would otherwise shift the rows after it
            raise InputError(f"{path}: the row '{r[:80]}' has {r.count(',') + 1} fields, the header {len(header)}")
    try:
        data = np.array([[float(x) for x in r.split(",")] for r in rows[1:]]).reshape(-1, len(header))
    except ValueError:
        raise InputError(f"{path}: not a table of numbers under the header {rows[0]}")
    return {h: data[:, k] for k, h in enumerate(header)}


def read_run_case(run_dir):
    """(the case as a run took it, RUN_DIR/granflow_case.toml, as a dict; its path)."""
    path = os.path.join(run_dir, "granflow_case.toml")
    try:
        with open(path, "rb") as f:
            return tomllib.load(f), path
    except OSError as e:
        raise InputError(f"cannot read {path}: {e.strerror}")
    except tomllib.TOMLDecodeError as e:
        raise InputError(f"{path}: {e}")


def require_rows(table, path):
    """A table with rows under its header (a run stopped before writing any has none)."""
    if not table or len(next(iter(table.values()))) == 0:
        raise InputError(f"{path}: no rows under its header (the run stopped before it wrote any?)")
    return table


def finite(text):
    """argparse type: a finite number."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number")
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"'{text}' is not a finite number")
    return value


def positive(text):
    """argparse type: a finite number above zero."""
    value = finite(text)
    if not value > 0:
        raise argparse.ArgumentTypeError(f"'{text}' is not a finite number above zero")
    return value


PICTURE_SUFFIXES = (".png", ".pdf", ".svg")


def figure_size(width, height):
    """A figure's size in inches for a frame of width x height drawn to scale with a colour bar beside
    it: 9 inches wide for a wide frame, 9 high for a tall one."""
    if height <= width:
        return 9.0, max(2.5, 7.5 * height / width + 1.0)
    return max(4.0, 7.5 * width / height + 2.2), 9.0


def picture_file(text):
    """argparse type for --png: a file name ending in .png (or .pdf, .svg); without a suffix, .png is
    added, as matplotlib would, so that the name said is the file written."""
    suffix = os.path.splitext(text)[1].lower()
    if not suffix:
        return text + ".png"
    if suffix not in PICTURE_SUFFIXES:
        raise argparse.ArgumentTypeError(f"'{text}': a picture ends in {', '.join(PICTURE_SUFFIXES)}")
    return text


def json_file(text):
    """argparse type for --json: a file name ending in .json, so that a slip of the keyboard does not
    write the numbers over a run's own file (its history.csv, say)."""
    if not text.lower().endswith(".json"):
        raise argparse.ArgumentTypeError(f"'{text}': the numbers go to a file ending in .json")
    return text


def sample_time(path):
    """The time on an output CSV's first line ('# ... at t = T s')."""
    with open(path) as f:
        m = re.search(r"t = ([-+0-9.eE]+)", f.readline())
    if not m:
        raise InputError(f"{path}: first line does not give the time ('# ... at t = T s')")
    return float(m.group(1))


def require_columns(table, path, names):
    missing = [n for n in names if n not in table]
    if missing:
        raise InputError(f"{path}: no column {', '.join(missing)} (has {', '.join(table)})")


def one_cell_columns(columns, path):
    """Which columns of a column_height_NNNNN.csv hold a layer at least one cell thick: whose soil
    height (sum of c dy) reaches the floor cell's height, as the history's toe_one_cell reads it."""
    if "x_east" not in columns or "floor_cell_height" not in columns:
        raise InputError(f"{path}: no columns x_east, floor_cell_height (written by an earlier granflow; run the "
                         "case again)")
    require_columns(columns, path, ["height"])
    return columns["height"] >= columns["floor_cell_height"] * (1 - 1e-9)


def one_cell_toe(columns, path):
    """Toe of a layer at least one cell thick: the east face of the farthest such column."""
    thick = one_cell_columns(columns, path)
    return float(columns["x_east"][thick].max()) if thick.any() else 0.0


def require_initial_volume(history, path, expected, what):
    """The run's soil (or water) volume, from its history's first row, is that of the case the script
    compares with (to 2 %): a run of another case is not scored against the wrong data."""
    require_columns(history, path, ["soil_volume"])
    if len(history["soil_volume"]) == 0:
        raise InputError(f"{path}: no rows (the run took no step)")
    volume = float(history["soil_volume"][0])
    if abs(volume / expected - 1) > 0.02:
        raise InputError(f"{path}: the run's initial volume is {volume:.6g}, not the {expected:.6g} of {what}; "
                         "a run of another case?")


def read_vtr(path):
    """VTK RectilinearGrid as granflow writes it: node coordinates x, y and cell arrays shaped
    (ny, nx[, ncomp]). Cell arrays are zlib-compressed in the appended section (header_type UInt64);
    files written before that hold them as text, and are read too."""
    try:
        with open(path, "rb") as f:
            raw = f.read()
    except OSError as e:
        raise InputError(f"cannot read {path}: {e.strerror}")
    try:
        return _parse_vtr(raw, path)
    except InputError:
        raise
    except (ValueError, KeyError, IndexError, AttributeError, UnicodeDecodeError, zlib.error) as e:
        raise InputError(f"{path}: not a whole fields file (damaged, or cut short)") from e


def _parse_vtr(raw, path):
    head, _, appended = raw.partition(b'<AppendedData encoding="raw">')
    text = head.decode()
    blob = appended[appended.index(b"_") + 1:] if appended else b""
    arrays = {}
    for attrs, body in re.findall(r"<DataArray([^>]*?)(?:/>|>([^<]*)</DataArray>)", text):
        name = re.search(r'Name="([^"]+)"', attrs).group(1)
        ncomp = int((re.search(r'NumberOfComponents="(\d+)"', attrs) or [0, 1])[1])
        if 'format="ascii"' in attrs:
            arrays[name] = (np.array(body.split(), dtype=float), ncomp)
        elif 'format="appended"' in attrs:
            at = int(re.search(r'offset="(\d+)"', attrs).group(1))
            blocks = int(np.frombuffer(blob, "<u8", 1, at)[0])
            sizes = np.frombuffer(blob, "<u8", blocks, at + 24)
            start, parts = at + 8 * (3 + blocks), []
            for size in sizes:
                parts.append(zlib.decompress(blob[start:start + int(size)]))
                start += int(size)
            arrays[name] = (np.frombuffer(b"".join(parts), "<f8"), ncomp)
        else:
            raise InputError(f"{path}: array {name} is neither text nor appended")
    x, y = arrays.pop("x")[0], arrays.pop("y")[0]
    nx, ny = len(x) - 1, len(y) - 1
    cells = {n: v.reshape(ny, nx, c) if c > 1 else v.reshape(ny, nx)
             for n, (v, c) in arrays.items() if v.size == nx * ny * c}
    return x, y, cells


def column_heights(run_dir):
    """{output index: (time, table)} of RUN_DIR/column_height_*.csv."""
    out = {}
    for path in sorted(glob.glob(os.path.join(run_dir, "column_height_*.csv"))):
        index = int(os.path.basename(path)[len("column_height_"):-len(".csv")])
        with open(path) as f:
            first = f.readline()
        try:
            time = float(first.split("t =")[1].split()[0])
        except (IndexError, ValueError):
            raise InputError(f"{path}: no time in its first line")
        out[index] = (time, read_csv(path))
    if not out:
        raise InputError(f"{run_dir}: no column_height_*.csv (not a run of a soil case?)")
    return out


def main_with_errors(main):
    try:
        sys.exit(main())
    except InputError as e:
        sys.exit(f"error: {e}")
    except OSError as e:
        sys.exit(f"error: {e.filename or ''}: {e.strerror}")

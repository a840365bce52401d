"""Reading granflow's CSV output and the reference data, for the comparison scripts.

A missing or malformed file is an InputError naming the file; `main_with_errors` turns it (and any
unreadable file) into one line `error: ...` and exit status 1 instead of a traceback.
"""
import sys

import numpy as np


class InputError(Exception):
    pass


def read_csv(path):
    """Columns of a CSV file with one header line; lines starting with '#' are comments."""
    try:
        with open(path) as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise InputError(f"cannot read {path}: {e.strerror}")
    rows = [l.strip() for l in lines if l.strip() and not l.startswith("#")]
    if not rows:
        raise InputError(f"{path}: no header line")
    header = rows[0].split(",")
    try:
        data = np.array([[float(x) for x in r.split(",")] for r in rows[1:]]).reshape(-1, len(header))
    except ValueError:
        raise InputError(f"{path}: not a table of numbers under the header {rows[0]}")
    return {h: data[:, k] for k, h in enumerate(header)}


def require_columns(table, path, names):
    missing = [n for n in names if n not in table]
    if missing:
        raise InputError(f"{path}: no column {', '.join(missing)} (has {', '.join(table)})")


def main_with_errors(main):
    try:
        sys.exit(main())
    except InputError as e:
        sys.exit(f"error: {e}")
    except OSError as e:
        sys.exit(f"error: {e.filename or ''}: {e.strerror}")

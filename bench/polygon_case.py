#!/usr/bin/python3
"""Write the shipped Bui case with its block replaced by a polygon of many vertices (a floor and a
wavy surface), to time laying such a shape on a mesh (docs/benchmarks.md, "Initial shapes of many
vertices").

Usage: bench/polygon_case.py VERTICES OUT.toml
"""
import math
import os
import sys

if len(sys.argv) != 3 or not sys.argv[1].isdigit() or int(sys.argv[1]) < 2:
    sys.exit("usage: bench/polygon_case.py VERTICES OUT.toml (VERTICES a whole number, at least 2)")
n = int(sys.argv[1])
here = os.path.dirname(os.path.abspath(__file__))
case = open(os.path.join(here, "..", "cases", "bui2008_experiment.toml")).read()
block = '[[initial.soil]]\nshape = "box"\nlower = [0.0, 0.0]\nupper = [0.2, 0.1]'
if block not in case:
    sys.exit("error: cases/bui2008_experiment.toml no longer holds the block this script replaces")
points = [(0.6, 0.0), (0.0, 0.0)]
for k in range(n):
    x = 0.6 * k / (n - 1)
    points.append((x, 0.05 + 0.03 * math.sin(40 * x) + 0.005 * math.sin(977 * x)))
polygon = '[[initial.soil]]\nshape = "polygon"\npoints = [' + ",".join(f"[{x:.9f},{y:.9f}]" for x, y in points) + "]"
with open(sys.argv[2], "w") as out:
    out.write(case.replace(block, polygon))

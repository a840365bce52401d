#!/usr/bin/env bash
# The main job: the lid-driven cavity at Re 1000 (128 x 128) to steady state, with its comparison
# against Ghia, Ghia & Shin (1982) as a PNG. Output in out/lid_driven_cavity_re1000/.
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/lid_driven_cavity_re1000
build/granflow run cases/lid_driven_cavity_re1000.toml -o "$out"
/usr/bin/python3 scripts/compare_cavity.py "$out" 1000 --png "$out/comparison_ghia1982.png"
echo "main job: results in $out (fields.pvd for ParaView, comparison_ghia1982.png)"

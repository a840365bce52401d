#!/usr/bin/env bash
# The main job: the bui2008_experiment collapse at the paper's resolution (300 x 100 cells) to
# t = 2 s, with its comparison against the experiment of Bui et al. (2008) as a PNG.
# Output in out/bui2008_experiment/ (fields.pvd for ParaView, surfaces, failure lines, history).
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/bui2008_experiment
build/granflow run cases/bui2008_experiment.toml -o "$out"
/usr/bin/python3 scripts/compare_bui2008.py "$out" --png "$out/comparison_bui2008.png" --json "$out/comparison.json"
echo "main job: results in $out (fields.pvd for ParaView, comparison_bui2008.png)"

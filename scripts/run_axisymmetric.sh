#!/usr/bin/env bash
# The axisymmetric collapses of [YS] Sec. 4 (lube2004_a05, lube2004_a2, ring_collapse), each with the
# Drucker-Prager, Mohr-Coulomb and Matsuoka-Nakai yield surfaces, then their comparison figures.
#   scripts/run_axisymmetric.sh [--coarse] [OUT]
# --coarse halves the cells per axis (3.33 mm instead of the paper's 1.67 mm), for a quick look.
# Output: OUT/<case>_<model>/ per run (default OUT = out/axisymmetric), OUT/<case>_*.png and
# OUT/axisymmetric.json with the numbers docs/validation.md quotes. Runs already finished on the
# same mesh (their lode_dissipation.csv stamped at the end time, their columns as many as asked) are
# not run again.
set -euo pipefail
cd "$(dirname "$0")/.."
coarse=0
if [ "${1:-}" = "--coarse" ]; then coarse=1; shift; fi
out=${1:-out/axisymmetric}
mkdir -p "$out"
declare -A cells=([lube2004_a05]="150,60" [lube2004_a2]="120,90" [ring_collapse]="180,45")
for case in lube2004_a05 lube2004_a2 ring_collapse; do
  extra=()
  columns=$(( 2 * ${cells[$case]%%,*} ))
  if [ $coarse = 1 ]; then extra=(--set "mesh.cells=[${cells[$case]}]"); columns=${cells[$case]%%,*}; fi
  for model in drucker_prager mohr_coulomb matsuoka_nakai; do
    dir="$out/${case}_${model}"
    last_columns=$(ls "$dir"/column_height_*.csv 2>/dev/null | tail -n 1 || true)
    if grep -qs "up to t = 0.5 s" "$dir/lode_dissipation.csv" && [ -n "$last_columns" ] &&
       grep -q '^x,height,x_east,floor_cell_height' "$last_columns" &&
       [ "$(grep -vc -e '^#' -e '^x,' "$last_columns")" = "$columns" ]; then
      continue
    fi
    build/granflow run "cases/$case.toml" -o "$dir" --overwrite --set soil.rheology.model="$model" "${extra[@]}"
  done
done
/usr/bin/python3 scripts/compare_axisymmetric.py "$out"

#!/usr/bin/env bash
# Whole-run benchmarks of granflow on 1 and 2 MPI ranks (wall seconds, steps, peak memory, iterations).
# Usage: bench/run_benchmarks.sh [cavity|bui2008|dam_break|lube2004|column_3d|column_3d_projection|all] [repetitions]
# Prints one Markdown table row per run; docs/benchmarks.md holds the figures and this command.
set -euo pipefail
cd "$(dirname "$0")/.."
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
which="${1:-all}"
reps="${2:-1}"
case $which in
  cavity | bui2008 | dam_break | lube2004 | column_3d | column_3d_projection | all) ;;
  *) echo "error: run_benchmarks.sh takes cavity, bui2008, dam_break, lube2004, column_3d, column_3d_projection or all, not '$which'" >&2; exit 2 ;;
esac
run() {  # name ranks case overrides...
  local name=$1 ranks=$2 case=$3
  shift 3
  for r in $(seq "$reps"); do
    local out log
    out=$(mktemp -d)
    log="$out/log"
    local start end
    start=$(date +%s.%N)
    if ! mpirun -np "$ranks" --oversubscribe build/granflow run "$case" -o "$out" --set output.progress_seconds=0 \
      --set output.fields=false "$@" > "$log" 2>&1; then
      echo "error: $name on $ranks ranks failed; its last lines:" >&2
      tail -n 5 "$log" >&2
      rm -rf "$out"
      exit 1
    fi
    end=$(date +%s.%N)
    local steps its peak
    steps=$(grep -oP 'in \K[0-9]+(?= steps)' "$log")
    peak=$(grep -oP '^peak memory \K[0-9]+(?= MB)' "$log")
    its=$(grep -oP 'outer iterations \K.*(?= iterations each)' "$log" | sed -E 's/ \(numerics\.outer_iterations[^)]*\)//; s/momentum iterations //; s/(pressure|coupled \(velocity and pressure\)) solves //; s/ \(/, /')
    printf "| %s | %d | %.1f | %s | %s | %s |\n" "$name" "$ranks" "$(awk -v a="$start" -v b="$end" 'BEGIN { print b - a }')" "$steps" "$peak" "$its"
    rm -rf "$out"
  done
}
echo "| run | ranks | wall s | steps | peak MB (all ranks) | outer its, momentum its, pressure (or coupled) solves, its/solve |"
echo "|---|---|---|---|---|---|"
if [[ $which == cavity || $which == all ]]; then
  for n in 1 2; do run "cavity Re 1000, 256 x 256, to steady state" $n cases/lid_driven_cavity_re1000.toml "--set" "mesh.cells=[256,256]" "--set" "time.end=400"; done
fi
if [[ $which == bui2008 || $which == all ]]; then
  # to t = 1 s, as the OpenFOAM reference run of docs/benchmarks.md (115 s)
  for n in 1 2; do run "bui2008_experiment 300 x 100 to t = 1 s" $n cases/bui2008_experiment.toml "--set" "time.end=1.0"; done
  # the step the case had before its thin front was converged in the step: Courant 1, two VoF sweeps
  # and two outer iterations per step
  courant_one=("--set" "time.courant=1" "--set" "time.interface_substeps=2" "--set" "numerics.outer_iterations=2"
               "--set" "numerics.viscosity_pressure=mean_of_last_two")
  for n in 1 2; do run "bui2008_experiment 300 x 100 to t = 1 s, Courant 1" $n cases/bui2008_experiment.toml \
    "--set" "time.end=1.0" "${courant_one[@]}"; done
  # that with one factorisation per step (the later outer iteration by the first's factorisation)
  for n in 1 2; do run "bui2008_experiment 300 x 100 to t = 1 s, Courant 1, one factorisation per step" $n \
    cases/bui2008_experiment.toml "--set" "time.end=1.0" "${courant_one[@]}" \
    "--set" "numerics.later_iterations=first_factorisation"; done
  # the same with the coupled solve over the whole domain instead of the soil and its air band
  for n in 1 2; do run "bui2008_experiment 300 x 100 to t = 1 s, whole domain" $n cases/bui2008_experiment.toml "--set" "time.end=1.0" \
    "--set" "numerics.air_band=0"; done
  # the same collapse with mu(I) friction (the numerics of Courant 1 above; it comes to rest sooner)
  for n in 1 2; do run "bui2008_experiment_mu_of_i 300 x 100 to t = 1 s" $n cases/bui2008_experiment_mu_of_i.toml "--set" "time.end=1.0"; done
  # the same with the projection and the cells' mixtures, one VoF sweep per step and three outer
  # iterations from the last step's velocity (faster; the pile does not come to rest)
  for n in 1 2; do run "bui2008_experiment 300 x 100 to t = 1 s, projection" $n cases/bui2008_experiment.toml "--set" "time.end=1.0" \
    "${courant_one[@]}" "--set" "numerics.pressure_coupling=projection" "--set" "numerics.air_band=0" "--set" "soil.face_fraction=cells" \
    "--set" "time.courant=0.5" "--set" "time.interface_substeps=1" \
    "--set" "numerics.outer_iterations=3" "--set" "numerics.first_viscosity=previous_step"; done
fi
if [[ $which == lube2004 || $which == all ]]; then
  # [YS] Sec. 4.1 at the paper's 1.67 mm cells to t = 0.5 s (the paper's steps were about 1e-6 s)
  for n in 1 2; do run "lube2004_a05 300 x 120 to t = 0.5 s" $n cases/lube2004_a05.toml; done
  # the same with the numerics the case had before: the projection over the whole domain, the cells'
  # viscosities and mixtures, one VoF sweep per step at a Courant number of 0.5
  for n in 1 2; do run "lube2004_a05 300 x 120 to t = 0.5 s, projection" $n cases/lube2004_a05.toml \
    "--set" "numerics.pressure_coupling=projection" "--set" "numerics.air_band=0" "--set" "soil.face_fraction=cells" \
    "--set" "soil.yield_pressure=cell" "--set" "soil.strain_rate=cell" "--set" "time.courant=0.5" \
    "--set" "time.interface_substeps=1" "--set" "numerics.first_viscosity=previous_step" \
    "--set" "numerics.viscosity_pressure=last_iterate" "--set" "solver.momentum.ksp_type=gmres" \
    "--set" "solver.momentum.pc_type=hypre"; done
fi
if [[ $which == dam_break || $which == all ]]; then
  for n in 1 2; do run "water_dam_break to t = 0.2 s" $n cases/water_dam_break.toml; done
fi
if [[ $which == column_3d || $which == all ]]; then
  # the 3D column (a quarter, 40 x 16 x 40 cells of 1 cm) to t = 0.5 s: the coupled solve over the soil
  # and an air band of 12 cells, one factorisation a step
  for n in 1 2; do run "lube2004_a05_3d 40 x 16 x 40 to t = 0.5 s" $n cases/lube2004_a05_3d.toml; done
fi
if [[ $which == column_3d_projection || $which == all ]]; then
  # the same under the projection
  for n in 1 2; do
    run "lube2004_a05_3d, projection, to t = 0.5 s" $n cases/lube2004_a05_3d.toml \
      --set 'numerics.pressure_coupling="projection"' --set numerics.air_band=0
  done
fi

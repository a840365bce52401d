#!/usr/bin/env bash
# Lube et al.'s column of a = 1/2 in 3D (cases/lube2004_a05_3d.toml, a quarter on cells of 1 cm) and
# its axisymmetric twin on the same cells and numerics (cases/lube2004_a05.toml with the overrides
# below), then their comparison (scripts/compare_column_3d.py) and its figure.
#   scripts/run_column_3d.sh [OUT] [RANKS]
# Output: OUT/column_3d/, OUT/column_axisymmetric/ and OUT/column_3d.png (default OUT = out/column_3d);
# RANKS (default 1) ranks for the 3D run. About 6 minutes for the 3D run on one rank.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:-out/column_3d}
ranks=${2:-1}
mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
mpirun -np "$ranks" --oversubscribe build/granflow run cases/lube2004_a05_3d.toml -o "$out/column_3d" --overwrite
# The twin: the 3D case's cells along r and y, its domain, and its numerics (the coupled solve with an
# air band of 12 cells, one factorisation a step, two outer iterations, one sweep per step, the step's
# Courant number 0.5).
build/granflow run cases/lube2004_a05.toml -o "$out/column_axisymmetric" --overwrite \
  --set 'mesh.cells=[40,16]' --set 'mesh.upper=[0.4,0.16]' \
  --set 'numerics.later_iterations="first_factorisation"' \
  --set 'numerics.first_viscosity="previous_step"' --set 'numerics.viscosity_pressure="last_iterate"' \
  --set time.interface_substeps=1 --set time.courant=0.5 --set time.dt=1e-3
/usr/bin/python3 scripts/compare_column_3d.py "$out/column_3d" "$out/column_axisymmetric" --png "$out/column_3d.png"

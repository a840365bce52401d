#!/usr/bin/env bash
# Runs every test (unit, verification, validation, parallel) of an already built tree.
set -euo pipefail
cd "$(dirname "$0")/../build"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
ctest --output-on-failure -j 2 "$@"

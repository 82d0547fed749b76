#!/usr/bin/env bash
# The README's first Quick start command: install what is missing, build, run the main job.
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/install-deps.sh
bash deploy/build.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=runs/quickstart
mkdir -p "$out"
for test in uct btt; do
  mpirun -np 1 build/engine/rockcal-dem run "examples/${test}_small.json" --out "$out/$test" > "$out/$test.json"
done
echo "results: $out/{uct,btt}/result.json, curves: $out/{uct,btt}/curve.csv"

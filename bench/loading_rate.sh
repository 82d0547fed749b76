#!/usr/bin/env bash
# Peak load against platen speed, with and without two-rate loading, on the sample of the field notes'
# ESys-Particle study (UCT, D = 20 R, H = 56 R, F_r0 = F_s0 = 64, local damping 0.7). Prints a table.
# Usage: bench/loading_rate.sh [speeds...]   (ROCKCAL_DEM overrides the engine binary)
set -euo pipefail
cd "$(dirname "$0")/.."
dem=${ROCKCAL_DEM:-build/engine/rockcal-dem}
speeds=("$@")
[ ${#speeds[@]} -gt 0 ] || speeds=(0.04 0.02 0.01 0.005)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
job() {  # speed slow_factor
  cat <<JSON
{"test": "uct", "sample": {"diameter": 20, "height": 56, "radius": 1.0},
 "material": {"density": 1.0, "kr": 8000, "nu": 0.2}, "bond": {"fr0": 64, "fs0": 64},
 "loading": {"platen_velocity": $1, "slow_factor": $2, "max_strain": 0.08}, "damping": {"local": 0.7}}
JSON
}
field() { grep -o "\"$2\": *[-0-9.e+]*" "$1" | head -1 | sed 's/.*: *//'; }
printf '%-8s %-12s %-10s %-12s %-8s %-10s\n' scheme speed_end slow_factor peak_load steps wall_s
fast=${speeds[0]}
for v in "${speeds[@]}"; do
  job "$v" 1.0 > "$work/single.json"
  "$dem" run "$work/single.json" --out "$work/single" > /dev/null 2>&1
  r="$work/single/result.json"
  printf '%-8s %-12s %-10s %-12s %-8s %-10s\n' single "$v" 1 "$(field "$r" peak_load)" "$(field "$r" steps)" "$(field "$r" wall_seconds)"
  f=$(awk -v a="$v" -v b="$fast" 'BEGIN { printf "%.6g", a / b }')
  if [ "$f" != "1" ]; then
    job "$fast" "$f" > "$work/two.json"
    "$dem" run "$work/two.json" --out "$work/two" > /dev/null 2>&1
    r="$work/two/result.json"
    printf '%-8s %-12s %-10s %-12s %-8s %-10s\n' two-rate "$v" "$f" "$(field "$r" peak_load)" "$(field "$r" steps)" "$(field "$r" wall_seconds)"
  fi
done

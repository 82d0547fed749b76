#!/usr/bin/env bash
# A formula "engine" for the calibration's service test: honours `run JOB.json --out DIR`, writes a
# result.json whose peak load is the synthetic power law of tests/calibration/synthetic.cpp
# (UCT = 2500 fr0^0.3 fs0^0.7, BTT = 420 fr0^0.8 fs0^0.2) times 1 + (s - 1) / 100 for sample seed s
# (default 1), and appends "test fr0 fs0 seed" to $FAKE_DEM_RUNS (when set) so the test can count
# what really ran. Seeds listed in $FAKE_DEM_NO_PEAK_SEEDS (space-separated) reach no peak. An
# elastic test measures E = 0.4 kr and nu = the job's nu + 0.05 (a packing eq. 3 does not describe).
set -eu
[ "${1:-}" = run ] || { echo "usage: $0 run JOB.json --out DIR" >&2; exit 2; }
job=$2
out=${4:-.}
value() { grep -o "\"$1\": *[0-9.eE+-]*" "$job" | head -1 | sed 's/.*: *//'; }
fr0=$(value fr0)
fs0=$(value fs0)
seed=$(value seed)
seed=${seed:-1}
test=$(grep -o '"test": *"[a-z]*"' "$job" | head -1 | sed 's/.*: *"\(.*\)"/\1/')
peak=$(awk -v t="$test" -v a="$fr0" -v b="$fs0" -v s="$seed" 'BEGIN {
  f = 1 + (s - 1) / 100
  if (t == "uct") printf "%.17g", 2500 * a^0.3 * b^0.7 * f; else printf "%.17g", 420 * a^0.8 * b^0.2 * f }')
modulus=1000.0
poisson=null
if [ "$test" = elastic ]; then
  modulus=$(awk -v k="$(value kr)" 'BEGIN { printf "%.17g", 0.4 * k }')
  poisson=$(awk -v n="$(value nu)" 'BEGIN { printf "%.17g", n + 0.05 }')
fi
[ -n "${FAKE_DEM_RUNS:-}" ] && echo "$test $fr0 $fs0 $seed" >> "$FAKE_DEM_RUNS"
reached=true
no_peak=''
case " ${FAKE_DEM_NO_PEAK_SEEDS:-} " in
  *" $seed "*) reached=false
               no_peak=", \"no_peak_reason\": \"no bond broke before the load fell (fake, seed $seed)\"" ;;
esac
cat > "$out/result.json.tmp" <<JSON
{"test": "$test", "peak_load": $peak, "strength": 1.0, "youngs_modulus": $modulus, "poisson_ratio": $poisson,
 "particles": 7, "wall_seconds": 0.01, "engine_version": "fake", "stop_reason": "post_peak",
 "peak_reached": $reached$no_peak}
JSON
mv "$out/result.json.tmp" "$out/result.json"

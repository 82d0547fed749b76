#!/usr/bin/env bash
# Fault-injection double for rockcal-dem, for the service's failure-handling tests only: it honours
# the engine's command line (`run JOB.json --out DIR`) and file contract, and picks a behaviour
# from the job's bond.fr0 so one sweep can mix healthy and broken jobs:
#   13 -> crashes (SIGSEGV) every time      17 -> hangs (for timeouts and cancels)
#   19 -> fails the first attempt only       23 -> exits 2 (invalid spec, must not be retried)
#   29 -> ignores SIGTERM and hangs (so the executor must escalate to SIGKILL)
#   61 -> exits 0 with a result that reached no peak ("peak_reached": false, a reason)
#   67 -> the same on even sample seeds only
#   anything else -> writes result.json, curve.csv and progress.json after FAKE_DEM_SLEEP seconds
# A formula of the seed s (default 1), so that ensembles have known statistics:
#   peak_load = fr0 + (s - 1), strength = fs0 + 2 (s - 1), youngs_modulus = 1000 + 10 (s - 1).
set -u
[ "${1:-}" = run ] || { echo "usage: $0 run JOB.json --out DIR" >&2; exit 2; }
job=$2
out=${4:-.}
fr0=$(grep -o '"fr0": *[0-9.eE+-]*' "$job" | head -1 | sed 's/.*: *//')
fs0=$(grep -o '"fs0": *[0-9.eE+-]*' "$job" | head -1 | sed 's/.*: *//')
test=$(grep -o '"test": *"[a-z]*"' "$job" | head -1 | sed 's/.*: *"\(.*\)"/\1/')
seed=$(grep -o '"seed": *[0-9]*' "$job" | head -1 | sed 's/.*: *//')
seed=${seed:-1}
echo "fake-rockcal-dem: test=$test fr0=$fr0 fs0=$fs0 seed=$seed pid=$$"
case "${fr0%.0}" in
  13) echo "fake-rockcal-dem: crashing"; kill -SEGV $$ ;;
  17) echo "fake-rockcal-dem: hanging"; sleep 600 & wait ;;
  19) attempts=$(grep -c '=== rockcal: attempt' "$out/log" 2>/dev/null || true)
      if [ "${attempts:-0}" -lt 2 ]; then echo "fake-rockcal-dem: transient failure"; exit 1; fi ;;
  23) echo "fake-rockcal-dem: invalid spec" >&2; exit 2 ;;
  29) trap '' TERM; echo "fake-rockcal-dem: ignoring SIGTERM"; sleep 600 & wait; sleep 600 ;;
esac
sleep "${FAKE_DEM_SLEEP:-0}"
reached=true
peak_fields=''
case "${fr0%.0}" in
  61) reached=false ;;
  67) [ $((seed % 2)) -eq 0 ] && reached=false ;;
esac
[ $reached = false ] && peak_fields=', "no_peak_reason": "the load fell on a loose particle with no bond broken (fake)"'
read -r peak strength modulus < <(awk -v a="$fr0" -v b="$fs0" -v s="$seed" \
  'BEGIN { printf "%.17g %.17g %.17g", a + (s - 1), b + 2 * (s - 1), 1000 + 10 * (s - 1) }')
echo '{"step": 10, "fraction": 1.0, "load": 1, "peak_load": 2, "broken_bonds": 0, "elapsed_s": 0}' > "$out/progress.json"
printf 'step,time_s,displacement_m,load_n,broken_bonds\n1,0.1,0.001,%s,0\n' "$peak" > "$out/curve.csv"
cat > "$out/result.json.tmp" <<JSON
{"test": "$test", "peak_load": $peak, "strength": $strength, "youngs_modulus": $modulus, "poisson_ratio": null,
 "particles": 7, "wall_seconds": 0.01, "engine_version": "fake", "stop_reason": "post_peak",
 "peak_reached": $reached$peak_fields, "ended_at": $EPOCHREALTIME}
JSON
mv "$out/result.json.tmp" "$out/result.json"
echo "fake-rockcal-dem: done"

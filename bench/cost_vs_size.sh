#!/usr/bin/env bash
# Memory and cost per particle-step of rockcal-dem from about 5k to 1M particles (issue 3): the
# paper's FCC UCT sample (R = 1, K_r = 8000, nu = 0.2, H / D = 139 / 49) scaled in size, 1 rank.
# Each size runs twice, for S and 2S steps; the cost per step is the difference of the two runs'
# process CPU seconds, so set-up (packing, bonding) drops out and other load on the machine
# inflates it little. The platens move slowly (0.005 m/s) so every size stays in the same, intact
# regime for the steps run. Memory is the larger run's peak resident set. Builds nothing; on demand only.
#
#   bench/cost_vs_size.sh                 sizes "24 37 49 63 91 136" (diameters)
#   DIAMETERS="24 49" PSTEPS=5e7 bench/cost_vs_size.sh
set -u
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
dem=${ROCKCAL_DEM:-$root/build/engine/rockcal-dem}
diameters=${DIAMETERS:-"24 37 49 63 91 136"}
psteps=${PSTEPS:-5e7}  # particle-steps of the shorter run
[[ -x "$dem" ]] || { echo "cost_vs_size: no engine at $dem" >&2; exit 2; }
[[ -x /usr/bin/time ]] || { echo "cost_vs_size: needs /usr/bin/time (apt-get install time)" >&2; exit 2; }
work=$(mktemp -d "${TMPDIR:-/tmp}/rockcal-size.XXXXXX")
trap 'rm -rf "$work"' EXIT

run() {  # diameter steps -> "particles bonds steps_run cpu_s rss_kb"
  local d=$1 steps=$2 h
  h=$(python3 -c "print(round($d * 139 / 49, 3))")
  cat > "$work/job.json" <<JOB
{"test": "uct", "sample": {"diameter": $d, "height": $h, "packing": "fcc", "radius": 1.0},
 "material": {"density": 1.0, "kr": 8000, "nu": 0.2}, "bond": {"fr0": 64, "fs0": 64},
 "loading": {"platen_velocity": 0.005, "max_strain": 0.5, "max_steps": $steps}, "damping": {"local": 0.7},
 "output": {"progress_seconds": 0}}
JOB
  /usr/bin/time -f "%U %S %M" -o "$work/time.txt" "$dem" run "$work/job.json" --out "$work/out" \
    > /dev/null 2>&1 || { echo "cost_vs_size: run failed (D=$d)" >&2; exit 1; }
  python3 - "$work" <<'PY'
import json, sys
w = sys.argv[1]
r = json.load(open(w + "/out/result.json"))
u, s, m = open(w + "/time.txt").read().split()
print(r["particles"], r["bonds"], r["steps"], float(u) + float(s), int(m))
PY
}

echo "cost_vs_size: $(date -u '+%F %H:%M') UTC, $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg)"
printf "%9s %10s %10s %8s %14s %16s %18s\n" D particles bonds steps "peak RSS MB" "bytes/particle" "CPU ns/particle-step"
for d in $diameters; do
  n_est=$(python3 -c "print(int(0.394 * $d ** 3))")
  s=$(python3 -c "print(max(10, int(float('$psteps') / $n_est)))")
  read -r n1 b1 s1 c1 m1 <<< "$(run "$d" "$s")"
  read -r n2 b2 s2 c2 m2 <<< "$(run "$d" $((2 * s)))"
  python3 -c "
n, b, s = $n2, $b2, $s2 - $s1
cost = ($c2 - $c1) / (n * s) * 1e9
print(f'{$d:9} {n:10} {b:10} {s:8} {$m2 / 1024:14.1f} {$m2 * 1024 / n:16.0f} {cost:18.1f}')"
done

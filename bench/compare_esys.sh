#!/usr/bin/env bash
# rockcal-dem vs ESys-Particle (the seed paper's engine) on the same sample, one core each, one
# after the other: the paper's full-size FCC UCT (examples/uct_paper.json), the same particles and
# bonds, eq. 3 stiffnesses, strengths, platen speed, local damping 0.7 and the same time step (the
# one rockcal-dem chooses, read from its result.json). ESys-Particle is only used here, when the
# Debian package `esys-particle` is installed; rockcal does not depend on it. Run on demand (never
# part of ctest).
#
#   bench/compare_esys.sh [STEPS]        default STEPS = 500 (both engines)
#
# Environment:
#   ROCKCAL_DEM  engine binary (default: build/engine/rockcal-dem of this checkout)
#   JOB          job (default examples/uct_paper.json; must be an FCC UCT with material.kr)
#   REPEATS      alternating rockcal/ESys pairs (default 2); best and spread are printed
#   ESYS_WORKERS ESys worker processes (default 1; mpirun -np workers+1, rank 0 is ESys's master)
#   KEEP         set to keep the run directories
#
# Default budget: 500 steps x 43k particles per run. Measured 2026-11-23 under load average 7-10
# (other builds): rockcal-dem ~22 s, ESys ~180 s + ~10 s set-up per run, 2 pairs in 7 minutes.
# ESys used ~90 CPU s per 500 steps, so on an idle machine expect ~90 s per ESys run and ~4 minutes
# in all. Set-up and the first ESys step are excluded from the rates, as rockcal-dem excludes its
# set-up from wall_seconds.
# CPU seconds (user + sys of all processes of a run, set-up included) are printed too; for ESys
# they include its master rank (rank 0), which waits for the worker in MPI calls that may poll.
set -u

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
steps=${1:-${STEPS:-500}}
dem=${ROCKCAL_DEM:-$root/build/engine/rockcal-dem}
job=${JOB:-$root/examples/uct_paper.json}
repeats=${REPEATS:-2}
workers=${ESYS_WORKERS:-1}

die() { echo "compare_esys: $*" >&2; exit 2; }
[[ "$steps" =~ ^[0-9]+$ && "$steps" -ge 2 ]] || die "STEPS must be an integer >= 2 (got '$steps')"
[[ "$repeats" =~ ^[0-9]+$ && "$repeats" -gt 0 ]] || die "REPEATS must be a positive integer"
[[ "$workers" =~ ^[0-9]+$ && "$workers" -gt 0 ]] || die "ESYS_WORKERS must be a positive integer"

if ! command -v esysparticle >/dev/null 2>&1 || ! /usr/bin/python3 -c 'import esys.lsm' >/dev/null 2>&1; then
  echo "compare_esys: ESys-Particle is not installed (Debian: apt-get install esys-particle);"
  echo "compare_esys: it is only needed for this comparison, not by rockcal. Nothing measured."
  exit 0
fi
[[ -x "$dem" ]] || die "no engine at $dem (build it, or set ROCKCAL_DEM=/path/to/rockcal-dem)"
command -v jq >/dev/null 2>&1 || die "needs jq (apt-get install jq)"
command -v mpirun >/dev/null 2>&1 || die "needs mpirun (ESys-Particle runs under MPI)"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

work=$(mktemp -d "${TMPDIR:-/tmp}/rockcal-esys.XXXXXX")
if [[ -z "${KEEP:-}" ]]; then trap 'rm -rf "$work"' EXIT; fi
jq --argjson n "$steps" '.loading = ((.loading // {}) + {max_steps: $n})' "$job" >"$work/job.json" ||
  die "jq failed on $job"

esys_version=$(dpkg-query -W -f '${Version}' esys-particle 2>/dev/null || echo unknown)
version=$(cd "$root" && git describe --always --dirty 2>/dev/null || echo unknown)
echo "compare_esys: $(date -u '+%Y-%m-%d %H:%M UTC'), $(uname -n), $(nproc) cores"
echo "  rockcal $dem (built $(date -u -r "$dem" '+%F %H:%M UTC')), 1 rank; bench/ of checkout $version"
echo "  esys    esys-particle $esys_version, $workers worker(s) (mpirun -np $((workers + 1)))"
echo "  job     $job, $steps steps each, $repeats alternating pair(s)"
echo "  load    before: $(cut -d' ' -f1-3 /proc/loadavg) (1, 5, 15 min)"

# CPU seconds of a command and all its descendants (GNU time), when available.
timed() {
  local file=$1; shift
  if [[ -x /usr/bin/time ]]; then /usr/bin/time -f '%U %S %e' -o "$file" "$@"; else "$@"; fi
}
cpu_of() { [[ -s "$1" ]] && awk 'END { printf "%.0f CPU s in %.0f s elapsed", $1 + $2, $3 }' "$1" || echo "CPU time not measured"; }

oversub=()
[[ $((workers + 1)) -gt $(nproc) ]] && oversub=(--oversubscribe)

rock_rates=() esys_rates=()
dt=""
for ((k = 1; k <= repeats; k++)); do
  out="$work/rockcal-$k"
  mkdir -p "$out"
  load_now=$(cut -d' ' -f1 /proc/loadavg)
  if ! timed "$out/cpu" "$dem" run "$work/job.json" --out "$out" >"$out/stdout" 2>"$out/stderr"; then
    die "rockcal-dem failed: $(tail -1 "$out/stderr")"
  fi
  r=$(jq -r .particle_steps_per_second "$out/result.json")
  dt=$(jq -r .dt "$out/result.json")
  read -r n_rock bonds_rock steps_rock wall_rock <<<"$(jq -r '"\(.particles) \(.bonds) \(.steps) \(.wall_seconds)"' "$out/result.json")"
  load_rock=$(tail -1 "$out/curve.csv" | cut -d, -f4)
  printf '  rockcal #%d: %s particles, %s bonds, %s steps (dt %s) in %.2f s: %.4g particle-steps/s; platen load %.6g N (load avg %s; %s)\n' \
    "$k" "$n_rock" "$bonds_rock" "$steps_rock" "$dt" "$wall_rock" "$r" "$load_rock" "$load_now" "$(cpu_of "$out/cpu")"
  rock_rates+=("$r")

  out="$work/esys-$k"
  mkdir -p "$out"
  load_now=$(cut -d' ' -f1 /proc/loadavg)
  (cd "$out" && timed cpu mpirun -np $((workers + 1)) "${oversub[@]}" esysparticle "$here/esys_uct.py" --job "$job" \
      --steps "$steps" --dt "$dt" --workers "$workers" >stdout 2>stderr)
  line=$(grep '^ESYS_RESULT ' "$out/stdout" | head -1 | cut -d' ' -f2-)
  [[ -n "$line" ]] || die "ESys-Particle run failed: $(tail -3 "$out/stderr")"
  e=$(jq -r .particle_steps_per_second <<<"$line")
  read -r n_esys bonds_esys wall_esys load_esys <<<"$(jq -r '"\(.particles) \(.bonds) \(.wall_seconds) \(.platen_load)"' <<<"$line")"
  printf '  esys    #%d: %s particles, %s bonds, steps 2-%s in %.2f s: %.4g particle-steps/s; platen load %.6g N (load avg %s; %s)\n' \
    "$k" "$n_esys" "$bonds_esys" "$steps" "$wall_esys" "$e" "$load_esys" "$load_now" "$(cpu_of "$out/cpu")"
  esys_rates+=("$e")
  [[ "$n_esys" == "$n_rock" && "$bonds_esys" == "$bonds_rock" ]] ||
    echo "  warning: the samples differ ($n_rock/$bonds_rock vs $n_esys/$bonds_esys particles/bonds)"
done
echo "  load    after:  $(cut -d' ' -f1-3 /proc/loadavg)"
[[ -n "${KEEP:-}" ]] && echo "  runs kept in $work"

stats() { printf '%s\n' "$@" | sort -g | awk 'NR == 1 { lo = $1 } { hi = $1 } END { printf "%.4g %.4g", hi, lo }'; }
read -r rock_best rock_worst <<<"$(stats "${rock_rates[@]}")"
read -r esys_best esys_worst <<<"$(stats "${esys_rates[@]}")"
echo
printf '%-28s %16s %22s\n' engine "best p-steps/s" "spread (all runs)"
printf '%-28s %16.4g %22s\n' "rockcal-dem, 1 rank" "$rock_best" "$(printf '%.3g-%.3g' "$rock_worst" "$rock_best")"
printf '%-28s %16.4g %22s\n' "ESys-Particle, $workers worker(s)" "$esys_best" "$(printf '%.3g-%.3g' "$esys_worst" "$esys_best")"
awk -v a="$rock_best" -v b="$esys_best" -v w="$workers" 'BEGIN {
  printf "ratio rockcal / ESys per core (best vs best): %.2f", a / (b / w)
  if (w > 1) printf "  (ESys rate divided by its %d workers)", w
  printf "\n" }'

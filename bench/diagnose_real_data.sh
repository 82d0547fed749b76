#!/usr/bin/env bash
# The diagnosis on real lab data: starts a `rockcal serve` of its own on an embedded SQLite store,
# submits a diagnosis request (default: the Zigong sandstone triaxial series at D/R 20,
# examples/diagnose_zigong.json), prints the verdict, the gap table and the candidates, writes
# the HTML report, and prints the wall time and the job counts from the store. Run on demand
# (never part of ctest): about half an hour on 2 cores with an empty store.
#
#   bench/diagnose_real_data.sh [REQUEST.json]
#
# Environment:
#   BUILD    build tree (default: build/ of this checkout)
#   OUT      directory of the store, the server log and the report (default runs/real_data);
#            kept, so a second run answers every job from the store
#   WORKERS  jobs at once (default: the number of cores)
set -euo pipefail

here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
root=$(cd "$here/.." && pwd)
request=${1:-$root/examples/diagnose_zigong.json}
build=${BUILD:-$root/build}
out=${OUT:-$root/runs/real_data}
workers=${WORKERS:-$(nproc)}

die() { echo "diagnose_real_data: $*" >&2; exit 2; }
[[ -r "$request" ]] || die "cannot read request $request"
[[ -x "$build/api/rockcal" && -x "$build/engine/rockcal-dem" ]] ||
  die "no rockcal / rockcal-dem under $build (run deploy/build.sh, or set BUILD)"
mkdir -p "$out"
rm -f "$out/port" # a port file left by an earlier run would be read before the server writes its own

# Open MPI refuses root without these; the jobs run without mpirun here (--ranks-per-job 0).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1

"$build/api/rockcal" serve --db "$out/store.db" --listen 127.0.0.1:0 --port-file "$out/port" \
  --workers "$workers" --ranks-per-job 0 --engine "$build/engine/rockcal-dem" \
  --max-jobs 20000 >"$out/serve.log" 2>&1 &
server=$!
trap 'kill "$server" 2>/dev/null; wait "$server" 2>/dev/null || true' EXIT
for _ in $(seq 100); do [[ -s "$out/port" ]] && break; sleep 0.1; done
[[ -s "$out/port" ]] || die "the server did not start (see $out/serve.log)"
url="http://127.0.0.1:$(cat "$out/port")"

name=$(basename "$request" .json)
start=$(date +%s)
"$build/api/rockcal" diagnose "$request" --server "$url" --html "$out/$name.html" |
  grep -Ev '^campaign [0-9]+ running: '
echo "wall: $(($(date +%s) - start)) s; report: $out/$name.html; store: $out/store.db"

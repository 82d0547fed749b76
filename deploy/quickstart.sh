#!/usr/bin/env bash
# The README's first Quick start command: install what is missing, build, and run the main job: the
# seed paper's lab case as an automatic (F_r0, F_s0) calibration, through the real service on an
# embedded SQLite file. Prints the progress and the calibration's summary table (the whole report
# as JSON: `rockcal status ID --json`).
set -euo pipefail
cd "$(dirname "$0")/.."
bash deploy/install-deps.sh
bash deploy/build.sh
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
out=runs/quickstart
mkdir -p "$out"
rm -f "$out/port"
build/api/rockcal serve --db "$out/rockcal.db" --listen 127.0.0.1:0 --port-file "$out/port" \
  --ranks-per-job 0 > "$out/server.log" 2>&1 &
server=$!
trap 'kill $server 2>/dev/null; wait $server 2>/dev/null || true' EXIT
for _ in $(seq 100); do [ -s "$out/port" ] && break; sleep 0.1; done
[ -s "$out/port" ] || { echo "the server did not start; see $out/server.log" >&2; exit 1; }
url="http://127.0.0.1:$(cat "$out/port")"
id=$(build/api/rockcal submit examples/calibrate_seed_lab.json --server "$url")
echo "calibration campaign $id on $url (database $out/rockcal.db)"
build/api/rockcal status "$id" --wait --server "$url"
echo "(the whole report as JSON: rockcal status $id --json, with rockcal serve --db $out/rockcal.db running)"

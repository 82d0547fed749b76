#!/usr/bin/env bash
# The dashboard's browser test (ctest runs it): installs what it needs, then drives Debian's
# chromium through the dashboard of a real `rockcal serve` (tests/dashboard/dashboard_test.mjs).
#   bash tests/dashboard/run.sh ROCKCAL_BINARY WORK_DIR
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
rockcal="$(realpath "${1:?usage: run.sh ROCKCAL_BINARY WORK_DIR}")"
mkdir -p "${2:?usage: run.sh ROCKCAL_BINARY WORK_DIR}"
work="$(realpath "$2")"
bash "$here/setup.sh" "$work"
export ROCKCAL_BIN="$rockcal" DASHBOARD_WORK="$work"
cd "$work"
# No --test-timeout: Node 18 (Debian 12) lacks it; ctest bounds the run (TIMEOUT 900).
exec node --test --test-reporter=spec "$here/dashboard_test.mjs"

#!/usr/bin/env bash
# The request-parser fuzz run of the default suite (tests/service/fuzz_requests_test.cpp), for
# longer: SECONDS per target (campaign requests through the service's parser and every kind's
# planner; job specs through the engine's parser). Prints the count of inputs, accepted and
# refused, and the slowest input; fails on a crash, a hang (> 2 s for one input) or an unclean
# rejection, printing the input.
# Usage: bench/fuzz_requests.sh [SECONDS] [SEED]   (default 300 s, seed 15; build/ must be built;
#        a sanitizer build: BUILD=build-asan)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${BUILD:-build}/tests/service/service_fuzz_tests
[[ -x "$bin" ]] || { echo "fuzz_requests: no $bin (build first)" >&2; exit 2; }
ROCKCAL_FUZZ_SECONDS=${1:-300} ROCKCAL_FUZZ_SEED=${2:-15} "$bin" --gtest_brief=1 | grep -E '^\[fuzz\]|FAILED|Failure|PASSED'

#!/usr/bin/env bash
# run_case.sh LABEL BINARY TEST_FULL_NAME [TIMEOUT]: one gtest case, niced, with a timeout and an
# 8 GB address-space limit; output to ${OUT:-runs/hardening}/LABEL/TEST_FULL_NAME.log, rc appended.
# Used to run issue 15's regression tests on 64e168e (tests back-ported by backport-64e168e.diff)
# and on main: docs/hardening-regressions.md.
label=$1 bin=$2 name=$3 t=${4:-120}
out=${OUT:-runs/hardening}/$label; mkdir -p "$out"
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
start=$(date +%s.%N)
( ulimit -v 8000000; exec nice -n 10 timeout -k 5 "$t" "$bin" --gtest_filter="$name" --gtest_color=no ) > "$out/$name.log" 2>&1
rc=$?
end=$(date +%s.%N)
printf '\n[run_case] rc=%s wall=%.1fs\n' "$rc" "$(echo "$end - $start" | bc)" >> "$out/$name.log"
echo "$label $name rc=$rc"

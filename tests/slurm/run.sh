#!/usr/bin/env bash
# The Slurm executor on a real Slurm: installs Debian's slurm and munge packages if missing, writes
# a one-node cluster on loopback into a temporary directory, starts munged, slurmctld and slurmd
# as processes this script owns (no systemd), runs the Slurm system tests against it, and stops
# everything it started, whatever happens. Usage: tests/slurm/run.sh [BUILD_DIR [GTEST ARGS]]
# (root only)
set -euo pipefail
cd "$(dirname "$0")/../.."
build=$(cd "${1:-build}" && pwd)
tests="$build/tests/slurm/slurm_system_tests"
[ -x "$tests" ] || { echo "slurm test: $tests not built" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || { echo "slurm test: needs root (apt-get, SlurmUser=root)" >&2; exit 1; }

packages=(slurmctld slurmd slurm-client munge)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "slurm test: installing ${missing[*]}" >&2
  # Without systemd, the packages' scripts would start munged and the Slurm daemons from
  # /etc/init.d and leave them running: forbid that for this install (policy-rc.d exit 101).
  policy=/usr/sbin/policy-rc.d
  own_policy=0
  if [ ! -e "$policy" ]; then
    printf '#!/bin/sh\nexit 101\n' > "$policy" && chmod 755 "$policy" && own_policy=1
  fi
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  [ "$own_policy" -eq 1 ] && rm -f "$policy"
fi

dir=$(mktemp -d /tmp/rockcal-slurm.XXXXXX)
pids=()
stop_cluster() {
  set +e
  if [ -n "${SLURM_CONF:-}" ] && [ -e "$SLURM_CONF" ]; then
    scancel --user=root --full 2>/dev/null
    for _ in $(seq 50); do [ -z "$(squeue -h -o %i 2>/dev/null)" ] && break; sleep 0.2; done
  fi
  for ((i = ${#pids[@]} - 1; i >= 0; i--)); do kill "${pids[i]}" 2>/dev/null; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null; done
  # slurmstepd outlives slurmd; find what this cluster started by its configuration file.
  for env in /proc/[0-9]*/environ; do
    if grep -qzx "SLURM_CONF=$dir/slurm.conf" "$env" 2>/dev/null; then
      pid=${env#/proc/}; pid=${pid%/environ}
      [ "$pid" != $$ ] && kill -9 "$pid" 2>/dev/null
    fi
  done
  rm -rf "$dir"
}
trap stop_cluster EXIT
trap 'exit 130' INT TERM

free_port() {
  local p
  for p in $(seq "$1" $(($1 + 200))); do
    (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null || { echo "$p"; return; }
  done
  echo "slurm test: no free port from $1" >&2
  exit 1
}
ctld_port=$(free_port 26817)
slurmd_port=$(free_port $((ctld_port + 1)))
host=$(hostname -s)
mkdir -p "$dir/munge" "$dir/state" "$dir/spool" "$dir/tmp" "$dir/pmix"
chmod 700 "$dir/munge"
if command -v mungekey >/dev/null; then
  mungekey --create --keyfile="$dir/munge/munge.key"
else
  dd if=/dev/urandom of="$dir/munge/munge.key" bs=1024 count=1 2>/dev/null
fi
chmod 400 "$dir/munge/munge.key"
socket="$dir/munge/munge.socket"
munged --foreground --force --key-file="$dir/munge/munge.key" --socket="$socket" \
  --pid-file="$dir/munge/munged.pid" --log-file="$dir/munge/munged.log" \
  --seed-file="$dir/munge/seed" > "$dir/munged.out" 2>&1 &
pids+=($!)

cat > "$dir/slurm.conf" <<CONF
# One node on loopback, for rockcal's tests. No cgroups: the test may run in a container.
ClusterName=rockcal-test
SlurmctldHost=$host(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
# Job and PMIx client directories inside this cluster's own directory: job ids restart at 1 in
# every new cluster, so /tmp/spmix_appdir_0_<job>.<step> left by an earlier one (a step killed
# before its clean-up) would make this cluster's step of the same id fail to launch.
TmpFS=$dir/tmp
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
# Accounting off, as on many clusters: sacct then knows nothing and the marker file must do.
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
KillWait=5
MinJobAge=3600
InactiveLimit=0
NodeName=rockcal-node NodeHostname=$host NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=debug Nodes=rockcal-node Default=YES MaxTime=INFINITE State=UP
CONF
printf 'PMIxCliTmpDirBase=%s\n' "$dir/pmix" > "$dir/mpi.conf"
export SLURM_CONF="$dir/slurm.conf"
for _ in $(seq 50); do [ -S "$socket" ] && break; sleep 0.1; done
slurmctld -D -f "$SLURM_CONF" > "$dir/slurmctld.out" 2>&1 &
pids+=($!)
slurmd -D -N rockcal-node -f "$SLURM_CONF" > "$dir/slurmd.out" 2>&1 &
pids+=($!)
ready=0
for _ in $(seq 120); do
  [ "$(sinfo -h -o %T 2>/dev/null)" = idle ] && { ready=1; break; }
  sleep 0.5
done
if [ "$ready" -ne 1 ]; then
  echo "slurm test: the cluster did not come up; logs:" >&2
  tail -n 20 "$dir"/*.out "$dir"/*.log "$dir/munge/munged.log" >&2 || true
  exit 1
fi
echo "slurm test: one-node cluster up ($(sinfo -V), ports $ctld_port/$slurmd_port, $dir)"

export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
start=$(date +%s)
status=0
"$tests" "${@:2}" || status=$?
echo "slurm test: $(($(date +%s) - start)) s, exit $status"
if [ "$status" -ne 0 ]; then
  tail -n 30 "$dir/slurmctld.log" "$dir/slurmd.log" >&2 || true
fi
exit "$status"

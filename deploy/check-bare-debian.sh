#!/usr/bin/env bash
# Checks the README's two Quick start commands where nothing is installed: a bare Debian 12
# (debootstrap, minbase) as root, with a fresh clone of this repository's HEAD. Prints each
# command's exit code and wall time; the logs stay in ROOT/root/rockcal/check-*.log.
#   bash deploy/check-bare-debian.sh [ROOT]     (default /var/tmp/rockcal-bare; needs root)
# A second run reuses ROOT's Debian but clones afresh. Remove ROOT to start from nothing.
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
root="${1:-/var/tmp/rockcal-bare}"
command -v debootstrap >/dev/null || { apt-get update -qq && apt-get install -y -qq debootstrap >/dev/null; }
if [ ! -x "$root/bin/bash" ]; then
  mkdir -p "$root"
  debootstrap --variant=minbase bookworm "$root" http://deb.debian.org/debian >/dev/null
fi
cp /etc/resolv.conf "$root/etc/resolv.conf"
# Where this host reaches the registries through a TLS-intercepting proxy, its CA goes along (a
# property of the host's network, not something rockcal needs): npm in the root trusts it too.
extra_ca=()
if [ -n "${NODE_EXTRA_CA_CERTS:-}" ] && [ -f "$NODE_EXTRA_CA_CERTS" ]; then
  cp "$NODE_EXTRA_CA_CERTS" "$root/etc/host-extra-ca.crt"
  extra_ca=(NODE_EXTRA_CA_CERTS=/etc/host-extra-ca.crt)
fi
rm -rf "$root/root/rockcal"
git clone -q "$repo" "$root/root/rockcal"
mounts=(proc sys dev dev/pts dev/shm)
cleanup() {
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do umount -l "$root/${mounts[$i]}" 2>/dev/null || true; done
}
trap cleanup EXIT
mount -t proc proc "$root/proc"
mount --rbind /sys "$root/sys"
mount --rbind /dev "$root/dev"
mountpoint -q "$root/dev/pts" || mount -t devpts devpts "$root/dev/pts"
mountpoint -q "$root/dev/shm" || mount -t tmpfs tmpfs "$root/dev/shm"
status=0
for cmd in "bash deploy/quickstart.sh" "bash deploy/test.sh"; do
  log="check-$(echo "$cmd" | sed 's/.*\///; s/\.sh//').log"
  start=$(date +%s)
  set +e
  chroot "$root" /usr/bin/env -i HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin TERM=dumb "${extra_ca[@]}" \
    bash -c "cd /root/rockcal && $cmd" > "$root/root/rockcal/$log" 2>&1
  rc=$?
  set -e
  echo "$cmd: exit $rc after $(( $(date +%s) - start )) s (log: $root/root/rockcal/$log)"
  tail -n 5 "$root/root/rockcal/$log" | sed 's/^/  | /'
  [ $rc -eq 0 ] || status=1
done
echo "node in the bare root: $(chroot "$root" node --version 2>/dev/null || echo none)"
exit $status

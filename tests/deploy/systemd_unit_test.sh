#!/usr/bin/env bash
# deploy/rockcal.service passes `systemd-analyze verify` with no warning at all (systemd's verify
# exits 0 on an unknown key, so any output fails the test too). Needs no running systemd; installs
# Debian's systemd package if systemd-analyze is missing. Usage: systemd_unit_test.sh UNIT ROCKCAL
set -euo pipefail
unit=$1 rockcal=$2
if ! command -v systemd-analyze >/dev/null; then
  [ "$(id -u)" -eq 0 ] || { echo "systemd-analyze missing and not root to install it" >&2; exit 1; }
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq && apt-get install -y -qq --no-install-recommends systemd >/dev/null
fi
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
# verify checks that ExecStart's program exists: point it at the built binary.
grep -q '^ExecStart=/usr/local/bin/rockcal serve ' "$unit" || { echo "unexpected ExecStart" >&2; exit 1; }
sed "s|^ExecStart=/usr/local/bin/rockcal |ExecStart=$rockcal |" "$unit" > "$dir/rockcal.service"
out=$(systemd-analyze verify "$dir/rockcal.service" 2>&1) || { echo "$out" >&2; exit 1; }
[ -z "$out" ] || { echo "systemd-analyze verify warned:" >&2; echo "$out" >&2; exit 1; }
for key in NoNewPrivileges=yes ProtectSystem=strict PrivateTmp=yes Restart=on-failure \
           User=rockcal StateDirectory=rockcal EnvironmentFile=-/etc/rockcal/rockcal.env; do
  grep -qx "$key" "$unit" || { echo "missing $key" >&2; exit 1; }
done
echo "systemd-analyze verify: ok"

#!/usr/bin/env bash
# Installs every Debian package rockcal's build and tests need. Idempotent; quiet when all is present.
set -euo pipefail
packages=(
  build-essential cmake ninja-build pkg-config git procps
  libopenmpi-dev openmpi-bin
  libeigen3-dev libsqlite3-dev sqlite3 nlohmann-json3-dev libcpp-httplib-dev libssl-dev
  libnlopt-cxx-dev libnlopt-dev libgtest-dev libgmock-dev libcli11-dev
  libspdlog-dev libfmt-dev libbenchmark-dev curl
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0
echo "install-deps: installing ${missing[*]}" >&2
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null

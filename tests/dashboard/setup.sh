#!/usr/bin/env bash
# What the dashboard's browser test needs beyond the build: Debian's chromium (and a font), and
# playwright-core from the npm registry at the version package-lock.json pins, installed into
# DEST/node_modules (the build tree, not the sources). Idempotent; quiet when all is present.
#   bash tests/dashboard/setup.sh DEST
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
dest="${1:?usage: setup.sh DEST}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)

missing=()
[ -x /usr/bin/chromium ] || missing+=(chromium)
dpkg-query -W -f='${Status}' fonts-dejavu-core 2>/dev/null | grep -q "install ok installed" || missing+=(fonts-dejavu-core)
command -v node >/dev/null || missing+=(nodejs)
command -v npm >/dev/null || missing+=(npm)
if [ ${#missing[@]} -gt 0 ]; then
  echo "dashboard test: installing ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
node_major="$(node -p 'process.versions.node.split(".")[0]')"
if [ "$node_major" -lt 18 ]; then
  echo "dashboard test: playwright-core needs Node.js 18 or newer (Debian 12's own); this machine has $(node --version)" >&2
  exit 1
fi

mkdir -p "$dest"
if ! cmp -s "$here/package-lock.json" "$dest/.installed-lock.json" || [ ! -d "$dest/node_modules/playwright-core" ]; then
  cp "$here/package.json" "$here/package-lock.json" "$dest/"
  (cd "$dest" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
  cp "$here/package-lock.json" "$dest/.installed-lock.json"
fi

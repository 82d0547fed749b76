#!/usr/bin/env bash
# Configures and builds rockcal into ./build (Release). Extra arguments go to cmake.
set -euo pipefail
cd "$(dirname "$0")/.."
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
cmake -S . -B build "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DROCKCAL_ENGINE_ONLY=OFF "$@" >/dev/null
cmake --build build -j "$(nproc)"

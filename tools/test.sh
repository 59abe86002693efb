#!/usr/bin/env bash
# Builds and runs rayq's whole test suite: installs what is missing, configures, builds, ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/tools/setup.sh"
build="${RAYQ_BUILD_DIR:-$root/build/test}"
jobs="${RAYQ_JOBS:-$(nproc)}"
# Release at -O2 without -g: the test build is compile-bound; assertions stay on (no NDEBUG).
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O2 >/dev/null
cmake --build "$build" -j "$jobs"
ctest --test-dir "$build" --output-on-failure -j "$jobs" "$@"

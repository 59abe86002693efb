#!/usr/bin/env bash
# rayq's main job: the validation report. Installs what is missing, configures and builds
# rayq-validate, then runs it (default preset: under 10 minutes on 2 cores). Arguments are passed
# to rayq-validate (--quick, --full, --out DIR, --shard I/N, merge …; see --help). Exits non-zero
# when a gate fails.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/tools/setup.sh"
build="${RAYQ_BUILD_DIR:-$root/build/release}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRAYQ_BUILD_TESTS=OFF >/dev/null
# rayq-bench-native: the -march=native benchmark copies the speed campaign reads the issue-7 targets from.
cmake --build "$build" -j "${RAYQ_JOBS:-$(nproc)}" --target rayq-validate rayq-bench-native
exec "$build/tools/validate/rayq-validate" "$@"

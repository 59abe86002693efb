#!/usr/bin/env bash
# rayq's main job. For now: a short demo that intersects rays with every primitive under every
# policy and prints the hits (the validation report replaces it). Installs what is missing,
# configures and builds first. Arguments are passed to the program.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/tools/setup.sh"
build="${RAYQ_BUILD_DIR:-$root/build/release}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DRAYQ_BUILD_TESTS=OFF >/dev/null
cmake --build "$build" -j "${RAYQ_JOBS:-$(nproc)}" --target rayq-demo
exec "$build/tools/rayq-demo" "$@"

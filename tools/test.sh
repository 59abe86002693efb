#!/usr/bin/env bash
# Builds and runs rayq's whole test suite: installs what is missing, configures, builds, ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/tools/setup.sh"
build="${RAYQ_BUILD_DIR:-$root/build/test}"
jobs="${RAYQ_JOBS:-$(nproc)}"
# Release at -O1 without -g: the test build is compile-bound (-O1 compiles the typed-test TUs in
# ~60% of -O2's time and the suite runs as fast); assertions stay on (no NDEBUG). With the
# sanitizer stage below, the kernel suite's C++17 copy and the validation tests other than the
# edge-case test are built there (clang, ASan + UBSan), and the rest here; without it, all here.
standards="17;20"; groups="stats;oracle;mesh;fit;fuzz"; embree_tests=ON
[ "${RAYQ_SANITIZE:-1}" != 0 ] && standards=20 && groups=fuzz && embree_tests=OFF
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
      -DRAYQ_KERNEL_TEST_STANDARDS="$standards" -DRAYQ_VALIDATION_TEST_GROUPS="$groups" \
      -DRAYQ_EMBREE_TESTS="$embree_tests" >/dev/null
cmake --build "$build" -j "$jobs"
ctest --test-dir "$build" --output-on-failure -j "$jobs" "$@"

# Issue 9, sanitizers and fuzzing (RAYQ_SANITIZE=0 skips them), with clang: the kernel suite
# (C++17), the validation tests (stats, the CGAL oracle, the mesh comparison, the fits), the
# Embree adapter's tests and the edge-case and replay test under ASan + UBSan (-O1), then each
# libFuzzer harness (five primitive families, the file parsers) for RAYQ_FUZZ_SECONDS (default
# 30) on its corpus (tools/sanitize/CMakeLists.txt). Every test of the suite thus runs under the
# sanitizers except the edge-case test's exact-oracle samples and the tools' smoke tests (of
# those, rayq-fuzz's and rayq-demo's run there too).
if [ "${RAYQ_SANITIZE:-1}" != 0 ]; then
  sanitize="${RAYQ_SANITIZE_BUILD_DIR:-$build-sanitize}"
  cmake -S "$root/tools/sanitize" -B "$sanitize" -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 \
        -DRAYQ_FUZZ_KERNEL_TESTS=ON -DRAYQ_FUZZ_SECONDS="${RAYQ_FUZZ_SECONDS:-30}" >/dev/null
  cmake --build "$sanitize" -j "$jobs" --target rayq_sanitize_ci
  ctest --test-dir "$sanitize" --output-on-failure -j "$jobs"
fi

#!/usr/bin/env bash
# Builds and runs rayq's whole test suite: installs what is missing, configures, builds, ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/tools/setup.sh"
build="${RAYQ_BUILD_DIR:-$root/build/test}"
jobs="${RAYQ_JOBS:-$(nproc)}"
# Release at -O1 without -g: the test build is compile-bound (-O1 compiles the typed-test TUs in
# ~60% of -O2's time and the suite runs as fast); assertions stay on (no NDEBUG). With the
# sanitizer stage below (the default), everything that runs is run there, under ASan + UBSan, and
# this build keeps what tests the compiler and the packaging: the kernel suite's C++20 copy, the
# README example, the header self-containment and find_package checks. With RAYQ_SANITIZE=0,
# the whole suite is built and run here.
# That C++20 copy is built with RAYQ_NO_FLATTEN (GCC compiles it in about a third of the time;
# the sanitizer stage tests the flattened build).
validation=ON; standards="17;20"; embree_tests=ON; no_flatten=OFF
[ "${RAYQ_SANITIZE:-1}" != 0 ] && validation=OFF && standards=20 && embree_tests=OFF && no_flatten=ON
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O1 \
      -DRAYQ_KERNEL_TEST_STANDARDS="$standards" -DRAYQ_BUILD_VALIDATION="$validation" -DRAYQ_BUILD_TOOLS="$validation" \
      -DRAYQ_VALIDATION_TEST_GROUPS="stats;oracle;mesh;fit;fuzz" -DRAYQ_EMBREE_TESTS="$embree_tests" \
      -DRAYQ_KERNEL_TESTS_NO_FLATTEN="$no_flatten" >/dev/null
cmake --build "$build" -j "$jobs"
ctest --test-dir "$build" --output-on-failure -j "$jobs" "$@"

# Issue 9, sanitizers and fuzzing (RAYQ_SANITIZE=0 skips them), with clang: the kernel suite
# (C++17), the validation suite's tests, the tools' smoke tests and the Embree adapter's tests
# under ASan + UBSan (-O1), then each libFuzzer harness (five primitive families, the file
# parsers) for RAYQ_FUZZ_SECONDS (default 30) on its corpus (tools/sanitize/CMakeLists.txt).
if [ "${RAYQ_SANITIZE:-1}" != 0 ]; then
  sanitize="${RAYQ_SANITIZE_BUILD_DIR:-$build-sanitize}"
  cmake -S "$root/tools/sanitize" -B "$sanitize" -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 \
        -DRAYQ_FUZZ_KERNEL_TESTS=ON -DRAYQ_FUZZ_SECONDS="${RAYQ_FUZZ_SECONDS:-30}" >/dev/null
  cmake --build "$sanitize" -j "$jobs"
  ctest --test-dir "$sanitize" --output-on-failure -j "$jobs"
fi

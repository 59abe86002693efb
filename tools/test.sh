#!/usr/bin/env bash
# Builds and runs rayq's whole test suite: installs what is missing, configures, builds, ctest.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
"$root/tools/setup.sh"
build="${RAYQ_BUILD_DIR:-$root/build/test}"
jobs="${RAYQ_JOBS:-$(nproc)}"
# Release at -O2 without -g: the test build is compile-bound; assertions stay on (no NDEBUG).
sanitize_cxx17=ON; [ "${RAYQ_SANITIZE:-1}" = 0 ] && sanitize_cxx17=OFF
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE=-O2 \
      -DRAYQ_SANITIZE_CXX17_TESTS=$sanitize_cxx17 >/dev/null
cmake --build "$build" -j "$jobs"
ctest --test-dir "$build" --output-on-failure -j "$jobs" "$@"

# Issue 9, sanitizers and fuzzing (RAYQ_SANITIZE=0 skips them). Above, the kernel tests' C++17
# copy ran under g++'s ASan + UBSan (the C++20 copy without). Here, with clang: the edge-case and
# replay test under ASan + UBSan (-O1), then each libFuzzer harness for RAYQ_FUZZ_SECONDS (default
# 30) on its corpus (validation/fuzz/CMakeLists.txt). The CGAL-based oracle and mesh tests are not
# sanitized: their TUs take minutes and gigabytes under ASan (/work/shared/DEPENDENCIES.md).
if [ "${RAYQ_SANITIZE:-1}" != 0 ]; then
  sanitize="${RAYQ_SANITIZE_BUILD_DIR:-$build-sanitize}"
  cmake -S "$root/validation/fuzz" -B "$sanitize" -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 \
        -DRAYQ_FUZZ_KERNEL_TESTS=OFF -DRAYQ_FUZZ_SECONDS="${RAYQ_FUZZ_SECONDS:-30}" >/dev/null
  cmake --build "$sanitize" -j "$jobs" --target rayq_sanitize_ci
  ctest --test-dir "$sanitize" --output-on-failure -j "$jobs"
fi

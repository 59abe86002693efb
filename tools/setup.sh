#!/usr/bin/env bash
# Installs the Debian packages rayq's build, tests and tools need, and nothing when they are
# all present (idempotent). Debian bookworm, run as root (or with sudo available).
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config   # build
  libgtest-dev                       # kernel tests
  libbenchmark-dev                   # benchmarks (tools/bench)
  libcgal-dev libgmp-dev libmpfr-dev libboost-dev   # validation/oracle: exact arithmetic
  libopenmesh-dev libeigen3-dev      # validation/mesh: tessellations
  nlohmann-json3-dev                 # validation/stats, the report: JSON summaries
  libceres-dev                       # validation/fit: error-model fits (issue 6)
  libembree-dev                      # adapters/embree: rayq primitives in Embree's BVH (issue 7)
  gnuplot-nox                        # the report's plots (SVG)
  chromium                           # the report's headless-browser test
  clang-14 libclang-rt-14-dev        # sanitizer build and libFuzzer harnesses (tools/sanitize)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "rayq setup: installing ${missing[*]}" >&2
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null

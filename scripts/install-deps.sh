#!/usr/bin/env bash
# Installs what building and testing Proxima needs on Debian 12, from Debian's packages.
# Run as root or with sudo available.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
export DEBIAN_FRONTEND=noninteractive
packages=(
  build-essential cmake ninja-build pkg-config git
  ccache                             # compiler cache: a warm cache makes rebuilds fast
  libglm-dev libqhull-dev            # the library: math, convex hulls
  libcli11-dev nlohmann-json3-dev    # the proxima tool
  libassimp-dev                      # the proxima tool: mesh files (OBJ, STL, PLY, glTF)
  libpng-dev                         # the proxima tool: sprite masks from PNG files
  libcairo2-dev                      # the proxima tool: pictures of captures (render, demos' PNG)
  libcpp-httplib-dev                 # the proxima tool: `proxima view` serves the web viewer
  chromium                           # the web viewer's browser test (viewer/test, playwright-core)
  libgtest-dev libgmock-dev          # tests
  libcgal-dev                        # exact reference computations in tests
  clang clang-format                 # the sanitizer build (clang), the formatting test
  libbenchmark-dev                   # benchmarks
  python3-pygame                     # reference answers and timings of the sprite tests and benchmark
                                     # (run with /usr/bin/python3, Debian's interpreter)
  pybind11-dev python3-dev python3-numpy python3-pytest python3-setuptools
                                     # the Python package (python/), built for /usr/bin/python3
  python3-dask python3-distributed python3-pil python3-open3d
                                     # its examples and tests: a sweep over worker processes,
                                     # PNG depth images, Open3D as a peer (tests and benchmarks only)
  libtbb-dev                         # the oneTBB executor example (examples/tbb_executor.cpp)
  # Peer libraries: references for the cross-validation tests and the side-by-side
  # benchmarks only; the library never links them.
  libfcl-dev libccd-dev libbullet-dev libode-dev libembree-dev
  libbox2d-dev                       # Box2D 2.4: the 2D module's peer (tests/d2, bench_d2_pairs)
)
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${packages[@]}" >/dev/null
echo "install-deps: ${#packages[@]} packages present"

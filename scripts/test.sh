#!/usr/bin/env bash
# Installs the dependencies, then builds and runs every test in three configurations:
# AddressSanitizer + UBSan (float), double precision, and release (float, with the package
# consumers: find_package, add_subdirectory, FetchContent). Warnings are errors. The last
# lines printed are ctest's summary of the release run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=$(nproc)

build_and_test() {
  local preset=$1; shift
  echo "== ${preset}: configure and build"
  cmake --preset "${preset}" "$@" >/dev/null || return 1
  cmake --build --preset "${preset}" -j "${jobs}" || return 1
  echo "== ${preset}: test"
  ctest --preset "${preset}" -j "${jobs}" || return 1
}

status=0
build_and_test ci-asan -DPROXIMA_TEST_PACKAGE=OFF || status=1
build_and_test ci-double -DPROXIMA_TEST_PACKAGE=OFF || status=1
build_and_test ci-release || status=1
exit "${status}"

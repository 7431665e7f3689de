#!/usr/bin/env bash
# Installs the dependencies, then builds and runs every test in three configurations:
# AddressSanitizer + UBSan (float), double precision, and release (float, with the benchmark
# programs, the workload tests and the package consumers: find_package, and FetchContent
# with PROXIMA_EXCEPTIONS=OFF). Warnings are errors. The last lines printed are ctest's
# summary of the release run. Compilation goes through ccache: a cold cache builds everything, a warm one
# (the same checkout rebuilt) only what changed.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
npm ci --prefix viewer --no-audit --no-fund  # three.js and playwright-core for viewer.browser
jobs=$(nproc)

launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="${PWD}" CCACHE_NOHASHDIR=1 CCACHE_MAXSIZE="${CCACHE_MAXSIZE:-8G}"
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi

# Open defects (tests/known_failures.txt): an exclusion regex of exact ctest names for one
# build (float, double, or asan: the clang sanitizer build), printed so that nobody mistakes
# the run for a clean one.
known_failures() {
  local precision=$1 names
  names=$(awk -v p="${precision}" '$1 == p { print $2 }' tests/known_failures.txt)
  [ -n "${names}" ] || return 0
  echo "== known failures excluded (${precision}; see docs/validation.md):" >&2
  echo "${names}" | sed 's/^/     /' >&2
  # Each name as "^name$|^name " (a parameterised test's name goes on after a space), with no
  # groups: CMake's regular expressions allow nine groups, and with ten or more names ctest
  # ran some of the excluded tests (seen with fourteen).
  echo "${names}" | sed 's/[.]/[.]/g; s/.*/^&$|^& /' | paste -sd'|'
}

build_and_test() {
  local preset=$1 precision=$2; shift 2
  echo "== ${preset}: configure and build"
  cmake --preset "${preset}" "${launcher[@]}" "$@" >/dev/null || return 1
  cmake --build --preset "${preset}" -j "${jobs}" || return 1
  echo "== ${preset}: test"
  local exclude
  exclude=$(known_failures "${precision}")
  if [ -n "${exclude}" ]; then
    ctest --preset "${preset}" -j "${jobs}" -E "${exclude}" || return 1
  else
    ctest --preset "${preset}" -j "${jobs}" || return 1
  fi
}

status=0
build_and_test ci-asan asan -DPROXIMA_TEST_PACKAGE=OFF || status=1
build_and_test ci-double double -DPROXIMA_TEST_PACKAGE=OFF -DPROXIMA_BUILD_BENCH=OFF || status=1
build_and_test ci-release float || status=1
exit "${status}"

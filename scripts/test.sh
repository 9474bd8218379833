#!/usr/bin/env bash
# Builds the library checks, tools, examples, tests and the Python package
# and runs the whole test suite (pytest included), then builds the tests
# again with AddressSanitizer and UndefinedBehaviorSanitizer and runs them
# (the programs the tests call are the release ones built first). This is
# the README's test command; .ci/run calls it. MREPAIR_SKIP_ASAN=1 runs the
# release suite only. The benchmark harness (nine heavy translation units,
# about 4 of CI's 30 minutes) is left out unless MREPAIR_BUILD_BENCHMARKS=ON;
# `cmake --preset release` alone builds it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
# The Python package and its pytest suite (one CTest test) join the release
# pass only, built for Debian's interpreter (not one a version manager put first on PATH).
cmake --preset release -DMREPAIR_BUILD_BENCHMARKS="${MREPAIR_BUILD_BENCHMARKS:-OFF}" \
  -DMREPAIR_BUILD_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3
cmake --build --preset release
ctest --preset release
if [ "${MREPAIR_SKIP_ASAN:-0}" != 1 ]; then
  cmake --preset asan
  cmake --build --preset asan
  ctest --preset asan
fi

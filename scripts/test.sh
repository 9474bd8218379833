#!/usr/bin/env bash
# Builds the library checks, tools, examples and tests and runs the whole
# test suite, then builds the tests again with AddressSanitizer and
# UndefinedBehaviorSanitizer and runs them (the programs the tests call are
# the release ones built first). This is the README's test command; .ci/run
# calls it. MREPAIR_SKIP_ASAN=1 runs the release suite only. The benchmark
# harness (nine heavy translation units, about 4 of CI's 30 minutes) is left
# out unless MREPAIR_BUILD_BENCHMARKS=ON; `cmake --preset release` alone
# builds it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
cmake --preset release -DMREPAIR_BUILD_BENCHMARKS="${MREPAIR_BUILD_BENCHMARKS:-OFF}"
cmake --build --preset release
ctest --preset release
if [ "${MREPAIR_SKIP_ASAN:-0}" != 1 ]; then
  cmake --preset asan
  cmake --build --preset asan
  ctest --preset asan
fi

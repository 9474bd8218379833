#!/usr/bin/env bash
# The CGAL 6 pass of the test command: fetches Debian 13's CGAL 6.0.1 into
# build/cgal-trixie (scripts/fetch_cgal.sh: nothing is installed, the system's
# CGAL 5.5 stays the default), then builds the test suite against it with
# AddressSanitizer and UndefinedBehaviorSanitizer and warnings as errors in
# mrepair's own code (preset `cgal6`), and runs it; the benchmark harness is
# compiled and linked in the same build. The tests that run the programs use
# those of build/release when it exists and skip otherwise.
#
#   bash scripts/test_cgal6.sh          # what CI runs (scripts/test.sh calls it)
#   bash scripts/test_cgal6.sh --all    # everything in Release against CGAL 6:
#                                       # tools, examples, harness, Python module
#                                       # and tests (build/cgal6-release), then ctest
set -euo pipefail
cd "$(dirname "$0")/.."
cgal_dir="$(bash scripts/fetch_cgal.sh build/cgal-trixie trixie | tail -n 1)"
if [ "${1:-}" = "--all" ]; then
  cmake --preset release -B build/cgal6-release -DCGAL_DIR="$cgal_dir" \
    -DMREPAIR_WARNINGS_AS_ERRORS=ON -DMREPAIR_BUILD_BENCHMARKS=ON \
    -DMREPAIR_BUILD_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3
  cmake --build build/cgal6-release -j 2
  ctest --test-dir build/cgal6-release -j 2 --output-on-failure --timeout 900
else
  # the harness only compiles and links here (it runs in the release pass)
  # (unoptimized and not instrumented: it does not run in this pass)
  cmake --preset cgal6 -DCGAL_DIR="$cgal_dir" -DMREPAIR_BUILD_BENCHMARKS="${MREPAIR_BUILD_BENCHMARKS:-ON}" \
    "-DMREPAIR_BENCH_COMPILE_OPTIONS=-O0;-fno-sanitize=all"
  cmake --build --preset cgal6
  ctest --preset cgal6
fi

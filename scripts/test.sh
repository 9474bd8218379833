#!/usr/bin/env bash
# The README's test command; .ci/run calls it. Two passes, one per supported
# CGAL release:
#  1. CGAL 5.5 (Debian 12's libcgal-dev): builds every target of the README's
#     default build (`cmake --preset release`: library checks, tools,
#     examples, tests, the benchmark harness, the studio's assets) and the
#     Python package in Release, and runs the whole suite (pytest included;
#     the harness runs every task once on a small generated input).
#  2. CGAL 6.0.1 (Debian 13's libcgal-dev, unpacked into build/cgal-trixie by
#     scripts/fetch_cgal.sh, nothing installed): builds the tests again, at
#     -O0 (half the compiler time of -O1 with the sanitizers; the tests that
#     run thousands of generated cases keep -O1), with
#     AddressSanitizer and UndefinedBehaviorSanitizer (arithmetic, shift,
#     bounds, bool, enum, return checks; not null/alignment/object-size/vptr/
#     pointer-overflow, which tripled GCC's time at -O1) and warnings as errors in
#     mrepair's code, and runs them (scripts/test_cgal6.sh; the tests that run
#     the programs use those of pass 1); the benchmark harness is compiled and
#     linked there too, so an API difference in it shows on both releases.
# The sanitizers run in the CGAL 6 pass rather than in a third one: CI has 60
# minutes and each pass takes about 20 of them on 2 cores; mrepair's memory and
# undefined-behaviour errors do not depend on the CGAL release, and the tests
# instantiate every public header on both mesh types, which is what catches an
# API difference. `cmake --preset asan` still builds the sanitized tests on 5.5.
#
# MREPAIR_SKIP_CGAL6=1 (or the older MREPAIR_SKIP_ASAN=1) runs pass 1 only.
# MREPAIR_BUILD_BENCHMARKS=OFF leaves the harness out of both passes (for a
# quicker local run; CI builds it). Each step prints its seconds.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
# The Python package and its pytest suite (one CTest test) join the release
# pass only, built for Debian's interpreter (not one a version manager put first on PATH).
started=$SECONDS
step() { echo "== test.sh: $1 ($((SECONDS - started)) s so far)"; }
step "configure (CGAL 5.5)"
# CI compiles every target a user builds but times none of them, so this
# pass trades optimization for compiler time (`cmake --preset release` keeps
# -O3 for the programs, the Python module and the harness, -O1 for the tests
# and examples): the tests and the examples at -O0 (GCC spends ~30% less than
# at -O1 on CGAL code: examples/repair.cpp 113 against 165 CPU-s), but the two
# test pairs that run thousands of generated cases (-O1 in Release, see
# test/CMakeLists.txt: at -O0 the invariants ran 78 + 63 s instead of 6 + 2 s)
# and compare_to_reference's exact ray casts (examples/CMakeLists.txt); the
# mrepair program, the Python module and the harness at -O1 (the repair
# command's TU took 337 s wall at -O3, the harness's two 371 and 356 s).
cmake --preset release -DMREPAIR_BUILD_BENCHMARKS="${MREPAIR_BUILD_BENCHMARKS:-ON}" \
  -DMREPAIR_BUILD_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3 \
  -DMREPAIR_EXAMPLE_OPTIMIZATION="${MREPAIR_EXAMPLE_OPTIMIZATION:--O0}" \
  -DMREPAIR_TEST_OPTIMIZATION="${MREPAIR_TEST_OPTIMIZATION:--O0}" \
  -DMREPAIR_PROGRAM_OPTIMIZATION="${MREPAIR_PROGRAM_OPTIMIZATION:--O1}" \
  -DMREPAIR_BENCH_COMPILE_OPTIONS="${MREPAIR_BENCH_COMPILE_OPTIONS:--O1}"
step "build (CGAL 5.5)"
cmake --build --preset release
step "ctest (CGAL 5.5)"
ctest --preset release
if [ "${MREPAIR_SKIP_CGAL6:-${MREPAIR_SKIP_ASAN:-0}}" != 1 ]; then
  step "CGAL 6 pass"
  bash scripts/test_cgal6.sh
fi
step "done"

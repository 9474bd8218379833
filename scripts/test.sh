#!/usr/bin/env bash
# The README's test command; .ci/run calls it. Two passes, one per supported
# CGAL release:
#  1. CGAL 5.5 (Debian 12's libcgal-dev): builds the library checks, tools,
#     examples, tests and the Python package in Release and runs the whole
#     suite (pytest included).
#  2. CGAL 6.0.1 (Debian 13's libcgal-dev, unpacked into build/cgal-trixie by
#     scripts/fetch_cgal.sh, nothing installed): builds the tests again with
#     AddressSanitizer and UndefinedBehaviorSanitizer and warnings as errors in
#     mrepair's code, and runs them (scripts/test_cgal6.sh; the tests that run
#     the programs use those of pass 1).
# The sanitizers run in the CGAL 6 pass rather than in a third one: CI has 60
# minutes and each pass takes about 20 of them on 2 cores; mrepair's memory and
# undefined-behaviour errors do not depend on the CGAL release, and the tests
# instantiate every public header on both mesh types, which is what catches an
# API difference. `cmake --preset asan` still builds the sanitized tests on 5.5.
#
# MREPAIR_SKIP_CGAL6=1 (or the older MREPAIR_SKIP_ASAN=1) runs pass 1 only.
# The benchmark harness (ten heavy translation units) is left out unless
# MREPAIR_BUILD_BENCHMARKS=ON; `cmake --preset release` alone builds it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
# The Python package and its pytest suite (one CTest test) join the release
# pass only, built for Debian's interpreter (not one a version manager put first on PATH).
cmake --preset release -DMREPAIR_BUILD_BENCHMARKS="${MREPAIR_BUILD_BENCHMARKS:-OFF}" \
  -DMREPAIR_BUILD_PYTHON=ON -DPython3_EXECUTABLE=/usr/bin/python3
cmake --build --preset release
ctest --preset release
if [ "${MREPAIR_SKIP_CGAL6:-${MREPAIR_SKIP_ASAN:-0}}" != 1 ]; then
  bash scripts/test_cgal6.sh
fi

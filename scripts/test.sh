#!/usr/bin/env bash
# Builds everything (library checks, tools, examples, benchmarks) and runs the
# whole test suite. This is the README's test command; .ci/run calls it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_deps.sh
cmake --preset release
cmake --build --preset release
ctest --preset release

#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/) with clang, writes the seed corpus and
# runs the given targets (or all) side by side, for SECONDS each.
#   usage: scripts/fuzz.sh read|soup|mesh|all... SECONDS   (e.g. `read soup 600`)
# Environment: MREPAIR_FUZZ_BUILD (build dir, default build/fuzz),
#   MREPAIR_FUZZ_JOBS (build jobs, default 1), MREPAIR_FUZZ_NICE (default 19),
#   MREPAIR_FUZZ_ARGS (extra libFuzzer flags).
# Per target, in the build dir: corpus/TARGET (the growing corpus, kept between
# runs), seeds/TARGET (written afresh), artifacts/TARGET/ (crash-, leak-,
# timeout-, oom- inputs), TARGET.log. Exits 1 when a run left an artifact.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
usage() { echo "usage: scripts/fuzz.sh read|soup|mesh|all... SECONDS" >&2; exit 2; }
[ $# -ge 2 ] || usage
seconds=${!#}
[[ "$seconds" =~ ^[0-9]+$ ]] || usage
targets=()
for a in "${@:1:$#-1}"; do
  case "$a" in
    all) targets+=(read soup mesh) ;;
    read|soup|mesh) targets+=("$a") ;;
    *) echo "unknown target '$a' (read, soup, mesh or all)" >&2; exit 2 ;;
  esac
done
build=${MREPAIR_FUZZ_BUILD:-$root/build/fuzz}
jobs=${MREPAIR_FUZZ_JOBS:-1}
nice_level=${MREPAIR_FUZZ_NICE:-19}

# clang with libFuzzer's runtime (Debian: clang + libclang-rt-14-dev)
if ! command -v clang++ >/dev/null || ! dpkg-query -W -f='${Status}' libclang-rt-14-dev 2>/dev/null | grep -q "install ok installed"; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO=sudo
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends clang libclang-rt-14-dev
fi
bash scripts/install_deps.sh

if [ ! -f "$build/CMakeCache.txt" ]; then
  # Debug: CGAL assertions stay on (a failed one is a finding); the targets add -O1
  CC=clang CXX=clang++ cmake -S "$root" -B "$build" -DCMAKE_BUILD_TYPE=Debug \
    -DMREPAIR_BUILD_FUZZERS=ON -DMREPAIR_BUILD_TESTS=OFF -DMREPAIR_BUILD_EXAMPLES=OFF \
    -DMREPAIR_BUILD_TOOLS=OFF -DMREPAIR_BUILD_BENCHMARKS=OFF
fi
cmake --build "$build" --target mrepair-fuzz-corpus -j "$jobs"
for t in "${targets[@]}"; do cmake --build "$build" --target "fuzz_$t" -j "$jobs"; done

rm -rf "$build/seeds"
"$build/fuzz/mrepair-fuzz-corpus" "$build/seeds"

run() {
  local t=$1
  mkdir -p "$build/corpus/$t" "$build/artifacts/$t"
  # the first corpus directory receives new inputs; the seeds are read only
  # shellcheck disable=SC2086
  nice -n "$nice_level" "$build/fuzz/fuzz_$t" "$build/corpus/$t" "$build/seeds/$t" \
    -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$build/artifacts/$t/" ${MREPAIR_FUZZ_ARGS:-} > "$build/$t.log" 2>&1 || true
  echo "fuzz_$t: $(grep -E '^(#[0-9]+\s+DONE|stat::number_of_executed_units)' "$build/$t.log" | tr '\n' ' ')"
}
for t in "${targets[@]}"; do run "$t" & done
wait

status=0
for t in "${targets[@]}"; do
  # slow-unit-* inputs are only reported (a loaded machine makes them); the rest are findings
  found=$(find "$build/artifacts/$t" -type f \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) | sort)
  if [ -n "$found" ]; then
    echo "fuzz_$t: findings in $build/artifacts/$t (log: $build/$t.log):"
    echo "$found"
    status=1
  fi
done
exit $status

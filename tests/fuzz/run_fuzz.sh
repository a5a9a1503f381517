#!/usr/bin/env bash
# Fuzzes the BVH reader with libFuzzer for a bounded time; exits non-zero on a finding.
#
# Usage: tests/fuzz/run_fuzz.sh [seconds=60]
# Environment: MOTIONSTYLE_FUZZ_BUILD (build folder, default <repo>/build/fuzz), MOTIONSTYLE_FUZZ_JOBS
# (parallel fuzzing processes, default 1).
#
# Configures a separate clang build with only the core BVH sources and the fuzz target (instrumented
# for coverage with AddressSanitizer and UBSan), then fuzzes from a scratch copy of the committed seed
# corpus (tests/fuzz/corpus/bvh) so the repository is never modified. A crashing input is kept as
# <build>/artifacts/crash-*; reproduce it with: <build>/tests/fuzz/fuzz_bvh_reader <that file>.
set -euo pipefail

seconds="${1:-60}"
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build="${MOTIONSTYLE_FUZZ_BUILD:-$root/build/fuzz}"
jobs="${MOTIONSTYLE_FUZZ_JOBS:-1}"

mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DMOTIONSTYLE_BUILD_FUZZ=ON -DMOTIONSTYLE_BUILD_GUI=OFF -DMOTIONSTYLE_BUILD_TESTS=OFF \
  -DMOTIONSTYLE_BUILD_BENCH=OFF -DMOTIONSTYLE_ARCH=portable >"$build/configure.log" 2>&1 ||
  { cat "$build/configure.log"; exit 1; }
cmake --build "$build" --target fuzz_bvh_reader

corpus=$(mktemp -d "${TMPDIR:-/tmp}/motionstyle-fuzz-corpus.XXXXXX")
trap 'rm -rf "$corpus"' EXIT
cp "$root"/tests/fuzz/corpus/bvh/* "$corpus"/
mkdir -p "$build/artifacts"

parallel=()
if [ "$jobs" -gt 1 ]; then parallel=(-jobs="$jobs" -workers="$jobs"); fi

echo "fuzzing parseBvh for ${seconds} s from $(ls "$corpus" | wc -l) seeds"
status=0
ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}" \
UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}" \
  "$build/tests/fuzz/fuzz_bvh_reader" -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 \
  -timeout=10 -dict="$root/tests/fuzz/bvh.dict" -print_final_stats=1 "${parallel[@]}" \
  -artifact_prefix="$build/artifacts/" "$corpus" || status=$?

if [ "$status" -ne 0 ]; then
  echo "run_fuzz.sh: FINDING (exit $status): see $build/artifacts/" >&2
  exit "$status"
fi
echo "run_fuzz.sh: no finding in ${seconds} s"

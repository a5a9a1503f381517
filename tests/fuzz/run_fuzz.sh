#!/usr/bin/env bash
# Fuzzes the BVH reader and/or the network file reader with libFuzzer for a bounded time; exits
# non-zero on a finding.
#
# Usage: tests/fuzz/run_fuzz.sh [seconds=60] [bvh|network|all=all]
#   seconds is PER TARGET: "run_fuzz.sh 30 all" fuzzes each of the two targets for 30 s, side by side.
# Environment: MOTIONSTYLE_FUZZ_BUILD (build folder, default <repo>/build/fuzz), MOTIONSTYLE_FUZZ_JOBS
# (parallel fuzzing processes per target, default 1).
#
# Configures a separate clang build with only the core sources each target needs and the fuzz targets
# (instrumented for coverage with AddressSanitizer and UBSan), then fuzzes each target from a scratch
# copy of its committed seed corpus (tests/fuzz/corpus/<target>) so the repository is never modified.
# A crashing input is kept as <build>/artifacts/<target>/crash-*; reproduce it with
# <build>/tests/fuzz/fuzz_bvh_reader <that file> (or fuzz_network_file).
set -euo pipefail

seconds="${1:-60}"
which="${2:-all}"
case "$which" in
  bvh) targets=(bvh) ;;
  network) targets=(network) ;;
  all) targets=(bvh network) ;;
  *) echo "run_fuzz.sh: unknown target '$which' (bvh, network or all)" >&2; exit 2 ;;
esac
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
build="${MOTIONSTYLE_FUZZ_BUILD:-$root/build/fuzz}"
jobs="${MOTIONSTYLE_FUZZ_JOBS:-1}"

# Per target: executable, what it fuzzes, dictionary, largest input (a seed network file is ~27 KB).
declare -A program=([bvh]=fuzz_bvh_reader [network]=fuzz_network_file)
declare -A subject=([bvh]="parseBvh" [network]="the network file reader")
declare -A dictionary=([bvh]=bvh.dict [network]=network.dict)
declare -A max_len=([bvh]=65536 [network]=65536)

mkdir -p "$build"
CC=clang CXX=clang++ cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DMOTIONSTYLE_BUILD_FUZZ=ON -DMOTIONSTYLE_BUILD_GUI=OFF -DMOTIONSTYLE_BUILD_TESTS=OFF \
  -DMOTIONSTYLE_BUILD_BENCH=OFF -DMOTIONSTYLE_ARCH=portable >"$build/configure.log" 2>&1 ||
  { cat "$build/configure.log"; exit 1; }
for target in "${targets[@]}"; do cmake --build "$build" --target "${program[$target]}"; done

corpus=$(mktemp -d "${TMPDIR:-/tmp}/motionstyle-fuzz-corpus.XXXXXX")
trap 'rm -rf "$corpus"' EXIT

parallel=()
if [ "$jobs" -gt 1 ]; then parallel=(-jobs="$jobs" -workers="$jobs"); fi

# The targets fuzz at the same time, one process each (a 2-core machine fuzzes both in the time of
# one); each one's output goes to <build>/fuzz-<target>.log and is printed when it ends.
declare -A pid=()
for target in "${targets[@]}"; do
  mkdir -p "$corpus/$target" "$build/artifacts/$target"
  cp "$root/tests/fuzz/corpus/$target"/* "$corpus/$target"/
  echo "fuzzing ${subject[$target]} for ${seconds} s from $(ls "$corpus/$target" | wc -l) seeds"
  ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}" \
  UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}" \
    "$build/tests/fuzz/${program[$target]}" -max_total_time="$seconds" -max_len="${max_len[$target]}" \
    -rss_limit_mb=2048 -timeout=10 -dict="$root/tests/fuzz/${dictionary[$target]}" -print_final_stats=1 \
    "${parallel[@]}" -artifact_prefix="$build/artifacts/$target/" "$corpus/$target" \
    >"$build/fuzz-$target.log" 2>&1 &
  pid[$target]=$!
done

findings=()
for target in "${targets[@]}"; do
  status=0
  wait "${pid[$target]}" || status=$?
  echo "--- ${subject[$target]} (exit $status): the end of $build/fuzz-$target.log"
  tail -n 25 "$build/fuzz-$target.log"
  if [ "$status" -ne 0 ]; then
    echo "run_fuzz.sh: FINDING in $target (exit $status): see $build/artifacts/$target/" >&2
    findings+=("$target")
  fi
done
if [ "${#findings[@]}" -gt 0 ]; then exit 1; fi
echo "run_fuzz.sh: no finding in ${seconds} s per target (${targets[*]}), run side by side"

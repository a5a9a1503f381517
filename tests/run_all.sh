#!/usr/bin/env bash
# The whole test suite, from a fresh Debian 12 machine: installs the dependencies, builds everything
# with warnings as errors, fuzzes the BVH parser and the network file reader for a bounded time, runs
# the unit tests under AddressSanitizer + UBSan, then runs every ctest test: unit, cli (motionstyle-cli
# end to end: exit codes, outputs, kill and mutation tests), gui (a real window under xvfb-run) and
# data (tests over ../shared/data, which skip with a message when the licensed dataset is absent).
#
# Environment: MOTIONSTYLE_BUILD_ROOT (default <repo>/build), MOTIONSTYLE_FUZZ_SECONDS (seconds PER fuzz
# target, default 30: the two targets run side by side), MOTIONSTYLE_SKIP_SANITIZERS=1 to skip the sanitizer
# pass (local iteration only).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build_root="${MOTIONSTYLE_BUILD_ROOT:-$root/build}"
jobs=$(nproc)

bash "$root/packaging/install-deps.sh"

echo "== build (Release, strict warnings)"
cmake -S "$root" -B "$build_root/release" -G Ninja -DCMAKE_BUILD_TYPE=Release -DMOTIONSTYLE_STRICT_WARNINGS=ON
cmake --build "$build_root/release" -j"$jobs"

echo "== fuzz the BVH parser and the network file reader (${MOTIONSTYLE_FUZZ_SECONDS:-30} s each)"
MOTIONSTYLE_FUZZ_BUILD="$build_root/fuzz" bash "$root/tests/fuzz/run_fuzz.sh" "${MOTIONSTYLE_FUZZ_SECONDS:-30}" all

if [ "${MOTIONSTYLE_SKIP_SANITIZERS:-0}" != "1" ]; then
  echo "== unit tests under AddressSanitizer + UBSan"
  # -O1 -g1 (line tables: enough for the sanitizers' stack traces): half the compile time of -O2 -g on
  # this Eigen-heavy code (7.7 vs 13.7 min on 2 cores) for ~30 s more test time.
  cmake -S "$root" -B "$build_root/sanitize" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMOTIONSTYLE_SANITIZE=ON \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DCMAKE_C_FLAGS_RELWITHDEBINFO="-O1 -g1" \
        -DMOTIONSTYLE_BUILD_CLI=OFF -DMOTIONSTYLE_BUILD_GUI=OFF -DMOTIONSTYLE_BUILD_BENCH=OFF -DMOTIONSTYLE_ARCH=portable
  cmake --build "$build_root/sanitize" -j"$jobs"
  # The whole-network gradient checks (TransformerGradient, LossNetworkGradient: 110 s of the pass's
  # 190 s under ASan) run every layer's code that the per-layer gradient tests run here already; the
  # release pass below runs them too.
  ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$build_root/sanitize" -L unit -E '^(TransformerGradient|LossNetworkGradient)\.' \
          --output-on-failure -j"$jobs"
fi

echo "== all tests (unit, gui, data)"
if [ -d "$root/../shared/data/bandai" ]; then
  echo "licensed dataset found: data-labelled tests run"
else
  echo "../shared/data/bandai is absent: data-labelled tests will report as skipped"
fi
ctest --test-dir "$build_root/release" --output-on-failure -j"$jobs"

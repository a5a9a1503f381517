#!/usr/bin/env bash
# The main job on bundled sample data, from a fresh Debian 12 machine: installs the dependencies,
# builds MotionStyle (Release), then runs the demo on the clips in resources/samples/.
# Environment: MOTIONSTYLE_BUILD_ROOT (default <repo>/build).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${MOTIONSTYLE_BUILD_ROOT:-$root/build}/release"

bash "$root/packaging/install-deps.sh"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
# Only what the demo runs: the tests and benchmarks are built by tests/run_all.sh.
cmake --build "$build" -j"$(nproc)" --target motionstyle-cli motionstyle

cli="$build/app/cli/motionstyle-cli"
samples="$root/resources/samples"
out="$build/demo"
mkdir -p "$out"
echo
echo "== What MotionStyle reads from the sample clips"
"$cli" info "$samples"/*.bvh
echo
echo "== Resampling the zombie walk (30 fps, Z-up) to 60 fps"
"$cli" convert "$samples/zombie_walk.bvh" "$out/zombie_walk_60fps.bvh" --fps 60
echo
echo "== IK clean-up of the zombie walk on its own skeleton (feet locked, bones exact, on the floor)"
"$cli" cleanup "$samples/zombie_walk.bvh" --out "$out/zombie_walk_clean.bvh" --metrics "$out/zombie_walk_clean.json"
echo
echo "Demo output is in $out. The desktop app: $build/app/gui/motionstyle $samples/*.bvh"

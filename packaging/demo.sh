#!/usr/bin/env bash
# The main job on bundled data, from a fresh Debian 12 machine: installs the dependencies, builds
# MotionStyle (Release), applies every shipped style network to the sample content clip with the CLI,
# then opens the desktop app on the demo (sample content and style clips, the bundled style network
# selected): one click on "Stylize & Clean Up" shows a stylized, cleaned result.
# Environment: MOTIONSTYLE_BUILD_ROOT (default <repo>/build); MOTIONSTYLE_DEMO_NO_GUI=1 skips the app.
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
echo "== The sample clips"
"$cli" info "$samples"/*.bvh
echo
echo "== The shipped networks"
"$cli" models
echo
echo "== Every shipped style on the CMU walk, cleaned up on its own skeleton (results in $out)"
for net in "$root"/resources/models/*.net; do
  name=$(basename "$net" .net)
  [ "$name" = loss_network ] && continue
  "$cli" stylize --net "$name" "$samples/cmu_131_01_walk.bvh" --out "$out/cmu_131_01_walk_$name.bvh" \
    --metrics "$out/cmu_131_01_walk_$name.json" | tail -n 2
done
echo
app="$build/app/gui/motionstyle"
if [ "${MOTIONSTYLE_DEMO_NO_GUI:-0}" = 1 ] || { [ -z "${DISPLAY:-}" ] && [ -z "${WAYLAND_DISPLAY:-}" ]; }; then
  echo "No display (or MOTIONSTYLE_DEMO_NO_GUI=1): open the app later with  $app --demo"
else
  echo "== Opening the app on the demo: press \"Stylize & Clean Up\" in the Result panel"
  exec "$app" --demo
fi

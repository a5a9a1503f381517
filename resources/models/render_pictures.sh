#!/usr/bin/env bash
# One picture per shipped style network: the sample content clip (green), the network's walk style
# clip (red) and the cleaned output (blue) at four times, rendered off-screen by the app's own
# viewport (motionstyle-filmstrip, app/gui/filmstrip_main.cpp) under Xvfb. Usage:
#
#   bash resources/models/render_pictures.sh [STYLE...]
#
# Environment: DATA (the Bandai dataset root, for the style clips), BUILD (default build/release),
# OUT (default resources/models/pictures). The pictures show the dataset's style clips as rendered
# stick figures; like the networks they fall under NOTICE (CC BY-NC 4.0).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
DATA="${DATA:-$root/../shared/data/bandai}"
BUILD="${BUILD:-$root/build/release}"
OUT="${OUT:-$here/pictures}"
tool="$BUILD/app/gui/motionstyle-filmstrip"
[[ -x "$tool" ]] || { echo "error: $tool not found: build first, or set BUILD" >&2; exit 2; }
[[ -d "$DATA/dataset-1/data" ]] || { echo "error: the Bandai dataset is not at $DATA (set DATA)" >&2; exit 2; }
mkdir -p "$OUT"

style_clip() {  # the walk style clip each network was trained with (train_models.sh)
  case $1 in
    elderly|exhausted|youthful|feminine|masculine) echo "$DATA/dataset-2/data/dataset-2_walk_$1_001.bvh" ;;
    *) echo "$DATA/dataset-1/data/dataset-1_walk_$1_001.bvh" ;;
  esac
}

styles=("$@")
[[ ${#styles[@]} -gt 0 ]] || styles=(elderly exhausted angry proud youthful feminine masculine sad happy)
for s in "${styles[@]}"; do
  xvfb-run -a -s "-screen 0 1920x1080x24" "$tool" --content "$root/resources/samples/cmu_131_01_walk.bvh" \
    --style-clip "$(style_clip "$s")" --net "$here/$s.net" --out "$OUT/$s.png" --tile 360x320 \
    --times 0.8,1.6,2.4,3.2 2>&1 | grep -v XDG_RUNTIME_DIR
done

#!/usr/bin/env bash
# A new style from one clip in seconds (issue 15, item 4): for each style, train-style --quick on the
# training content of the shipped networks (dataset-2's normal-style locomotion, every 5th held out)
# from ONE style clip (its walk), then eval on the held-out clips against that clip. Prints the wall
# time of each training (data loading included) and the style distance ratio (after / before, eq. 5)
# and content distance; goal: ratio <= 0.5 within 20 s. Needs ../shared/data/bandai; not a timed test.
#
#   bash tests/bench/quality/bench_quick_style.sh [STYLE...]     (default: five styles of both parts)
set -euo pipefail
root="$(cd "$(dirname "$0")/../../.." && pwd)"
DATA="${DATA:-$root/../shared/data/bandai}"
CLI="${CLI:-$root/build/release/app/cli/motionstyle-cli}"
D1="$DATA/dataset-1/data"
D2="$DATA/dataset-2/data"
[[ -d "$D1" && -d "$D2" ]] || { echo "skipped: the Bandai dataset is not at $DATA (set DATA)"; exit 0; }
[[ -x "$CLI" ]] || { echo "error: $CLI not found: build first, or set CLI" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/content"
for f in "$D2"/dataset-2_{walk,run,walk-turn-left,walk-turn-right}_normal_*.bvh; do ln -s "$f" "$work/content/"; done
styles=("$@")
[[ ${#styles[@]} -gt 0 ]] || styles=(elderly angry youthful proud masculine)
printf "%-10s %8s %8s %9s\n" style seconds ratio content
for s in "${styles[@]}"; do
  clip="$D2/dataset-2_walk_${s}_001.bvh"
  [[ -f "$clip" ]] || clip="$D1/dataset-1_walk_${s}_001.bvh"
  start=$(date +%s.%N)
  "$CLI" train-style --loss-network loss_network --content "$work/content" --style "$clip" --holdout 5 --quick \
    --out "$work/$s.net" >"$work/$s.log" 2>&1 || { echo "error: training $s failed" >&2; tail -3 "$work/$s.log" >&2; exit 1; }
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  mapfile -t held < <(sed -n 's/^held out: //p' "$work/$s.log" | grep -v ' clip(s)')
  "$CLI" eval --loss-network loss_network --net "$work/$s.net" --style "$clip" "${held[@]}" --json "$work/$s.json" >/dev/null
  python3 - "$work/$s.json" "$s" "$seconds" <<'PY'
import json, sys
summary = json.load(open(sys.argv[1]))["summary"]
print("%-10s %8.1f %8.3f %9.3f" % (sys.argv[2], float(sys.argv[3]), summary["style_distance"]["ratio"],
      summary["content_distance"]["after"]))
PY
done

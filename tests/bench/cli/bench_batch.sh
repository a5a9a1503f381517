#!/usr/bin/env bash
# Batch stylize + clean-up throughput (issue 15's goal: 100 clips x 1 style at least 1.7x faster on
# both cores than with --jobs 1). Prints the wall time of each run and the ratio; not a timed test.
#
#   bash tests/bench/cli/bench_batch.sh [CLIPS] [STYLE]
#
# CLIPS: how many clips (default 100): the first CLIPS .bvh files of Bandai dataset 2 when
# ../shared/data/bandai is present (30 fps, 2-10 s each), else copies of the committed fixtures.
# STYLE: a shipped network's name (default elderly). CLI: motionstyle-cli (default: the release build).
set -euo pipefail
root="$(cd "$(dirname "$0")/../../.." && pwd)"
count="${1:-100}"
style="${2:-elderly}"
CLI="${CLI:-$root/build/release/app/cli/motionstyle-cli}"
[[ -x "$CLI" ]] || { echo "error: $CLI not found: build first, or set CLI" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/clips"
bandai="$root/../shared/data/bandai/dataset-2/data"
if [[ -d "$bandai" ]]; then
  source_name="Bandai dataset 2"
  mapfile -t files < <(find "$bandai" -name '*.bvh' | sort)
  cp "${files[@]:0:$count}" "$work/clips/"
else
  source_name="the committed fixtures (zombie, CMU 131_01), copied"
  for ((i = 0; i < count; ++i)); do
    if ((i % 2 == 0)); then cp "$root/tests/data/zombie.bvh" "$work/clips/clip_$i.bvh"
    else cp "$root/tests/data/cmu_131_01.bvh" "$work/clips/clip_$i.bvh"; fi
  done
fi
clips=$(find "$work/clips" -name '*.bvh' | wc -l)
frames=$(for f in "$work/clips"/*.bvh; do awk '/^Frames:/{print $2; exit}' "$f"; done | paste -sd+ | bc)
echo "batch stylize --net $style: $clips clips of $source_name, $frames frames in all, on $(nproc) cores"
run() {  # run JOBS: prints the wall seconds
  local start end
  start=$(date +%s.%N)
  "$CLI" stylize --net "$style" "$work/clips" --out "$work/out_$1" --jobs "$1" >"$work/log_$1" 2>&1 || {
    echo "error: --jobs $1 failed:" >&2; tail -5 "$work/log_$1" >&2; exit 1; }
  end=$(date +%s.%N)
  echo "$end - $start" | bc
}
one=$(run 1)
two=$(run "$(nproc)")
printf "  --jobs 1: %.1f s (%.0f frames/s)\n" "$one" "$(echo "$frames / $one" | bc -l)"
printf "  --jobs %d: %.1f s (%.0f frames/s)\n" "$(nproc)" "$two" "$(echo "$frames / $two" | bc -l)"
printf "  speed-up %.2fx (goal >= 1.7x on 2 cores)\n" "$(echo "$one / $two" | bc -l)"
cmp -s <(cd "$work/out_1" && find . -type f | sort | xargs md5sum) <(cd "$work/out_$(nproc)" && find . -type f | sort | xargs md5sum) \
  && echo "  outputs identical" || echo "  outputs DIFFER between the runs"

#!/usr/bin/env bash
# The commands that make and use networks, end to end on tiny data (issue 14: train-loss-network, train-style,
# transfer, eval and pack were only run with --help): what each writes reads back and says what was
# asked (kind, epochs, loss weights, precision), eval's JSON holds every clip, and the --weights
# parser accepts what it documents and refuses the rest with exit 2, writing nothing.
# Usage: cli_pipeline_test.sh <motionstyle-cli> <tests/data>
set -u
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"  # cli, data, work, failures, expect, fail

content="$data/zombie.bvh"
style="$data/cmu_131_01.bvh"
tiny="--epochs 1 --hidden 8 --threads 1"

# The loss network.
expect 0 "wrote $work/ae.net: 1 epochs" "$cli" train-loss-network --data "$content" --out "$work/ae.net" $tiny
expect 0 "loss network" "$cli" info "$work/ae.net"
expect 0 "8 hidden units" "$cli" info "$work/ae.net"
[ -e "$work/ae.net.checkpoint" ] && fail "train-loss-network left its checkpoint"

# --weights: what the help documents, and nothing else.
for bad in "style=" "bogus=1" "style=1," "" "style=-1" "style=abc" "content=1,,style=2"; do
  expect 2 "--weights" "$cli" train-style --loss-network "$work/ae.net" --content "$content" --style "$style" \
    --out "$work/refused.net" $tiny --weights "$bad"
done
[ -e "$work/refused.net" ] && fail "a refused --weights still wrote a network"

# The style network, with the weights it was given recorded in it.
expect 0 "wrote $work/style.net: 1 epochs" "$cli" train-style --loss-network "$work/ae.net" --content "$content" \
  --style "$style" --out "$work/style.net" $tiny --weights content=1,style=50,foot=0.5,traj=0.25
expect 0 "loss weights: content 1, style 50, foot 0.5, bone 0.03, trajectory 0.25" "$cli" info "$work/style.net"
# --quick: the quick schedule's epochs (a usable style in seconds); it is a number of epochs, so not
# with --epochs.
expect 0 "wrote $work/quick.net: 6 epochs" "$cli" train-style --loss-network "$work/ae.net" --content "$content" \
  --style "$style" --out "$work/quick.net" --quick --hidden 8 --threads 1
expect 2 "not both" "$cli" train-style --loss-network "$work/ae.net" --content "$content" --style "$style" \
  --out "$work/quick2.net" --quick --epochs 3
expect 0 "wrote $work/out.bvh: 300 frames" "$cli" stylize --net "$work/style.net" "$content" --out "$work/out.bvh"
# The style refinement: on by default (the network stores its style target), off with 0, and a bad
# count refused before anything is written.
expect 0 "refinement steps: up to 120" "$cli" stylize --net "$work/style.net" "$content" --out "$work/refined.bvh" --no-cleanup
expect 0 "refinement steps: 0" "$cli" stylize --net "$work/style.net" "$content" --out "$work/plain.bvh" --no-cleanup \
  --refine-steps 0
cmp -s "$work/refined.bvh" "$work/plain.bvh" && fail "stylize --refine-steps 0 wrote the refined clip"
for bad in -1 2.5 100000 x; do
  expect 2 "--refine-steps" "$cli" stylize --net "$work/style.net" "$content" --out "$work/refused.bvh" --refine-steps "$bad"
done
[ -e "$work/refused.bvh" ] && fail "a refused --refine-steps still wrote a clip"
# The style target the refinement aims at: read from the clip (the zombie walks), or --kind; both in the
# log and --metrics; anything else refused before anything is written.
expect 0 "aimed at the style's walk (read from the clip" "$cli" stylize --net "$work/style.net" "$content" \
  --out "$work/read.bvh" --no-cleanup --metrics "$work/read.json"
expect 0 "aimed at the style's walk turning left (--kind)" "$cli" stylize --net "$work/style.net" "$content" \
  --out "$work/told.bvh" --no-cleanup --kind walk-turn-left --metrics "$work/told.json"
python3 - "$work/read.json" "$work/told.json" <<'PY' || fail "stylize --metrics' style_target"
import json, sys
read, told = (json.load(open(f))["style_target"] for f in sys.argv[1:])
assert read == {"kind": "walk", "from": "clip"}, read
assert told == {"kind": "walk-turn-left", "from": "--kind"}, told
PY
for bad in jog Walk ""; do
  expect 2 "--kind must be auto, walk, run" "$cli" stylize --net "$work/style.net" "$content" --out "$work/refused.bvh" \
    --kind "$bad"
done
[ -e "$work/refused.bvh" ] && fail "a refused --kind still wrote a clip"
expect 0 "frames       300 at 30 fps" "$cli" info "$work/out.bvh"

# eval: one entry per clip in the JSON.
expect 0 "evaluated 1 clip" "$cli" eval --loss-network "$work/ae.net" --net "$work/style.net" --style "$style" "$content" \
  --json "$work/eval.json"
python3 - "$work/eval.json" <<'PY' || fail "eval's JSON"
import json, sys
report = json.load(open(sys.argv[1]))
assert report["format"] and isinstance(report["clips"], list) and len(report["clips"]) == 1, report.keys()
assert "summary" in report
PY
# eval judges what stylize writes: refined by default, as the network leaves it with --refine-steps 0.
expect 0 "evaluated 1 clip" "$cli" eval --loss-network "$work/ae.net" --net "$work/style.net" --style "$style" "$content" \
  --json "$work/eval_plain.json" --refine-steps 0
python3 - "$work/eval.json" "$work/eval_plain.json" <<'PY' || fail "eval --refine-steps 0 judged the refined output"
import json, sys
refined, plain = (json.load(open(f))["summary"]["style_distance"]["after"] for f in sys.argv[1:3])
assert refined < plain, (refined, plain)
PY
expect 2 "--refine-steps" "$cli" eval --loss-network "$work/ae.net" --net "$work/style.net" --style "$style" "$content" \
  --refine-steps -3

# pack: f16 halves the file, the network still stylizes, and packs back to f32.
expect 0 "f16" "$cli" pack "$work/style.net" --out "$work/style16.net" --precision f16
expect 0 "weights f16" "$cli" info "$work/style16.net"
big=$(stat -c %s "$work/style.net")
small=$(stat -c %s "$work/style16.net")
[ $((small * 10)) -lt $((big * 6)) ] || fail "pack f16 wrote $small bytes from $big"
expect 0 "wrote" "$cli" stylize --net "$work/style16.net" "$content" --out "$work/out16.bvh"
expect 0 "f32" "$cli" pack "$work/style16.net" --out "$work/style32.net" --precision f32

# transfer (the optimisation method): a clip on the input's skeleton.
expect 0 "wrote $work/transfer.bvh: 300 frames" "$cli" transfer --loss-network "$work/ae.net" --style "$style" "$content" \
  --out "$work/transfer.bvh" --iterations 5
expect 0 "frames       300 at 30 fps" "$cli" info "$work/transfer.bvh"

echo "$failures failure(s)"
[ "$failures" -eq 0 ]

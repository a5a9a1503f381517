#!/usr/bin/env bash
# End-to-end checks of motionstyle-cli: exit codes (0 ok, 2 bad input naming the file and line),
# --help on every command, and a convert round trip. Usage: cli_test.sh <motionstyle-cli> <tests/data>
set -u
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"  # cli, data, work, failures, expect, fail

# Bad input first: each gives exit code 2 and names the file and line.
printf 'garbage\n' >"$work/garbage.bvh"
printf '' >"$work/empty.bvh"
head -c 2000 "$data/zombie.bvh" >"$work/truncated.bvh"
sed 's/^Frames:.*/Frames: 1000000000/' "$data/zombie.bvh" >"$work/billion.bvh"
expect 2 "garbage.bvh:1:" "$cli" info "$work/garbage.bvh"
expect 2 "empty.bvh" "$cli" info "$work/empty.bvh"
expect 2 "truncated.bvh:" "$cli" info "$work/truncated.bvh"
expect 2 "billion.bvh:" "$cli" info "$work/billion.bvh"
expect 2 "no-such.bvh" "$cli" info "$work/no-such.bvh"
expect 2 "garbage.bvh:1:" "$cli" convert "$work/garbage.bvh" "$work/out.bvh"
expect 2 "unknown option" "$cli" info --frobnicate "$data/zombie.bvh"
expect 2 "unknown command" "$cli" frobnicate
expect 2 "fps" "$cli" convert "$data/zombie.bvh" "$work/out.bvh" --fps -3
expect 2 "usage" "$cli"

# Help everywhere.
expect 0 "usage" "$cli" --help
for command in $("$cli" --help | awk '/^commands:/{on=1; next} on && /^  [a-z]/{print $1}'); do
  expect 0 "usage: motionstyle-cli $command" "$cli" "$command" --help
done

# Former names still work (one name per idea: the loss network was the autoencoder).
expect 0 "usage: motionstyle-cli train-loss-network" "$cli" train-ae --help
expect 0 "loss network" "$cli" info "$data/zombie.bvh" --ae autoencoder
expect 2 "option --loss-network given more than once" "$cli" info "$data/zombie.bvh" --ae autoencoder \
  --loss-network loss_network

# Working commands.
expect 0 "up axis      +Z" "$cli" info "$data/zombie.bvh"
expect 0 "locomotion   walk (read from its contacts and turning" "$cli" info "$data/zombie.bvh"
# A folder: every .bvh below it, as stylize and cleanup take folders.
mkdir -p "$work/takes/day2"
cp "$data/zombie.bvh" "$work/takes/a.bvh"
cp "$data/cmu_131_01.bvh" "$work/takes/day2/b.bvh"
expect 0 "takes/day2/b.bvh" "$cli" info "$work/takes"
[ "$(grep -c 'familiarity' "$work/out")" = 2 ] || fail "info of a folder did not describe its two clips"
expect 0 '"unit"' "$cli" info --json "$data/cmu_131_01.bvh"
expect 0 "wrote" "$cli" convert "$data/cmu_131_01.bvh" "$work/cmu60.bvh" --fps 60
# A rig the automatic mapping reads in part: --write-mapping writes the mapping to complete by hand,
# refused with its gaps named until they are filled in.
sed 's/JOINT LeftKnee/JOINT KnieL/; s/JOINT RightKnee/JOINT KnieR/' "$data/cmu_131_01.bvh" >"$work/knie.bvh"
expect 2 "write-mapping" "$cli" info "$work/knie.bvh" --mapping "$work/none.json" --write-mapping "$work/knie.json"
expect 2 "refusing to overwrite an input" "$cli" info "$work/knie.bvh" --write-mapping "$work/knie.bvh"
expect 0 "found 9 of 21 joints; fill in Hips" "$cli" info "$work/knie.bvh" --write-mapping "$work/knie.json"
expect 2 "knie.json:[0-9]*: no rig joint given" "$cli" info "$work/knie.bvh" --mapping "$work/knie.json"
sed -i 's/"Hips": ""/"Hips": "Hips"/; s/"LeftHip": ""/"LeftHip": "LeftHip"/; s/"LeftKnee": ""/"LeftKnee": "KnieL"/;
        s/"LeftAnkle": ""/"LeftAnkle": "LeftAnkle"/; s/"LeftToe": ""/"LeftToe": "LeftToe"/; s/"RightHip": ""/"RightHip": "RightHip"/;
        s/"RightKnee": ""/"RightKnee": "KnieR"/; s/"RightAnkle": ""/"RightAnkle": "RightAnkle"/; s/"RightToe": ""/"RightToe": "RightToe"/;
        s/"Spine": ""/"Spine": "Chest"/; s/"Chest": ""/"Chest": "Chest2"/; s/"Neck": ""/"Neck": "Neck"/' "$work/knie.json"
expect 0 "mapping      complete (file:" "$cli" info "$work/knie.bvh" --mapping "$work/knie.json"
expect 0 "360 at 60 fps" "$cli" info "$work/cmu60.bvh"

expect 2 "garbage.bvh:1:" "$cli" cleanup "$work/garbage.bvh" --out "$work/clean.bvh"
expect 0 "foot skate" "$cli" cleanup "$data/zombie.bvh" --out "$work/clean.bvh" --metrics "$work/clean.json"
expect 0 "27 (+7 end sites)" "$cli" info "$work/clean.bvh"
grep -q '"cleaned"' "$work/clean.json" || { echo "FAIL: no cleaned metrics"; failures=$((failures + 1)); }
expect 2 "fps" "$cli" cleanup "$data/zombie.bvh" --out "$work/clean60.bvh" --fps 0
expect 0 "at 60 fps" "$cli" cleanup "$data/zombie.bvh" --out "$work/clean60.bvh" --fps 60
expect 0 "599 at 60 fps" "$cli" info "$work/clean60.bvh"

# A failed convert never leaves a half-written output: the old file survives.
printf 'precious\n' >"$work/keep.bvh"
expect 2 "" "$cli" convert "$work/garbage.bvh" "$work/keep.bvh"
if [ "$(cat "$work/keep.bvh")" != "precious" ]; then echo "FAIL: output overwritten"; failures=$((failures + 1)); fi

# Shipped networks (models, bare names), against a resources folder made here: bad input first.
mkdir -p "$work/res/models" "$work/res/samples"
expect 1 "looked in: $work/absent" env MOTIONSTYLE_RESOURCES="$work/absent" "$cli" models
expect 0 "no shipped networks" env MOTIONSTYLE_RESOURCES="$work/res" "$cli" models
printf 'junk' >"$work/res/models/broken.net"
expect 2 "broken.*UNREADABLE" env MOTIONSTYLE_RESOURCES="$work/res" "$cli" models
expect 2 "models/broken.net" env MOTIONSTYLE_RESOURCES="$work/res" "$cli" info broken
expect 2 "no shipped network of that name (shipped: broken" env MOTIONSTYLE_RESOURCES="$work/res" \
  "$cli" stylize --net elderly "$data/zombie.bvh" --out "$work/styled.bvh"
expect 2 "no-such.net" env MOTIONSTYLE_RESOURCES="$work/res" "$cli" stylize --net "$work/no-such.net" \
  "$data/zombie.bvh" --out "$work/styled.bvh"

# Other studios' clips (issue 12), on networks trained here in a second: familiarity, keeping the path,
# adapting the loss network and retraining a style from its stored targets. Bad input first.
tiny="--epochs 1 --hidden 8 --threads 1"
expect 2 "--augment" "$cli" train-loss-network --data "$data/zombie.bvh" --out "$work/ae.net" --augment bogus $tiny
expect 2 "girdle_offset_degrees" "$cli" train-loss-network --data "$data/zombie.bvh" --out "$work/ae.net" --augment girdle=100 $tiny
expect 0 "wrote" "$cli" train-loss-network --data "$data/zombie.bvh" --out "$work/ae.net" --augment on --dropout 0 $tiny
for bad in "" "style=1," "style=" "=1" "style=1x" "bogus=1" "style=-1"; do
  expect 2 "--weights" "$cli" train-style --loss-network "$work/ae.net" --content "$data/zombie.bvh" --style "$data/cmu_131_01.bvh" \
    --out "$work/style.net" --weights "$bad" $tiny
done
expect 0 "wrote" "$cli" train-style --loss-network "$work/ae.net" --content "$data/zombie.bvh" --style "$data/cmu_131_01.bvh" \
  --out "$work/style.net" $tiny
expect 0 "style targets: cmu, (default)" "$cli" info "$work/style.net"
expect 0 "familiarity  " "$cli" info "$data/cmu_131_01.bvh" --loss-network "$work/ae.net"
expect 0 '"level"' "$cli" info --json "$data/cmu_131_01.bvh" --loss-network "$work/ae.net"
expect 2 "--path" "$cli" stylize --net "$work/style.net" "$data/zombie.bvh" --out "$work/kept.bvh" --path sideways
expect 0 "path: content" "$cli" stylize --net "$work/style.net" "$data/zombie.bvh" --out "$work/kept.bvh" \
  --metrics "$work/kept.json"
grep -q '"familiarity"' "$work/kept.json" || { echo "FAIL: no familiarity in the metrics"; failures=$((failures + 1)); }
expect 0 "path: style" "$cli" stylize --net "$work/style.net" "$data/zombie.bvh" --out "$work/free.bvh" --path style
expect 0 "network's own path" "$cli" eval --loss-network "$work/ae.net" --net "$work/style.net" --style "$data/cmu_131_01.bvh" \
  "$data/zombie.bvh" --json "$work/eval.json"
grep -q '"network_path"' "$work/eval.json" || { echo "FAIL: no network_path in eval"; failures=$((failures + 1)); }
expect 0 "optimised in [0-9]\.[0-9]s: style distance" "$cli" transfer --loss-network "$work/ae.net" --style "$data/cmu_131_01.bvh" "$data/zombie.bvh" \
  --out "$work/transfer.bvh" --iterations 2 --constraint-iterations 1 --metrics "$work/transfer.json"
grep -q '"style_distance"' "$work/transfer.json" || { echo "FAIL: no style distance in transfer's metrics"; failures=$((failures + 1)); }
# A clip that opens with its rig's rest pose, as CMU's files do: frame 0 kept as it was in what cleanup
# and stylize write, and named by info.
awk '/^Frames:/ { print "Frames: " $2 + 1; next }
     /^Frame Time/ { print; rest = 1; next }
     rest == 1 { line = $1 " " $2 " " $3; for (i = 4; i <= NF; i++) line = line " 0"; print line; rest = 2 }
     { print }' "$data/cmu_131_01.bvh" >"$work/rest_pose.bvh"
first_frame() { awk '/^Frame Time/ { getline; for (i = 1; i <= NF; i++) printf "%.4f ", $i; exit }' "$1"; }
expect 0 "rest pose    frame 0" "$cli" info "$work/rest_pose.bvh"
expect 0 "721 frames" "$cli" cleanup "$work/rest_pose.bvh" --out "$work/rest_clean.bvh"
[ "$(first_frame "$work/rest_clean.bvh")" = "$(first_frame "$work/rest_pose.bvh")" ] || fail "cleanup changed the rest-pose frame"
expect 0 "721 frames" "$cli" stylize --net "$work/style.net" "$work/rest_pose.bvh" --out "$work/rest_styled.bvh"
[ "$(first_frame "$work/rest_styled.bvh")" = "$(first_frame "$work/rest_pose.bvh")" ] || fail "stylize changed the rest-pose frame"
[ "$(first_frame "$work/rest_styled.bvh")" != "$(first_frame "$data/cmu_131_01.bvh")" ] || fail "the test clip has no rest pose"

# Foot contacts saved beside a clip (the app's Save Contact Tracks) decide the locks of cleanup and
# stylize (stylize ignored them). Here every track off: no foot is locked anywhere.
cp "$data/zombie.bvh" "$work/tracked.bvh"
expect 0 "wrote" "$cli" stylize --net "$work/style.net" "$work/tracked.bvh" --out "$work/tracked_detected.bvh"
python3 - "$work/tracked.bvh" <<'PY'
import json, sys
text = open(sys.argv[1]).read()
frames = int(text.split("Frames:")[1].split()[0])
fps = 1.0 / float(text.split("Frame Time:")[1].split()[0])
tracks = {name: "0" * frames for name in ("LeftHeel", "LeftToe", "RightHeel", "RightToe")}
json.dump({"format": "motionstyle-contacts", "version": 1, "fps": fps, "frames": frames, "tracks": tracks},
          open(sys.argv[1] + ".contacts.json", "w"))
PY
expect 0 "contacts from $work/tracked.bvh.contacts.json" "$cli" stylize --net "$work/style.net" "$work/tracked.bvh" \
  --out "$work/tracked_edited.bvh"
cmp -s "$work/tracked_detected.bvh" "$work/tracked_edited.bvh" && fail "stylize ignored the contact tracks beside the clip"
expect 0 "contacts from $work/tracked.bvh.contacts.json" "$cli" cleanup "$work/tracked.bvh" --out "$work/tracked_clean.bvh"
# Tracks of another take (other frames): exit 2 naming the file, nothing written.
sed -i 's/"frames": [0-9]*/"frames": 5/; s/"0\{5,\}"/"00000"/g' "$work/tracked.bvh.contacts.json"
expect 2 "tracked.bvh.contacts.json" "$cli" stylize --net "$work/style.net" "$work/tracked.bvh" --out "$work/tracked_other.bvh"
[ -e "$work/tracked_other.bvh" ] && fail "stylize wrote with the contact tracks of another take"

expect 2 "no-such" "$cli" adapt --loss-network "$work/ae.net" --data "$work/no-such" --out "$work/adapted.net" --threads 1
expect 2 "--out" "$cli" adapt --loss-network "$work/ae.net" --data "$data/cmu_131_01.bvh"
expect 0 "before -> after" "$cli" adapt --loss-network "$work/ae.net" --data "$data/cmu_131_01.bvh" --out "$work/adapted.net" \
  --epochs 2 --threads 1
expect 0 "adapted_on: cmu_131_01.bvh" "$cli" info "$work/adapted.net"
# The reconstruction memory: bad input first, then one written beside the network, which adapt finds,
# keeps and records; one of another network is refused.
expect 2 "remember needs --data" "$cli" remember --loss-network "$work/ae.net" --out "$work/ae.memory"
expect 2 "--out is --loss-network" "$cli" remember --loss-network "$work/ae.net" --data "$data/zombie.bvh" --out "$work/ae.net"
expect 2 "no-such.memory" "$cli" adapt --loss-network "$work/ae.net" --data "$data/zombie.bvh" --out "$work/a.net" \
  --memory "$work/no-such.memory" --epochs 1
expect 2 "/dev/zero: not a reconstruction memory" timeout 20 "$cli" adapt --loss-network "$work/ae.net" --data "$data/zombie.bvh" \
  --out "$work/a.net" --memory /dev/zero --epochs 1
expect 0 "reconstruction memory of 1 clips" "$cli" remember --loss-network "$work/ae.net" --data "$data/cmu_131_01.bvh" \
  --description "the CMU sample" --out "$work/ae.memory" --threads 1
expect 0 "remembers: 1 clips" "$cli" info "$work/ae.memory"
expect 2 "cannot go with --train-encoder" "$cli" adapt --loss-network "$work/ae.net" --data "$data/zombie.bvh" --out "$work/a.net" \
  --memory "$work/ae.memory" --train-encoder --epochs 1
expect 0 "memory of the CMU sample" "$cli" adapt --loss-network "$work/ae.net" --data "$data/zombie.bvh" \
  --out "$work/adapted_kept.net" --epochs 2 --threads 1
expect 0 "adapted_memory: the CMU sample" "$cli" info "$work/adapted_kept.net"
# Its own memory is written beside it; adapting it again keeps the CMU sample and the zombie.
[ -f "$work/adapted_kept.memory" ] || fail "adapt wrote no memory beside its output"
expect 0 "memory of the CMU sample; the 1 clip(s) it was adapted on (zombie.bvh)" "$cli" adapt \
  --loss-network "$work/adapted_kept.net" --data "$data/cmu_131_01.bvh" --out "$work/adapted_twice.net" --epochs 1 --threads 1
expect 2 "the memory beside --out" "$cli" adapt --loss-network "$work/ae.net" --data "$data/zombie.bvh" \
  --memory "$work/adapted_kept.memory" --out "$work/adapted_kept.net" --epochs 1
expect 2 "another loss network" "$cli" adapt --data "$data/zombie.bvh" --out "$work/a.net" --memory "$work/ae.memory" --epochs 1
# Without --loss-network: the shipped one, as the app preselects it (the option was required), with
# its shipped memory.
expect 0 "memory of the Bandai" "$cli" adapt --data "$data/cmu_131_01.bvh" --out "$work/adapted_shipped.net" --epochs 1 --threads 1
expect 0 "wrote $work/quick_shipped.net: 1 epochs" "$cli" train-style --content "$data/zombie.bvh" --style "$data/cmu_131_01.bvh" \
  --out "$work/quick_shipped.net" $tiny
expect 0 "256 hidden units" "$cli" info "$work/quick_shipped.net"
expect 2 "stores no style targets\|--style" "$cli" train-style --loss-network "$work/adapted.net" --content "$data/cmu_131_01.bvh" \
  --out "$work/retrained.net" $tiny
expect 0 "wrote" "$cli" train-style --loss-network "$work/adapted.net" --init "$work/style.net" --content "$data/cmu_131_01.bvh" \
  --out "$work/retrained.net" $tiny
expect 0 "style_targets_from" "$cli" info "$work/retrained.net"

if [ "$failures" -ne 0 ]; then echo "$failures CLI check(s) failed"; exit 1; fi
echo "all CLI checks passed"

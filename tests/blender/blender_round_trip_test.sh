#!/usr/bin/env bash
# Blender (Debian's blender 3.4, headless) as the user's other tool, both ways:
#   1. What MotionStyle writes, Blender reads as the same motion: a stylized clip (the zombie at 30 fps,
#      CMU 131_01 at 120 fps) imported into Blender and exported again holds the motion MotionStyle
#      wrote, frame by frame (bvh_pose_distance: every distance between two joints within 0.001 of
#      the file's unit; Blender writes six decimals).
#   2. What Blender writes, MotionStyle reads as the same motion: Blender's export of the zombie (its own
#      axes, position channels on every joint) holds the zombie's motion, and stylizing it gives the
#      zombie's stylized motion (every joint-to-joint distance within 0.2 inch, 0.5 cm: the network
#      and the clean-up's solver see the same features up to rounding).
# Skipped (exit 77) with a message where Blender is not installed (apt-get install blender).
#
#   bash blender_round_trip_test.sh MOTIONSTYLE_CLI BVH_POSE_DISTANCE TESTS_DATA
set -u
pose_distance="$2"
source "$(dirname "${BASH_SOURCE[0]}")/../cli/cli_test_lib.sh"  # cli, work, failures, expect, fail
data="$3"
driver="$(dirname "${BASH_SOURCE[0]}")/blender_bvh.py"
command -v blender >/dev/null || { echo "SKIP: Blender is not installed (apt-get install blender)"; exit 77; }

# through_blender IN OUT: Blender imports IN and exports OUT; prints what it read.
through_blender() {
  blender -b --factory-startup --python "$driver" -- "$1" "$2" >"$work/blender.txt" 2>&1
  local code=$?
  grep '^blender:' "$work/blender.txt"
  [ "$code" -eq 0 ] && [ -s "$2" ] || { fail "Blender could not read or write $1"; tail -20 "$work/blender.txt"; }
}
# within A B LIMIT: the two files' motions are within LIMIT (bvh_pose_distance), with equal frame counts.
within() {
  local report
  report=$("$pose_distance" "$1" "$2") || { fail "bvh_pose_distance $1 $2"; return; }
  echo "$report"
  awk -v limit="$3" '{ exit !($2 == $3 && $7 <= limit) }' <<< "$report" || fail "$(basename "$2") is not $(basename "$1")'s motion: $report"
}

# A file Blender cannot read fails the driver (so a silent pass is not possible).
printf 'garbage\n' >"$work/garbage.bvh"
blender -b --factory-startup --python "$driver" -- "$work/garbage.bvh" "$work/never.bvh" >/dev/null 2>&1 &&
  fail "the Blender driver passed a file that is not BVH"

# 1. MotionStyle -> Blender.
for clip in zombie cmu_131_01; do
  expect 0 "wrote $work/$clip.styled.bvh" "$cli" stylize --net elderly "$data/$clip.bvh" --out "$work/$clip.styled.bvh"
  through_blender "$work/$clip.styled.bvh" "$work/$clip.styled.blender.bvh"
  within "$work/$clip.styled.bvh" "$work/$clip.styled.blender.bvh" 0.001
done
grep -q "bones 27 frames 300 fps 30$" <(through_blender "$work/zombie.styled.bvh" "$work/again.bvh") ||
  fail "Blender did not read the stylized zombie's 27 bones, 300 frames at 30 fps"

# 2. Blender -> MotionStyle.
through_blender "$data/zombie.bvh" "$work/zombie.blender.bvh"
within "$data/zombie.bvh" "$work/zombie.blender.bvh" 0.001
expect 0 "familiar" "$cli" info "$work/zombie.blender.bvh"
expect 0 "wrote" "$cli" stylize --net elderly "$work/zombie.blender.bvh" --out "$work/zombie.blender.styled.bvh"
within "$work/zombie.styled.bvh" "$work/zombie.blender.styled.bvh" 0.2

if [ "$failures" -ne 0 ]; then echo "$failures Blender check(s) failed"; exit 1; fi
echo "all Blender checks passed"

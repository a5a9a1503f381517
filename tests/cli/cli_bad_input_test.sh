#!/usr/bin/env bash
# Hostile input to motionstyle-cli (issue 13): every bad file or option value is exit 2 with a message
# naming the file (and line where one applies) or the option; never 1 (internal error), never a signal,
# never a hang. Valid but odd files (Frames: 0) are described by info and refused clearly by the
# commands that need motion. Usage: cli_bad_input_test.sh <motionstyle-cli> <tests/data>
set -u
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"  # cli, data, work, failures, expect, fail

# The shipped networks (stylize --net elderly, --loss-network loss_network) from the source tree's resources.
MOTIONSTYLE_RESOURCES="$(cd "$data/../.." && pwd)/resources"
export MOTIONSTYLE_RESOURCES

# Clips derived from zombie.bvh (Frames on line 166, Frame Time on line 167, first frame on line 168).
zombie="$data/zombie.bvh"
sed 's/^Frames:.*/Frames: 0/; 168,$d' "$zombie" >"$work/empty_clip.bvh"
sed 's/OFFSET .*/OFFSET 0 0 0/' "$zombie" >"$work/flat.bvh"
awk '/OFFSET/ { sub(/OFFSET .*/, "OFFSET " NR % 7 + 1 " 0 0") } { print }' "$zombie" >"$work/line.bvh"
sed 's/^Frame Time:.*/Frame Time: 10/' "$zombie" >"$work/slow.bvh"
sed 's/^Frame Time:.*/Frame Time: 0.5/' "$zombie" >"$work/two_fps.bvh"
sed 's/^Frame Time:.*/Frame Time: 5e-324/' "$zombie" >"$work/denormal.bvh"
sed '170s/^ *[^ ]*/ 1e308/' "$zombie" >"$work/huge.bvh"
sed '170s/^\( *[^ ]* *[^ ]* *[^ ]*\) *[^ ]*/\1 1e300/' "$zombie" >"$work/huge_rotation.bvh"

# 1. Frames: 0 is a valid, empty clip: info describes it; commands that need motion say so (exit 2).
expect 0 "frames       0" "$cli" info "$work/empty_clip.bvh"
expect 0 '"frames": 0' "$cli" info --json "$work/empty_clip.bvh"
expect 0 "wrote" "$cli" convert "$work/empty_clip.bvh" "$work/out.bvh"
expect 2 "empty_clip.bvh:166:.*no frames" "$cli" convert "$work/empty_clip.bvh" "$work/out.bvh" --fps 60
expect 2 "empty_clip.bvh:166:.*no frames" "$cli" cleanup "$work/empty_clip.bvh" --out "$work/out.bvh"
expect 2 "empty_clip.bvh:166:.*no frames" "$cli" stylize --net elderly "$work/empty_clip.bvh" --out "$work/out.bvh"

# 2. A skeleton with no height (all offsets zero, or all on one line) cannot be measured.
for clip in flat line; do
  expect 2 "$clip.bvh:.*line\|$clip.bvh:.*height" "$cli" info "$work/$clip.bvh"
  expect 2 "$clip.bvh:.*line\|$clip.bvh:.*height" "$cli" info "$work/$clip.bvh" --unit cm
  expect 2 "$clip.bvh:.*line\|$clip.bvh:.*height" "$cli" cleanup "$work/$clip.bvh" --out "$work/out.bvh"
  expect 2 "$clip.bvh:.*line\|$clip.bvh:.*height" "$cli" cleanup "$work/$clip.bvh" --out "$work/out.bvh" --unit cm
done

# 3. Frame times outside the physical range are refused on read; no resampling beyond 100x.
expect 2 "slow.bvh:167:.*frame time" "$cli" info "$work/slow.bvh"
expect 2 "denormal.bvh:167:.*frame time" "$cli" info "$work/denormal.bvh"
expect 2 "denormal.bvh:167:.*frame time" "$cli" cleanup "$work/denormal.bvh" --out "$work/out.bvh"
expect 2 "two_fps.bvh.*100 times" "$cli" convert "$work/two_fps.bvh" "$work/out.bvh" --fps 1000
expect 2 "two_fps.bvh.*100 times" "$cli" cleanup "$work/two_fps.bvh" --out "$work/out.bvh" --fps 1000
expect 0 "wrote" "$cli" convert "$work/two_fps.bvh" "$work/out.bvh" --fps 60

# 4. Unknown length units are usage errors that list the known ones.
expect 2 "cm, m, mm, inch, ft, dm, cmu" "$cli" info "$zombie" --unit furlong
expect 2 "cm, m, mm, inch, ft, dm, cmu" "$cli" cleanup "$zombie" --out "$work/out.bvh" --unit furlong
expect 2 "cm, m, mm, inch, ft, dm, cmu" "$cli" stylize --net elderly "$zombie" --out "$work/out.bvh" --unit furlong

# 5. Absurd numeric options are refused with their range (before anything runs: the timeout and the
# tiny settings only bound a regression).
tiny="--epochs 1 --hidden 8 --threads 1"
quick="--iterations 2 --constraint-iterations 1"
expect 2 "\-\-lr must be in" timeout 60 "$cli" transfer --ae autoencoder --style "$zombie" "$zombie" --out "$work/out.bvh" \
  $quick --lr 1e308
expect 2 "\-\-style-weight must be in" timeout 60 "$cli" transfer --loss-network loss_network --style "$zombie" "$zombie" \
  --out "$work/out.bvh" $quick --style-weight 1e308
expect 2 "\-\-lr must be in" timeout 60 "$cli" train-loss-network --data "$zombie" --out "$work/ae.net" $tiny --lr 1e308
expect 2 "\-\-sparsity must be in" timeout 60 "$cli" train-loss-network --data "$zombie" --out "$work/ae.net" $tiny --sparsity 1e308
expect 2 "\-\-clip must be in" timeout 60 "$cli" train-loss-network --data "$zombie" --out "$work/ae.net" $tiny --clip 1e308
expect 2 "\-\-foot must be in" timeout 60 "$cli" train-loss-network --data "$zombie" --out "$work/ae.net" $tiny --foot 1e308
expect 2 "\-\-epochs must be in" timeout 60 "$cli" train-loss-network --data "$zombie" --out "$work/ae.net" --hidden 8 --threads 1 \
  --epochs 2000000000
expect 2 "\-\-weights" timeout 60 "$cli" train-style --loss-network loss_network --content "$zombie" --style "$zombie" \
  --out "$work/style.net" $tiny --weights style=1e308
expect 2 "\-\-lr must be in" timeout 60 "$cli" adapt --loss-network loss_network --data "$zombie" --out "$work/a.net" --epochs 1 \
  --threads 1 --lr 1e308

# 6. A mapping file the user names must exist (as for cleanup).
expect 2 "missing.json" "$cli" info "$zombie" --mapping "$work/missing.json"
expect 2 "missing.json" "$cli" cleanup "$zombie" --out "$work/out.bvh" --mapping "$work/missing.json"

# 7. Numbers std::stod would take but nobody means.
for bad in 0x10 inf nan 60abc " 60" "60 " 1e999 ""; do
  expect 2 "\-\-fps" "$cli" convert "$zombie" "$work/out.bvh" --fps "$bad"
done
expect 2 "\-\-strength" "$cli" stylize --net elderly "$zombie" --out "$work/out.bvh" --strength 0x1
expect 0 "at 60 fps" "$cli" convert "$zombie" "$work/out.bvh" --fps 60
expect 0 "at 60 fps" "$cli" convert "$zombie" "$work/out.bvh" --fps 6e1
expect 0 "at 60 fps" "$cli" convert "$zombie" "$work/out.bvh" --fps +60.0

# 8. Non-physical values are refused on read, with the line; the solver never floods stderr.
expect 2 "huge.bvh:170:" "$cli" info "$work/huge.bvh"
expect 2 "huge.bvh:170:" "$cli" cleanup "$work/huge.bvh" --out "$work/out.bvh"
expect 2 "huge_rotation.bvh:170:" "$cli" cleanup "$work/huge_rotation.bvh" --out "$work/out.bvh"
# A clip at the bound (values of 1e5) still solves or fails quietly: stderr stays small.
sed '170s/^\( *[^ ]* *[^ ]* *[^ ]*\) *[^ ]*/\1 99999/' "$zombie" >"$work/big_rotation.bvh"
"$cli" cleanup "$work/big_rotation.bvh" --out "$work/out.bvh" >"$work/out" 2>"$work/err"
code=$?
bytes=$(wc -c <"$work/err")
if [ "$code" -ne 0 ] && [ "$code" -ne 2 ]; then fail "cleanup of big_rotation.bvh exit $code"; fi
if [ "$bytes" -gt 2000 ]; then fail "cleanup of big_rotation.bvh wrote $bytes bytes to stderr"; head -c 500 "$work/err"; fi

# 9. Not a BVH at all: devices and binary files stop at once (no 1 GiB read, no hang).
printf 'HIERARCHY\0\0\0\0' >"$work/nul.bvh"
for device in /dev/zero /dev/urandom; do
  expect 2 "$device" timeout 10 "$cli" info "$device"
  expect 2 "$device" timeout 10 "$cli" cleanup "$device" --out "$work/out.bvh"
done
expect 2 "nul.bvh:1:" "$cli" info "$work/nul.bvh"
if [ -x /usr/bin/time ]; then
  /usr/bin/time -v "$cli" info /dev/zero >/dev/null 2>"$work/time"
  rss_kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time")
  if [ -n "$rss_kb" ] && [ "$rss_kb" -gt 200000 ]; then fail "info /dev/zero peaked at $rss_kb kB"; fi
fi

# Every input above through every reading command: exit 0 or 2, never 1, never a signal.
for clip in empty_clip flat line slow two_fps denormal huge huge_rotation big_rotation nul; do
  for command in info convert cleanup stylize; do
    case $command in
      info) args=(info "$work/$clip.bvh") ;;
      convert) args=(convert "$work/$clip.bvh" "$work/out.bvh" --fps 30) ;;
      cleanup) args=(cleanup "$work/$clip.bvh" --out "$work/out.bvh") ;;
      stylize) args=(stylize --net elderly "$work/$clip.bvh" --out "$work/out.bvh") ;;
    esac
    timeout 120 "$cli" "${args[@]}" >"$work/out" 2>"$work/err"
    code=$?
    if [ "$code" -ne 0 ] && [ "$code" -ne 2 ]; then fail "exit $code: ${args[*]}"; head -c 500 "$work/err"; fi
  done
done

if [ "$failures" -ne 0 ]; then echo "$failures CLI check(s) failed"; exit 1; fi
echo "all bad-input CLI checks passed"

#!/usr/bin/env bash
# Nothing the user owns is lost (issue 13): every command refuses, with exit 2 and before any work, an
# output that is one of its inputs or another output (also through symlinks and hard links) or that
# cannot be written; it writes all its outputs or none; an overwritten output keeps its mode and a
# symlink stays a symlink; stale temporaries of killed runs are removed; a completed training removes
# its checkpoints unless --keep-checkpoints. Usage: cli_outputs_test.sh <motionstyle-cli> <tests/data>
set -u
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"  # cli, data, work, failures, expect, fail

unchanged() {  # unchanged <file> <copy>: the file still holds what the copy holds
  cmp -s "$1" "$2" || fail "$1 was changed"
}

cp "$data/zombie.bvh" "$work/in.bvh"
cp "$data/zombie.bvh" "$work/in.orig"
cp "$data/cmu_131_01.bvh" "$work/style.bvh"
cp "$data/cmu_131_01.bvh" "$work/style.orig"
tiny="--epochs 1 --hidden 8 --threads 1"
expect 0 "wrote" "$cli" train-loss-network --data "$work/in.bvh" --out "$work/ae.net" $tiny
expect 0 "wrote" "$cli" train-style --loss-network "$work/ae.net" --content "$work/in.bvh" --style "$work/style.bvh" \
  --out "$work/net.net" $tiny

# An output that is an input: refused, the input untouched.
expect 2 "--out is the input clip" "$cli" cleanup "$work/in.bvh" --out "$work/in.bvh"
expect 2 "refusing to overwrite an input" "$cli" cleanup "$work/in.bvh" --out "$work/c.bvh" --metrics "$work/in.bvh"
expect 2 "are the same file" "$cli" cleanup "$work/in.bvh" --out "$work/c.bvh" --metrics "$work/c.bvh"
expect 2 "--out is the input clip" "$cli" stylize --net "$work/net.net" "$work/in.bvh" --out "$work/in.bvh"
expect 2 "--metrics is the input clip" "$cli" stylize --net "$work/net.net" "$work/in.bvh" --out "$work/s.bvh" \
  --metrics "$work/in.bvh"
expect 2 "--out is --net" "$cli" stylize --net "$work/net.net" "$work/in.bvh" --out "$work/net.net"
expect 2 "--out is the input clip" "$cli" transfer --loss-network "$work/ae.net" --style "$work/style.bvh" "$work/in.bvh" \
  --out "$work/in.bvh" --iterations 1 --constraint-iterations 0
expect 2 "--out is --style" "$cli" transfer --loss-network "$work/ae.net" --style "$work/style.bvh" "$work/in.bvh" \
  --out "$work/style.bvh" --iterations 1 --constraint-iterations 0
expect 2 "--json is an evaluated clip" "$cli" eval --loss-network "$work/ae.net" --net "$work/net.net" --style "$work/style.bvh" \
  "$work/in.bvh" --json "$work/in.bvh"
expect 2 "--out is --style" "$cli" train-style --loss-network "$work/ae.net" --content "$work/in.bvh" --style "$work/style.bvh" \
  --out "$work/style.bvh" $tiny
expect 2 "--out is --data" "$cli" train-loss-network --data "$work/in.bvh" --out "$work/in.bvh" $tiny
expect 2 "--out is a clip inside --data" "$cli" train-loss-network --data "$work" --out "$work/in.bvh" $tiny
expect 2 "--out is --loss-network" "$cli" adapt --loss-network "$work/ae.net" --data "$work/style.bvh" --out "$work/ae.net" --epochs 1
expect 2 "OUT is IN" "$cli" convert "$work/in.bvh" "$work/in.bvh"
ln -s "$work/in.bvh" "$work/link.bvh"
ln "$work/in.bvh" "$work/hard.bvh"
expect 2 "--out is the input clip" "$cli" cleanup "$work/in.bvh" --out "$work/link.bvh"
expect 2 "--out is the input clip" "$cli" cleanup "$work/in.bvh" --out "$work/hard.bvh"
expect 2 "--out is the input clip" "$cli" cleanup "$work/link.bvh" --out "$work/in.bvh"
rm "$work/link.bvh" "$work/hard.bvh"
unchanged "$work/in.bvh" "$work/in.orig"
unchanged "$work/style.bvh" "$work/style.orig"
expect 0 "f16" "$cli" pack "$work/net.net" --out "$work/net.net"  # pack rewrites in place, by design

# An output that cannot be written: refused before any work, nothing written.
mkdir "$work/dir"
expect 2 "is a folder" "$cli" cleanup "$work/in.bvh" --out "$work/dir"
expect 2 "cannot create a file" "$cli" cleanup "$work/in.bvh" --out "$work/c.bvh" --metrics /proc/motionstyle.json
[ -e "$work/c.bvh" ] && fail "cleanup wrote its clip although --metrics could not be written"
expect 2 "cannot create a file" "$cli" stylize --net "$work/net.net" "$work/in.bvh" --out "$work/s.bvh" \
  --metrics /proc/motionstyle.json
[ -e "$work/s.bvh" ] && fail "stylize wrote its clip although --metrics could not be written"
expect 2 "does not exist" "$cli" eval --loss-network "$work/ae.net" --net "$work/net.net" --style "$work/style.bvh" \
  "$work/in.bvh" --json "$work/no-such-folder/eval.json"
expect 2 "is a folder" "$cli" train-style --loss-network "$work/ae.net" --content "$work/in.bvh" --style "$work/style.bvh" \
  --out "$work/dir" $tiny
expect 2 "cannot create a file" "$cli" train-loss-network --data "$work/in.bvh" --out /proc/motionstyle.net $tiny
[ -n "$(ls -A "$work/dir")" ] && fail "a refused training left files in $work/dir"
ls "$work" | grep -q "^dir.checkpoint" && fail "a refused training left a checkpoint"

# What the user owns is kept: an overwritten output's mode, a symlink to elsewhere.
cp "$work/in.bvh" "$work/private.bvh"
chmod 600 "$work/private.bvh"
expect 0 "wrote" "$cli" cleanup "$work/in.bvh" --out "$work/private.bvh"
[ "$(stat -c %a "$work/private.bvh")" = "600" ] || fail "mode changed to $(stat -c %a "$work/private.bvh")"
mkdir "$work/store"
cp "$work/in.bvh" "$work/store/take.bvh"
ln -s store/take.bvh "$work/take.bvh"
expect 0 "wrote" "$cli" cleanup "$work/in.bvh" --out "$work/take.bvh"
[ -L "$work/take.bvh" ] || fail "the symlink was replaced by a regular file"
cmp -s "$work/store/take.bvh" "$work/in.bvh" && fail "the symlink's target was not written"

# Stale temporaries of a killed run are removed by the next run; a live process's are not.
sleep 0 & dead=$!
wait "$dead"
touch "$work/.c.bvh.tmp-$dead-0123abcd" "$work/.c.bvh.tmp-$$-4567"
expect 0 "wrote" "$cli" cleanup "$work/in.bvh" --out "$work/c.bvh"
[ -e "$work/.c.bvh.tmp-$dead-0123abcd" ] && fail "a dead process's temporary was left"
[ -e "$work/.c.bvh.tmp-$$-4567" ] || fail "a live process's temporary was removed"
rm -f "$work/.c.bvh.tmp-$$-4567"

# A completed training removes its checkpoint unless --keep-checkpoints.
expect 0 "wrote" "$cli" train-loss-network --data "$work/in.bvh" --out "$work/gone.net" $tiny
ls "$work"/gone.net.checkpoint* >/dev/null 2>&1 && fail "train-loss-network left its checkpoint"
expect 0 "wrote" "$cli" train-loss-network --data "$work/in.bvh" --out "$work/kept.net" $tiny --keep-checkpoints
[ -f "$work/kept.net.checkpoint" ] && [ -f "$work/kept.net.checkpoint.state" ] || fail "--keep-checkpoints removed them"
expect 0 "wrote" "$cli" train-style --loss-network "$work/ae.net" --content "$work/in.bvh" --style "$work/style.bvh" \
  --out "$work/gone_style.net" $tiny
ls "$work"/gone_style.net.checkpoint* >/dev/null 2>&1 && fail "train-style left its checkpoint"
expect 0 "before -> after" "$cli" adapt --loss-network "$work/ae.net" --data "$work/style.bvh" --out "$work/adapted.net" \
  --epochs 1 --threads 1
ls "$work"/adapted.net.checkpoint* >/dev/null 2>&1 && fail "adapt left its checkpoint"
ls -A "$work" | grep -q '\.tmp-' && fail "temporaries left: $(ls -A "$work" | grep '\.tmp-')"

# A result that was not produced never passes for one: no time limit unless the user sets one, and
# then the frames it cut are named.
expect 2 "--time-limit" "$cli" cleanup "$work/in.bvh" --out "$work/c.bvh" --time-limit 0
expect 2 "--time-limit" "$cli" stylize --net "$work/net.net" "$work/in.bvh" --out "$work/s.bvh" --time-limit nan
expect 0 "time budget of 0.00 s exhausted" "$cli" cleanup "$work/in.bvh" --out "$work/c.bvh" --time-limit 0.000001
expect 0 "wrote" "$cli" cleanup "$work/in.bvh" --out "$work/c.bvh"
grep -q "time budget" "$work/out" && fail "a clean-up without --time-limit was cut short"

if [ "$failures" -ne 0 ]; then echo "$failures output check(s) failed"; exit 1; fi
echo "all output checks passed"

#!/usr/bin/env bash
# kill -9 at random points while a command writes over an existing output (issue 13): after every
# kill the output is either the old file or the complete new one, never a mix or a truncation; the
# next run removes the temporaries the killed ones left; the output keeps its mode throughout.
# Usage: cli_kill_test.sh <motionstyle-cli> <tests/data> [trials=20]
set -u
source "$(dirname "${BASH_SOURCE[0]}")/cli_test_lib.sh"  # cli, data, work, failures, expect, fail
trials="${3:-20}"

# A clip long enough that writing it takes a measurable share of the run (120 fps -> 1000 fps).
"$cli" convert "$data/cmu_131_01.bvh" "$work/long.bvh" --fps 1000 >/dev/null || { echo "FAIL: setup"; exit 1; }
"$cli" convert "$data/zombie.bvh" "$work/old.bvh" >/dev/null || { echo "FAIL: setup"; exit 1; }
"$cli" convert "$work/long.bvh" "$work/new.bvh" >/dev/null || { echo "FAIL: setup"; exit 1; }
cmp -s "$work/old.bvh" "$work/new.bvh" && { echo "FAIL: old and new outputs must differ"; exit 1; }

start=$(date +%s%N)
"$cli" convert "$work/long.bvh" "$work/timing.bvh" >/dev/null
run_ns=$(( $(date +%s%N) - start ))
echo "an uninterrupted run takes $((run_ns / 1000000)) ms; killing at random points in its last 70 %"

old_seen=0
new_seen=0
for trial in $(seq 1 "$trials"); do
  cp "$work/old.bvh" "$work/out.bvh"
  chmod 640 "$work/out.bvh"
  "$cli" convert "$work/long.bvh" "$work/out.bvh" >/dev/null 2>&1 &
  pid=$!
  delay_ns=$(( run_ns * 3 / 10 + (RANDOM * 32768 + RANDOM) % (run_ns * 7 / 10 + 1) ))  # the write is at the end
  sleep "$(printf '0.%09d' "$delay_ns")"
  kill -9 "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  if cmp -s "$work/out.bvh" "$work/old.bvh"; then old_seen=$((old_seen + 1))
  elif cmp -s "$work/out.bvh" "$work/new.bvh"; then new_seen=$((new_seen + 1))
  else fail "trial $trial: out.bvh is neither the old nor the complete new file ($(stat -c %s "$work/out.bvh") bytes)"
  fi
  [ "$(stat -c %a "$work/out.bvh")" = "640" ] || fail "trial $trial: mode changed to $(stat -c %a "$work/out.bvh")"
done
echo "after $trials kills: $old_seen old, $new_seen new; temporaries left by the kills: $(ls -A "$work" | grep -c '\.tmp-')"

"$cli" convert "$work/long.bvh" "$work/out.bvh" >/dev/null || fail "the run after the kills failed"
cmp -s "$work/out.bvh" "$work/new.bvh" || fail "the run after the kills did not write the new file"
leftover=$(ls -A "$work" | grep '\.tmp-')
[ -z "$leftover" ] || fail "temporaries left after the next run: $leftover"

if [ "$failures" -ne 0 ]; then echo "$failures kill check(s) failed"; exit 1; fi
echo "all kill checks passed"

#!/usr/bin/env bash
# Batch mode of stylize and cleanup (issue 15): several clips and folders into one output folder on
# several threads; a bad clip is reported at the end and does not stop the rest (exit 2); no output
# is ever an input; each clip's output is the same bytes as the one-clip command writes.
# Usage: cli_batch_test.sh <motionstyle-cli> <tests/data>
set -u
. "$(dirname "$0")/cli_test_lib.sh"

mkdir -p "$work/in/sub" "$work/elsewhere"
cp "$data/zombie.bvh" "$work/in/a.bvh"
cp "$data/cmu_131_01.bvh" "$work/in/sub/b.bvh"
printf 'HIERARCHY\nnonsense\n' >"$work/in/broken.bvh"
printf 'not a clip' >"$work/in/notes.txt"
cp "$data/zombie.bvh" "$work/elsewhere/a.bvh"

# 1. A folder with a broken clip: the good ones are written, the broken one named at the end, exit 2.
expect 2 "broken.bvh:2" "$cli" cleanup "$work/in" --out "$work/cleaned" --metrics "$work/metrics" --jobs 2
grep -q "2 of 3 clip(s) written" "$work/out" || fail "no '2 of 3 clip(s) written' summary"
for f in cleaned/a.bvh cleaned/sub/b.bvh metrics/a.bvh.json metrics/sub/b.bvh.json; do
  [ -s "$work/$f" ] || fail "batch cleanup did not write $f"
done
[ -e "$work/cleaned/broken.bvh" ] && fail "a failed clip left an output"
[ -e "$work/cleaned/notes.txt" ] && fail "a file that is not a clip was taken"

# 2. Each output is the one-clip command's (same bytes), whatever the number of jobs.
expect 0 "wrote" "$cli" cleanup "$work/in/sub/b.bvh" --out "$work/single_b.bvh"
cmp -s "$work/single_b.bvh" "$work/cleaned/sub/b.bvh" || fail "batch cleanup differs from the one-clip command"
expect 0 "2 of 2 clip(s) written" "$cli" stylize --net elderly "$work/in/a.bvh" "$work/in/sub/b.bvh" --out "$work/styled" \
  --jobs 2
expect 0 "wrote" "$cli" stylize --net elderly "$work/in/a.bvh" --out "$work/single_a.bvh"
cmp -s "$work/single_a.bvh" "$work/styled/a.bvh" || fail "batch stylize differs from the one-clip command"
expect 0 "2 of 2 clip(s) written" "$cli" stylize --net elderly "$work/in/a.bvh" "$work/in/sub/b.bvh" --out "$work/styled1" \
  --jobs 1
cmp -s "$work/styled1/b.bvh" "$work/styled/b.bvh" || fail "--jobs 1 and --jobs 2 differ"

# 3. Nothing is ever written over an input, and nothing starts when one output would be.
before=$(md5sum "$work/in/a.bvh")
expect 2 "refusing to overwrite an input" "$cli" cleanup "$work/in/a.bvh" "$work/in/sub/b.bvh" --out "$work/in"
[ "$(md5sum "$work/in/a.bvh")" = "$before" ] || fail "an input was overwritten"
# Two clips that would write one output.
expect 2 "a.bvh" "$cli" cleanup "$work/in/a.bvh" "$work/elsewhere/a.bvh" --out "$work/clash"
[ -e "$work/clash" ] && fail "a clash left its output folder behind"

# 4. Usage: --out a file with several clips, --contacts with several clips, --jobs out of range, a
# folder without clips, a clip that does not exist.
touch "$work/a_file"
expect 2 "is a file" "$cli" cleanup "$work/in/a.bvh" "$work/in/sub/b.bvh" --out "$work/a_file"
expect 2 "\-\-contacts" "$cli" cleanup "$work/in/a.bvh" "$work/in/sub/b.bvh" --out "$work/o" --contacts "$work/x.json"
expect 2 "\-\-jobs must be in" "$cli" cleanup "$work/in" --out "$work/o" --jobs 0
mkdir -p "$work/empty"
expect 2 "holds no .bvh" "$cli" stylize --net elderly "$work/empty" --out "$work/o"
expect 2 "no-such.bvh" "$cli" cleanup "$work/in/a.bvh" "$work/no-such.bvh" --out "$work/never"
[ -e "$work/never" ] && fail "a command that never started left its output folder"

# 5. The output folder inside the input folder (shots/ -> shots/cleaned/): run again, the same clips are
# written over the first run's outputs, which are not taken for inputs.
mkdir -p "$work/shots/sub"
cp "$data/zombie.bvh" "$work/shots/a.bvh"
cp "$data/cmu_131_01.bvh" "$work/shots/sub/b.bvh"
expect 0 "2 of 2 clip(s) written" "$cli" cleanup "$work/shots" --out "$work/shots/cleaned" --jobs 2
expect 0 "2 of 2 clip(s) written" "$cli" cleanup "$work/shots" --out "$work/shots/cleaned" --jobs 2
[ -e "$work/shots/cleaned/cleaned" ] && fail "the second run took the first run's outputs for inputs"
cmp -s "$work/shots/cleaned/sub/b.bvh" "$work/cleaned/sub/b.bvh" || fail "the rerun's output differs"
# Given by name, a clip in the output folder is still an input: refused.
expect 2 "refusing to overwrite an input" "$cli" cleanup "$work/shots/cleaned/a.bvh" "$work/shots/a.bvh" \
  --out "$work/shots/cleaned"

if [ "$failures" -ne 0 ]; then echo "$failures batch check(s) failed"; exit 1; fi
echo "all batch checks passed"

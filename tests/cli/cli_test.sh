#!/usr/bin/env bash
# End-to-end checks of motionstyle-cli: exit codes (0 ok, 2 bad input naming the file and line),
# --help on every command, and a convert round trip. Usage: cli_test.sh <motionstyle-cli> <tests/data>
set -u
cli="$1"
data="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

expect() {  # expect <code> <grep pattern or ""> <command...>
  local code="$1" pattern="$2"
  shift 2
  "$@" >"$work/out" 2>"$work/err"
  local got=$?
  if [ "$got" -ne "$code" ]; then
    echo "FAIL: exit $got, expected $code: $*"; cat "$work/err"; failures=$((failures + 1)); return
  fi
  if [ -n "$pattern" ] && ! grep -q -- "$pattern" "$work/out" "$work/err"; then
    echo "FAIL: no '$pattern' in the output of: $*"; cat "$work/out" "$work/err"; failures=$((failures + 1)); return
  fi
  echo "ok: $*"
}

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

# Working commands.
expect 0 "up axis      +Z" "$cli" info "$data/zombie.bvh"
expect 0 '"unit"' "$cli" info --json "$data/cmu_131_01.bvh"
expect 0 "wrote" "$cli" convert "$data/cmu_131_01.bvh" "$work/cmu60.bvh" --fps 60
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

if [ "$failures" -ne 0 ]; then echo "$failures CLI check(s) failed"; exit 1; fi
echo "all CLI checks passed"

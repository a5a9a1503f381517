#!/usr/bin/env bash
# A user's path through the real app with real X events (xdotool), as ctest runs it under xvfb-run:
# the demo opened, "Stylize & Clean Up" clicked, the strength slider dragged by the mouse for about a
# second and let go, then, after a look, the next style picked from the style list. Checked from the
# app's own log (app_log.h): results follow the hand while it moves, the last one answers where the
# slider was let go, and the next style was computed ahead while the result rested (shown without a
# job). Prints the latencies.
#
#   bash tests/gui/user_drag_test.sh MOTIONSTYLE_BINARY
#
# Exit 0 passed, 1 failed, 77 skipped (no xdotool or no X display).
set -u
app_binary=${1:?usage: user_drag_test.sh MOTIONSTYLE_BINARY}
command -v xdotool >/dev/null || { echo "SKIP: xdotool is not installed (packaging/install-deps.sh)"; exit 77; }
[ -n "${DISPLAY:-}" ] || { echo "SKIP: no X display (run under xvfb-run)"; exit 77; }

scratch=$(mktemp -d)
log="$scratch/motionstyle.log"
app_pid=
cleanup() { [ -n "$app_pid" ] && kill "$app_pid" 2>/dev/null; wait 2>/dev/null; rm -rf "$scratch"; }
trap cleanup EXIT
fail() { echo "FAIL: $*"; echo "--- the app's log:"; cat "$log" 2>/dev/null; echo "--- its output:"; cat "$scratch/app.txt"; exit 1; }

# wait_for PATTERN SECONDS: until a log line matches
wait_for() {
  local deadline=$(( $(date +%s) + $2 ))
  until grep -q "$1" "$log" 2>/dev/null; do
    [ "$(date +%s)" -lt "$deadline" ] || return 1
    sleep 0.2
  done
}
# control NAME: "x y w h" of a named control, from the app's log
control() { grep "control: $1 at " "$log" | tail -1 | sed -E 's/.* at ([0-9-]+) ([0-9-]+) size ([0-9]+) ([0-9]+)$/\1 \2 \3 \4/'; }

"$app_binary" --demo --log "$log" > "$scratch/app.txt" 2>&1 &
app_pid=$!
wait_for "control: StrengthSlider at" 120 || fail "the window did not come up (no control positions in the log)"

read -r bx by bw bh <<< "$(control StylizeButton)"
xdotool mousemove $(( bx + bw / 2 )) $(( by + bh / 2 )) click 1
wait_for "live: Stylize -> cleaned result" 120 || fail "no result after clicking Stylize & Clean Up"
# The status bar reports the result (the demo's "press Stylize" hint once stayed up and hid it).
wait_for "status: Stylized and cleaned up" 10 || fail "the status bar does not report the result"

# The slider starts at 1.0: its handle at the right end. Press there, move left for about a second.
read -r sx sy sw sh <<< "$(control StrengthSlider)"
y=$(( sy + sh / 2 ))
x=$(( sx + sw - 8 ))
xdotool mousemove "$x" "$y" mousedown 1
for step in $(seq 1 30); do
  xdotool mousemove $(( x - step * sw / 60 )) "$y"
  sleep 0.03
done
while_dragging=$(grep -c "live: the strength changed" "$log")
xdotool mouseup 1
sleep 3  # the job for the last value runs after the release

[ "$while_dragging" -ge 3 ] || fail "only $while_dragging result(s) arrived while the hand moved the slider"
last=$(grep "live: the strength changed" "$log" | tail -1 | sed -E 's/.*strength ([0-9.]+),.*/\1/')
# Let go at 1.0 - 30/60 of the slider's width: 0.5 give or take the handle's width.
awk -v s="$last" 'BEGIN { exit !(s >= 0.4 && s <= 0.6) }' || fail "the last result is for strength $last, the slider was let go near 0.5"
latencies=$(grep "live: the strength changed" "$log" | sed -E 's/.*on screen ([0-9]+) ms.*/\1/' | sort -n)
count=$(wc -l <<< "$latencies")
median=$(sed -n "$(( (count + 1) / 2 ))p" <<< "$latencies")

# The user looks at the result, then picks the next style in the list: it was computed ahead while
# they looked (result_panel_look_ahead.cpp), so it is shown without a job.
wait_for "look-ahead: " 60 || fail "no neighbouring style was computed ahead while the result rested"
read -r cx cy cw ch <<< "$(control NetworkChoice)"
[ -n "$cx" ] || fail "the style list's position is not in the log"
switches_before=$(grep -c "live: the style changed" "$log")
xdotool mousemove $(( cx + cw / 2 )) $(( cy + ch / 2 )) click 1
sleep 0.5
xdotool key Down Return
deadline=$(( $(date +%s) + 60 ))
until [ "$(grep -c "live: the style changed" "$log")" -gt "$switches_before" ]; do
  [ "$(date +%s)" -lt "$deadline" ] || fail "no result after picking the next style in the list"
  sleep 0.2
done
switch=$(grep "live: the style changed" "$log" | tail -1)
grep -q "remembered" <<< "$switch" || fail "the next style was computed after the switch, not ahead: $switch"
switch_ms=$(sed -E 's/.*on screen ([0-9]+) ms.*/\1/' <<< "$switch")

echo "PASS: $while_dragging results while dragging, $count in all, the last for strength $last;" \
     "latency median $median ms, max $(tail -1 <<< "$latencies") ms (real X events from xdotool, which shares the cores);" \
     "the next style, computed ahead, on screen $switch_ms ms after it was picked"

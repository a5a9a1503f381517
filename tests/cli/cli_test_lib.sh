# Shared by the tests/cli scripts (sourced, after `set -u`): the CLI and data folder from the script's
# arguments, a scratch folder removed on exit, a failure count, and the checks every script uses.
#   cli_test_lib.sh sets: cli ($1), data ($2), work (scratch folder), failures (0)
cli="$1"
data="$2"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
failures=0

# expect <code> <grep pattern or ""> <command...>: the command exits with <code> and, unless the
# pattern is empty, its stdout or stderr holds the pattern. On failure shows what it printed (the
# first 2,000 bytes: a hostile file's message can be long).
expect() {
  local code="$1" pattern="$2"
  shift 2
  "$@" >"$work/out" 2>"$work/err"
  local got=$?
  if [ "$got" -ne "$code" ]; then
    echo "FAIL: exit $got, expected $code: $*"; head -c 2000 "$work/out" "$work/err"; failures=$((failures + 1)); return
  fi
  if [ -n "$pattern" ] && ! grep -q -- "$pattern" "$work/out" "$work/err"; then
    echo "FAIL: no '$pattern' in the output of: $*"; head -c 2000 "$work/out" "$work/err"; failures=$((failures + 1)); return
  fi
  echo "ok: $*"
}

# fail <message>: counts a failed check.
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

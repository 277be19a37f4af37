#!/usr/bin/env bash
# Ctrl+C (SIGINT) cancels the running step cleanly: `plenopath render` and `plenopath track` stop at their
# next progress report with "cancelled" on stderr and exit code 130, and track writes no path file.
set -u
cli=$1
fail() { echo "FAIL: $*"; exit 1; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

# Waits (up to 60 s) until file $2 holds text $3, or process $1 has ended.
wait_for() {
  for _ in $(seq 600); do
    grep -q "$3" "$2" 2> /dev/null && return 0
    kill -0 "$1" 2> /dev/null || return 1
    sleep 0.1
  done
  return 1
}

# Interrupts process $1 once $2 holds $3; sets `code` to its exit code.
interrupt() {
  if ! wait_for "$1" "$2" "$3"; then
    wait "$1"; code="ended-early:$?"; return
  fi
  kill -INT "$1"
  wait "$1"; code=$?
}

# render along the whole automatic walk of the office sample (thousands of frames): far longer than the
# test waits, so the signal always lands mid-run.
"$cli" render --plan office-sample --size 256x128 --out "$tmp/long" 2> "$tmp/render.err" &
interrupt $! "$tmp/render.err" "render: 1/"
[[ $code == 130 ]] || fail "render: exit $code after SIGINT: $(cat "$tmp/render.err")"
grep -q "plenopath render: cancelled" "$tmp/render.err" || fail "render: no 'cancelled': $(cat "$tmp/render.err")"
grep -q "error" "$tmp/render.err" && fail "render: a cancel is not an error: $(cat "$tmp/render.err")"

# track: a 240-frame capture; the signal arrives while it reads the frames.
"$cli" render --plan office-sample --size 128x64 --frames 240 --quiet --out "$tmp/cap" || fail "render capture"
"$cli" track --capture "$tmp/cap/frames" --out "$tmp/path.json" 2> "$tmp/track.err" &
interrupt $! "$tmp/track.err" "track: frames"
[[ $code == 130 ]] || fail "track: exit $code after SIGINT: $(cat "$tmp/track.err")"
grep -q "plenopath track: cancelled" "$tmp/track.err" || fail "track: no 'cancelled': $(cat "$tmp/track.err")"
[[ -e "$tmp/path.json" ]] && fail "track: a cancelled run wrote its path"
echo "ok"

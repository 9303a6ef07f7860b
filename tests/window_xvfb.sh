#!/usr/bin/env bash
# window_xvfb: opens the real GLFW window under Xvfb, takes a screenshot with
# the C key, toggles wireframe with F through xdotool, takes another, and
# checks that both screenshots exist and differ.
# Usage: window_xvfb.sh MEADOW_BINARY
set -u
bin=$1
root=$(cd "$(dirname "$0")/.." && pwd)
command -v Xvfb >/dev/null && command -v xdotool >/dev/null || { echo "SKIP: Xvfb or xdotool missing"; exit 77; }
tmp=$(mktemp -d)
# Xvfb picks a free display itself and writes its number to fd 3 once it
# accepts connections (no collision with stale locks, no guessing when ready).
# -noreset: by default the server resets when its last client leaves, so the
# program could connect while the xdotool probe's disconnect resets it
# ("Failed to open display" in a loaded CI run).
Xvfb -displayfd 3 -screen 0 640x480x24 -nolisten tcp -noreset 3>"$tmp/display" >"$tmp/xvfb.log" 2>&1 &
xpid=$!
mpid=""
cleanup() { [ -n "$mpid" ] && kill "$mpid" 2>/dev/null; kill "$xpid" 2>/dev/null; wait 2>/dev/null; rm -rf "$tmp"; }
trap cleanup EXIT
for _ in $(seq 300); do [ -s "$tmp/display" ] && break; sleep 0.1; done
[ -s "$tmp/display" ] || { echo "FAIL: Xvfb did not start"; cat "$tmp/xvfb.log"; exit 1; }
export DISPLAY=:$(head -1 "$tmp/display")
# Make sure the server answers before the program connects.
for _ in $(seq 100); do xdotool getdisplaygeometry >/dev/null 2>&1 && break; sleep 0.1; done
xdotool getdisplaygeometry >/dev/null 2>&1 || { echo "FAIL: Xvfb on $DISPLAY does not answer"; cat "$tmp/xvfb.log"; exit 1; }
cd "$root"
"$bin" --scene scenes/tiny.json --size 320x240 --frames 100000 --out "$tmp/out" --screenshot-every 0 \
  >"$tmp/meadow.log" 2>&1 &
mpid=$!
wid=""
for _ in $(seq 300); do
  wid=$(xdotool search --onlyvisible --name '^meadow' 2>/dev/null | head -1)
  [ -n "$wid" ] && break
  sleep 0.2
done
[ -n "$wid" ] || { echo "FAIL: no meadow window on $DISPLAY"; cat "$tmp/meadow.log" "$tmp/xvfb.log"; exit 1; }
grep -q "platform: glfw" "$tmp/meadow.log" || { echo "FAIL: not the GLFW back end"; cat "$tmp/meadow.log"; exit 1; }
shot() { # shot N: press C and wait for the Nth screenshot
  xdotool key --window "$wid" c 2>/dev/null
  for _ in $(seq 150); do
    [ "$(ls "$tmp/out"/shot-*.png 2>/dev/null | wc -l)" -ge "$1" ] && return 0
    sleep 0.2
  done
  return 1
}
sleep 1
# Hide the HUD (it shows changing frame times) and pause: the image must
# then stay identical until F toggles wireframe.
xdotool key --window "$wid" h 2>/dev/null
xdotool key --window "$wid" p 2>/dev/null
sleep 0.5
shot 1 || { echo "FAIL: key C wrote no screenshot"; cat "$tmp/meadow.log"; exit 1; }
shot 2 || { echo "FAIL: second screenshot missing"; cat "$tmp/meadow.log"; exit 1; }
xdotool key --window "$wid" f 2>/dev/null
sleep 0.5
shot 3 || { echo "FAIL: third screenshot missing"; cat "$tmp/meadow.log"; exit 1; }
mapfile -t s < <(ls "$tmp/out"/shot-*.png)
if ! cmp -s "${s[0]}" "${s[1]}"; then echo "FAIL: paused frames differ (${s[0]} vs ${s[1]})"; exit 1; fi
if cmp -s "${s[1]}" "${s[2]}"; then echo "FAIL: wireframe key F changed nothing"; exit 1; fi
a=${s[1]}; b=${s[2]}
xdotool key --window "$wid" Escape 2>/dev/null
for _ in $(seq 100); do kill -0 "$mpid" 2>/dev/null || break; sleep 0.1; done
if kill -0 "$mpid" 2>/dev/null; then echo "FAIL: Escape did not close the window"; exit 1; fi
wait "$mpid"; rc=$?
[ "$rc" = 0 ] || { echo "FAIL: meadow exited $rc"; cat "$tmp/meadow.log"; exit 1; }
echo "ok: window screenshots differ after wireframe toggle ($a, $b)"

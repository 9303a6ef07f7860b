#!/usr/bin/env bash
# world_run: the open world through the program (docs/WORLD.md) on
# llvmpipe: the 1 and 4 km worlds in hybrid and billboard modes and the
# 1 km world in blade mode each run 6 frames at 96x54 (the scenes'
# density, 16 walkers, the camera path's first 0.1 s) and must finish
# (exit 0) with tiles streamed in (hybrid, blade) and billboard ring cells
# generated (hybrid, billboard); the GPU memory of the 1 and 4 km runs of
# each mode must be equal (nothing grows with the world); the 1 km hybrid
# with grass.billboards none streams tiles, has no ring and holds
# less GPU memory; the GI volumes are refused on a world with exit 2 and
# one error line.
# Usage: world_run.sh MEADOW_BINARY
set -u
bin=$1
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
secs=120
[ "${MEADOW_SANITIZED:-0}" = 1 ] && secs=480

# The rasterizer is named: `raster: auto` picks by a timing, so a loaded
# machine could pick another path (and its buffers) for one of the worlds.
run() { # name scene-file mode
  timeout $secs "$bin" --headless --quiet --scene "$2" --mode "$3" --raster hw --size 96x54 \
    --frames 6 --screenshot-every 0 --out "$tmp/$1" >"$tmp/$1.log" 2>&1
}
for r in "w1:world_1km:hybrid" "w4:world_4km:hybrid" "w1b:world_1km:blade" "w1r:world_1km:billboard" \
         "w4r:world_4km:billboard"; do
  IFS=: read -r name scene mode <<<"$r"
  run "$name" "$root/scenes/bench/$scene.json" "$mode"
  rc=$?
  if [ $rc -ne 0 ] || [ ! -f "$tmp/$name/summary.txt" ]; then
    echo "FAIL: $scene in $mode mode: exit $rc"; tail -3 "$tmp/$name.log"; fail=1; continue
  fi
  streamed=$(sed -n 's/.*tiles streamed in \([0-9]*\)[,;].*/\1/p' "$tmp/$name/summary.txt")
  cells=$(sed -n 's/^billboard ring: .*cells generated \([0-9]*\)$/\1/p' "$tmp/$name/summary.txt")
  if [ "$mode" != billboard ] && { [ -z "$streamed" ] || [ "$streamed" -le 0 ]; }; then
    echo "FAIL: $scene in $mode mode: no tiles streamed in (summary: '$streamed')"; fail=1
  fi
  if [ "$mode" != blade ] && { [ -z "$cells" ] || [ "$cells" -le 0 ]; }; then
    echo "FAIL: $scene in $mode mode: no billboard ring cells generated (summary: '$cells')"; fail=1
  fi
  echo "$scene $mode: $(grep -E '^gpu_memory_mb' "$tmp/$name/summary.txt"), tiles streamed in ${streamed:-0}," \
    "ring cells generated ${cells:-0}"
done
for pair in "w1:w4:hybrid" "w1r:w4r:billboard"; do
  IFS=: read -r a b mode <<<"$pair"
  m1=$(sed -n 's/^gpu_memory_mb: //p' "$tmp/$a/summary.txt" 2>/dev/null)
  m4=$(sed -n 's/^gpu_memory_mb: //p' "$tmp/$b/summary.txt" 2>/dev/null)
  if [ -z "$m1" ] || [ "$m1" != "$m4" ]; then
    echo "FAIL: $mode mode: GPU memory differs between the 1 km ($m1 MB) and the 4 km world ($m4 MB)"; fail=1
  fi
done

# grass.billboards none: the hybrid on a world without the ring
# (tiles, then the canopy), in less GPU memory than with it.
sed -e 's/"grass": {/"grass": {"billboards": "none",/' -e "s|\"models/|\"$root/models/|g" \
  "$root/scenes/bench/world_1km.json" >"$tmp/noring.json"
run noring "$tmp/noring.json" hybrid
rc=$?
m0=$(sed -n 's/^gpu_memory_mb: //p' "$tmp/noring/summary.txt" 2>/dev/null)
m1=$(sed -n 's/^gpu_memory_mb: //p' "$tmp/w1/summary.txt" 2>/dev/null)
if [ $rc -ne 0 ] || grep -q "^billboard ring" "$tmp/noring/summary.txt" || ! grep -q "tiles streamed in [1-9]" \
  "$tmp/noring/summary.txt" || ! python3 -c "import sys; sys.exit(0 if float('$m0') < float('$m1') else 1)"; then
  echo "FAIL: billboards none: exit $rc, GPU $m0 MB against $m1 MB with the ring"; tail -3 "$tmp/noring.log"
  fail=1
else
  echo "world_1km hybrid, billboards none: gpu_memory_mb: $m0 (ring: $m1), no ring"
fi

sed 's/"grass": {/"grass": {"gi": true,/' "$root/scenes/bench/world_1km.json" >"$tmp/gi.json"
timeout $secs "$bin" --headless --scene "$tmp/gi.json" --size 96x54 --frames 2 --out "$tmp/gi" >"$tmp/gi.out" 2>&1
rc=$?
if [ $rc -ne 2 ] || [ "$(grep -c error: "$tmp/gi.out")" -ne 1 ]; then
  echo "FAIL: grass.gi on a world: exit $rc"; cat "$tmp/gi.out"; fail=1
fi
[ $fail -eq 0 ] && echo ok
exit $fail

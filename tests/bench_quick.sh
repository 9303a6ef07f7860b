#!/usr/bin/env bash
# bench_quick: `meadow bench --quick`, its stability suite
# (--stability), its tile scaling sweeps (--scaling) and `meadow compare`
# run on llvmpipe and
# produce every file they promise (CSV, JSON, charts, tables, screenshots,
# montage).
# Usage: bench_quick.sh MEADOW_BINARY OUTDIR
set -u
bin=$1; out=$2
rm -rf "$out"; mkdir -p "$out"
fail=0
"$bin" bench --quick --quiet --scene scenes/tiny.json --out "$out/bench" || { echo "FAIL: bench exit $?"; fail=1; }
for f in bench.csv bench.json; do
  [ -s "$out/bench/$f" ] || { echo "FAIL: missing $f"; fail=1; }
done
for g in billboard_collision billboard_springs blade_proxies blade_tessellation blade_distance_levels hybrid_switch_distance modes; do
  for ext in dat png svg; do
    [ -s "$out/bench/bench_$g.$ext" ] || { echo "FAIL: missing bench_$g.$ext"; fail=1; }
  done
done
rows=$(($(wc -l <"$out/bench/bench.csv") - 1))
[ "$rows" -ge 13 ] || { echo "FAIL: bench.csv has $rows rows"; fail=1; }
python3 -c "import json,sys; d=json.load(open('$out/bench/bench.json')); assert len(d['configs'])==$rows" 2>/dev/null \
  || { echo "FAIL: bench.json does not parse or disagrees with the CSV"; fail=1; }
"$bin" bench --stability --quick --quiet --scene scenes/tiny.json --out "$out/stability" \
  || { echo "FAIL: bench stability exit $?"; fail=1; }
for f in stability.csv stability.md; do
  [ -s "$out/stability/$f" ] || { echo "FAIL: missing $f"; fail=1; }
done
cases="tunnelling framerate_blade framerate_bb thin_bb concave_bb concave_blade large_bb squeeze_blade squeeze_bb
       resting_blade spikes_blade spikes_bb steep_blade many_bb many_blade bb_border wall_blade wall_bb"
for c in $cases; do
  [ -s "$out/stability/stability_$c.png" ] || { echo "FAIL: missing stability_$c.png"; fail=1; }
  grep -q "^$c," "$out/stability/stability.csv" || { echo "FAIL: stability.csv has no $c rows"; fail=1; }
  grep -q "^| $c |" "$out/stability/stability.md" || { echo "FAIL: stability.md has no $c row"; fail=1; }
done
# --case runs one case alone; an unknown name is an error
"$bin" bench --stability --quick --quiet --case resting_blade --scene scenes/tiny.json --out "$out/one" \
  || { echo "FAIL: bench stability --case exit $?"; fail=1; }
others=$(awk -F, 'NR > 1 && $1 != "resting_blade"' "$out/one/stability.csv" 2>/dev/null | wc -l)
rows=$(awk -F, 'NR > 1 && $1 == "resting_blade"' "$out/one/stability.csv" 2>/dev/null | wc -l)
[ "$others" = 0 ] && [ "$rows" = 2 ] || { echo "FAIL: --case resting_blade wrote $rows rows of it, $others of others"; fail=1; }
if "$bin" bench --stability --quick --quiet --case no_such_case --out "$out/none" 2>/dev/null; then
  echo "FAIL: --case no_such_case succeeded"; fail=1
fi
"$bin" bench --scaling --quick --quiet --out "$out/scaling" || { echo "FAIL: bench scaling exit $?"; fail=1; }
for f in scaling.csv scaling_field.dat scaling_field.png scaling_field.svg scaling_active.dat scaling_active.png \
         scaling_active.svg; do
  [ -s "$out/scaling/$f" ] || { echo "FAIL: missing $f"; fail=1; }
done
# 3 field sizes with 4 slots each, then 1, 2, 4, 8, 16 slots
slots=$(awk -F, 'NR > 1 {printf "%s ", $5}' "$out/scaling/scaling.csv" 2>/dev/null)
[ "$slots" = "4 4 4 1 2 4 8 16 " ] || { echo "FAIL: scaling.csv slots '$slots'"; fail=1; }
"$bin" compare --quiet --scene scenes/tiny.json --frames 4 --out "$out/compare" || { echo "FAIL: compare exit $?"; fail=1; }
for f in compare.png compare.json compare-billboard.png compare-blade.png compare-hybrid.png compare-reference.png; do
  [ -s "$out/compare/$f" ] || { echo "FAIL: missing $f"; fail=1; }
done
if command -v ffmpeg >/dev/null; then
  "$bin" compare --video --quiet --scene scenes/tiny.json --frames 12 --out "$out/video" \
    || { echo "FAIL: compare --video exit $?"; fail=1; }
  for m in billboard blade hybrid; do
    [ -s "$out/video/clip-$m.mp4" ] || { echo "FAIL: missing clip-$m.mp4"; fail=1; }
    [ "$(ls "$out/video/clip-$m" 2>/dev/null | wc -l)" = 12 ] || { echo "FAIL: clip-$m has not 12 frames"; fail=1; }
  done
else
  echo "note: ffmpeg not installed, compare --video not checked"
fi
[ $fail = 0 ] && echo "ok: bench and compare wrote every file"
exit $fail

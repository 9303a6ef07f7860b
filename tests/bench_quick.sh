#!/usr/bin/env bash
# bench_quick: `meadow bench --quick`, its stability suite
# (--stability), its tile scaling sweeps (--scaling) and `meadow compare`
# run on llvmpipe and
# produce every file they promise (CSV, JSON, charts, tables, screenshots,
# montage); a bench session calibrates a scene's `raster: auto`.
# The steps are independent and run in two lanes at once (sweep and
# scaling; stability, compare and cube_texel), each step's time printed.
# Under the sanitizers (MEADOW_SANITIZED=1) the sweep renders 2 frames per
# configuration instead of 8: every configuration, chart and file is still
# made, but its accuracy checks, which need the 8 frames, are the plain
# run's.
# Usage: bench_quick.sh MEADOW_BINARY OUTDIR
set -u
bin=$1; out=$2
rm -rf "$out"; mkdir -p "$out"
sanitized=${MEADOW_SANITIZED:-0}

sweep() {
local fail=0 frames=()
[ "$sanitized" = 1 ] && frames=(--frames 2)
"$bin" bench --quick --quiet "${frames[@]}" --scene scenes/tiny.json --out "$out/bench" 2>"$out/bench.log" \
  || { echo "FAIL: bench exit $?"; cat "$out/bench.log"; fail=1; }
for f in bench.csv bench.json; do
  [ -s "$out/bench/$f" ] || { echo "FAIL: missing $f"; fail=1; }
done
for g in billboard_collision billboard_springs blade_proxies blade_proxies_overpush blade_tessellation blade_distance_levels \
         hybrid_switch_distance modes; do
  for ext in dat png svg; do
    [ -s "$out/bench/bench_$g.$ext" ] || { echo "FAIL: missing bench_$g.$ext"; fail=1; }
  done
done
rows=$(($(wc -l <"$out/bench/bench.csv") - 1))
[ "$rows" -ge 13 ] || { echo "FAIL: bench.csv has $rows rows"; fail=1; }
python3 -c "import json,sys; d=json.load(open('$out/bench/bench.json')); assert len(d['configs'])==$rows" 2>/dev/null \
  || { echo "FAIL: bench.json does not parse or disagrees with the CSV"; fail=1; }
[ "$sanitized" = 1 ] && { echo "note: sanitizers: 2 frames per configuration, accuracy not checked"; return $fail; }
# The billboard penetration measure sees the cube-map resolution it charts:
# 16 and 32 texels per face once gave identical depths (an axis-aligned
# box, exact in the axis-aligned cube maps at both); the ball does not
# (0.0409 against 0.0393 m depth p95 on llvmpipe).
python3 - "$out/bench/bench.csv" <<'EOF' || fail=1
import csv, sys
rows = {r["label"]: float(r["depth_p95"]) for r in csv.DictReader(open(sys.argv[1]))
        if r["group"] == "billboard_collision"}
a, b = rows.get("cube16_sub6_k2"), rows.get("cube32_sub6_k2")
if a is None or b is None or not (a > 0 and b > 0 and abs(a - b) > 1e-3 * max(a, b)):
    print(f"FAIL: billboard penetration does not answer the cube map: cube16 {a}, cube32 {b}")
    sys.exit(1)
EOF
# Chart measures that answer their knob (issue 33): the billboards' shape
# deviation from their finest configuration is 0 for it and differs
# between the two cube maps; the blade proxies' over-push is largest for the
# bounding sphere (cover_16 lies closer to the box).
python3 - "$out/bench/bench.csv" <<'EOF' || fail=1
import csv, sys
rows = {r["label"]: r for r in csv.DictReader(open(sys.argv[1]))}
dev = {k: float(rows[k]["shape_deviation"]) for k in ("cube16_sub6_k2", "cube32_sub6_k2", "cube32_sub6_k8") if k in rows}
push = {k: float(rows[k]["overpush_p95"]) for k in ("bound_1", "cover_16") if k in rows}
bad = 0
if len(dev) != 3 or not (dev["cube32_sub6_k8"] == 0 and dev["cube16_sub6_k2"] > 0 and dev["cube32_sub6_k2"] > 0
                      and dev["cube16_sub6_k2"] != dev["cube32_sub6_k2"]):
    print(f"FAIL: shape deviation does not answer the billboard knobs: {dev}"); bad = 1
if len(push) != 2 or not (push["bound_1"] > 2 * push["cover_16"] > 0):
    print(f"FAIL: over-push does not answer the blade proxies: {push}"); bad = 1
sys.exit(bad)
EOF
# Charts whose accuracy once did not answer their knob (issue 33): the blade
# proxies' cube maps at 16 and 32 texels (an axis-aligned box whose edges
# snapped to the same texel borders at both), the over-push of proxies
# inside the box (0 by construction: left out of that chart), the canopy
# distances on a field that ended before them (the chart runs on
# scenes/bench/canopy.json). The bench warns of identical rows; none here.
for g in blade_proxies blade_proxies_overpush hybrid_canopy_distance; do
  if grep -q "chart $g: identical accuracy" "$out/bench.log"; then
    echo "FAIL: $(grep "chart $g: identical accuracy" "$out/bench.log")"; fail=1
  fi
done
python3 - "$out/bench" <<'EOF3' || fail=1
import json, sys
d = sys.argv[1]
bad = []
def labels(chart):
    return [l.split()[2] for l in open(f"{d}/bench_{chart}.dat") if not l.startswith("#")]
p, o = labels("blade_proxies"), labels("blade_proxies_overpush")
inside = ["inscribed_1", "cubemap_16"]  # the 16-texel map snaps every edge of the box inward
if any(x not in p or x in o for x in inside) or sorted(o + inside) != sorted(p):
    bad.append(f"over-push chart {o} against the proxies' {p}: {inside} (inside the box) belong to the first only")
j = json.load(open(f"{d}/bench.json"))
rows = {c["label"]: c for c in j["configs"]}
# The tested points' depth: the 16-texel map (edges inward) leaves some
# inside the box, the 32-texel one (edges outward) fewer.
a, b = rows.get("cubemap_16", {}).get("depth_p95"), rows.get("cubemap_32", {}).get("depth_p95")
if a is None or b is None or not (a > b + 1e-4 and b >= 0):
    bad.append(f"blade cube maps: depth p95 {a} at 16 texels, {b} at 32")
can = [c for c in j["configs"] if c["group"] == "hybrid_canopy_distance"]
if len(can) != 2 or any(c["scene"] != "scenes/bench/canopy.json" for c in can) or "canopy_image_error_floor" not in j:
    got = [(c["label"], c["scene"]) for c in can]
    bad.append(f"canopy chart not on scenes/bench/canopy.json with its own floor: {got}")
elif not can[0]["image_error"] > can[1]["image_error"] > 0:
    bad.append(f"canopy 45 m does not err more than 60 m: {[(c['label'], c['image_error']) for c in can]}")
for m in bad:
    print("FAIL:", m)
sys.exit(1 if bad else 0)
EOF3
return $fail
}

stability() {
local fail=0
"$bin" bench --stability --quick --quiet --scene scenes/tiny.json --out "$out/stability" \
  || { echo "FAIL: bench stability exit $?"; fail=1; }
for f in stability.csv stability.md; do
  [ -s "$out/stability/$f" ] || { echo "FAIL: missing $f"; fail=1; }
done
cases="tunnelling framerate_blade framerate_bb thin_bb concave_bb concave_blade large_bb squeeze_blade squeeze_bb
       resting_blade spikes_blade spikes_bb steep_blade many_bb many_blade bb_border wall_blade wall_bb"
for c in $cases; do
  [ -s "$out/stability/stability_$c.png" ] || { echo "FAIL: missing stability_$c.png"; fail=1; }
  [ -s "$out/stability/stability_${c}_paper.png" ] || { echo "FAIL: missing stability_${c}_paper.png"; fail=1; }
  grep -q "^$c," "$out/stability/stability.csv" || { echo "FAIL: stability.csv has no $c rows"; fail=1; }
  grep -q "^| $c |" "$out/stability/stability.md" || { echo "FAIL: stability.md has no $c row"; fail=1; }
done
# --case runs one case alone; an unknown name is an error
"$bin" bench --stability --quick --quiet --case resting_blade --scene scenes/tiny.json --out "$out/one" \
  || { echo "FAIL: bench stability --case exit $?"; fail=1; }
others=$(awk -F, 'NR > 1 && $1 != "resting_blade"' "$out/one/stability.csv" 2>/dev/null | wc -l)
rows=$(awk -F, 'NR > 1 && $1 == "resting_blade"' "$out/one/stability.csv" 2>/dev/null | wc -l)
# two values in the paper and the default variant
[ "$others" = 0 ] && [ "$rows" = 4 ] || { echo "FAIL: --case resting_blade wrote $rows rows of it, $others of others"; fail=1; }
# Measures that grow with their failure (issue 33): thin_bb's wall crossing
# and the spikes cases' pose jump differ between the easy and the hard
# value, and the papers' methods as printed tunnel at 300 m/s where this
# project's swept collision does not.
python3 - "$out/stability/stability.csv" <<'EOF2' || fail=1
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
def vals(case, variant):
    return [(float(r["value"]), float(r["measure"]), r["fails"] == "1") for r in rows
            if r["case"] == case and r["variant"] == variant]
bad = 0
for case, variant in [("thin_bb", "default"), ("spikes_bb", "default"), ("spikes_blade", "default"),
                      ("spikes_blade", "paper")]:
    v = vals(case, variant)
    if len(v) != 2 or not v[1][1] > v[0][1]:
        print(f"FAIL: {case} ({variant}) measure does not grow over its knob: {v}"); bad = 1
for variant, want in [("paper", True), ("default", False)]:
    v = vals("tunnelling", variant)
    if len(v) != 2 or v[1][2] != want:
        print(f"FAIL: tunnelling ({variant}) at 300 m/s fails={v[1][2] if len(v) == 2 else None}, want {want}"); bad = 1
sys.exit(bad)
EOF2
if "$bin" bench --stability --quick --quiet --case no_such_case --out "$out/none" 2>/dev/null; then
  echo "FAIL: --case no_such_case succeeded"; fail=1
fi
return $fail
}

scaling() {
local fail=0
"$bin" bench --scaling --quick --quiet --out "$out/scaling" || { echo "FAIL: bench scaling exit $?"; fail=1; }
for f in scaling.csv scaling_field.dat scaling_field.png scaling_field.svg scaling_active.dat scaling_active.png \
         scaling_active.svg; do
  [ -s "$out/scaling/$f" ] || { echo "FAIL: missing $f"; fail=1; }
done
# 3 field sizes with 4 slots each, then 1, 2, 4, 8, 16 slots
slots=$(awk -F, 'NR > 1 {printf "%s ", $5}' "$out/scaling/scaling.csv" 2>/dev/null)
[ "$slots" = "4 4 4 1 2 4 8 16 " ] || { echo "FAIL: scaling.csv slots '$slots'"; fail=1; }
return $fail
}

compare_runs() {
local fail=0
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
# `--raster auto` is calibrated in bench sessions too (a session draws the
# hardware path unless the command line names a path or auto: the scene
# default, auto, would make its images depend on timing).
"$bin" compare --scene scenes/tiny.json --raster auto --frames 2 --out "$out/compare_auto" 2>"$out/compare_auto.log" >/dev/null \
  || { echo "FAIL: compare of a raster auto scene exit $?"; fail=1; }
grep -q "raster auto: a frame takes" "$out/compare_auto.log" \
  || { echo "FAIL: a bench session did not calibrate raster auto"; fail=1; }
return $fail
}

cube_texel() {
local fail=0
# grass.cube_texel raises the cube-map resolution with the largest collider:
# a 0.4 m sphere at 0.02 m texels needs 40 per face (above the default 32).
python3 -c "import json; s=json.load(open('scenes/tiny.json')); s['grass']['cube_texel']=0.02; json.dump(s, open('$out/texel.json','w'))"
"$bin" --headless --scene "$out/texel.json" --frames 1 --screenshot-every 0 --out "$out/texel" 2>"$out/texel.log" >/dev/null \
  || { echo "FAIL: cube_texel scene exit $?"; fail=1; }
grep -q "collision cube maps: 40 texels per face" "$out/texel.log" \
  || { echo "FAIL: grass.cube_texel did not raise the cube resolution to 40"; fail=1; }
return $fail
}

lane() { # lane NAME STEP...: the steps in turn, their output in OUT/lane_NAME.log
  local name=$1 step t0 fail=0; shift
  for step in "$@"; do
    t0=$SECONDS
    "$step" || fail=1
    echo "$step: $((SECONDS - t0)) s"
  done >"$out/lane_$name.log" 2>&1
  return $fail
}
lane a sweep scaling & lane_a=$!
lane b stability compare_runs cube_texel & lane_b=$!
fail=0
wait $lane_a || fail=1
wait $lane_b || fail=1
cat "$out/lane_a.log" "$out/lane_b.log"
[ $fail = 0 ] && echo "ok: bench and compare wrote every file"
exit $fail

#!/usr/bin/env bash
# bench_papers: `meadow bench --papers DIR --quick` on llvmpipe, on a tiny
# variant (scenes/tiny.json for the ablations, 96x64, 4 frames; the leaves
# figure on orthmann.json with 1 and 4 balls; every figure the median of 3
# sessions) writes every table it promises,
# complete (every ablation on both paths, every column filled, the papers
# table with the four papers' rows and ours on both paths), and its measures
# move: a culling test switched off culls nothing and draws more blades than
# with it on, collision off leaves no collider, and four balls collide with
# more octree leaves than one.
# Usage: bench_papers.sh MEADOW_BINARY OUTDIR
set -u
bin=$1; out=$2
rm -rf "$out"; mkdir -p "$out"
fail=0
"$bin" bench --papers "$out/p" --quick --quiet --scene scenes/tiny.json --size 96x64 --frames 4 2>"$out/log" \
  || { echo "FAIL: bench --papers exit $?"; cat "$out/log"; fail=1; }
for f in papers.json papers.md ablation.csv leaves.csv papers_leaves.dat papers_leaves.png papers_leaves.svg; do
  [ -s "$out/p/$f" ] || { echo "FAIL: missing $f"; fail=1; }
done
python3 - "$out/p" <<'EOF' || fail=1
import csv, json, sys
d = sys.argv[1]
bad = []
rows = list(csv.DictReader(open(f"{d}/ablation.csv")))
variants = ["all", "collision_off", "culling_off", "orientation_off", "frustum_off", "distance_off", "occlusion_off"]
got = [(r["variant"], r["raster"]) for r in rows]
if got != [(v, p) for v in variants for p in ("hw", "compute")]:
    bad.append(f"ablation rows {got}")
for r in rows:
    if any(v == "" for v in r.values()) or float(r["frame_ms"]) <= 0 or float(r["physics_ms"]) <= 0:
        bad.append(f"incomplete row {r}")
tests = ["orientation", "frustum", "distance", "occlusion"]
for p in ("hw", "compute"):
    row = {r["variant"]: r for r in rows if r["raster"] == p}
    a = row["all"]
    for t in tests:
        off = row[f"{t}_off"]
        if not (int(a[f"culled_{t}"]) > 0 and int(off[f"culled_{t}"]) == 0 and int(off["drawn"]) > int(a["drawn"])):
            bad.append(f"{p}: {t} off: culled {a['culled_' + t]} -> {off['culled_' + t]}, drawn {a['drawn']} -> {off['drawn']}")
    c = row["culling_off"]
    if any(int(c[f"culled_{t}"]) for t in tests) or int(c["drawn"]) <= max(int(row[f"{t}_off"]["drawn"]) for t in tests):
        bad.append(f"{p}: culling off culls {[c['culled_' + t] for t in tests]} and draws {c['drawn']}")
    if int(row["collision_off"]["colliders"]) != 0 or int(a["colliders"]) == 0:
        bad.append(f"{p}: colliders {a['colliders']} -> {row['collision_off']['colliders']} with collision off")
leaves = list(csv.DictReader(open(f"{d}/leaves.csv")))
if [(r["colliders"], r["raster"]) for r in leaves] != [("1", "hw"), ("1", "compute"), ("4", "hw"), ("4", "compute")]:
    bad.append(f"leaves rows {[(r['colliders'], r['raster']) for r in leaves]}")
for r in leaves:
    if min(float(r[k]) for k in ("collide_ms", "render_ms", "frame_ms")) <= 0:
        bad.append(f"leaves row without timings {r}")
for p in ("hw", "compute"):
    l = {r["colliders"]: float(r["colliding_leaves"]) for r in leaves if r["raster"] == p}
    if not 0 < l.get("1", 0) < l.get("4", 0):
        bad.append(f"{p}: colliding leaves do not grow with the balls: {l}")
md = open(f"{d}/papers.md").read()
table = [l for l in md.split("### Ablations")[0].splitlines() if l.startswith("| ") and not l.startswith(("| scene", "| ---"))]
names = [l.split(" | ")[0][2:] for l in table]
if names != ["orthmann", "nature", "helicopter", "fan128", "tiny"]:
    bad.append(f"papers table rows {names}")
for l in table:
    cells = l.strip("|").split(" | ")
    if len(cells) != 9 or any(c.strip() == "" for c in cells):
        bad.append(f"papers table row incomplete: {l}")
if not table or "frame " not in table[-1].split(" | ")[5] or "frame " not in table[-1].split(" | ")[6]:
    bad.append("papers table: tiny lacks ours on both paths")
for s in ("### Ablations", "#### tiny", "### Billboard cost against colliding leaves", "papers_leaves.png"):
    if s not in md:
        bad.append(f"papers.md lacks {s}")
j = json.load(open(f"{d}/papers.json"))
if not j["renderer"] or len(j["runs"]) != 2 * (len(variants) + 1) + 4:
    bad.append(f"papers.json: renderer {j['renderer']!r}, {len(j['runs'])} runs")
# Every figure is the median of 3 sessions (issue 33: each configuration
# runs at least 3 times), its frame spread beside it.
if j.get("runs_per_figure") != 3 or any(r["frame_ms_spread"] < 0 for r in j["runs"]):
    bad.append(f"papers.json: runs_per_figure {j.get('runs_per_figure')}")
if any(float(r["frame_ms_spread"]) < 0 for r in rows + leaves) or "median of 3 runs" not in md:
    bad.append("ablation/leaves tables without the spread over their 3 runs")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
EOF
if "$bin" bench --papers "$out/x" --perf "$out/y" 2>/dev/null; then echo "FAIL: --papers with --perf accepted"; fail=1; fi
[ $fail = 0 ] && echo "bench_papers: ok"
exit $fail

#!/usr/bin/env bash
# bench_perf: `meadow bench --perf DIR --quick` on llvmpipe writes a
# perf.json with every run (tiny.json in each mode, hw and compute; both
# floors measured) and
# regenerates only the marked sections of a doc (the table, the summary); `meadow bench --baseline`
# on synthetic perf.json files fails a pass 20 % + 0.03 ms slower (exit 1),
# passes one 10 % slower (exit 0), notes faster, missing and new passes, and
# refuses a renderer mismatch (exit 2) unless --force.
# Usage: bench_perf.sh MEADOW_BINARY OUTDIR
set -u
bin=$1; out=$2
rm -rf "$out"; mkdir -p "$out"
fail=0

# ---- --perf --quick ----
printf '# Doc\n\nhand-written above\n\n<!-- perf:begin -->\nstale table\n<!-- perf:end -->\n\nhand-written below\n' \
  >"$out/doc.md"
printf '<!-- perf-summary:begin -->\nstale summary\n<!-- perf-summary:end -->\n' >>"$out/doc.md"
"$bin" bench --perf "$out/perf" --quick --quiet --doc "$out/doc.md" 2>"$out/perf.log" \
  || { echo "FAIL: bench --perf --quick exit $?"; cat "$out/perf.log"; fail=1; }
python3 - "$out/perf/perf.json" <<'EOF' || fail=1
import json, sys
d = json.load(open(sys.argv[1]))
names = [r["name"] for r in d["runs"]]
want = [f"tiny/{m}/{r}" for m in ("hybrid", "billboard", "blade") for r in ("hw", "compute")]
ok = d["renderer"] and d["date"] and names == want
for r in d["runs"]:
    ok = ok and len(r["passes"]) >= 2 and abs(sum(r["passes"].values()) - r["frame_ms"]) < 1e-3 * len(r["passes"])
    ok = ok and (r["raster"] == "hw" or "raster.composite" in r["passes"] or r["fell_back"])
    ok = ok and r["floor_ms"] > 0 and r["compute_floor_ms"] > 0
if not ok:
    print(f"FAIL: perf.json: runs {names}, want {want}, each with passes summing to frame_ms and both floors")
    sys.exit(1)
EOF
for n in 1 2 3 4 5 6; do
  grep -q "^perf: *$n/6 tiny/" "$out/perf.log" || { echo "FAIL: no progress line $n/6"; fail=1; }
done
grep -q "hand-written above" "$out/doc.md" && grep -q "hand-written below" "$out/doc.md" \
  || { echo "FAIL: the doc lost its hand-written text"; fail=1; }
grep -q "stale table" "$out/doc.md" && { echo "FAIL: the doc's section was not replaced"; fail=1; }
grep -q "stale summary" "$out/doc.md" && { echo "FAIL: the doc's summary was not replaced"; fail=1; }
grep -q "^tiny at 320x180 on .*: hybrid [0-9.]* -> [0-9.]* ms, billboard" "$out/doc.md" \
  || { echo "FAIL: the doc's summary has no tiny hybrid/billboard/blade line"; fail=1; }
grep -q "^| tiny/blade/compute | 320x180" "$out/doc.md" || { echo "FAIL: the doc has no tiny/blade/compute row"; fail=1; }
cp "$out/doc.md" "$out/doc2.md"
"$bin" bench --perf "$out/x" --from "$out/perf/perf.json" --doc "$out/doc2.md" --quiet \
  || { echo "FAIL: --perf --from exit $?"; fail=1; }
cmp -s "$out/doc.md" "$out/doc2.md" || { echo "FAIL: regenerating from the same perf.json changed the doc"; fail=1; }
printf 'no markers\n' >"$out/nomark.md"
"$bin" bench --perf "$out/x" --from "$out/perf/perf.json" --doc "$out/nomark.md" 2>"$out/err"
[ $? = 2 ] && grep -q "perf:begin" "$out/err" || { echo "FAIL: a doc without markers is not exit 2"; fail=1; }
"$bin" bench --baseline "$out/perf/perf.json" --from "$out/perf/perf.json" >/dev/null \
  || { echo "FAIL: a run against itself exit $?"; fail=1; }

# ---- --baseline on synthetic runs ----
perf() { # perf FILE RENDERER DRAW_MS PHYSICS_MS [EXTRA_PASS]
  printf '{ "renderer": "%s", "date": "x", "frames": 400, "quick": false, "runs": [\n' "$2" >"$1"
  printf '  { "name": "nature/blade/hw", "passes": { "blade.draw": %s, "blade.physics": %s%s } },\n' "$3" "$4" "${5:-}" \
    >>"$1"
  printf '  { "name": "fan128/blade/hw", "passes": { "blade.draw": 2.0 } } ] }\n' >>"$1"
}
expect() { # expect RC NAME PATTERN args...
  local want=$1 name=$2 pat=$3; shift 3
  "$bin" bench "$@" >"$out/cmp.out" 2>&1
  local rc=$?
  if [ "$rc" != "$want" ] || ! grep -q -- "$pat" "$out/cmp.out"; then
    echo "FAIL: $name: exit $rc (want $want), output lacks '$pat':"; sed 's/^/    /' "$out/cmp.out"; fail=1
  else
    echo "ok: $name (exit $rc)"
  fi
}
perf "$out/base.json" "GPU A" 1.0 0.05
perf "$out/slow20.json" "GPU A" 1.23 0.05     # 1.0 x 1.20 + 0.03: over 1.17
perf "$out/slow10.json" "GPU A" 1.10 0.05     # within 1.17
perf "$out/short.json" "GPU A" 1.0 0.075      # 0.05 x 1.5: within 0.05 x 1.15 + 0.02
perf "$out/fast.json" "GPU A" 0.5 0.05
perf "$out/other.json" "GPU B" 1.0 0.05
perf "$out/extra.json" "GPU A" 1.0 0.05 ', "blade.cull": 0.1'
expect 1 "20 % + 0.03 ms slower fails" "| nature/blade/hw | blade.draw | 1.0000 | 1.2300 | +23.0 % | 1.1700 |" \
  --baseline "$out/base.json" --from "$out/slow20.json"
expect 0 "10 % slower passes" "0 slower" --baseline "$out/base.json" --from "$out/slow10.json"
expect 0 "short pass within 0.02 ms passes" "0 slower" --baseline "$out/base.json" --from "$out/short.json"
expect 0 "faster suggests an update" "update the baseline" --baseline "$out/base.json" --from "$out/fast.json"
expect 2 "renderer mismatch refused" "cannot be compared" --baseline "$out/base.json" --from "$out/other.json"
expect 0 "renderer mismatch with --force" "0 slower" --baseline "$out/base.json" --from "$out/other.json" --force
expect 0 "new pass listed" "new pass: nature/blade/hw blade.cull" --baseline "$out/base.json" --from "$out/extra.json"
expect 0 "missing pass listed" "missing pass: nature/blade/hw blade.cull" --baseline "$out/extra.json" \
  --from "$out/base.json"
printf '{ "renderer": "GPU A", "runs": [ { "name": "x" } ] }\n' >"$out/bad.json"
expect 2 "malformed baseline refused" "bad.json:1: a run needs" --baseline "$out/bad.json" --from "$out/base.json"
expect 2 "missing baseline refused" "nope.json" --baseline "$out/nope.json" --from "$out/base.json"
[ $fail = 0 ] && echo "ok: bench --perf and --baseline"
exit $fail

#!/usr/bin/env bash
# peer_field: a peer's 80 m field of 320k blades (scenes/peer.json) thinned
# as the Jahrmann demo by scene keys alone (grass.lod rule levels, 8
# levels, one blade in 8 left at 165 m; nothing hard-wired culls by
# distance): about 52 % of the blades drawn, the rest culled by
# orientation, frustum, patch and the levels. The levels key moves it:
# with rule off the distance test culls nothing.
# Usage: peer_field.sh MEADOW_BINARY
set -u
bin=$1
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
run() { # out-dir extra-args...
  local out=$1
  shift
  "$bin" --headless --quiet --scene "$root/scenes/peer.json" --screenshot-every 0 --out "$tmp/$out" "$@" >/dev/null \
    2>"$tmp/$out.err" || { echo "FAIL: $out: the run failed"; cat "$tmp/$out.err"; exit 1; }
}
run levels
sed 's/"rule": "levels"/"rule": "off"/' "$root/scenes/peer.json" >"$tmp/off.json"
"$bin" --headless --quiet --scene "$tmp/off.json" --screenshot-every 0 --out "$tmp/off" >/dev/null 2>"$tmp/off.err" ||
  { echo "FAIL: off: the run failed"; cat "$tmp/off.err"; exit 1; }
python3 - "$tmp/levels/summary.txt" "$tmp/off/summary.txt" <<'PY'
import re, sys
def counts(path):
    s = open(path).read()
    blades = int(re.search(r"^blades: (\d+)", s, re.M).group(1))
    drawn = int(re.search(r"^blade_survivors: (\d+)", s, re.M).group(1))
    culled = [int(x) for x in re.search(r"^blade_culled \([^)]*\): ([\d ]+)", s, re.M).group(1).split()]
    return blades, drawn, culled
b, d, c = counts(sys.argv[1])
print(f"levels: {d} of {b} blades drawn ({100 * d / b:.1f} %), culled (orientation frustum distance occlusion patch) {c}")
fail = []
if not 300000 <= b <= 340000: fail.append(f"{b} blades, not about 320k")
if not 0.50 <= d / b <= 0.54: fail.append(f"{100 * d / b:.1f} % drawn, not about 52 %")
b2, d2, c2 = counts(sys.argv[2])
print(f"off: {d2} of {b2} drawn, distance culled {c2[2]}")
if c2[2] != 0: fail.append(f"rule off still culls {c2[2]} by distance")
if d2 <= d: fail.append("the levels key drew no fewer blades than rule off")
for f in fail: print("FAIL:", f)
sys.exit(1 if fail else 0)
PY

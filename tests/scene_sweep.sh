#!/usr/bin/env bash
# scene_sweep: every numeric scene key, taken from the key table itself
# (`meadow --scene-keys`, rendered from src/scene/scene_fields.c), set in
# tests/data/scenes/sweep_base.json to the low end of its accepted range,
# the high end, and a tiny positive value. Each run (one frame, the base's
# 64x36 target) must finish its frame (exit 0, summary.txt) or be refused
# as bad input (exit 2, exactly one error line, no source path), within
# MEADOW_SWEEP_SECONDS (default 30) and under a MEADOW_SWEEP_VMEM_KB
# (default 2500000, 2.4 GiB) address-space cap: what exhausted the machine
# before resource admission (admit.h) must now be refused. Runs for
# numeric keys only; strings, enums and arrays are the fuzzer's.
# Under the sanitizers (MEADOW_SANITIZED=1) each key runs once, at the end
# its place in the table picks (1st key low, 2nd high, 3rd tiny, 4th low,
# ...): every key, every kind of end and of outcome (a frame, the parser's
# refusal, admission's) in a third of the runs; MEADOW_SWEEP_FULL=1 runs
# all of them there too.
# Usage: scene_sweep.sh MEADOW_BINARY [JOBS]
set -u
bin=$1
jobs=${2:-2}
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
secs=${MEADOW_SWEEP_SECONDS:-30}
vmem=${MEADOW_SWEEP_VMEM_KB:-2500000}
# Under ASan (MEADOW_SANITIZED=1, set by .ci/sanitize) the shadow memory
# needs terabytes of address space: no ulimit, the same budget told to
# admission instead, and more time: the grass.density 10000 run, most of it
# the canopy table with wind poses (3.1 s plain), took 71 s there.
if [ "${MEADOW_SANITIZED:-0}" = 1 ]; then
  export MEADOW_MEMORY_LIMIT_MB=$((vmem / 1024 / 2))
  vmem=unlimited
  secs=$((secs * 6))
fi

"$bin" --scene-keys >"$tmp/keys.md" || { echo "FAIL: meadow --scene-keys"; exit 1; }
subset=0
[ "${MEADOW_SANITIZED:-0}" = 1 ] && [ "${MEADOW_SWEEP_FULL:-0}" != 1 ] && subset=1
python3 - "$tmp/keys.md" "$root/tests/data/scenes/sweep_base.json" "$tmp" "$subset" <<'EOF' || exit 1
import json, re, sys
keys_md, base_path, tmp, subset = sys.argv[1:5]
base = json.load(open(base_path))
runs, nkeys = [], 0
for line in open(keys_md):
    m = re.match(r'\| `([^`]+)` \| ([^|]+) \| ([^|]+) \| [^|]* \| ([^|]*)\|', line)
    if not m:
        continue
    key, typ, accepted, doc = (g.strip() for g in m.groups())
    n = 1
    if re.match(r'\[\d+ (integers|numbers)\]', typ):
        n = int(typ[1])
    elif typ == '[min, max]':
        n = 2
    elif typ not in ('integer', 'number', 'integer: 1 or 4'):
        continue  # strings, enums, objects, arrays, mixed types
    integer = 'integer' in typ
    r = re.search(r'\[(-?[\d.e+]+), (-?[\d.e+]+)\]', accepted)
    if r:
        lo, hi = float(r.group(1)), float(r.group(2))
    else:  # a list of values (msaa: 0, 1, 2, 4, ...)
        vals = [float(v) for v in re.findall(r'-?[\d.]+', accepted)]
        lo, hi = min(vals), max(vals)
    tiny = 1 if integer else 1e-6
    only = re.match(r'\*([a-z_]+)\*(?:, \*([a-z_]+)\*)* only:', doc)
    types = set(re.findall(r'\*([a-z_]+)\*', doc.split('only:')[0])) if only else None
    ends = (('lo', lo), ('hi', hi), ('tiny', tiny))
    if subset == '1':
        ends = (ends[nkeys % 3],)
    nkeys += 1
    for label, v in ends:
        v = int(v) if integer else v
        runs.append((key, label, v if n == 1 else [v] * n, types))

def entry_of(scene, parts, types):
    """The object holding the key's last part: first entry of an array
    (of a type that accepts the key)."""
    o = scene
    for p in parts[:-1]:
        if p.endswith('[]'):
            arr = o[p[:-2]]
            cands = [e for e in arr if types is None or e.get('type', 'directional') in types] or arr
            o = cands[0]
        else:
            o = o.setdefault(p, {})
    return o

with open(tmp + '/runs.txt', 'w') as out:
    for i, (key, label, v, types) in enumerate(runs):
        scene = json.loads(json.dumps(base))
        parts = key.split('.')
        entry_of(scene, parts, types)[parts[-1]] = v
        path = '%s/s%03d.json' % (tmp, i)
        json.dump(scene, open(path, 'w'))
        out.write('%s %s=%s %s\n' % (path, key, label, json.dumps(v).replace(' ', '')))
print('%d runs of %d keys%s' % (len(runs), nkeys, ' (sanitizers: each key once)' if subset == '1' else ''))
EOF

one() { # one SCENE KEY=END VALUE
  local scene=$1 what=$2 value=$3 out=${1%.json}
  local t0=$SECONDS
  (ulimit -v "$vmem"; cd "$root" && timeout -k 5 "$secs" "$bin" --headless --quiet --scene "$scene" --frames 1 \
    --screenshot-every 0 --out "$out" >/dev/null 2>"$out.err")
  local rc=$? errs
  errs=$(grep -c 'error' "$out.err")
  local took=$((SECONDS - t0))
  if [ "$rc" = 0 ] && grep -q '^frames: 1$' "$out/summary.txt" 2>/dev/null; then
    echo "ok   $what $value: a frame (${took} s)"
  elif [ "$rc" = 2 ] && [ "$errs" = 1 ] && ! grep -qE '\.c:[0-9]+|src/' "$out.err"; then
    echo "ok   $what $value: refused: $(grep error "$out.err" | sed "s|$out.json|SCENE|")"
  else
    echo "FAIL $what $value: exit $rc, $errs error line(s) after ${took} s:"
    sed 's/^/    /' "$out.err" | head -8
  fi
}
export -f one
export bin root secs vmem
xargs -P "$jobs" -L 1 bash -c 'one "$@"' _ <"$tmp/runs.txt" >"$tmp/log.txt"
sort -k2 "$tmp/log.txt"
fails=$(grep -c '^FAIL' "$tmp/log.txt")
# Each kind of outcome occurs (the sanitizers' subset must keep all three):
# a frame, the parser's refusal (SCENE:LINE:), admission's (the value that fits).
for kind in "a frame|a frame" "the parser's refusal|refused: meadow: error: SCENE:[0-9]+: " \
            "an admission refusal|refused: meadow: error: SCENE: .* that fits is "; do
  grep -qE "^ok .*: ${kind#*|}" "$tmp/log.txt" || { echo "FAIL: no run ended in ${kind%%|*}"; fails=$((fails + 1)); }
done
echo "$(wc -l <"$tmp/runs.txt") runs, $fails failed"
[ "$fails" = 0 ]

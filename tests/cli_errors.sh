#!/usr/bin/env bash
# cli_errors: every bad command line, scene file or terrain mesh gives exactly
# one error line on stderr and exit code 2, with no crash and no GL error.
# Usage: cli_errors.sh MEADOW_BINARY
set -u
bin=$1
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
wait_for() { # wait_for TEST-ARGS...: up to 60 s for `test ARGS` to hold
  for _ in $(seq 600); do test "$@" && return 0; sleep 0.1; done
  echo "FAIL: waited 60 s for: test $*"; fail=1; return 1
}

expect2() { # expect2 "pattern in message" args...
  local pat=$1; shift
  # a run that gets as far as --out gets its own folder: the default, out,
  # may be locked by another test's run (ctest -j)
  case " $* " in *" --headless "*) case " $* " in *" --out "*) ;; *) set -- --out "$tmp/o" "$@" ;; esac ;; esac
  timeout 60 "$bin" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$?
  local errs
  errs=$(grep -c 'error' "$tmp/stderr")
  # (a refusal after the GL started had ended with "warning: gfx: N
  # prefetched programs never made", news only after a run that went through)
  if [ "$rc" != 2 ] || [ "$errs" != 1 ] || ! grep -q -- "$pat" "$tmp/stderr" ||
    grep -q 'prefetched programs never made' "$tmp/stderr"; then
    echo "FAIL: meadow $* -> exit $rc, $errs error line(s), want exit 2 and one line matching '$pat':"
    sed 's/^/    /' "$tmp/stderr"
    fail=1
  else
    echo "ok: meadow $* -> $(grep error "$tmp/stderr")"
  fi
}

expect2 "unknown option '--bogus'" --bogus
expect2 "--frames '-5'" --frames -5
expect2 "--frames 'abc'" --frames abc
expect2 "--size '0x100'" --size 0x100
expect2 "--raster 'gpu'" --raster gpu
expect2 "--raster-samples '2'" --raster-samples 2
expect2 "--size '-640x480'" --size -640x480
expect2 "--size '100000x100'" --size 100000x100
expect2 "--seed 'x1'" --seed x1
expect2 "--mode 'grass'" --mode grass
expect2 "needs a value" --scene
expect2 "unknown command 'fly'" fly
expect2 "options of .meadow bench." --perf "$tmp/p"
expect2 "--from needs --perf or --baseline" bench --from "$tmp/p.json"
expect2 "--force needs --baseline" bench --perf "$tmp/p" --force
expect2 "--baseline: empty path" bench --baseline ""
# --help's default of every option that sets a scene key is the key's
# default in the scene table (--raster said hw, the key's default is auto).
"$bin" --help >"$tmp/help.txt"
"$bin" --scene-keys >"$tmp/keys.md"
python3 - "$tmp/help.txt" "$tmp/keys.md" <<'PY' || fail=1
import re, sys
help_text, keys = open(sys.argv[1]).read(), open(sys.argv[2]).read()
options = {'--frames': 'frames', '--seed': 'seed', '--size': 'size', '--mode': 'mode',
           '--blade-render': 'grass.blade_render', '--raster': 'raster', '--raster-samples': 'raster_samples',
           '--character-height': 'characters[].height'}
first = lambda v: re.split(r'[ :;]', v.strip().strip('"'))[0]
bad = 0
for opt, key in options.items():
    entry = re.search(r'^  ' + re.escape(opt) + r' .*(?:\n {20,}.*)*', help_text, re.M)
    said = entry and re.search(r"default: the scene's \(([^)]*)\)", ' '.join(entry.group(0).split()))
    row = re.search(r'^\| `' + re.escape(key) + r'` \|[^|]*\|[^|]*\| ([^|]*) \|', keys, re.M)
    table = re.sub(r'\[(\d+), (\d+)\]', r'\1x\2', row.group(1)) if row else None
    if not said or not table or first(said.group(1)) != first(table):
        print(f"FAIL: --help's {opt} default ({said.group(1) if said else 'none'}) is not scene key {key}'s ({table})")
        bad = 1
    else:
        print(f"ok: --help's {opt} default {first(said.group(1))} is scene key {key}'s")
sys.exit(bad)
PY
# Empty values and paths longer than the program keeps (they were ignored,
# or cut without a word: --out at 1023 bytes, --character at 255).
# characters[].height and --character-height take one range, the key's
# (the key took 1e-9 where the option refused below 0.01).
expect2 "--character-height '1e-9': expected metres in 0.01..1000 (scene key characters\[\].height)" --character-height 1e-9
printf '{ "characters": [ { "model": "models/humanoid.gltf",\n  "height": 1e-9 } ] }\n' >"$tmp/height.json"
expect2 'height.json:2: field "characters\[0\].height": 1e-09 is out of range \[0.01, 1000\]' --headless --scene "$tmp/height.json"
expect2 "--character: empty model path" --character ""
expect2 "--clip: empty clip name" --clip ""
expect2 "--scene: empty path" --scene ""
long=/tmp/$(printf 'a%.0s' $(seq 1100))
expect2 "--out: 1105 bytes, more than the 1023 this program keeps" --out "$long"
expect2 "--scene: 1105 bytes, more than the 1023" --scene "$long"
expect2 "--character: 305 bytes, more than the 255" --character "${long:0:305}"
expect2 "--clip: 100 bytes, more than the 63" --clip "$(printf 'c%.0s' $(seq 100))"
# clip ranges: START:END on --clip and named ranges (characters[].clips) that
# are reversed, negative, past the timeline (the walk's 1000 ticks), not
# numbers, or too many names
tiny=(--headless --scene "$root/scenes/tiny.json" --frames 1 --size 64x36 --screenshot-every 0)
expect2 'clip range "5:2" in .*humanoid.gltf: end 2 is not after start 5' "${tiny[@]}" \
  --character models/humanoid.gltf --clip 5:2
expect2 'clip range "-1:5" in .*: start -1 is negative' "${tiny[@]}" --character models/humanoid.gltf --clip -1:5
expect2 "clip range \"0:5000\" in .*: end 5000 is past the timeline's 1000 ticks (clip 0 'walk')" "${tiny[@]}" \
  --character models/humanoid.gltf --clip 0:5000
expect2 'no clip "a:b" in .*humanoid.gltf' "${tiny[@]}" --character models/humanoid.gltf --clip a:b
clips_scene() { # clips_scene FILE CLIPS_JSON: one humanoid playing "walk" of CLIPS_JSON
  printf '{ "characters": [ { "model": "models/humanoid.gltf", "clip": "walk",\n  "clips": %s } ] }\n' "$2" >"$1"
}
clips_scene "$tmp/clips_past.json" '{ "walk": [1, 5000] }'
expect2 "character 0: clips.walk \[1, 5000\] in .*: end 5000 is past the timeline's 1000 ticks" \
  --headless --scene "$tmp/clips_past.json"
clips_scene "$tmp/clips_reversed.json" '{ "walk": [14, 1] }'
expect2 'clips_reversed.json:2: field "characters\[0\].clips.walk": end 1 is not after start 14' \
  --headless --scene "$tmp/clips_reversed.json"
clips_scene "$tmp/clips_negative.json" '{ "walk": [-1, 14] }'
expect2 'field "characters\[0\].clips.walk\[0\]": -1 is out of range \[0, 1e+07\]' \
  --headless --scene "$tmp/clips_negative.json"
clips_scene "$tmp/clips_text.json" '{ "walk": ["1", 14] }'
expect2 'field "characters\[0\].clips.walk\[0\]": expected number, got string' --headless --scene "$tmp/clips_text.json"
clips_scene "$tmp/clips_many.json" "{ $(for n in a b c d e f g h i; do printf '"%s": [0, 1], ' $n; done)\"j\": [0, 1] }"
expect2 'field "characters\[0\].clips": 10 names, more than the maximum 8 (SCENE_MAX_CLIP_RANGES)' \
  --headless --scene "$tmp/clips_many.json"
expect2 "--perf: 1105 bytes, more than the 1023" bench --perf "$long"
printf '{ "terrain": { "type": "mesh", "mesh": "%s" } }\n' "${long:0:300}" >"$tmp/longmesh.json"
expect2 'longmesh.json:1: field "terrain.mesh": string of 300 bytes is longer than the maximum 255' \
  --headless --scene "$tmp/longmesh.json"
expect2 "cannot be combined" bench --perf "$tmp/p" --scaling
expect2 "--case needs .meadow bench --stability." bench --case resting_blade
expect2 "missing.json" --headless --scene "$tmp/missing.json"
printf '{ "seed": 1,\n  "terrain": { "size": 10,\n' >"$tmp/truncated.json"
expect2 "truncated.json:2: unexpected end of file" --headless --scene "$tmp/truncated.json"
printf '{\n  "seed": 1,\n  "grass": { "density": "lots" }\n}\n' >"$tmp/wrongtype.json"
expect2 'wrongtype.json:3.*grass.density' --headless --scene "$tmp/wrongtype.json"
printf '{\n  "sed": 1\n}\n' >"$tmp/unknown.json"
expect2 'unknown.json:2.*sed' --headless --scene "$tmp/unknown.json"
printf '{\n  "grass": { "stiffness": [0, 10] }\n}\n' >"$tmp/stiffness0.json"
expect2 'stiffness0.json:2: field "grass.stiffness\[0\]": 0 is out of range (0, 100\]' --headless --scene "$tmp/stiffness0.json"
printf '{\n  "raster": "gpu"\n}\n' >"$tmp/raster.json"
expect2 'raster.json:2.*raster' --headless --scene "$tmp/raster.json"
printf '{\n  "grass": { "blade_distance": "far" }\n}\n' >"$tmp/bladedist.json"
expect2 'bladedist.json:2: field "grass.blade_distance": expected number' --headless --scene "$tmp/bladedist.json"
printf '{\n  "grass": { "clearings": {\n    "fraction": 1.5 } }\n}\n' >"$tmp/fraction.json"
expect2 'fraction.json:3: field "grass.clearings.fraction": 1.5 is out of range' --headless --scene "$tmp/fraction.json"
printf '{ "grass": { "clearings": { "type": "image", "image": "%s/nope.png" } } }\n' "$tmp" >"$tmp/noimage.json"
expect2 'grass.clearings.image: cannot find .*nope.png' --headless --scene "$tmp/noimage.json"
printf 'not a png\n' >"$tmp/garbage.png"
printf '{ "grass": { "clearings": { "type": "image", "image": "%s/garbage.png" } } }\n' "$tmp" >"$tmp/badimage.json"
expect2 'garbage.png: cannot load image' --headless --scene "$tmp/badimage.json"
printf '{ "terrain": { "type": "mesh", "mesh": "%s/nope.obj" } }\n' "$tmp" >"$tmp/badmesh.json"
expect2 'nope.obj' --headless --scene "$tmp/badmesh.json"
printf 'this is not a mesh\n' >"$tmp/garbage.obj"
printf '{ "terrain": { "type": "mesh", "mesh": "%s/garbage.obj" } }\n' "$tmp" >"$tmp/garbagemesh.json"
expect2 'garbage.obj' --headless --scene "$tmp/garbagemesh.json"
# Fuzz regressions that once hung or crashed assimp, fed through the program.
exts=(obj ply gltf glb stl)
for reg in "$root"/tests/data/fuzz_regressions/mesh_*; do
  # Under ASan (MEADOW_SANITIZED=1, set by .ci/sanitize) a throwing operator
  # new that cannot allocate aborts the process instead of throwing
  # std::bad_alloc for assimp to catch; the normal run covers this file.
  if [ "${MEADOW_SANITIZED:-0}" = 1 ] && [[ $reg == *huge_allocation* ]]; then
    echo "skipped under ASan: $(basename "$reg")"
    continue
  fi
  b=$(head -c1 "$reg" | od -An -tu1 | tr -d ' ')
  e=${exts[$((b % 5))]}
  tail -c +2 "$reg" >"$tmp/fz.$e"
  printf '{ "terrain": { "type": "mesh", "mesh": "%s/fz.%s" } }\n' "$tmp" "$e" >"$tmp/fz.json"
  expect2 "fz.$e" --headless --scene "$tmp/fz.json"
done
printf '{ "mode": "blade", "terrain": { "size": 2000 }, "grass": { "density": 10000 } }\n' >"$tmp/huge.json"
expect2 "more than the 50000000 a full blade field holds" --headless --scene "$tmp/huge.json"
expect2 "nope.gltf" --headless --scene "$root/scenes/tiny.json" --character "$tmp/nope.gltf"
mkdir -p "$tmp/ro" && touch "$tmp/ro/file"
expect2 'not a directory' --headless --scene "$root/scenes/tiny.json" --out "$tmp/ro/file"
# Inputs that exhaust the machine are refused before anything is allocated:
# an endless file, and tiles too small for the hybrid's table.
expect2 '/dev/zero: cannot read: not a regular file' --headless --scene /dev/zero
# A FIFO as the scene or grass.lod_table is refused without blocking in
# open(2) (which waited for a writer forever, deaf to SIGINT, holding --out).
mkfifo "$tmp/fifo.json"
# The 2 s a signal or a refusal may take; 10 s under the sanitizers, whose
# runs are 5-10x slower (the summary a signalled run writes took 2.2 s
# under ASan on a loaded 2-core machine, 27 ms without).
limit_ms=2000
[ "${MEADOW_SANITIZED:-0}" = 1 ] && limit_ms=10000
t0=$(date +%s%N)
expect2 'fifo.json: cannot read: not a regular file' --headless --scene "$tmp/fifo.json"
ms=$((($(date +%s%N) - t0) / 1000000))
[ "$ms" -lt "$limit_ms" ] || { echo "FAIL: a FIFO as --scene took $ms ms to refuse (want < $limit_ms ms)"; fail=1; }
python3 -c "import json,sys; s=json.load(open(sys.argv[1])); s['grass']['lod_table']=sys.argv[2]; \
json.dump(s, open(sys.argv[3],'w'))" "$root/scenes/tiny.json" "$tmp/fifo.json" "$tmp/lod_fifo.json"
timeout 60 "$bin" --headless --quiet --scene "$tmp/lod_fifo.json" --size 64x36 --frames 1 --screenshot-every 0 \
  --out "$tmp/lod_fifo" >/dev/null 2>"$tmp/lod_fifo.log"
rc=$?
{ [ "$rc" = 0 ] && grep -q "warning: grass.lod_table: .*fifo.json: not a regular file" "$tmp/lod_fifo.log"; } \
  || { echo "FAIL: a FIFO as grass.lod_table gave exit $rc:"; sed 's/^/    /' "$tmp/lod_fifo.log"; fail=1; }
printf '{ "terrain": { "type": "mesh", "mesh": "/dev/zero" } }\n' >"$tmp/zeromesh.json"
expect2 'terrain.mesh: /dev/zero: not a regular file' --headless --scene "$tmp/zeromesh.json"
printf '{ "grass": { "clearings": { "type": "image", "image": "/dev/zero" } } }\n' >"$tmp/zeroimage.json"
expect2 '/dev/zero: cannot load image: not a regular file' --headless --scene "$tmp/zeroimage.json"
printf '{ "grass": { "tile_size": 0.001 } }\n' >"$tmp/tiny_tiles.json"
expect2 'the smallest tile_size that fits is' --headless --scene "$tmp/tiny_tiles.json"
# Values in range that cannot run are refused by resource admission
# (admit.h) with the key and the value that fits; the command line
# takes the scene key's range (one table); a NUL is not an end of file;
# a key of the other terrain type is refused.
printf '{ "grass": { "tile_size": 1000 } }\n' >"$tmp/tile1000.json"
expect2 'grass.tile_size 1000 needs .*: the largest grass.tile_size that fits is' --headless --scene "$tmp/tile1000.json"
printf '{ "terrain": { "size": 10000 } }\n' >"$tmp/terrain10k.json"
expect2 'the smallest tile_size that fits is 9.77 m' --headless --scene "$tmp/terrain10k.json"
printf '{ "grass": { "subdiv": [8, 8] } }\n' >"$tmp/subdiv8.json"
expect2 'grass.subdiv \[8, 8\] needs 112 geometry-shader output vertices.*the largest that fits is \[8, ' \
  --headless --scene "$tmp/subdiv8.json"
printf '{ "grass": { "density": 0.001, "tile_size": 2 } }\n' >"$tmp/sparse.json"
expect2 'grass.density 0.001 puts 0.004 blades on a tile.*smallest grass.density that fits is 0.25' \
  --headless --scene "$tmp/sparse.json"
python3 -c "import json; print(json.dumps({'colliders': [{'type': 'sphere', 'position': [i, 0.5, 0]} for i in range(120)],
  'characters': [{'model': 'models/humanoid.gltf'}] * 9}))" >"$tmp/objects.json"
expect2 'colliders: 120 colliders and 9 character(s) are 129 objects, more than the 128 .* is 119' \
  --headless --scene "$tmp/objects.json"
# 16 humanoids (the most a scene holds) take 608 sphere proxies, more than
# the 512 the blade physics once held (refused, and before that "logged
# once" and dropped): they run, with no warning. Past the 4096 a step holds
# the refusal names the key that takes them: a thin capsule's length, also
# beside the 16, and a capsule of radius 1e-9 (its count saturates; 1e11
# overflowed an int, and the scene was admitted).
python3 -c "import json,sys; s=json.load(open(sys.argv[1])); \
s['characters']=[{'model': 'models/humanoid.gltf', 'path': [[i - 8, -2], [i - 8, 2]]} for i in range(16)]; \
json.dump(s, open(sys.argv[2],'w')); \
s['colliders']=[{'type': 'capsule', 'radius': 0.01, 'length': 40}]; json.dump(s, open(sys.argv[3],'w'))" \
  "$root/scenes/tiny.json" "$tmp/chars16.json" "$tmp/chars16_capsule.json"
for mode in blade hybrid; do
  "$bin" --headless --scene "$tmp/chars16.json" --mode $mode --size 64x36 --frames 2 --screenshot-every 0 \
    --out "$tmp/chars16_$mode" >/dev/null 2>"$tmp/chars16.log" &&
    ! grep -Ei 'sphere|left out|error' "$tmp/chars16.log" >/dev/null ||
    { echo "FAIL: 16 characters in $mode mode:"; cat "$tmp/chars16.log"; fail=1; }
done
printf '{ "colliders": [ { "type": "capsule", "radius": 0.01, "length": 50 } ] }\n' >"$tmp/capsule.json"
expect2 'colliders\[0\].length 50 over radius 0.01 takes 5001 .*more than its 4096: the largest colliders\[0\].length that fits is 40.94' \
  --headless --scene "$tmp/capsule.json"
expect2 'colliders\[0\].length 40 over radius 0.01 takes 4001 .* 4609 with the rest.*that fits is 34.86' \
  --headless --scene "$tmp/chars16_capsule.json"
printf '{ "colliders": [ { "type": "capsule", "radius": 1e-9, "length": 100 } ] }\n' >"$tmp/capsule0.json"
expect2 'colliders\[0\].length 100 over radius 1e-09 takes 1000000001 .*that fits is 0$' \
  --headless --scene "$tmp/capsule0.json"
printf '{ "size": [8, 100] }\n' >"$tmp/size8.json"
expect2 'field "size\[0\]": 8 is out of range \[16, 16384\]' --headless --scene "$tmp/size8.json"
expect2 "--size '16385x100': expected WxH with each side in 16..16384 (scene key size)" --size 16385x100
# The largest size the option takes is admitted only if the compute
# rasterizer's visibility buffer fits (raster auto makes one): counted
# before the GL starts, against memory and against the 4 GiB one GL buffer
# holds (it was admitted and failed with GL_OUT_OF_MEMORY, for minutes).
expect2 '--size 16384x16384 needs .*: the largest --size that fits is [0-9]*x[0-9]*$' \
  --headless --scene "$root/scenes/tiny.json" --size 16384x16384
MEADOW_MEMORY_LIMIT_MB=2400 expect2 \
  '--size 16384x16384 needs 17.19 GB of memory .*(compute rasterizer 10.74 GB).*the largest --size that fits is' \
  --headless --scene "$root/scenes/tiny.json" --size 16384x16384
expect2 "--seed '4294967296': expected an integer in 0..4294967295 (scene key seed)" --seed 4294967296
printf '{ "seed": 1\0 }' >"$tmp/nul.json"
expect2 'nul.json:1: a NUL byte at offset 11' --headless --scene "$tmp/nul.json"
# Invalid UTF-8 in a string is refused by the parser with its line, and no
# raw byte reaches the message (it was accepted, then echoed in an error).
printf '{\n  "mode": "hy\377brid" }\n' >"$tmp/utf8.json"
expect2 'utf8.json:2: invalid UTF-8 in a string (byte 0xff at offset 15)' --headless --scene "$tmp/utf8.json"
[ "$(tr -d '\000-\177' <"$tmp/stderr" | wc -c)" = 0 ] || { echo "FAIL: the UTF-8 error printed raw bytes"; fail=1; }
printf '{ "terrain": { "mesh": "models/torus.obj" } }\n' >"$tmp/hfmesh.json"
expect2 'unknown key "mesh" for terrain type "heightfield"' --headless --scene "$tmp/hfmesh.json"
# A camera must look somewhere: position = target is refused (also a path
# key's); one looking straight down renders the field (its view matrix had
# +y as up, parallel to the view: a blank frame of sky colour).
printf '{ "camera": {\n  "position": [1, 2, 3],\n  "target": [1, 2, 3] } }\n' >"$tmp/lookself.json"
expect2 'lookself.json:3: field "camera.target": \[1, 2, 3\] is camera.position' --headless --scene "$tmp/lookself.json"
printf '{ "camera": { "path": [ { "t": 0, "position": [0, 1, 0], "target": [0, 0, 0] },\n  { "t": 1, "position": [5, 1, 0], "target": [5, 1, 0] } ] } }\n' >"$tmp/lookself_path.json"
expect2 'lookself_path.json:2: field "camera.path\[1\].target": .* is camera.path\[1\].position' \
  --headless --scene "$tmp/lookself_path.json"
png_colours() { # png_colours FILE: distinct colours of an 8-bit RGB(A) PNG
  python3 - "$1" <<'PY'
import struct, sys, zlib
d = open(sys.argv[1], 'rb').read()
i, idat = 8, b''
while i < len(d):
    n, t = struct.unpack('>I4s', d[i:i + 8])
    if t == b'IHDR': w, h, depth, ctype = struct.unpack('>IIBB', d[i + 8:i + 18])
    if t == b'IDAT': idat += d[i + 8:i + 8 + n]
    i += 12 + n
bpp = {2: 3, 6: 4}[ctype]
raw, stride, prev, colours = zlib.decompress(idat), w * bpp, bytearray(w * bpp), set()
for y in range(h):
    f, row = raw[y * (stride + 1)], bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
    for x in range(stride):
        a, b, c = row[x - bpp] if x >= bpp else 0, prev[x], prev[x - bpp] if x >= bpp else 0
        p = a + b - c
        pr = a if abs(p - a) <= abs(p - b) and abs(p - a) <= abs(p - c) else b if abs(p - b) <= abs(p - c) else c
        row[x] = (row[x] + (0, a, b, (a + b) // 2, pr)[f]) & 255
    colours.update(bytes(row[x:x + bpp]) for x in range(0, stride, bpp))
    prev = row
print(len(colours))
PY
}
python3 -c "import json,sys; s=json.load(open(sys.argv[1])); s['camera']={'position': [0, 10, 0], 'target': [0, 0, 0]}; \
json.dump(s, open(sys.argv[2],'w'))" "$root/scenes/tiny.json" "$tmp/down.json"
"$bin" --headless --quiet --scene "$tmp/down.json" --size 128x72 --frames 3 --screenshot-every 3 --out "$tmp/down" \
  >/dev/null 2>&1
colours=$(png_colours "$tmp/down/shot-000003.png" 2>/dev/null)
[ "${colours:-0}" -gt 16 ] \
  || { echo "FAIL: a camera looking straight down drew ${colours:-no} colour(s) (a blank frame: 1)"; fail=1; }
# A UTF-8 byte order mark before the scene's JSON is accepted.
{ printf '\xef\xbb\xbf'; sed "s|\"models/|\"$root/models/|g" "$root/scenes/tiny.json"; } >"$tmp/bom.json"
"$bin" --headless --quiet --scene "$tmp/bom.json" --size 64x36 --frames 1 --screenshot-every 0 --out "$tmp/bom" \
  >/dev/null 2>&1 || { echo "FAIL: a scene file with a UTF-8 byte order mark was refused"; fail=1; }
# grass.lod_table (scene_lod.h): a table of this renderer sets the hybrid's
# distances and says so in summary.txt; one of another renderer leaves the
# scene's with a warning.
"$bin" --headless --quiet --scene "$root/scenes/tiny.json" --size 64x36 --frames 1 --screenshot-every 0 \
  --out "$tmp/lod0" >/dev/null 2>&1
renderer=$(sed -n 's/^renderer: //p' "$tmp/lod0/summary.txt")
lod_table() { # renderer file
  printf '{"renderer": "%s", "paths": {"hw": {"switch_distance": 3, "canopy_distance": 9, "gpu_ms": 1,
    "image_error": 0.5, "budget": 0.6, "met": true, "candidates": 4}}}\n' "$1" >"$2"
}
lod_table "$renderer" "$tmp/lod_here.json"
lod_table "Some Other GPU" "$tmp/lod_other.json"
for t in here other; do
  python3 -c "import json,sys; s=json.load(open(sys.argv[1])); s['grass']['lod_table']=sys.argv[2]; \
s['raster']='hw'; json.dump(s, open(sys.argv[3],'w'))" "$root/scenes/tiny.json" "$tmp/lod_$t.json" "$tmp/lod_$t.scene.json"
  "$bin" --headless --quiet --scene "$tmp/lod_$t.scene.json" --size 64x36 --frames 1 --screenshot-every 0 \
    --out "$tmp/lod_$t" >/dev/null 2>"$tmp/lod_$t.log"
done
grep -q "^hybrid distances: switch 3.0 m, canopy 9.0 m (hw path, from" "$tmp/lod_here/summary.txt" \
  || { echo "FAIL: grass.lod_table of this renderer did not set the distances"; fail=1; }
grep -q "^hybrid distances: switch 4.0 m, canopy 60.0 m (.*not this GL" "$tmp/lod_other/summary.txt" \
  && grep -q "warning: grass.lod_table" "$tmp/lod_other.log" \
  || { echo "FAIL: grass.lod_table of another renderer was not refused with a warning"; fail=1; }
# Interrupted runs still write their summary: GNU timeout signals the
# program and then its process group, so one timeout delivers SIGINT two to
# four times (a second-signal-kills rule lost the summary and bench tables
# that way). Two SIGINTs sent back to back stand for it: timeout itself,
# descheduled for a second between its signals on a loaded CI machine, made
# the second one count as a user's second Ctrl-C (which kills, by design).
rm -rf "$tmp/intr"
"$bin" --headless --quiet --scene "$root/scenes/tiny.json" --size 64x36 --frames 1000000 --screenshot-every 0 \
  --out "$tmp/intr" >/dev/null 2>&1 &
runner=$!
wait_for -s "$tmp/intr/.meadow.lock" && sleep 1 # its handler is in place before it locks --out; then frames
kill -INT "$runner"; kill -INT "$runner"
wait "$runner"
rc=$?
grep -q "interrupted" "$tmp/intr/summary.txt" 2>/dev/null \
  || { echo "FAIL: a run interrupted by two SIGINTs wrote no summary saying so"; fail=1; }
[ "$rc" = 130 ] || { echo "FAIL: an interrupted run exited $rc, not 130"; fail=1; }
# A context that cannot be made under a small address-space limit says
# the limit may be the cause (EGL says only "eglInitialize failed"); exit 1,
# a runtime failure. ASan's shadow memory rules out the limit.
if [ "${MEADOW_SANITIZED:-0}" != 1 ]; then
  prlimit --as=157286400 "$bin" --headless --scene "$root/scenes/tiny.json" --frames 1 --out "$tmp/as150" \
    >/dev/null 2>"$tmp/as150.log"
  rc=$?
  { [ "$rc" = 1 ] && [ "$(grep -c 'error' "$tmp/as150.log")" = 1 ] && grep -q \
    "error: no OpenGL 4.5 context: .*the address space is limited to 150 MiB (ulimit -v): that limit may be the cause" \
    "$tmp/as150.log"; } || { echo "FAIL: no context under prlimit --as=150M gave exit $rc:"; sed 's/^/    /' "$tmp/as150.log"; fail=1; }
fi
# SIGHUP (the terminal closed) ends a run as SIGINT does: the summary says
# so, exit 130 (it was the default action: exit 129, no summary), within
# limit_ms.
rm -rf "$tmp/hup"
"$bin" --headless --quiet --scene "$root/scenes/tiny.json" --size 64x36 --frames 1000000 --screenshot-every 0 \
  --out "$tmp/hup" >/dev/null 2>&1 &
runner=$!
wait_for -s "$tmp/hup/.meadow.lock" && sleep 1
t0=$(date +%s%N)
kill -HUP "$runner"
wait "$runner"
rc=$?
ms=$((($(date +%s%N) - t0) / 1000000))
{ [ "$rc" = 130 ] && grep -q "interrupted" "$tmp/hup/summary.txt" 2>/dev/null && [ "$ms" -lt "$limit_ms" ]; } \
  || { echo "FAIL: a run sent SIGHUP exited $rc after $ms ms (want 130 within $limit_ms ms, the summary written)"; fail=1; }
# --quiet prints no summary (it printed the whole of summary.txt).
"$bin" --headless --quiet --scene "$root/scenes/tiny.json" --size 64x36 --frames 1 --screenshot-every 0 \
  --out "$tmp/quiet" >"$tmp/quiet.out" 2>"$tmp/quiet.err"
rc=$?
{ [ "$rc" = 0 ] && [ ! -s "$tmp/quiet.out" ] && ! grep -q '^meadow:' "$tmp/quiet.err" && [ -s "$tmp/quiet/summary.txt" ]; } \
  || { echo "FAIL: --quiet gave exit $rc, $(wc -l <"$tmp/quiet.out") line(s) on stdout, $(grep -c '^meadow:' "$tmp/quiet.err") on stderr"; fail=1; }
# Output a script can trust. A run that cannot write what it promised (here
# summary.txt and the first screenshot, each blocked by a folder of its
# name, as a full disk would) exits 1 naming what is missing.
mkdir -p "$tmp/blocked/summary.txt" "$tmp/blocked/shot-000001.png"
"$bin" --headless --quiet --scene "$root/scenes/tiny.json" --size 64x36 --frames 2 --screenshot-every 1 \
  --out "$tmp/blocked" >/dev/null 2>"$tmp/blocked.log"
rc=$?
{ [ "$rc" = 1 ] && grep -q "error: .*could not write summary.txt and 1 of 2 screenshots (first shot-000001.png)" \
  "$tmp/blocked.log"; } || { echo "FAIL: unwritten outputs gave exit $rc:"; sed 's/^/    /' "$tmp/blocked.log"; fail=1; }
# An --out folder in use by another run is refused: first held by flock(1)
# (in a process that becomes the sleep, so killing it frees the lock),
# then by a second meadow run; the lock goes with the process that held it.
# Each wait is for an event, not a guess of time: under ctest -j on a busy
# machine the holder took longer than a fixed 0.2 s to lock, and the run
# under test then took the lock itself and succeeded.
mkdir -p "$tmp/shared"
(exec 9>"$tmp/shared/.meadow.lock" && flock 9 && touch "$tmp/held" && exec sleep 60) &
holder=$!
wait_for -e "$tmp/held"
expect2 'shared is in use by another run' --headless --scene "$root/scenes/tiny.json" --out "$tmp/shared"
kill "$holder"
wait "$holder" 2>/dev/null
"$bin" --headless --quiet --scene "$root/scenes/tiny.json" --size 64x36 --frames 1000000 --screenshot-every 0 \
  --out "$tmp/shared" >/dev/null 2>&1 &
runner=$!
wait_for -s "$tmp/shared/.meadow.lock"
expect2 "shared is in use by another run (.*locked by process $runner)" --headless --scene "$root/scenes/tiny.json" \
  --out "$tmp/shared"
kill -INT "$runner"
wait "$runner"
"$bin" --headless --quiet --scene "$root/scenes/tiny.json" --size 64x36 --frames 1 --screenshot-every 0 \
  --out "$tmp/shared" >/dev/null 2>&1 || { echo "FAIL: --out still refused after the run holding it ended"; fail=1; }
exit $fail

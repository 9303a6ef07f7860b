#!/usr/bin/env bash
# cli_characters: the character options from the command line: --list-clips
# (clips, durations, keys; exit 0), a wrong clip (one error line naming the
# available clips, exit 2), --clip/--character-height without characters,
# --character-height reported in summary.txt, texture problems (a
# Windows path, a corrupt PNG) as warnings of a run that exits 0, named
# clip ranges from the scene and --clip, and the fallback from a clip
# without duration.
# Usage: cli_characters.sh MEADOW_BINARY
set -u
bin=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0
run=(--headless --scene scenes/tiny.json --frames 1 --size 64x48 --screenshot-every 0 --out "$tmp/out")

# expect RC "pattern" args...: exit RC, the pattern in stdout or stderr, and
# exactly one error line when RC is 2 (none when it is 0)
expect() {
  local want=$1 pat=$2; shift 2
  timeout 120 "$bin" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local rc=$? errs
  errs=$(grep -c 'error' "$tmp/stderr")
  if [ "$rc" = "$want" ] && [ "$errs" = $((want / 2)) ] && cat "$tmp/stdout" "$tmp/stderr" | grep -q -- "$pat"; then
    echo "ok: meadow $* -> $(cat "$tmp/stdout" "$tmp/stderr" | grep -m1 -- "$pat")"
  else
    echo "FAIL: meadow $* -> exit $rc, $errs error line(s); want exit $want and '$pat':"
    sed 's/^/    /' "$tmp/stdout" "$tmp/stderr"
    fail=1
  fi
}
expect0() { expect 0 "$@"; }
expect2() { expect 2 "$@"; }

expect0 '0 "walk": 1.000 s, [0-9]* keys' --list-clips models/humanoid.gltf
expect0 '1 "idle": 2.000 s' --list-clips models/humanoid.gltf
expect2 "model file nope.gltf not found" --list-clips nope.gltf
expect2 "no clip \"run\" .*its clips: 0 'walk' (1 s), 1 'idle' (2 s)" "${run[@]}" \
  --character models/humanoid.gltf --clip run
expect2 "--clip: the scene has no characters" "${run[@]}" --clip walk
expect2 "--character-height: the scene has no characters" "${run[@]}" --character-height 2
expect2 "--character-height 'tall'" --character-height tall
expect2 "--character-height '0'" --character-height 0
expect0 "height 3.500 m" "${run[@]}" --character models/humanoid.gltf --character-height 3.5
grep -q "^character 0: models/humanoid.gltf: height 3.500 m, scale 2.08" "$tmp/out/summary.txt" ||
  { echo "FAIL: summary.txt lacks the fitted height and scale"; sed 's/^/    /' "$tmp/out/summary.txt"; fail=1; }

# texture problems are warnings: a Windows path resolved beside the model, a
# corrupt PNG
mkdir -p "$tmp/m"
printf '\x89PNG\r\n\x1a\nnot really' > "$tmp/m/skin.png"
printf 'newmtl t\nKd 1 1 1\nmap_Kd C:\\art\\skin.png\n' > "$tmp/m/quad.mtl"
printf 'mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1.7 0\nv 0 1.7 0\nvt 0 0\nusemtl t\nf 1/1 2/1 3/1 4/1\n' > "$tmp/m/quad.obj"
expect0 "warning: .*skin.png unreadable" "${run[@]}" --character "$tmp/m/quad.obj"
cat "$tmp/out/summary.txt" | grep -q "^character 0: .*quad.obj: height 1.700 m, scale 1 " ||
  { echo "FAIL: the quad's summary line"; grep character "$tmp/out/summary.txt"; fail=1; }
# scene keys: up/forward/height/rotation, and forward along up refused
scene() { # scene FILE CHARACTER_JSON: scenes/tiny.json with one character
  python3 -c 'import json,sys; s=json.load(open("scenes/tiny.json")); s["characters"]=[json.loads(sys.argv[2])]; json.dump(s,open(sys.argv[1],"w"))' "$1" "$2"
}
scene "$tmp/bad.json" '{"model": "models/humanoid.gltf", "up": "+z", "forward": "-z"}'
expect2 "characters\[0\].forward.*lies along up" --headless --scene "$tmp/bad.json" --frames 1 --out "$tmp/out"
scene "$tmp/keys.json" '{"model": "models/humanoid.gltf", "up": "+y", "forward": "+x", "height": 1.2, "rotation": 45}'
expect0 "height 1.200 m" --headless --scene "$tmp/keys.json" --frames 1 --size 64x48 --screenshot-every 0 --out "$tmp/out"
grep -q "^character 0: models/humanoid.gltf: height 1.200 m, .*up +y: scene; forward +x: scene" "$tmp/out/summary.txt" ||
  { echo "FAIL: summary.txt of the scene keys"; grep character "$tmp/out/summary.txt"; fail=1; }
# named ranges of one clip (characters[].clips) play by name from the scene
# and from --clip; a clip without duration (the clips fixture's first) gives
# way to the next that moves, with one warning naming both
scene "$tmp/range.json" '{"model": "models/humanoid.gltf", "clips": {"stride": [250, 750]}, "clip": "stride"}'
expect0 "character 0: models/humanoid.gltf" --headless --scene "$tmp/range.json" --frames 1 --size 64x48 \
  --screenshot-every 0 --out "$tmp/out"
scene "$tmp/range_run.json" '{"model": "models/humanoid.gltf", "clips": {"stride": [250, 750]}, "clip": "run"}'
expect2 "no clip \"run\" .*its scene ranges: 'stride'" --headless --scene "$tmp/range_run.json" --frames 1 \
  --size 64x48 --screenshot-every 0 --out "$tmp/out"
expect0 "character 0: models/humanoid.gltf" --headless --scene "$tmp/range_run.json" --clip stride --frames 1 \
  --size 64x48 --screenshot-every 0 --out "$tmp/out"
expect0 "warning: character 0: clip 'pose' of .*clips.gltf has no duration (one frame); playing 'grow'" "${run[@]}" \
  --character tests/data/models/clips.gltf
[ "$(grep -c "playing 'grow'" "$tmp/stderr")" = 1 ] || { echo "FAIL: the fallback warned more than once"; fail=1; }
exit $fail

#!/usr/bin/env bash
# frame_log: `meadow --frame-log` writes frames.csv (src/app/app_trace.c):
# a header and one row per frame, screenshot frames flagged, and the wall
# and submit times of the frames summary.txt times give its p50 and worst
# (the same numbers, so the log cannot drift from the summary); the tile
# and GPU pass columns are there and hold numbers, and a pass that stopped
# running reads empty; the CPU time inside the passes is positive and within
# the frame's submit time, the frame's steps within its wall time; a run
# without the option writes no frames.csv.
# Usage: frame_log.sh MEADOW_BINARY
set -u
bin=$1
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin" --headless --quiet --scene "$root/scenes/tiny.json" --size 96x54 --frames 40 --screenshot-every 10 \
  --frame-log --out "$tmp/log" >/dev/null 2>"$tmp/log.err" || { echo "FAIL: the run failed"; cat "$tmp/log.err"; exit 1; }
"$bin" --headless --quiet --scene "$root/scenes/tiny.json" --size 96x54 --frames 2 --screenshot-every 0 \
  --out "$tmp/none" >/dev/null 2>&1 || { echo "FAIL: the run without --frame-log failed"; exit 1; }
python3 - "$tmp/log/frames.csv" "$tmp/log/summary.txt" "$tmp/none" <<'PY'
import csv, math, os, re, sys
rows = list(csv.DictReader(open(sys.argv[1])))
summary = open(sys.argv[2]).read()
fail = []
if len(rows) != 40: fail.append(f"{len(rows)} rows, want 40")
if [int(r["frame"]) for r in rows] != list(range(1, 41)): fail.append("frames are not 1..40 in order")
shots = [int(r["frame"]) for r in rows if r["screenshot"] == "1"]
if shots != [10, 20, 30, 40]: fail.append(f"screenshot frames {shots}, want 10, 20, 30, 40")
for col in ("tiles_active", "blades_simulated", "tiles_streamed", "tiles.physics_ms", "terrain_ms"):
    if col not in rows[0]: fail.append(f"no column {col}")
    elif any(r[col] == "" or not math.isfinite(float(r[col])) for r in rows[-5:]): fail.append(f"{col} not a number")
warm = int(re.search(r"\((\d+) frames left out", summary).group(1))
timed = [r for r in rows if int(r["frame"]) > warm and r["screenshot"] == "0"]
for name, col in (("wall \\(CPU and GPU\\)", "wall_ms"), ("cpu \\(submit\\)", "submit_ms")):
    m = re.search(name + r"\s+p50\s+([\d.]+).*worst\s+([\d.]+)", summary)
    v = sorted(float(r[col]) for r in timed)
    p50 = v[math.ceil(0.5 * len(v)) - 1]
    if abs(p50 - float(m.group(1))) > 0.002 or abs(v[-1] - float(m.group(2))) > 0.002:
        fail.append(f"{col}: log p50 {p50} worst {v[-1]}, summary p50 {m.group(1)} worst {m.group(2)}")
steps = ["timers_cpu_ms", "steps_cpu_ms", "target_cpu_ms", "draw_cpu_ms", "drawn_cpu_ms"]
for r in rows[1:]:
    total = sum(float(r[c]) for c in steps)
    # The steps lie within the frame's wall time (the last one ends after
    # the submit time is taken, so a preempted thread can pass submit).
    if not 0.0 < total <= float(r["wall_ms"]) + 0.005 or float(r["draw_cpu_ms"]) <= 0.0:
        fail.append(f"frame {r['frame']}: the frame's steps {total:.3f} ms not in (0, wall {r['wall_ms']}]")
        break
    parts = sum(float(r[c]) for c in rows[0] if c.startswith("update_"))
    if not 0.0 < parts <= float(r["steps_cpu_ms"]) + 0.01:
        fail.append(f"frame {r['frame']}: the update's parts {parts:.3f} ms not in (0, steps {r['steps_cpu_ms']}]")
        break
cpu_cols = [c for c in rows[0] if c.endswith("_cpu_ms") and c not in steps and not c.startswith("update_")]
if "tiles.physics_cpu_ms" not in cpu_cols: fail.append("no CPU column for tiles.physics")
for r in rows[1:]:
    inside = sum(float(r[c]) for c in cpu_cols if r[c])
    if not 0.0 < inside <= float(r["submit_ms"]) + 0.01:
        fail.append(f"frame {r['frame']}: CPU ms inside passes {inside:.3f} not in (0, submit {r['submit_ms']}]")
        break
# A GPU column reads empty where its pass ran in none of the frame and the 3
# before it (TRACE_GPU_LAG), not the pass's last result repeated; raster auto
# (tiny.json's default) runs the compute passes only while it calibrates.
stopped = 0
for c in [c[:-7] for c in cpu_cols]:
    ran = [float(r[c + "_cpu_ms"] or 0) > 0.0 for r in rows]
    for k in range(3, len(rows)):
        if not any(ran[k - 3:k + 1]):
            stopped += 1
            if rows[k][c + "_ms"] != "":
                fail.append(f"frame {rows[k]['frame']}: {c}_ms reads {rows[k][c + '_ms']}, its pass ran in none of frames {rows[k - 3]['frame']}-{rows[k]['frame']}")
                break
if stopped == 0: fail.append("no pass stopped running (raster auto's calibration): the empty-cell rule was not tested")
if os.path.exists(os.path.join(sys.argv[3], "frames.csv")): fail.append("a run without --frame-log wrote frames.csv")
for f in fail: print("FAIL:", f)
if not fail: print(f"ok: frames.csv has 40 rows, {len(rows[0])} columns, p50 and worst equal to summary.txt's")
sys.exit(1 if fail else 0)
PY

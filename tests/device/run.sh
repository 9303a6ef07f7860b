#!/bin/bash
# Device run (GPU machine): bundle the Release build with
# ../shared/gpu/bundle.sh into .bundle (meadow and the GL test binaries),
# copy this file to .bundle/run.sh and run it from the repository root with
# OUT set to a folder for results:
#   .bundle/run.sh [SECTION...]
# (When the working tree holds other uncommitted work, copy the build's
# shaders/ scenes/ models/ tests/ and this file into .bundle/tree, link
# .bundle/tree/.bundle to .. and run from .bundle/tree.)
# Sections (default: tests bench scaling report):
#   tests        renderer, GPU-vs-CPU tests on NVIDIA
#   bench        benchmark scenes with the floor (summary per scene)
#   scaling      tiled vs full-field blades, field 25..200 m (memory, counts)
#   tilescaling  `meadow bench --scaling` (also part of report) -> $OUT/tilescaling.tgz
#   stability    `meadow bench --stability` alone -> $OUT/stability.tgz
#   report       `meadow bench --report` on scenes/meadow.json at 1280x720
#                (RESULTS.md, charts' data, stability, scaling) -> $OUT/report_docs.tgz
#                (docs/RESULTS.md and images) and $OUT/report_data.tgz (CSV, JSON, .dat, .gp)
#                REPORT_PAPERS=1: with --papers too (RESULTS.md's papers section; adds
#                the papers section's 68 figures, each the median of 3 sessions, to
#                the 560 s limit)
#   raster       every bench scene (and meadow_large in each mode) with
#                --raster hw and --raster compute, 300 frames: pass medians
#                side by side, and four meadow_large screenshots -> $OUT
#   samples      compute rasterizer samples per pixel (4 vs 1) against the
#                hardware path on meadow.json and meadow_large: timings, and
#                the frame-120 screenshots -> $OUT (compare them with
#                eval_image_ssim off the machine)
#   perf         `meadow bench --perf` (bench scenes x {hw, compute}, 400 frames): $OUT/perf.json and the
#                regenerated $OUT/PERFORMANCE.md; then `meadow bench --baseline docs/perf/h100.json`
#                on that perf.json (a note instead when the baseline does not exist yet)
#   admission    test_admit, the bench scenes' gpu_memory_mb against
#                gpu_memory_estimate_mb, and a scene past the GPU's memory
#                (exit 2 naming grass.cube_resolution)
#   naturesweep  the bench sweep on scenes/bench/nature.json with the GL
#                debug callback on (MEADOW_GL_DEBUG=1), log -> $OUT
#   ab           shader A/B in one command: meadow_large (hybrid, billboard,
#                blade) and nature (or $AB_RUNS: "SCENE:MODE ...", SCENE a
#                bench scene's name or one under scenes/) with --raster
#                compute, 200 frames, with the build's shaders and then with
#                those under each folder of $AB_ROOT (space-separated folders
#                holding a shaders/ tree, e.g. `git archive REV shaders | tar x
#                -C .bundle/old`); pass medians of each to $R. The binary must
#                suit every shader tree.
#   seam         the hybrid seam and its floor (summary.txt) of meadow.json and
#                meadow_large, hw and compute, ending at frames $SEAM_FRAMES
#                (default 3 60 120 240); $SEAM_ROOT (a folder holding shaders/,
#                scenes/ and models/, e.g. another revision's): its shaders instead
#   large        the hybrid on meadow_large (docs/HYBRID.md's table): the
#                hybrid_canopy_distance chart against the all-blade reference
#                (billboard and blade mode drawn as far, the hybrid at each
#                canopy distance, both paths; $LARGE_FRAMES frames, default
#                40; lod.json), the tiles' pull/tess A/B (hw, 200 frames),
#                and the switch and canopy seams every 30th frame 30-300
#                ($SEAM_FRAMES) of meadow_large and meadow.json on both
#                paths: the canopy seam's colour score, the switch seam's
#                score and its floor
#                -> $OUT/large_chart.tgz (bench.csv/json, lod.json, .dat/.gp),
#                three of the chart's frames
#   papers       `meadow bench --papers` (blade ablations of the four paper scenes
#                on both paths, billboard cost vs colliding leaves with 1-16 balls,
#                the papers table; each figure the median of 3 sessions;
#                $PAPERS_FRAMES frames, default 60; $PAPERS_LIMIT s limit, default 500)
#                -> $OUT/papers.tgz (papers.md, .json, .csv, chart); papers.md to $R
#   occlusion    occlusion culling of billboard batches (grass.bb_occlusion,
#                docs/BILLBOARDS.md) A/B: meadow_large in hybrid and
#                billboard mode and orthmann, --raster hw, 400 frames, the
#                key off then on: pass medians (bb.render + bb.occlusion on
#                against bb.render off), drawn quads, skipped leaves, frame
#                times; the frame-400 screenshots of each -> $OUT/occ-*.png
#   gi           global illumination (grass.gi) A/B: meadow_large hybrid on
#                both paths and billboard mode (hw), 400 frames, the key off
#                then on: pass medians, frame times, the volumes' start-up
#                line; the frame-400 screenshots -> $OUT/gi-*.png
#   startup      every bench scene, 400 frames: start-up stages, frame-time
#                percentiles (p50/p95/p99/worst after warm-up), GPU pass
#                medians/means/max and the work counters; meadow_large also
#                with --frames 1 twice (cold and warm shader cache)
#   coldstart    the 2 km world in each mode (compute path), 30 frames, with
#                the driver's shader disk cache off (__GL_SHADER_DISK_CACHE=0:
#                every program compiled, as on a fresh machine) and then on,
#                twice (the second run warm): start-up stages and the
#                programs' compile and link time (summary.txt)
for f in .bundle/debs/*.deb; do dpkg -x $f / ; done; ldconfig
export LD_LIBRARY_PATH=$PWD/.bundle/lib
M=.bundle/bin/meadow
R=$OUT/report.txt

tests() {
  echo "== default scene, 10 frames"; $M --headless --frames 10 --out /tmp/o0 2>&1 | grep -E "GL_RENDERER|error"
  for t in test_gfx_smoke test_gfx_upload test_blade_gpu_physics test_blade_gpu_cull test_blade_tiles test_bb_gpu_collide \
           test_bb_gpu_dynamics test_bb_gpu_many test_character_gpu test_app_modes test_hybrid_trail \
           test_hybrid_switch test_tiles_scaling test_raster test_raster_modes test_blade_surface test_hybrid_seam \
           test_bb_gpu_generate test_gi_gpu test_bb_gpu_gi test_bb_gpu_occlusion test_blade_render \
           test_tiles_stream test_terrain_world_gpu test_terrain_world_render test_bb_ring; do
    echo "== $t"; MEADOW_TEST_OUT=/tmp/t-$t timeout -k 10 120 .bundle/bin/$t > /tmp/$t.log 2>&1; echo "rc=$?"
    grep -E "CHECK|max|worst|differ|coverage|colour|mode sw|ok$|FAIL|test_image|^[a-d]\)|variant|queued|mismatch|grass share" /tmp/$t.log | head -14
  done
}

bench() {
  for s in orthmann nature helicopter fan128 meadow_large; do
    echo "== bench $s"
    timeout -k 10 150 $M --headless --quiet --scene scenes/bench/$s.json --frames 400 --screenshot-every 400 --floor \
      --out /tmp/b-$s > /tmp/b-$s.log 2>&1
    echo "rc=$?"; sed -n '/gpu passes/,$p' /tmp/b-$s/summary.txt 2>/dev/null; grep -E "error|warn" /tmp/b-$s.log | head -5
  done
  cp /tmp/b-meadow_large/shot-000400.png $OUT/meadow_large.png 2>/dev/null
}

scaling() {
  echo "== scaling: one ball crossing the centre, field 25..200 m"
  for mode in hybrid blade; do for size in 25 50 100 200; do
    sed -e "s/\"size\": 200/\"size\": $size/" -e "s/\"mode\": \"hybrid\"/\"mode\": \"$mode\"/" \
      scenes/bench/scaling.json > /tmp/scale.json
    timeout -k 10 100 $M --headless --quiet --scene /tmp/scale.json --frames 300 --screenshot-every 0 \
      --out /tmp/s-$mode-$size > /dev/null 2>&1
    echo "-- $mode $size m: $(grep -E 'physics|gpu_memory|blades:|blade_tiles' /tmp/s-$mode-$size/summary.txt | tr -s ' ' | tr '\n' ';')"
  done; done
}

tilescaling() {
  echo "== bench --scaling"
  ( time timeout -k 10 300 $M bench --scaling --quiet --out /tmp/tsc ) 2>&1 | tail -8
  cat /tmp/tsc/scaling.csv
  tar czf $OUT/tilescaling.tgz -C /tmp tsc 2>/dev/null
}

report() {
  echo "== bench report"
  ( time timeout -k 10 560 $M bench --report /tmp/rep/docs --scene scenes/meadow.json --frames 60 --size 1280x720 \
      ${REPORT_PAPERS:+--papers /tmp/rep/papers} --quiet --out /tmp/rep/out ) 2>&1 | tail -20
  tar czf $OUT/report_docs.tgz -C /tmp/rep docs 2>/dev/null
  ( cd /tmp/rep && tar czf $OUT/report_data.tgz --exclude='*.png' --exclude='*.mp4' out ) 2>/dev/null
  ls -la $OUT
}

# The stability suite alone (three variants per case): $OUT/stability.tgz
# (stability.csv, stability.md, screenshots).
stability() {
  echo "== bench --stability"
  ( time timeout -k 10 560 $M bench --stability --quiet --out /tmp/stab ) 2>&1 | tr '\r' '\n' | tail -6
  tar czf $OUT/stability.tgz -C /tmp stab 2>/dev/null
}

naturesweep() {
  echo "== nature sweep with the GL debug callback"
  command -v nvidia-smi > /dev/null && { nvidia-smi --query-gpu=memory.used --format=csv -l 5 > $OUT/gpumem.log & }
  ( time MEADOW_GL_DEBUG=1 timeout -k 10 400 $M bench --scene scenes/bench/nature.json --frames 90 \
      --out /tmp/ns > $OUT/naturesweep.log 2>&1 ) 2>&1 | tail -4
  kill %1 2> /dev/null
  echo "GL debug messages: $(grep -c "GL: " $OUT/naturesweep.log)"; grep -m8 -iE "error|GL: |0 billboards" $OUT/naturesweep.log
  cp /tmp/ns/bench.csv $OUT/naturesweep.csv 2>/dev/null
}

raster() {
  echo "== raster: hardware vs compute rasterizer"
  run_pair() { # name scene extra-args...
    local name=$1 scene=$2; shift 2
    for r in hw compute; do
      timeout -k 10 150 $M --headless --quiet --scene $scene --frames 300 --screenshot-every 300 --raster $r "$@" \
        --out /tmp/r-$name-$r > /tmp/r-$name-$r.log 2>&1
      echo "-- $name $r rc=$? $(grep -E '^raster:' /tmp/r-$name-$r/summary.txt)"
      sed -n '/gpu passes/,/gpu_frame_ms/p' /tmp/r-$name-$r/summary.txt | grep -vE 'gpu passes'
      grep -E "error|warn" /tmp/r-$name-$r.log | head -3
    done
  }
  for s in orthmann nature helicopter fan128; do run_pair $s scenes/bench/$s.json; done
  for m in hybrid billboard blade; do run_pair large_$m scenes/bench/meadow_large.json --mode $m; done
  timeout -k 10 150 $M --headless --quiet --scene scenes/bench/meadow_large.json --frames 60 --screenshot-every 0 \
    --raster auto --out /tmp/r-auto > /dev/null 2>&1; echo "-- meadow_large auto: $(grep -E '^raster:' /tmp/r-auto/summary.txt)"
  for n in large_hybrid-hw large_hybrid-compute large_billboard-compute large_blade-compute; do
    cp /tmp/r-$n/shot-000300.png $OUT/$n.png 2>/dev/null
  done
}

startup() {
  echo "== startup and frame times"
  for s in orthmann nature helicopter fan128 meadow_large; do
    timeout -k 10 150 $M --headless --quiet --scene scenes/bench/$s.json --frames 400 --screenshot-every 0 \
      --out /tmp/st-$s > /tmp/st-$s.log 2>&1
    echo "-- $s rc=$?"
    sed -n '/gpu passes/,/gpu_frame_ms/p;/^frame times/,/^items per frame/p' /tmp/st-$s/summary.txt
    grep -E "error|warn" /tmp/st-$s.log | head -3
  done
  for run in 1 2; do
    ( time timeout -k 10 60 $M --headless --quiet --scene scenes/bench/meadow_large.json --frames 1 --screenshot-every 0 \
        --out /tmp/st1-$run > /dev/null 2>&1 ) 2>&1 | grep real
    echo "-- meadow_large --frames 1, run $run"; sed -n '/^startup_ms/,/^startup work/p' /tmp/st1-$run/summary.txt
  done
}

coldstart() {
  echo "== cold start"
  for mode in hybrid blade billboard; do
    for c in 0 1 1; do
      ( time __GL_SHADER_DISK_CACHE=$c timeout -k 10 120 $M --headless --quiet --scene scenes/bench/world.json \
          --mode $mode --raster compute --frames 30 --screenshot-every 0 --out /tmp/cs-$mode > /dev/null 2>&1 ) 2>&1 | grep real
      echo "-- world $mode, disk cache $c"; sed -n '/^startup_ms/,/^startup programs/p' /tmp/cs-$mode/summary.txt
    done
  done
}

samples() {
  echo "== raster samples per pixel"
  for s in meadow meadow_large; do
    f=scenes/$s.json; [ $s = meadow_large ] && f=scenes/bench/meadow_large.json
    for v in hw:4 compute:4 compute:1; do
      r=${v%:*}; n=${v#*:}
      timeout -k 10 150 $M --headless --quiet --scene $f --frames 120 --screenshot-every 120 --raster $r \
        --raster-samples $n --out /tmp/ss-$s-$r$n > /dev/null 2>&1
      echo "-- $s $r samples $n rc=$? $(grep -E '^gpu_frame' /tmp/ss-$s-$r$n/summary.txt)"
      grep -E "^  (bb.raster|blade.raster|tiles.raster|raster)" /tmp/ss-$s-$r$n/summary.txt
      cp /tmp/ss-$s-$r$n/shot-000120.png $OUT/$s-$r$n.png 2>/dev/null
    done
  done
}

ab() {
  echo "== shader A/B: AB_ROOT=${AB_ROOT:-unset} against the build's shaders"
  for root in $AB_ROOT; do [ -d "$root/shaders" ] || { echo "AB_ROOT: $root holds no shaders/ folder"; return; }; done
  for run in ${AB_RUNS:-meadow_large:hybrid meadow_large:billboard meadow_large:blade nature:blade}; do
    s=${run%:*}; m=${run#*:}; scene=scenes/bench/$s.json; [ -f "$scene" ] || scene=scenes/$s.json
    for root in build $AB_ROOT; do
      tag=$(basename $root); o=/tmp/ab-$s-$m-$tag
      env $([ $root != build ] && echo MEADOW_ROOT=$root MEADOW_SHADER_DIR=$root/shaders) timeout -k 5 60 $M --headless --quiet --scene $scene --mode $m \
        --raster compute --frames 200 --screenshot-every 0 --out $o > $o.log 2>&1
      echo "-- $s $m $tag rc=$? $(grep -E '^gpu_frame_ms' $o/summary.txt)"
      sed -n '/gpu passes/,/gpu_frame_ms/p' $o/summary.txt | grep -E "^  (bb|tiles|blade|raster|terrain)"
      grep -E "error" $o.log | head -3
    done
  done
}

seam() {
  local root=${SEAM_ROOT:-$PWD}
  for sc in scenes/meadow.json scenes/bench/meadow_large.json; do
    for r in hw compute; do
      for fr in ${SEAM_FRAMES:-3 60 120 240}; do
        MEADOW_ROOT=$root MEADOW_SHADER_DIR=$root/shaders $M --headless --quiet --scene $root/$sc --mode hybrid --raster $r --frames $fr \
          --screenshot-every 100000 --out /tmp/seam > /dev/null 2>&1
        echo "== seam $sc $r frame $fr: $(grep -A4 '^hybrid seam' /tmp/seam/summary.txt | sed 's/^hybrid seam.*score/score/' | tr '\n' ' ' | sed 's/  */ /g')"
      done
    done
  done
}

large() {
  local L=scenes/bench/meadow_large.json
  rm -rf /tmp/lc
  # SIGINT first: the bench stops after the configuration it is running
  # and writes what it has (a blade-mode session of meadow_large takes ~20 s).
  ( time timeout -s INT -k 150 ${LARGE_LIMIT:-330} $M bench --scene $L --chart hybrid_canopy_distance \
      --frames ${LARGE_FRAMES:-40} --out /tmp/lc --quiet ) > /tmp/lc.log 2>&1
  echo "== chart rc=$?"; tr '\r' '\n' < /tmp/lc.log | grep -E '^bench: [0-9]|^real'
  [ "${LARGE_CHART_ONLY:-0}" = 1 ] && { (cd /tmp/lc && tar czf $OUT/large_chart.tgz --exclude=frames .); \
    cat /tmp/lc/lod.json; return; }
  cut -d, -f1-7 /tmp/lc/bench.csv 2>/dev/null; cat /tmp/lc/lod.json 2>/dev/null
  grep -o '"image_error_floor": [0-9.]*' /tmp/lc/bench.json 2>/dev/null
  (cd /tmp/lc && tar czf $OUT/large_chart.tgz --exclude=frames .)
  for f in reference hybrid_canopy_distance_blade hybrid_canopy_distance_canopy45m; do
    cp /tmp/lc/frames/$f.png $OUT/ 2>/dev/null
  done
  for br in pull tess; do
    timeout -k 10 120 $M --headless --quiet --scene $L --mode hybrid --raster hw --blade-render $br --frames 200 \
      --screenshot-every 0 --out /tmp/ab-$br > /dev/null 2>&1
    echo "== tiles $br rc=$?: $(grep -E '^  tiles\.(draw|cull)|^gpu_frame_ms' /tmp/ab-$br/summary.txt | tr -s ' ' | tr '\n' ';')"
  done
  for sc in $L scenes/meadow.json; do for r in hw compute; do
    for fr in ${SEAM_FRAMES:-30 60 90 120 150 180 210 240 270 300}; do
      timeout -k 5 60 $M --headless --quiet --scene $sc --mode hybrid --raster $r --frames $fr --screenshot-every 100000 \
        --out /tmp/seam > /dev/null 2>&1
      # the canopy seam's colour score (its coverage term compares unlike
      # things), the switch seam's score and its floor
      echo "== seam $sc $r frame $fr: $(grep -A3 -E '^(hybrid|canopy) seam' /tmp/seam/summary.txt | grep -E 'seam|floor' \
        | sed -e 's/ (blades to the ground canopy[^)]*)//' -e 's/ (last frame against[^)]*)//' \
              -e 's/ (billboards placed[^)]*)//' -e 's/; coverage step.*//' | tr '\n' ' ')"
    done
  done; done
}

papers() {
  echo "== bench --papers"
  rm -rf /tmp/papers
  # SIGINT first: the bench stops after the session it is running (its tables
  # are written only by a complete run; the log says how far it got).
  ( time timeout -s INT -k 30 ${PAPERS_LIMIT:-500} $M bench --papers /tmp/papers --frames ${PAPERS_FRAMES:-60} --quiet ) \
    > $OUT/papers.log 2>&1
  echo "rc=$?"; tail -6 $OUT/papers.log
  cat /tmp/papers/papers.md 2>/dev/null || echo "no papers.md: bench --papers failed"
  tar czf $OUT/papers.tgz -C /tmp papers 2>/dev/null
}

perf() {
  echo "== bench --perf"
  rm -rf /tmp/perf; mkdir -p /tmp/perf
  cp docs/PERFORMANCE.md /tmp/perf/PERFORMANCE.md 2>/dev/null \
    || echo "note: no docs/PERFORMANCE.md here: regenerate it at home with bench --perf DIR --from perf.json"
  doc=(); [ -f /tmp/perf/PERFORMANCE.md ] && doc=(--doc /tmp/perf/PERFORMANCE.md)
  # Progress goes straight to $OUT/perf.log, so a run cut short still says
  # how far it got (a GPU hang ends the run after 30 s: gfx_frame_end).
  ( time timeout -k 10 560 $M bench --perf /tmp/perf "${doc[@]}" ${PERF_FRAMES:+--frames $PERF_FRAMES} --quiet ) > $OUT/perf.log 2>&1
  tail -22 $OUT/perf.log
  cp /tmp/perf/perf.json /tmp/perf/PERFORMANCE.md $OUT/ 2>/dev/null
  if [ ! -f /tmp/perf/perf.json ]; then
    echo "no perf.json: bench --perf failed"
  elif [ -f docs/perf/h100.json ]; then
    echo "== bench --baseline docs/perf/h100.json"
    $M bench --baseline docs/perf/h100.json --from /tmp/perf/perf.json 2>&1; echo "baseline rc=$?"
  else
    echo "note: no docs/perf/h100.json yet; commit \$OUT/perf.json as docs/perf/h100.json to make this run the baseline"
  fi
}

# A/B of a boolean grass key: each scene:mode:raster of the list with the
# key off, then on (scene a bench scene's name).
key_ab() {
  local key=$1 tag=$2 runs=$3
  for sm in $runs; do
    s=${sm%%:*}; mode=${sm#*:}; mode=${mode%%:*}; r=${sm##*:}
    for on in false true; do
      sed "s/\"grass\": {/\"grass\": {\"$key\": $on,/" scenes/bench/$s.json > /tmp/$tag-$s.json
      o=/tmp/$tag-$s-$mode-$r-$on
      timeout -k 10 150 $M --headless --scene /tmp/$tag-$s.json --mode $mode --raster $r --frames 400 \
        --screenshot-every 400 --out $o > $o.log 2>&1
      echo "== $tag $s $mode $r $key=$on rc=$?"
      grep -E "^  (terrain|tiles\.draw|tiles\.raster|bb\.render|bb\.raster|bb\.occlusion) |gpu_frame_ms|bb\.drawn|bb\.occlu|wall \(CPU" \
        $o/summary.txt 2>/dev/null
      grep -E "gi: |error|warn" $o.log | head -3
      cp $o/shot-000400.png $OUT/$tag-$s-$mode-$r-$on.png 2>/dev/null
    done
  done
}

occlusion() {
  key_ab bb_occlusion occ "meadow_large:hybrid:hw meadow_large:billboard:hw orthmann:billboard:hw"
}

gi() {
  key_ab gi gi "meadow_large:hybrid:hw meadow_large:hybrid:compute meadow_large:billboard:hw"
}

# Resource admission on the NVIDIA GL (GL_NVX_gpu_memory_info): the
# estimate against gfx's count after start-up (test_admit and the bench
# scenes' summaries), and a scene past the GPU's memory refused naming it.
admission() {
  echo "== test_admit"
  MEADOW_TEST_OUT=/tmp/t-admit timeout -k 10 120 .bundle/bin/test_admit > /tmp/admit.log 2>&1; echo "rc=$?"
  grep -E "counted|CHECK|refused" /tmp/admit.log
  for s in orthmann nature meadow_large; do
    echo "== $s"
    timeout -k 10 120 $M --headless --quiet --scene scenes/bench/$s.json --frames 2 --screenshot-every 0 \
      --out /tmp/a-$s > /dev/null 2>&1; echo "rc=$?"; grep -E "^gpu_memory" /tmp/a-$s/summary.txt
  done
  echo "== 100 colliders, grass.cube_resolution 4096 (206 GB of cube maps)"
  python3 -c "import json; print(json.dumps({'grass': {'cube_resolution': 4096}, 'colliders':
    [{'type': 'sphere', 'position': [i, 0.5, 0]} for i in range(100)]}))" > /tmp/a-cubes.json
  timeout -k 10 120 $M --headless --scene /tmp/a-cubes.json --frames 2 --out /tmp/a-cubes 2>&1 | grep -E "error"
  echo "rc=${PIPESTATUS[0]} (want 2)"
}

# The open world (docs/WORLD.md): the 1, 2 and 4 km worlds over their whole
# camera path on the compute path (hybrid, with the billboard ring), the
# 2 km world in blade mode, the 2 and 4 km worlds in billboard mode (the
# ring alone); memory, frame percentiles, submit, start-up and the ring's
# passes (bb.ring: cells generated, bb.raster) from summary.txt; each
# run's frame log (--frame-log) to $OUT/frames-SCENE-MODE-build.csv.gz.
# WORLD_RUNS="SCENE:MODE ..." runs those instead; WORLD_AB_ROOT (folders
# holding a shaders/ tree, as the ab section's AB_ROOT) runs each again
# with those shaders, the tag in place of "build".
world() {
  local runs=() sm root
  for sm in ${WORLD_RUNS:-world_1km:hybrid world:hybrid world_4km:hybrid world:blade world:billboard world_4km:billboard}; do
    for root in build $WORLD_AB_ROOT; do runs+=("$sm:$root"); done
  done
  for run in "${runs[@]}"; do
    s=${run%%:*}; rest=${run#*:}; mode=${rest%%:*}; root=${rest#*:}
    tag=$(basename $root); o=/tmp/world-$s-$mode-$tag
    ( time env $([ $root != build ] && echo MEADOW_ROOT=$root MEADOW_SHADER_DIR=$root/shaders) timeout -k 10 300 $M --headless \
      --scene scenes/bench/$s.json --mode $mode --raster compute --screenshot-every 0 --frame-log --out $o ) > $o.log 2>&1
    echo "== $s $mode $tag rc=$?"
    gzip -c $o/frames.csv > $OUT/frames-$s-$mode-$tag.csv.gz 2>/dev/null # per frame: where a spike sits
    grep -E "^frames|^gpu_frame|^gpu_memory|^host_memory|wall \(CPU|cpu \(|p99/p50|spikes|^startup_ms|^  [a-z_]+ +[0-9.]+$|^billboard ring|^  (terrain|tiles\.[a-z]*|raster\.[a-z]*|bb\.[a-z_]*|character[a-z.]*) " \
      $o/summary.txt 2>/dev/null || tail -5 $o.log
    grep -E "real|error|warn" $o.log | head -4
  done
}

sections=${*:-tests bench scaling report}
for s in $sections; do $s >> $R 2>&1; done

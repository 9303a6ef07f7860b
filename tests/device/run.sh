#!/bin/bash
# Usage (GPU machine): bundle the Release build with ../shared/gpu/bundle.sh into
# .bundle (meadow and the GL test binaries), copy this file to .bundle/run.sh,
# and run it from the repository root with OUT set to a folder for results.
# Device run: renderer, GPU-vs-CPU tests on NVIDIA, benchmark scenes with the
# floor, field-size scaling, and the bench report.
for f in .bundle/debs/*.deb; do dpkg -x $f / ; done; ldconfig
export LD_LIBRARY_PATH=$PWD/.bundle/lib
M=.bundle/bin/meadow
R=$OUT/report.txt
{
echo "== default scene, 10 frames"; $M --headless --frames 10 --out /tmp/o0 2>&1 | grep -E "GL_RENDERER|error"
for t in test_gfx_smoke test_blade_gpu_physics test_blade_gpu_cull test_blade_tiles test_bb_gpu_collide test_bb_gpu_dynamics test_character_gpu test_app_modes; do
  echo "== $t"; MEADOW_TEST_OUT=/tmp/t-$t timeout 120 .bundle/bin/$t > /tmp/$t.log 2>&1; echo "rc=$?"; grep -E "CHECK|max|worst|differ|coverage|mode sw|ok$|FAIL|test_image" /tmp/$t.log | head -8
done
} > $R 2>&1
for s in orthmann nature helicopter fan128 meadow_large; do
  echo "== bench $s" >> $R
  timeout 150 $M --headless --quiet --scene scenes/bench/$s.json --frames 400 --screenshot-every 400 --floor --out /tmp/b-$s > /tmp/b-$s.log 2>&1
  echo "rc=$?" >> $R; sed -n '/gpu passes/,$p' /tmp/b-$s/summary.txt >> $R 2>/dev/null; grep -E "error|warn" /tmp/b-$s.log | head -5 >> $R
done
echo "== scaling: one ball crossing the centre, field 25..200 m" >> $R
for mode in hybrid blade; do for size in 25 50 100 200; do
  sed -e "s/\"size\": 200/\"size\": $size/" -e "s/\"mode\": \"hybrid\"/\"mode\": \"$mode\"/" scenes/bench/scaling.json > /tmp/scale.json
  timeout 100 $M --headless --quiet --scene /tmp/scale.json --frames 300 --screenshot-every 0 --out /tmp/s-$mode-$size > /dev/null 2>&1
  echo "-- $mode $size m: $(grep -E 'physics|gpu_memory|blades:|blade_tiles' /tmp/s-$mode-$size/summary.txt | tr -s ' ' | tr '\n' ';')" >> $R
done; done
cp /tmp/b-meadow_large/shot-000400.png $OUT/meadow_large.png 2>/dev/null
cp /tmp/b-nature/shot-000400.png $OUT/nature.png 2>/dev/null
echo "== bench report" >> $R
( time timeout 330 $M bench --report /tmp/rep/docs --scene scenes/bench/nature.json --frames 90 --quiet --out /tmp/rep/out ) >> $R 2>&1
tar czf $OUT/report.tgz -C /tmp/rep docs out 2>/dev/null

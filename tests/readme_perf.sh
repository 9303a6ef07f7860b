#!/usr/bin/env bash
# readme_perf: README.md's performance block (between the perf-summary
# markers) is what `meadow bench --perf --from docs/perf/h100.json`
# generates, so its figures are the committed baseline's. Regenerates a copy
# of README.md and compares; on a difference, prints it and the command that
# fixes it.
# Usage: readme_perf.sh MEADOW_BINARY OUTDIR
set -u
bin=$1; out=$2
rm -rf "$out"; mkdir -p "$out"
cp README.md "$out/README.md"
"$bin" bench --perf "$out/x" --from docs/perf/h100.json --doc "$out/README.md" --quiet 2>"$out/log" \
  || { echo "FAIL: bench --perf --from docs/perf/h100.json exit $?"; cat "$out/log"; exit 1; }
if ! diff -u README.md "$out/README.md"; then
  echo "FAIL: README.md's perf-summary block differs from docs/perf/h100.json;"
  echo "      regenerate: meadow bench --perf out/x --from docs/perf/h100.json --doc README.md"
  exit 1
fi
echo "ok: README.md's performance block matches docs/perf/h100.json"

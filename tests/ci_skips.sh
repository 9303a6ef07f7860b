#!/usr/bin/env bash
# ci_skips: .ci/check_skips, the guard that fails CI on an unexpected skip,
# run on made-up ctest output: no skip passes, an expected skip naming its
# feature passes, and an unexpected skip, or an expected one skipping for
# another reason, fails.
set -u
root=$(cd "$(dirname "$0")/.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail=0

ctest_out() { # ctest_out NAME STATUS: what ctest prints for a run of test_a and NAME
  printf 'Test project /b\n1/2 Test #1: test_a ........   Passed    0.10 sec\n'
  printf '2/2 Test #2: %s ........%s   0.01 sec\n' "$1" "$2"
}
last_log() { # last_log NAME OUTPUT: LastTest.log of that run
  printf '1/2 Testing: test_a\n1/2 Test: test_a\nOutput:\n----\nok\n<end of output>\n'
  printf '2/2 Testing: %s\n2/2 Test: %s\nOutput:\n----\n%s\n<end of output>\n' "$1" "$1" "$2"
}
expect() { # expect RC WHAT: runs the guard on $tmp/out, $tmp/log, $tmp/allow
  bash "$root/.ci/check_skips" "$tmp/out" "$tmp/log" "$tmp/allow" >"$tmp/said" 2>&1
  local rc=$?
  if [ "$rc" = "$1" ]; then echo "ok: $2 -> exit $rc"; else echo "FAIL: $2 -> exit $rc, want $1:"; cat "$tmp/said"; fail=1; fi
}

printf '# comment\ntest_tess GL_ARB_tessellation_shader\n' >"$tmp/allow"
ctest_out test_b '   Passed ' >"$tmp/out"; last_log test_b ok >"$tmp/log"
expect 0 "no skip"
ctest_out test_gl_thing '***Skipped' >"$tmp/out"; last_log test_gl_thing 'SKIP: no GL 4.5 context: eglInitialize failed' >"$tmp/log"
expect 1 "unexpected skip (no EGL)"
ctest_out test_tess '***Skipped' >"$tmp/out"; last_log test_tess 'SKIP: GL_ARB_tessellation_shader missing' >"$tmp/log"
expect 0 "expected skip naming its feature"
last_log test_tess 'SKIP: no GL 4.5 context: eglInitialize failed' >"$tmp/log"
expect 1 "expected test skipping for another reason"
rm "$tmp/allow"; expect 2 "missing allow-list"
# The real allow-list parses and expects nothing of this made-up test.
cp "$root/tests/expected_skips.txt" "$tmp/allow"
ctest_out test_gl_thing '***Skipped' >"$tmp/out"; last_log test_gl_thing 'SKIP: no GL 4.5 context' >"$tmp/log"
expect 1 "tests/expected_skips.txt and a skip it does not list"
[ $fail = 0 ] && echo "ok: the skip guard passes and fails where it should"
exit $fail

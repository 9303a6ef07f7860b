/* bench_local: what the files of the bench module (bench.c: sweeps,
 * charts, the report and the `meadow bench` dispatch; bench_compare.c;
 * bench_cli.c) share: the harness's lower modules, offscreen sessions and
 * their metrics (src/measure), the stability suite (src/stability) and the
 * cost measures (src/perf). */
#ifndef MEADOW_BENCH_LOCAL_H
#define MEADOW_BENCH_LOCAL_H

#include "bench/bench.h"
#include "eval/eval.h"
#include "measure/measure.h"
#include "measure/measure_session.h"
#include "perf/perf.h"
#include "stability/stability.h"

#endif

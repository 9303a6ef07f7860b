/* bench_lod: the rule that picks a path's default chain from the rows of
 * the hybrid_canopy_distance chart (GL-free; bench.c writes the pick to
 * lod.json, scene_lod.h reads it). A tier stays in the chain only where
 * it is cheaper within the error and memory budgets. */
#ifndef MEADOW_BENCH_LOD_H
#define MEADOW_BENCH_LOD_H

#include <stdbool.h>

#define BENCH_LOD_GPU_MB 400.0 /* the default chain's GPU memory at most (MiB) */
#define BENCH_LOD_ERROR 0.35   /* the default chain's image error at most (eval_image units) */

/* One measured row of a path. */
typedef struct bench_lod_row_t {
    bool candidate; /* a hybrid chain (blade and billboard mode are not) */
    double wall_ms; /* the larger of the GPU pass sum and the CPU's wall clock per frame */
    double error;   /* image error against the all-blade reference */
    double gpu_mb;  /* GPU memory held */
} bench_lod_row_t;

/* The candidate of least wall time within max_error and max_mb (*met =
 * true); none within both: the candidate of least error within max_mb,
 * else of least error of all (*met = false). Returns its index, or -1
 * when no row is a candidate. */
int bench_lod_pick(const bench_lod_row_t *rows, int n, double max_error, double max_mb, bool *met);

#endif

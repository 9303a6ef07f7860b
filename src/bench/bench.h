/* bench: the evaluation harness of the meadow program: `meadow bench`
 * (configuration sweeps with speed-vs-accuracy charts, the stability suite,
 * the tile scaling sweeps, the RESULTS.md report), `meadow compare` (the
 * same frame in every mode against the reference) and the offscreen
 * sessions both are built on. It drives app_world (src/app) through
 * app_world.h and uses eval (src/eval) for image errors and report files. */
#ifndef MEADOW_BENCH_H
#define MEADOW_BENCH_H

#include "app/app.h"
#include "app/app_world.h"

/* `meadow bench [--quick] [--stability | --scaling | --report DIR]`.
 * Returns the process exit code. */
int bench_run(const app_options_t *o);
/* `meadow compare [--video]`. Returns the process exit code. */
int bench_compare(const app_options_t *o);
/* The montage of `meadow compare` in the current context: the scene's frame
 * `frames` rendered in every mode and as the reference, written to `out`
 * (`meadow --montage` ends a headless run with it; see app_run). */
int bench_compare_write(const app_options_t *o, const char *out, int frames);

/* ---- offscreen sessions ----------------------------------------------------------- */
typedef struct bench_metrics_t {
    double frame_ms;         /* sum of the medians of every GPU pass */
    double pass_ms[GFX_TIMER_MAX_PASSES];
    char pass_name[GFX_TIMER_MAX_PASSES][32];
    int pass_count;
    double cpu_ms;           /* mean CPU time per frame (wall clock) */
    bool raster_compute;     /* the grass went through the compute rasterizer */
    /* Accuracy (filled by the systems that exist in the scene; -1 = n/a). */
    double penetration_fraction; /* grass sample points inside colliders */
    double penetration_max;      /* deepest sample, metres */
    double blade_length_error;   /* mean |L - h| / h */
    double spring_error;         /* billboard mean |l - l0| / l0 */
} bench_metrics_t;

typedef struct bench_session_desc_t {
    const app_options_t *opts; /* scene, seed, size */
    scene_mode_t mode;
    bool mode_set;
    int frames;       /* simulated and drawn; default 60 */
    int warmup;       /* frames excluded from timings; default frames/4 */
    int msaa;         /* 0 = the scene's */
    bool reference;   /* the reference rendering (see app_world_t) */
    app_tuning_t tuning;
    void (*tweak)(scene_desc_t *s, void *user); /* parameter overrides */
    void *user;
} bench_session_desc_t;

/* Runs one scene offscreen in the current context: builds the world, runs
 * the frames, reads the last frame into `last` (if non-NULL) and fills
 * `metrics`. Returns 0, or the exit code of the failure. */
int bench_session_run(const bench_session_desc_t *desc, core_image_t *last, bench_metrics_t *metrics);

#endif

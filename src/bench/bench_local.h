/* bench_local: private interface between the files of the bench module:
 * bench_metrics.c (accuracy metrics, docs/METRICS.md), bench_session.c
 * (offscreen runs with per-frame hooks), bench.c (sweeps and charts),
 * bench_stability.c (where each method breaks), bench_scaling.c (tile
 * simulation cost), bench_perf.c (the bench scenes' pass medians, perf.json,
 * docs/PERFORMANCE.md), bench_baseline.c (against a committed baseline),
 * bench_papers.c (ablations, Orthmann's leaves figure, the papers table) and
 * bench_compare.c. */
#ifndef MEADOW_BENCH_LOCAL_H
#define MEADOW_BENCH_LOCAL_H

#include "bench/bench.h"
#include "eval/eval.h"

/* Metrics beyond bench_metrics_t (filled next to it by bench_metrics_measure). */
typedef struct bench_metrics_ext_t {
    long near_samples;   /* grass sample points within reach of a collider */
    long inside_samples; /* of those, inside the exact shape */
    long nonfinite;      /* blade or billboard values that are NaN or infinite */
    double below_ground; /* fraction of blade tips more than 1 cm under the terrain */
    int deformed;        /* billboards with a deformed mesh */
    double tested_max;   /* deepest of the points the blades' collision tests (tip v2 and midpoint m,
                            Jahrmann & Wimmer 2017 sec. 5.3) inside an exact collider, m */
} bench_metrics_ext_t;

/* Accuracy metrics of the world's current state into m (reads GPU buffers
 * back), plus the extra counts into x (may be NULL). */
void bench_metrics_measure(world_t *w, bench_metrics_t *m, bench_metrics_ext_t *x);
/* Largest tip offset max |v2 - v2_twin| (m) between two blade worlds built
 * from the same scene and seed; INFINITY when a value is not finite. When
 * prev (blade_gpu_info(world_info(w).blades).padded_count x 3 floats, NULL to skip) is
 * given, *jitter gets the largest change of (v2 - v2_twin) since the
 * previous call with the same prev (0 while *primed is false), prev is
 * updated and *primed set. */
double bench_metrics_blade_offset(world_t *w, world_t *twin, float *prev, bool *primed, double *jitter);
/* Fraction of real blades whose roots lie inside `radius` of the line from
 * a to b (xz plane, roots between the ends) that are deflected from the twin
 * by more than frac x their height; *corridor gets their count. With `ever`
 * (blade_gpu_info(world_info(w).blades).padded_count bytes, zeroed before the first call;
 * NULL to skip) a blade counts once deflected in this or any earlier call
 * with the same mask. */
double bench_metrics_blade_coverage(world_t *w, world_t *twin, const float a[2], const float b[2],
                                    float radius, float frac, uint8_t *ever, long *corridor);
/* Largest distance (m) of a deformed billboard mesh vertex from its wind
 * pose at the field's time; 0 when no mesh is deformed. */
double bench_metrics_bb_offset(world_t *w);
/* Trail coverage of billboards: of those rooted within `radius` of the
 * segment a-b (xz, strictly between its ends), the share whose deformed
 * mesh has moved a vertex more than frac x their height from the wind pose,
 * now or in an earlier call (ever[i], billboards entries, updated). */
double bench_metrics_bb_coverage(world_t *w, const float a[2], const float b[2], float radius, float frac,
                                 uint8_t *ever, long *corridor);

/* Texture distortion of the deformed billboard meshes (docs/METRICS.md). */
typedef struct bench_bb_distortion_t {
    double max_stretch; /* max |l / l0 - 1| over structural springs; INFINITY when not finite */
    long folded;        /* cells with signed area ratio <= 0 against their reference normal */
    long cells;         /* cells of the deformed meshes */
    long nonfinite;     /* mesh coordinates that are NaN or infinite */
    int deformed;       /* billboards with a deformed mesh */
} bench_bb_distortion_t;
/* Measures the deformed billboards of w now (all zero without billboards). */
void bench_metrics_bb_distortion(world_t *w, bench_bb_distortion_t *out);

/* ---- measures that grow with their failure (docs/METRICS.md) ---- */
/* Wall crossing (stability case thin_bb): of the billboards rooted outside
 * box collider `collider` within reach (max(width, height)) of its thin
 * face and along its length, the share with a non-root vertex (deformed
 * mesh or wind pose) beyond the box's mid-plane, under its top and within
 * its length; *near gets their count. */
double bench_metrics_bb_crossing(world_t *w, int collider, long *near);
/* Pose jump of billboards: the largest change of any vertex's offset from
 * its wind pose since the previous call with the same prev (billboards x
 * N x M x 3 floats; 0 while *primed is false, which the call sets). */
double bench_metrics_bb_jump(world_t *w, float *prev, bool *primed);
/* Deformed billboards' offsets from their wind pose, sampled bilinearly
 * at BENCH_POSE_SIDE^2 points of (u, v) in [0, 1]^2 (any mesh size), in
 * billboard order: a configuration's shape against a reference's
 * (bench_bb_pose_deviation). */
#define BENCH_POSE_SIDE 5
#define BENCH_POSE_SAMPLES (BENCH_POSE_SIDE * BENCH_POSE_SIDE)
typedef struct bench_bb_pose_t {
    int count;
    int *index;                            /* billboard index, ascending */
    float (*off)[BENCH_POSE_SAMPLES][3];   /* offsets from the wind pose (m) */
} bench_bb_pose_t;
bool bench_metrics_bb_pose(world_t *w, bench_bb_pose_t *out);
void bench_bb_pose_free(bench_bb_pose_t *p);
/* Shape deviation: mean over the billboards deformed in either of the
 * largest sample distance between a's offsets and ref's (a billboard not
 * deformed in one has zero offsets there), m. */
double bench_bb_pose_deviation(const bench_bb_pose_t *a, const bench_bb_pose_t *ref);
/* Over-push of blade proxies: for every real blade whose eta rose since
 * the previous call (pushed this step; eta_prev, padded_count floats,
 * updated; nothing counts while primed is false), the distance (m, >= 0)
 * of its curve (8 samples) from the nearest exact collider into dist
 * (padded_count entries). Returns their count. */
long bench_metrics_blade_overpush(world_t *w, float *eta_prev, bool primed, double *dist);
/* The q-quantile (0..1, linear between ranks) of v[0..n) (sorts v); 0 for n = 0. */
double bench_percentile(double *v, long n, double q);

/* Grass roots inside the world-space box lo..hi: real blade roots v0 in
 * blade mode, billboard root centres in billboard mode (0 otherwise). */
long bench_metrics_roots_in(world_t *w, const float lo[3], const float hi[3]);

/* Per-frame hooks of an offscreen session (all optional). */
typedef struct bench_session_hooks_t {
    /* Replaces the world's blade sphere proxies; only for blade-mode worlds
     * without characters (the world update is then world_update_spheres). */
    world_spheres_fn blade_spheres;
    /* Called after every simulated step. */
    void (*frame)(world_t *w, int frame, float t, void *user);
    /* Step length of frame `frame` (default: the scene's dt every step);
     * lets the stability suite inject frame spikes. */
    float (*step_dt)(int frame, float dt, void *user);
    /* Called after every drawn frame with the target it went into. */
    void (*drawn)(const gfx_target_t *target, int frame, void *user);
    void *user;
    bool draw_last_only;    /* simulate every frame, draw the last one only */
    bench_metrics_ext_t *ext; /* filled with the metrics when non-NULL */
} bench_session_hooks_t;

/* Loads the world of a session (scene, mode, tweak; a tweaked heightfield is
 * rebuilt) and makes its GPU resources into *out. Returns 0, or the exit
 * code with *out NULL. */
int bench_session_world(const bench_session_desc_t *desc, world_t **out);
int bench_session_run_hooks(const bench_session_desc_t *desc, const bench_session_hooks_t *hooks, core_image_t *last,
                            bench_metrics_t *metrics);

/* Stability suite: writes stability.csv, stability.md and
 * stability_<case>.png into out; with report (a folder) the screenshots
 * also go to report/images and md (when non-NULL) gets the table with links
 * relative to report; o->stability_case, when set, runs that case alone
 * (o->quick: two values per case).
 * Needs a current GL context (gfx_init done). Returns 0 or 1 (1 also for
 * an unknown case name). */
int bench_stability_run(const bench_options_t *o, const char *out, core_buf_t *md, const char *report);

/* Simulation cost of the tiled blade field (bench_scaling.c): one run. */
typedef struct bench_scaling_point_t {
    float side;        /* terrain side, m */
    int balls;         /* resting balls, each on its own tile */
    int frames;
    int slots;         /* slots simulated by the latest update */
    long blades;       /* blades simulated by the latest update */
    double physics_ms; /* median "tiles.physics" GPU time */
    long full_blades;  /* the full-field blade mode (field sweep, not --quick) */
    double full_ms;    /* its median "blade.physics"; -1 when not run */
} bench_scaling_point_t;

#define BENCH_SCALING_MAX 6
typedef struct bench_scaling_t {
    int field_count, active_count;
    bench_scaling_point_t field[BENCH_SCALING_MAX];  /* 1x, 4x, 16x (64x) area, 4 balls */
    bench_scaling_point_t active[BENCH_SCALING_MAX]; /* 1, 2, 4, 8, 16 (32) balls */
    double slope, intercept, r2; /* least squares ms = intercept + slope * slots (active sweep) */
    char renderer[256];
} bench_scaling_t;

/* `bench --scaling`: the field and active sweeps; writes scaling.csv, the
 * .dat files and charts into out, fills res and (when non-NULL) md with the
 * table. Needs a current GL context (gfx_init done). Returns 0 or 1. */
int bench_scaling_run(const app_options_t *o, const char *out, bool quick, bench_scaling_t *res, core_buf_t *md);

/* Jahrmann & Wimmer 2017's ablation (one table, bench_papers.c): blade
 * mode with every feature, without collision (no colliders and no
 * characters), without culling (every BLADE_CULL_* test skipped,
 * world_tuning_t.cull_disable), without each test alone. Run on the papers'
 * scenes for costs and culled counts (bench --papers) and on the sweep's
 * scene for image error (the blade_ablation chart). */
typedef struct bench_ablation_t {
    const char *name;      /* "all", "collision_off", "culling_off", "<test>_off" */
    bool no_collision;
    unsigned cull_disable; /* BLADE_CULL_* bits */
} bench_ablation_t;
#define BENCH_ABLATION_COUNT 7
extern const bench_ablation_t bench_ablations[BENCH_ABLATION_COUNT];

/* `bench --papers DIR` (bench_papers.c): blade-mode ablations of the papers'
 * scenes (or --scene alone, unless md is given: --report's --scene is the
 * sweep's), billboard cost against colliding leaves, the
 * papers table; writes papers.json, ablation.csv, leaves.csv, the
 * papers_leaves chart and papers.md into dir, and (md non-NULL) appends the
 * RESULTS.md section, its chart linked as images/papers_leaves.png. Needs a
 * current GL context (gfx_init done). Returns 0, 1, or 2 (bad folder or
 * scene). */
int bench_papers_run(const bench_options_t *o, const char *dir, core_buf_t *md);

/* ---- bench --perf / --baseline (bench_perf.c, bench_baseline.c) ------------------ */
#define BENCH_PERF_MAX_RUNS 32

/* One session of the perf set: a scene in one mode through one rasterizer. */
typedef struct bench_perf_run_t {
    char name[64];        /* "<scene>/<mode>/<raster>", the key baselines match on */
    char scene[256];      /* scene file */
    char mode[16], raster[16];
    bool fell_back;       /* compute asked for, hardware path drawn */
    int size[2], msaa;
    double frame_ms;      /* sum of the pass medians (bb.generate left out, as in summary.txt) */
    double cpu_ms;        /* mean wall-clock ms per frame after warm-up */
    double floor_ms;      /* measure_floor_ms of the grass triangles; -1 = not measured */
    double compute_floor_ms; /* measure_floor_compute_ms of the same; -1 = not measured */
    double memory_mb;     /* GPU memory held by gfx at the last frame */
    long blades, blades_drawn, billboards, triangles;
    int pass_count;
    char pass_name[GFX_TIMER_MAX_PASSES][32];
    double pass_ms[GFX_TIMER_MAX_PASSES]; /* medians */
} bench_perf_run_t;

typedef struct bench_perf_t {
    char renderer[256], gl_version[256], date[32]; /* date: UTC, ISO 8601 */
    int frames;
    bool quick;
    int run_count;
    bench_perf_run_t runs[BENCH_PERF_MAX_RUNS];
} bench_perf_t;

/* Reads a perf.json (bench_perf.c's format). Returns 0, or 2 after one error
 * line naming the file (and line). */
int bench_perf_read(const char *path, bench_perf_t *p);
/* The run named `name`, or NULL. */
const bench_perf_run_t *bench_perf_find(const bench_perf_t *p, const char *name);
/* The regression check of `bench --baseline`: every pass median of cur
 * against base. Prints the offending passes (slower by more than
 * BENCH_BASELINE_SLOWER_FRAC + BENCH_BASELINE_SLOWER_MS), notes faster,
 * missing and new ones. Returns 0, 1 (a pass is slower) or 2 (the
 * renderers differ and force is false). */
#define BENCH_BASELINE_SLOWER_FRAC 0.15
#define BENCH_BASELINE_SLOWER_MS 0.02
int bench_baseline_check(const bench_perf_t *cur, const bench_perf_t *base, const char *base_path, bool force);
/* `bench --perf DIR` and `bench --baseline FILE` (dispatched from bench_run).
 * Returns the process exit code. */
int bench_perf_main(const bench_options_t *o);

#endif

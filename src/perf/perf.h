/* perf: the harness's cost measures: the bench scenes' pass medians
 * (perf.c: perf.json, docs/PERFORMANCE.md, README's block) and the check
 * against a committed baseline (perf_baseline.c), the tiled blade field's
 * scaling (perf_scaling.c), and the papers' ablations and leaves figure
 * (perf_papers.c), each over offscreen sessions (measure_session.h). */
#ifndef MEADOW_PERF_H
#define MEADOW_PERF_H

#include "core/core.h"
#include "gfx/gfx.h"
#include "world/world.h"

/* What every session of a cost measure starts from: the program's options
 * as the world takes them (app_world_options; each measure sets its own
 * scene, mode and raster path over them), the program's frame count
 * (frames_set: --frames given; else each measure's own default) and
 * whether the run was asked to stop (app_interrupted; NULL: never). */
typedef struct perf_session_desc_t {
    world_options_t world;
    int frames;
    bool frames_set;
    bool (*interrupted)(void);
} perf_session_desc_t;

/* Ctrl-C or a signal asked the measures to stop after the current session. */
static inline bool perf_interrupted(const perf_session_desc_t *o) { return o->interrupted && o->interrupted(); }

/* Simulation cost of the tiled blade field (perf_scaling.c): one run. */
typedef struct perf_scaling_point_t {
    float side;        /* terrain side, m */
    int balls;         /* resting balls, each on its own tile */
    int frames;
    int slots;         /* slots simulated by the latest update */
    long blades;       /* blades simulated by the latest update */
    double physics_ms; /* median "tiles.physics" GPU time */
    long full_blades;  /* the full-field blade mode (field sweep, not --quick) */
    double full_ms;    /* its median "blade.physics"; -1 when not run */
} perf_scaling_point_t;

#define PERF_SCALING_MAX 6
typedef struct perf_scaling_t {
    int field_count, active_count;
    perf_scaling_point_t field[PERF_SCALING_MAX];  /* 1x, 4x, 16x (64x) area, 4 balls */
    perf_scaling_point_t active[PERF_SCALING_MAX]; /* 1, 2, 4, 8, 16 (32) balls */
    double slope, intercept, r2; /* least squares ms = intercept + slope * slots (active sweep) */
    char renderer[256];
} perf_scaling_t;

/* `bench --scaling`: the field and active sweeps; writes scaling.csv, the
 * .dat files and charts into out, fills res and (when non-NULL) md with the
 * table. Needs a current GL context (gfx_init done). Returns 0 or 1. */
int perf_scaling_run(const perf_session_desc_t *o, const char *out, bool quick, perf_scaling_t *res, core_buf_t *md);

/* Jahrmann & Wimmer 2017's ablation (one table, perf_papers.c): blade
 * mode with every feature, without collision (no colliders and no
 * characters), without culling (every BLADE_CULL_* test skipped,
 * grass_tuning_t.cull_disable), without each test alone. Run on the papers'
 * scenes for costs and culled counts (bench --papers) and on the sweep's
 * scene for image error (the blade_ablation chart). */
typedef struct perf_ablation_t {
    const char *name;      /* "all", "collision_off", "culling_off", "<test>_off" */
    bool no_collision;
    unsigned cull_disable; /* BLADE_CULL_* bits */
} perf_ablation_t;
#define PERF_ABLATION_COUNT 7
extern const perf_ablation_t perf_ablations[PERF_ABLATION_COUNT];

/* `bench --papers DIR` (perf_papers.c): blade-mode ablations of the papers'
 * scenes (or --scene alone, unless md is given: --report's --scene is the
 * sweep's), billboard cost against colliding leaves, the
 * papers table; writes papers.json, ablation.csv, leaves.csv, the
 * papers_leaves chart and papers.md into dir, and (md non-NULL) appends the
 * RESULTS.md section, its chart linked as images/papers_leaves.png. Needs a
 * current GL context (gfx_init done). Returns 0, 1, or 2 (bad folder or
 * scene). */
int perf_papers_run(const perf_session_desc_t *o, bool quick, const char *dir, core_buf_t *md);

/* ---- bench --perf / --baseline (perf.c, perf_baseline.c) ------------------ */
#define PERF_MAX_RUNS 32

/* One session of the perf set: a scene in one mode through one rasterizer. */
typedef struct perf_run_t {
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
} perf_run_t;

typedef struct perf_t {
    char renderer[256], gl_version[256], date[32]; /* date: UTC, ISO 8601 */
    int frames;
    bool quick;
    int run_count;
    perf_run_t runs[PERF_MAX_RUNS];
} perf_t;

/* Reads a perf.json (perf.c's format). Returns 0, or 2 after one error
 * line naming the file (and line). */
int perf_read(const char *path, perf_t *p);
/* The run named `name`, or NULL. */
const perf_run_t *perf_find(const perf_t *p, const char *name);
/* The regression check of `bench --baseline`: every pass median of cur
 * against base. Prints the offending passes (slower by more than
 * PERF_BASELINE_SLOWER_FRAC + PERF_BASELINE_SLOWER_MS), notes faster,
 * missing and new ones. Returns 0, 1 (a pass is slower) or 2 (the
 * renderers differ and force is false). */
#define PERF_BASELINE_SLOWER_FRAC 0.15
#define PERF_BASELINE_SLOWER_MS 0.02
int perf_baseline_check(const perf_t *cur, const perf_t *base, const char *base_path, bool force);
/* `bench --perf DIR` and `bench --baseline FILE` (dispatched from bench_run).
 * Returns the process exit code. */
typedef struct perf_options_t {
    perf_session_desc_t session; /* the program's options the sessions start from */
    const char *out;             /* --out DIR: where perf.json goes without --perf */
    bool quick;                  /* the quick set (CI) */
    const char *perf;            /* --perf DIR */
    const char *baseline;        /* --baseline FILE */
    const char *perf_from;       /* --from FILE */
    const char *doc;             /* --doc FILE */
    bool force;                  /* --force */
} perf_options_t;
int perf_main(const perf_options_t *o);

#endif

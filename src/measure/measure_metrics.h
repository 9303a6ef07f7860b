/* measure_metrics: accuracy measures of a world's grass as it stands
 * (measure_metrics.c, docs/METRICS.md): penetration of colliders, blade
 * length and billboard spring errors, offsets from an undisturbed twin,
 * trail coverage, billboard distortion, crossing and pose jumps, and the
 * GL-free statistics they share. They read the grass back through the
 * billboard and blade modules' read APIs (world_info's objects). */
#ifndef MEADOW_MEASURE_METRICS_H
#define MEADOW_MEASURE_METRICS_H

#include "world/world_harness.h"

/* What a session measures (measure_session.h): timings, then accuracy. */
typedef struct measure_metrics_t {
    double frame_ms;         /* sum of the medians of every GPU pass */
    double pass_ms[GFX_TIMER_MAX_PASSES];
    char pass_name[GFX_TIMER_MAX_PASSES][32];
    int pass_count;
    double cpu_ms;           /* mean CPU time per frame (wall clock) */
    double gpu_mb;           /* GPU storage gfx holds at the session's end, target included (MiB) */
    bool raster_compute;     /* the grass went through the compute rasterizer */
    /* Accuracy (filled by the systems that exist in the scene; -1 = n/a). */
    double penetration_fraction; /* grass sample points inside colliders */
    double penetration_max;      /* deepest sample, metres */
    double blade_length_error;   /* mean |L - h| / h */
    double spring_error;         /* billboard mean |l - l0| / l0 */
} measure_metrics_t;

/* Metrics beyond measure_metrics_t (filled next to it by measure_metrics). */
typedef struct measure_metrics_ext_t {
    long near_samples;   /* grass sample points within reach of a collider */
    long inside_samples; /* of those, inside the exact shape */
    long nonfinite;      /* blade or billboard values that are NaN or infinite */
    double below_ground; /* fraction of blade tips more than 1 cm under the terrain */
    int deformed;        /* billboards with a deformed mesh */
    double tested_max;   /* deepest of the points the blades' collision tests (tip v2 and midpoint m,
                            Jahrmann & Wimmer 2017 sec. 5.3) inside an exact collider, m */
} measure_metrics_ext_t;

/* Accuracy metrics of the world's current state into m (reads GPU buffers
 * back), plus the extra counts into x (may be NULL). */
void measure_metrics(world_t *w, measure_metrics_t *m, measure_metrics_ext_t *x);
/* Largest tip offset max |v2 - v2_twin| (m) between two blade worlds built
 * from the same scene and seed; INFINITY when a value is not finite. When
 * prev (blade_gpu_info(world_info(w).blades).padded_count x 3 floats, NULL to skip) is
 * given, *jitter gets the largest change of (v2 - v2_twin) since the
 * previous call with the same prev (0 while *primed is false), prev is
 * updated and *primed set. */
double measure_blade_offset(world_t *w, world_t *twin, float *prev, bool *primed, double *jitter);
/* Fraction of real blades whose roots lie inside `radius` of the line from
 * a to b (xz plane, roots between the ends) that are deflected from the twin
 * by more than frac x their height; *corridor gets their count. With `ever`
 * (blade_gpu_info(world_info(w).blades).padded_count bytes, zeroed before the first call;
 * NULL to skip) a blade counts once deflected in this or any earlier call
 * with the same mask. */
double measure_blade_coverage(world_t *w, world_t *twin, const float a[2], const float b[2],
                                    float radius, float frac, uint8_t *ever, long *corridor);
/* Largest distance (m) of a deformed billboard mesh vertex from its wind
 * pose at the field's time; 0 when no mesh is deformed. */
double measure_bb_offset(world_t *w);
/* Trail coverage of billboards: of those rooted within `radius` of the
 * segment a-b (xz, strictly between its ends), the share whose deformed
 * mesh has moved a vertex more than frac x their height from the wind pose,
 * now or in an earlier call (ever[i], billboards entries, updated). */
double measure_bb_coverage(world_t *w, const float a[2], const float b[2], float radius, float frac,
                                 uint8_t *ever, long *corridor);

/* Texture distortion of the deformed billboard meshes (docs/METRICS.md). */
typedef struct measure_bb_distortion_t {
    double max_stretch; /* max |l / l0 - 1| over structural springs; INFINITY when not finite */
    long folded;        /* cells with signed area ratio <= 0 against their reference normal */
    long cells;         /* cells of the deformed meshes */
    long nonfinite;     /* mesh coordinates that are NaN or infinite */
    int deformed;       /* billboards with a deformed mesh */
} measure_bb_distortion_t;
/* Measures the deformed billboards of w now (all zero without billboards). */
void measure_bb_distortion(world_t *w, measure_bb_distortion_t *out);

/* ---- measures that grow with their failure (docs/METRICS.md) ---- */
/* Wall crossing (stability case thin_bb): of the billboards rooted outside
 * box collider `collider` within reach (max(width, height)) of its thin
 * face and along its length, the share with a non-root vertex (deformed
 * mesh or wind pose) beyond the box's mid-plane, under its top and within
 * its length; *near gets their count. */
double measure_bb_crossing(world_t *w, int collider, long *near);
/* Pose jump of billboards: the largest change of any vertex's offset from
 * its wind pose since the previous call with the same prev (billboards x
 * N x M x 3 floats; 0 while *primed is false, which the call sets). */
double measure_bb_jump(world_t *w, float *prev, bool *primed);
/* Deformed billboards' offsets from their wind pose, sampled bilinearly
 * at MEASURE_POSE_SIDE^2 points of (u, v) in [0, 1]^2 (any mesh size), in
 * billboard order: a configuration's shape against a reference's
 * (measure_bb_pose_deviation). */
#define MEASURE_POSE_SIDE 5
#define MEASURE_POSE_SAMPLES (MEASURE_POSE_SIDE * MEASURE_POSE_SIDE)
typedef struct measure_bb_pose_t {
    int count;
    int *index;                            /* billboard index, ascending */
    float (*off)[MEASURE_POSE_SAMPLES][3];   /* offsets from the wind pose (m) */
} measure_bb_pose_t;
bool measure_bb_pose(world_t *w, measure_bb_pose_t *out);
void measure_bb_pose_free(measure_bb_pose_t *p);
/* Shape deviation: mean over the billboards deformed in either of the
 * largest sample distance between a's offsets and ref's (a billboard not
 * deformed in one has zero offsets there), m. */
double measure_bb_pose_deviation(const measure_bb_pose_t *a, const measure_bb_pose_t *ref);
/* Over-push of blade proxies: for every real blade whose eta rose since
 * the previous call (pushed this step; eta_prev, padded_count floats,
 * updated; nothing counts while primed is false), the distance (m, >= 0)
 * of its curve (8 samples) from the nearest exact collider into dist
 * (padded_count entries). Returns their count. */
long measure_blade_overpush(world_t *w, float *eta_prev, bool primed, double *dist);
/* The q-quantile (0..1, linear between ranks) of v[0..n) (sorts v); 0 for n = 0. */
double measure_percentile(double *v, long n, double q);

/* Grass roots inside the world-space box lo..hi: real blade roots v0 in
 * blade mode, billboard root centres in billboard mode (0 otherwise). */
long measure_roots_in(world_t *w, const float lo[3], const float hi[3]);

#endif

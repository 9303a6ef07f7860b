/* measure_session: one offscreen run of a scene in an existing GL context
 * (measure_session.c): the world from its options and set-up, its frames
 * through world_frame, timings, the last frame and the accuracy metrics
 * (measure_metrics.h), with optional per-frame hooks. What `meadow
 * compare`, the sweeps, the stability suite and the perf set are built on. */
#ifndef MEADOW_MEASURE_SESSION_H
#define MEADOW_MEASURE_SESSION_H

#include "measure/measure_metrics.h"

typedef struct measure_session_desc_t {
    world_options_t world; /* scene, seed, size (app_world_options of a command line) */
    scene_mode_t mode;
    bool mode_set;
    int frames;       /* simulated and drawn; default 60 */
    int warmup;       /* frames excluded from timings; default frames/4 */
    int msaa;         /* 0 = the scene's */
    bool reference;   /* the reference rendering (see world_t) */
    grass_tuning_t tuning;
    void (*tweak)(scene_desc_t *s, void *user); /* parameter overrides */
    void *user;
} measure_session_desc_t;

/* Runs one scene offscreen in the current context: builds the world, runs
 * the frames, reads the last frame into `last` (if non-NULL) and fills
 * `metrics`. Returns 0, or the exit code of the failure. */
int measure_session_run(const measure_session_desc_t *desc, core_image_t *last, measure_metrics_t *metrics);

/* Per-frame hooks of an offscreen session (all optional). */
typedef struct measure_session_hooks_t {
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
    measure_metrics_ext_t *ext; /* filled with the metrics when non-NULL */
} measure_session_hooks_t;

/* Loads the world of a session (scene, mode, tweak; a tweaked heightfield is
 * rebuilt) and makes its GPU resources into *out. Returns 0, or the exit
 * code with *out NULL. */
int measure_session_world(const measure_session_desc_t *desc, world_t **out);
int measure_session_run_hooks(const measure_session_desc_t *desc, const measure_session_hooks_t *hooks, core_image_t *last,
                            measure_metrics_t *metrics);

#endif

/* world: everything a run simulates and draws: the terrain, analytic
 * colliders, characters and the grass systems the mode selects
 * (billboards, blades, tiles). One object, world_t, made by world_load and
 * world_make_gpu, advanced and drawn by world_frame, the one frame sequence
 * of the program (src/app) and the evaluation harness (src/bench). The
 * grass is a grass_t (src/grass/grass.h) the world steps and draws. Its
 * struct lives in world_local.h; what only the harness and tests need
 * (tuning knobs, a step or a draw alone) is in world_harness.h.
 * docs/DESIGN.md "Frame structure". */
#ifndef MEADOW_WORLD_H
#define MEADOW_WORLD_H

#include <cglm/cglm.h>
#include <stdbool.h>
#include <stdint.h>

#include "admit/admit.h"
#include "character/character.h"
#include "gfx/gfx.h"
#include "grass/grass.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "terrain/terrain.h"

typedef struct world_t world_t;

/* What world_load takes from a command line. Zero means "not given": the
 * scene file decides. */
typedef struct world_options_t {
    const char *scene;      /* default scenes/meadow.json */
    uint64_t seed;          /* with seed_set: as the scene key seed */
    bool seed_set;
    int width, height;      /* the target's size; 0: the scene's */
    scene_mode_t mode;      /* with mode_set: replaces the scene's */
    bool mode_set;
    int blade_render;       /* 0: the scene's, else 1 + scene_blade_render_t */
    int raster;             /* 0: the scene's, else 1 + scene_raster_t */
    int raster_samples;     /* compute rasterizer samples per pixel (1 or 4); 0: the scene's */
    bool view_cards;        /* billboards' view-dependent clump cards (bb_view_desc_t.on) */
    const char *character;  /* replaces the scene's character models */
    const char *clip;       /* NAME|INDEX|START:END of every character */
    float character_height; /* every character's height (m); 0: the scene's */
} world_options_t;

/* The view of a camera on a target of width x height: grass_view_make
 * with the camera's own position and far plane; overlay and wireframe
 * off. */
void world_view_make(grass_view_t *v, const cam_t *cam, int w, int h, float time, float dt);

/* Start-up stages: wall-clock ms from the start of a run to the end of its
 * first frame on the GPU (summary.txt "startup"). The world times its own;
 * the program the context and the first frame. */
enum {
    WORLD_STAGE_SCENE,       /* scene file and CLI overrides */
    WORLD_STAGE_TERRAIN,     /* heightfield or terrain mesh (CPU) */
    WORLD_STAGE_CONTEXT,     /* GL context, gfx, render target */
    WORLD_STAGE_TERRAIN_GPU, /* terrain and collider buffers and programs */
    WORLD_STAGE_CHARACTERS,  /* models, clips, skinning buffers */
    WORLD_STAGE_BILLBOARDS,  /* bb_field_make (its own stages in bb_stats_t) */
    WORLD_STAGE_BLADES,      /* blade field or tiles */
    WORLD_STAGE_FIRST_FRAME, /* first update + draw, until its fence signals */
    WORLD_STAGES
};
const char *world_stage_name(int stage);

/* Frames world_frame leaves unfinished on the GPU by default. */
#define WORLD_FRAMES_IN_FLIGHT 2

/* Scene file, options and terrain (no GL) into a new world (*out; NULL on
 * failure). Returns 0, 1 (out of memory) or 2 after one error line (bad
 * scene file or terrain mesh). */
int world_load(const world_options_t *o, world_t **out);
/* GPU resources for every system the scene needs. False when they cannot
 * be made (logged; world_info's input_error says whether it was bad input). */
bool world_make_gpu(world_t *w);
void world_destroy(world_t *w);

/* What the world is and holds (pointers valid until the next call that
 * changes the world). The systems are NULL when the world has none. */
typedef struct world_info_t {
    const scene_desc_t *scene; /* resolved, options applied */
    const char *scene_path;
    const terrain_mesh_t *terrain;
    scene_mode_t mode;
    bool reference;      /* blades everywhere, maximum tessellation, no culling */
    bool raster_compute; /* the grass goes through the compute rasterizer */
    int raster_samples;  /* its samples per pixel; 0: the scene's default */
    bool canopy;         /* the ground canopy beyond the billboards is drawn */
    bool input_error;    /* a model file or the admission refused the run (exit 2) */
    const double *stage_ms;  /* WORLD_STAGES entries; the context and first frame are the caller's */
    const admit_t *admitted; /* the memory and work estimate the run was admitted with */
    const char *lod_note;    /* grass.lod_table: what was chosen and why; "" without one */
    bool billboards, blades, tiles; /* the grass holds a billboard field, a blade field, tiles */
    character_set_t *characters;
    grass_t *grass; /* NULL before world_make_gpu; its drivers: grass_harness.h (the measures) */
    /* CPU wall ms of the frame's simulation steps by part, WORLD_UPDATE_PARTS
     * entries: colliders and characters, billboards, blade spheres, blades
     * and tiles (cleared by each world_frame; the frame log). */
    const double *update_ms;
} world_info_t;
#define WORLD_UPDATE_PARTS 4
world_info_t world_info(world_t *w);

/* Switches between the hardware and the compute rasterizer at run time. */
void world_set_raster(world_t *w, bool compute);
/* Switches the grass mode at run time, keeping the simulation state. */
void world_set_mode(world_t *w, scene_mode_t mode);
/* Samples per pixel of the frame's target: the scene's msaa with the
 * hardware path; 1 with the compute rasterizer, which anti-aliases the
 * grass with its own samples (docs/RASTER.md says why). */
int world_target_samples(const world_t *w);
/* Remakes *t (size kept, `label`) when its samples differ from
 * world_target_samples (a live switch of the rasterizer, a fall-back).
 * False when it cannot be made (logged). */
bool world_fit_target(const world_t *w, gfx_target_t *t, const char *label);

/* ---- one frame (world_frame.c): the program's and every bench session's ---- */
typedef enum world_frame_result_t {
    WORLD_FRAME_DRAWN,     /* simulated, drawn, paced */
    WORLD_FRAME_UPDATED,   /* simulated only (update_only) */
    WORLD_FRAME_NO_TARGET, /* the target could not be made (logged) */
    WORLD_FRAME_GPU_LOST,  /* the GPU did not finish the frame (the caller logs) */
} world_frame_result_t;
/* One frame. Zero means default where noted. */
typedef struct world_frame_desc_t {
    gfx_target_t *target; /* fitted (world_fit_target), cleared and drawn into */
    const char *label;    /* the target's label when it is remade */
    cam_t *cam;           /* the view; moved along the scene's camera path with follow_path */
    bool follow_path;
    double t;  /* simulated time at the end of the frame */
    float dt;  /* step length */
    int steps; /* simulation steps ending at t, dt apart; 0: none (paused) */
    /* Non-NULL: each step calls this instead of the world's own step (the
     * harness's blade spheres, world_harness.h). */
    void (*step)(world_t *w, float t, float dt, void *user);
    /* Called after the steps, with t. */
    void (*updated)(world_t *w, float t, void *user);
    bool update_only; /* return after the steps (nothing drawn, nothing paced) */
    int overlay;      /* grass_view_t.overlay */
    bool wireframe;
    /* Called after the draw, before pacing (HUD, screenshots, present). */
    void (*drawn)(world_t *w, const grass_view_t *v, gfx_target_t *target, void *user);
    void *user;    /* for step, updated and drawn */
    int in_flight; /* gfx_frame_end's frames left unfinished; 0: WORLD_FRAMES_IN_FLIGHT */
    /* Non-NULL: plat_time when the frame began and after each of its
     * WORLD_FRAME_MARKS - 1 steps (timer frame, simulation steps, target fit
     * and clear, draw, drawn); for the frame log (app_trace.h). */
    double *marks;
} world_frame_desc_t;
#define WORLD_FRAME_MARKS 6
/* Steps, camera path, view (scene dt), target fit, clear, draw, drawn,
 * gfx_frame_end. Starts the pass timers' frame. */
world_frame_result_t world_frame(world_t *w, const world_frame_desc_t *d);
/* The scene's `raster: auto` at start-up: draws cam's view at time 0 with
 * each rasterizer (the least GPU ms of 5 after a warm-up draw), keeps the
 * faster and returns true for compute; ms gets both times, wall_ms (when
 * non-NULL) the measure's. Clears the pass timers' statistics. */
bool world_raster_auto(world_t *w, const cam_t *cam, const gfx_target_t *target, double ms[2], double *wall_ms);

#endif

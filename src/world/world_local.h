/* app_world: everything the program simulates and draws each frame: the
 * terrain, analytic colliders, characters, and the grass systems selected by
 * the mode. Used by the app module and the evaluation harness (src/bench),
 * which goes through the access functions at the end. */
#ifndef MEADOW_APP_WORLD_H
#define MEADOW_APP_WORLD_H

#include <cglm/cglm.h>

#include "app/app.h"
#include "app/app_admit.h"
#include "gfx/gfx.h"
#include "scene/camera.h"
#include "scene/terrain.h"
#include "scene/terrain_clipmap.h"
#include "billboard/bb.h"
#include "blade/blade.h"
#include "blade/blade_canopy.h"
#include "blade/blade_tiles.h"
#include "character/character.h"
#include "eval/eval_image.h"
#include "raster/raster.h"

/* Per-frame view, shared by every draw. */
typedef struct app_view_t {
    mat4 view, proj, viewproj, inv_viewproj;
    vec4 planes[6];
    vec3 camera;
    vec3 sun_dir;
    float far; /* the camera's far plane (m) */
    int width, height;
    float time, dt;
    int overlay; /* debug overlay, key O: 0 off, 1 tile/leaf state, 2 LOD, 3 collision strength */
} app_view_t;

/* The terrain, and in the hybrid the ground canopy it is shaded as beyond
 * the billboards (blade_canopy.h, shaders/common/canopy.glsl). */
typedef struct app_terrain_t {
    gfx_buffer_t vbo, ibo;
    GLuint vao, empty_vao;
    int index_count;
    /* World terrains (TERRAIN_WORLD): the clipmap's levels and index ranges
     * (its arrays freed once uploaded: vbo holds the grid, ibo the ranges);
     * prog is terrain_world.vert made with terrain_world_defines. */
    bool world;
    terrain_clipmap_t clipmap;
    gfx_program_t prog, sky;
    /* Ground canopy: its table, the extent map that thins it (the tiles'
     * texture, borrowed), and this frame's fade (start, end of the switch
     * distance; end 0: none). */
    blade_canopy_uniforms_t canopy;
    GLuint extent;
    float extent_origin[2], extent_spacing;
    float canopy_fade[2];
    gi_bind_t gi; /* global illumination of the ground and its canopy; zero: off */
} app_terrain_t;

bool app_terrain_make(app_terrain_t *t, const terrain_mesh_t *mesh);
void app_terrain_destroy(app_terrain_t *t);
/* The canopy's table and the extent map that thins it (an R8 texture the
 * caller owns, 0: none; common/extent.glsl says which texel). */
void app_terrain_set_canopy(app_terrain_t *t, const blade_canopy_t *c, GLuint extent, const float origin[2],
                            float spacing);
void app_terrain_draw(const app_terrain_t *t, const app_view_t *v);



/* ---- analytic colliders (scene "colliders") ---------------------------------- */
#include "scene/scene.h"
#include "collide/collide_shape.h"

typedef struct app_collider_t {
    scene_collider_t desc;
    collide_mesh_t mesh;
    gfx_buffer_t vbo, ibo;
    GLuint vao;
    vec3 position, velocity; /* this frame */
    float bound_radius;
} app_collider_t;

typedef struct app_colliders_t {
    app_collider_t items[SCENE_MAX_COLLIDERS];
    int count;
    gfx_program_t prog;
} app_colliders_t;

bool app_colliders_make(app_colliders_t *c, const scene_desc_t *s);
void app_colliders_destroy(app_colliders_t *c);
/* Places every collider at time t on its path. Path y is the height of the
 * collider's centre above the ground under it (heightfield terrains), so a
 * ball rolls over hills; on mesh terrains y is absolute. */
void app_colliders_update(app_colliders_t *c, const terrain_mesh_t *terrain, float t);
void app_colliders_draw(const app_colliders_t *c, const app_view_t *v);

/* Knobs that are not scene-file fields (bench sweeps). Zero = default. */
typedef struct app_tuning_t {
    int tess_max;           /* blade tessellation level cap; default the blade module's */
    int distance_levels;    /* blade distance-cull levels n (eq. 19-20) */
    unsigned cull_disable;  /* BLADE_CULL_* tests to skip */
    bool blade_cube_proxies; /* blades collide against depth cube maps instead of
                                sphere proxies (the set's cube proxies; not the tiles) */
    uint32_t placement_seed; /* seeds where grass stands instead of the scene seed: full-field
                                blades (blade_seed and the clearing thinning's draw) and
                                billboards (bb_field_desc_t.placement_seed); terrain,
                                clearings and clump textures keep the scene seed (not the
                                hybrid tiles). The image error's noise floor (docs/METRICS.md) */
    bool view_cards;         /* billboards' view-dependent clump cards (bb_view_desc_t.on) */
    bool paper;              /* both papers' methods as printed (the stability suite's paper
                                variant): blade_env_t.paper with eq. 12's length and the
                                paper's eta gain k = 1, bb_field_desc_t.paper, and no swept
                                colliders (the collide set's objects do not sweep) */
} app_tuning_t;

/* ---- start-up stages -------------------------------------------------------------
 * Wall-clock ms of each stage from the start of app_run to the end of the
 * first frame on the GPU (summary.txt "startup"). app_world_load and
 * app_world_make_gpu time their own stages; app_run the context and the
 * first frame. */
enum {
    APP_STAGE_SCENE,       /* scene file and CLI overrides */
    APP_STAGE_TERRAIN,     /* heightfield or terrain mesh (CPU) */
    APP_STAGE_CONTEXT,     /* GL context, gfx, render target */
    APP_STAGE_TERRAIN_GPU, /* terrain and collider buffers and programs */
    APP_STAGE_CHARACTERS,  /* models, clips, skinning buffers */
    APP_STAGE_BILLBOARDS,  /* bb_field_make (its own stages in bb_stats_t) */
    APP_STAGE_BLADES,      /* blade field or tiles */
    APP_STAGE_FIRST_FRAME, /* first update + draw, until its fence signals */
    APP_STAGES
};
const char *app_stage_name(int stage);

/* ---- frame times (app_run) ---------------------------------------------------------- */
#define APP_FRAMES_IN_FLIGHT 2
#define APP_WARMUP_FRAMES 60
#define APP_FRAME_HISTORY 16384
typedef struct app_frame_times_t {
    int warmup;                     /* frames left out at the start */
    double wall[APP_FRAME_HISTORY]; /* ms, frame end to frame end */
    double cpu[APP_FRAME_HISTORY];  /* ms, frame start to the last command submitted */
    double thread[APP_FRAME_HISTORY]; /* ms of the main thread's CPU time over the same span */
    int frame[APP_FRAME_HISTORY];   /* the frame's number in the run */
    int count, next;
    int shots;                      /* frames left out for writing a screenshot */
} app_frame_times_t;

/* ---- the world ------------------------------------------------------------------ */
typedef struct app_world_t {
    scene_desc_t scene; /* resolved, CLI overrides applied */
    char scene_path[1024];
    terrain_mesh_t terrain_mesh;
    core_image_t clearings_image; /* grass.clearings.image (type image), 1 channel */
    app_terrain_t terrain;
    app_colliders_t colliders;
    scene_mode_t mode;
    bool reference; /* blades everywhere, maximum tessellation, no culling */
    app_tuning_t tuning;
    bool gpu_ready;
    /* Billboards (Orthmann et al. 2009), built for billboard and hybrid
     * modes (and on the first switch to them); NULL while there are none. */
    bb_field_t *bb;
    /* Blades (Jahrmann & Wimmer 2017), built for blade and hybrid modes. */
    blade_gpu_t *blades; /* NULL until made */
    bool have_blades;
    blade_env_t blade_env; /* winds fixed at load */
    int cube_res;          /* collision cube-map side: grass.cube_resolution, raised by grass.cube_texel
                              (cube_resolution_for) */
    GLuint blade_cubes;    /* blade mode's CPU cube maps of the colliders
                              (blade_gpu_upload_cubes; owned by blades) */
    /* Grass through the compute rasterizer (scene "raster" compute, or auto
     * when it measured faster); the visibility buffer follows the target's
     * size. Wireframe and debug overlays always use the hardware path. */
    bool raster_compute;
    int raster_samples; /* --raster-samples, else the scene key raster_samples (1 or 4) */
    raster_t raster;
    /* Hybrid mode on heightfields: tiled blades (Fan et al. 2015) with
     * per-blade state only for tiles objects touch. */
    blade_tiles_t *tiles; /* NULL until made */
    bool have_tiles;
    float camera[3]; /* of the last draw (activation and representation) */
    bool drawn;      /* camera holds a draw's camera */
    /* The colliders of the latest step (app_world_update), taken by the
     * billboards, the blades and the tiles. */
    collide_set_t collide;
    /* Walking characters (scene "characters" or --character). */
    character_set_t chars;
    bool have_chars;
    const char *character_override, *clip_override;
    float character_height; /* --character-height; 0 = the scene's */
    bool input_error; /* a model file failed to load: exit code 2 */
    /* Global illumination (scene grass.gi, app_gi.c): the volumes, made at
     * start-up; gi.ao.id 0 when off. */
    gi_gpu_t gi;
    char lod_note[512]; /* grass.lod_table: what was chosen and why (summary.txt); "" without one */
    app_admit_t admitted; /* the memory and work estimate the run was admitted with (app_admit.h) */
    bool stepped;          /* app_world_update ran (its first step seeds the collide set at t - dt) */
    float time;
    double stage_ms[APP_STAGES]; /* start-up, see APP_STAGE_* */
} app_world_t;

/* Module-internal (app_world.c, app_gi.c): the extent map of the layout both
 * grass models share (bb_layout_free it). */
bool app_world_extent_layout(const app_world_t *w, bb_layout_t *lay, bb_gen_desc_t *gen);
/* The global illumination volumes of w's scene into w->gi and the
 * terrain's bind; false (logged) when they cannot be made. */
bool app_gi_make(app_world_t *w);

/* Scene file, CLI overrides and terrain (no GL). Returns 0, or 2 after one
 * error line (bad scene file or terrain mesh). */
int app_world_load(app_world_t *w, const app_options_t *o);
/* GPU resources for every system the scene needs. */
bool app_world_make_gpu(app_world_t *w);
/* Simulates one fixed step at simulated time t. */
void app_world_update(app_world_t *w, float t, float dt);
/* Draws into `target` (bound by the caller): opaque objects first, then
 * their depth is resolved for the blades' occlusion culling, then grass. */
void app_world_draw(app_world_t *w, const app_view_t *v, const gfx_target_t *target, bool wireframe);
/* Half width (m) of the hybrid cross-fade band around grass.switch_distance:
 * blades fade out and billboards fade in over [switch - it, switch + it]. */
#define APP_SWITCH_FADE 1.0f
/* Half width (m) of the canopy's band around grass.canopy_distance:
 * billboards fade out and the ground canopy fades in over [canopy - it,
 * canopy + it]. */
#define APP_CANOPY_FADE 4.0f
/* Blade mode on a world terrain: blades drawn to grass.blade_distance,
 * default this (m); the ground canopy beyond (docs/WORLD.md). */
#define APP_WORLD_BLADE_DISTANCE 80.0f
/* Towards the sun (normalised where used): every view's sun_dir, the one
 * the clump bakes (BLADE_CLUMP_SUN) and the canopy's table light with. */
#define APP_SUN_DIR BLADE_CLUMP_SUN
/* ---- hybrid seam (app_seam.c, docs/METRICS.md "Hybrid seam") ------------------ */
/* A frame for eval_image_seam: colour, distance to the visible surface and
 * class per pixel (row 0 at the top). */
typedef struct app_seam_frame_t {
    core_image_t img;
    float *dist;
    uint8_t *cls;
} app_seam_frame_t;
/* Reads the frame drawn into t with view v (blocking): colour and distance;
 * cls EVAL_SEAM_GROUND where the visible surface is the terrain, else
 * EVAL_SEAM_SKIP (what a background frame needs). */
bool app_seam_frame_read(const app_world_t *w, const app_view_t *v, const gfx_target_t *t, app_seam_frame_t *f);
/* Classes of a frame against the background (the same view with no grass):
 * skipped where the background does not show the terrain, grass where the
 * colour differs from it by more than 8 levels in a channel, else ground. */
void app_seam_frame_classify(app_seam_frame_t *f, const app_seam_frame_t *background);
/* Draws the view into t in `mode`, with no grass at all when !grass (the
 * background), and reads it (app_seam_frame_read). The world's systems are
 * used as they are (nothing is built or simulated) and keep their state. */
bool app_seam_frame_draw(app_world_t *w, const app_view_t *v, const gfx_target_t *t, scene_mode_t mode, bool grass,
                         app_seam_frame_t *f);
void app_seam_frame_free(app_seam_frame_t *f);
/* The scene's switch distance and the fade band of app_world_draw. */
eval_seam_desc_t app_seam_desc(const app_world_t *w);
/* The seam of the hybrid frame drawn into t with view v, against the same
 * view drawn again with billboards only, both classified against it drawn
 * with no grass (which is what t holds afterwards). False when the world is
 * not in hybrid mode or a window of the band shows no grass or fewer than
 * 100 counted pixels (in either frame). */
bool app_world_seam(app_world_t *w, const app_view_t *v, const gfx_target_t *t, eval_seam_t *out);
/* The same at the canopy's band (grass.canopy_distance +- APP_CANOPY_FADE):
 * billboards to the ground canopy, against billboards to the horizon.
 * False as app_world_seam, and without a canopy. */
bool app_world_canopy_seam(app_world_t *w, const app_view_t *v, const gfx_target_t *t, eval_seam_t *out);
/* The seam's noise floor for this view: the billboards built again with
 * APP_SEAM_FLOOR_PLACEMENTS other placement seeds, each drawn
 * billboard-only (undeformed) against the world's own billboard-only frame:
 * what the measure reads where only where billboards stand differs
 * (docs/METRICS.md). One placement's score varies by 2-7x from seed to
 * seed (meadow_large at frame 120 on the H100: 0.039, 0.208, 0.049), so
 * the floor is their mean (score and terms), each placement's score kept
 * beside it. The world's billboards are kept and restored. False as
 * app_world_seam, or when a field cannot be built. */
#define APP_SEAM_FLOOR_PLACEMENTS 3
typedef struct app_seam_floor_t {
    eval_seam_t mean; /* score, delta_e, delta_l, coverage: means over the placements */
    double score[APP_SEAM_FLOOR_PLACEMENTS];
} app_seam_floor_t;
bool app_world_seam_floor(app_world_t *w, const app_view_t *v, const gfx_target_t *t, app_seam_floor_t *out);
/* Builds the world's billboard field (w->bb) for placement seed
 * `placement_seed` (0: the scene seed); app_world_seam_floor's second field. */
bool app_world_make_billboards(app_world_t *w, uint32_t placement_seed);
/* Switches between the hardware and the compute rasterizer at run time. */
void app_world_set_raster(app_world_t *w, bool compute);
/* Samples per pixel of the frame's target: the scene's msaa with the
 * hardware path; 1 with the compute rasterizer, which anti-aliases the
 * grass with its own samples, so the opaque scene (terrain, sky,
 * characters, balls) is drawn single-sampled there. On the H100 the 4x
 * target's fill and the composite into it cost 2.3 ms of a 9.3 ms
 * meadow_large frame, 1.2 ms at one sample (docs/RASTER.md). */
int app_world_target_samples(const app_world_t *w);
/* Remakes *t (size kept, `label`) when its samples differ from
 * app_world_target_samples: called before every frame, so a live switch of
 * the rasterizer (or a fall-back) gets its target. False when it cannot be
 * made (logged). */
bool app_world_fit_target(const app_world_t *w, gfx_target_t *t, const char *label);
/* Switches the grass mode at run time, keeping the simulation state. */
void app_world_set_mode(app_world_t *w, scene_mode_t mode);
void app_world_destroy(app_world_t *w);

typedef struct app_world_stats_t {
    long blades;            /* real blades on the GPU */
    long blade_survivors;   /* in the last draw command */
    unsigned blade_culled[4]; /* orientation, frustum, distance, occlusion */
    long blade_patch_culled;
    unsigned tiles_culled[4]; /* the hybrid's tiles: orientation, frustum, distance, occlusion */
    long tiles_tile_culled;   /* blades of blade tiles culled by the CPU frustum test */
    long billboards;
    int bb_deformed;
    double bb_generate_ms, bb_make_ms; /* GPU generation pass, CPU make (once) */
    double bb_make_stage_ms[BB_MAKE_STAGES];
    int characters;
    int tiles_active, tiles_recovering, tiles_blade, tile_slots_used, tile_slots_total;
    long tile_blades_simulated;
    long tile_handovers, tile_seeded; /* blades -> billboards, billboards -> blades, run totals */
    long triangles;         /* estimated triangles drawn by the grass */
} app_world_stats_t;

/* Counts of the last frame (blocking reads: for summaries, not the frame). */
void app_world_stats(app_world_t *w, app_world_stats_t *st);

/* Fills the whole per-frame view from a camera and target size; every other
 * field (overlay) is 0 = off. */
void app_view_make(app_view_t *v, const cam_t *cam, int w, int h, float time, float dt);

/* GPU ms to draw `triangles` trivial triangles from a prebuilt buffer into a
 * w x h target with `samples` MSAA (median of 12 draws); -1 on failure. */
double app_floor_ms(long triangles, int w, int h, int samples);
/* The same triangles through the compute rasterizer (raster_samples per
 * pixel: 1 or 4) into a w x h target of `samples`: raster_begin, the draw
 * with trivial shading and raster_end, median GPU ms of 12; -1 when it
 * cannot be measured, 0 for no triangles. */
double app_floor_compute_ms(long triangles, int w, int h, int samples, int raster_samples);

/* ---- access for the evaluation harness (src/bench; app_world_access.c) ------------ */
const scene_desc_t *app_world_scene(const app_world_t *w);
const char *app_world_scene_path(const app_world_t *w);
const terrain_mesh_t *app_world_terrain(const app_world_t *w);
const app_colliders_t *app_world_colliders(const app_world_t *w);
scene_mode_t app_world_mode(const app_world_t *w);
bool app_world_is_reference(const app_world_t *w);
/* A model file failed to load (exit code 2 rather than 1). */
bool app_world_input_error(const app_world_t *w);
/* The systems the world has built, or NULL. */
blade_gpu_t *app_world_blades(app_world_t *w);
bb_field_t *app_world_billboards(app_world_t *w);
blade_tiles_t *app_world_tiles(app_world_t *w);
character_set_t *app_world_characters(app_world_t *w);

/* What an offscreen session changes between app_world_load and
 * app_world_make_gpu. Zero = keep what the scene and options say. */
typedef struct app_world_setup_t {
    scene_mode_t mode;
    bool mode_set;
    int msaa;       /* 0 = the scene's */
    bool reference; /* the reference rendering (see app_world_t) */
    app_tuning_t tuning;
    void (*tweak)(scene_desc_t *s, void *user); /* scene parameter overrides */
    void *user;
} app_world_setup_t;
/* Applies `setup`; a tweak that changes a heightfield terrain rebuilds it.
 * Returns false after one error line when that fails. */
bool app_world_setup(app_world_t *w, const app_world_setup_t *setup);

/* Blade sphere proxies that replace the world's: writes at most max, returns
 * the count. */
typedef int (*app_world_spheres_fn)(app_world_t *w, blade_sphere_t *out, int max, void *user);
/* app_world_update of a world with blades only (no billboards, characters or
 * tiles) with the spheres of `spheres` in place of the world's (same order:
 * colliders, then one blade step). */
void app_world_update_spheres(app_world_t *w, float t, float dt, app_world_spheres_fn spheres, void *user);

/* ---- one frame (app_frame.c) ------------------------------------------------------
 * The frame sequence of the program (app_run) and of every bench session:
 * written once here so both measure and show the same work. */
typedef enum app_frame_result_t {
    APP_FRAME_DRAWN,     /* simulated, drawn, paced */
    APP_FRAME_UPDATED,   /* simulated only (update_only) */
    APP_FRAME_NO_TARGET, /* the target could not be made (logged) */
    APP_FRAME_GPU_LOST,  /* the GPU did not finish the frame (the caller logs) */
} app_frame_result_t;
/* One frame. Zero means default where noted. */
typedef struct app_frame_desc_t {
    gfx_target_t *target; /* fitted (app_world_fit_target), cleared and drawn into */
    const char *label;    /* the target's label when it is remade */
    cam_t *cam;           /* the view; moved along the scene's camera path with follow_path */
    bool follow_path;
    double t;  /* simulated time at the end of the frame */
    float dt;  /* step length */
    int steps; /* app_world_update steps ending at t, dt apart; 0: none (paused) */
    /* Non-NULL: the steps are app_world_update_spheres with these spheres. */
    app_world_spheres_fn spheres;
    /* Called after the steps, with t. */
    void (*updated)(app_world_t *w, float t, void *user);
    bool update_only; /* return after the steps (nothing drawn, nothing paced) */
    int overlay;      /* app_view_t.overlay */
    bool wireframe;
    /* Called after the draw, before pacing (HUD, screenshots, present). */
    void (*drawn)(app_world_t *w, const app_view_t *v, gfx_target_t *target, void *user);
    void *user;    /* for spheres, updated and drawn */
    int in_flight; /* gfx_frame_end's frames left unfinished; 0: APP_FRAMES_IN_FLIGHT */
} app_frame_desc_t;
/* Steps, camera path, view (scene dt), target fit, clear, app_world_draw,
 * drawn, gfx_frame_end. Starts the pass timers' frame. */
app_frame_result_t app_world_frame(app_world_t *w, const app_frame_desc_t *d);
/* The scene's `raster: auto` at start-up: draws cam's view at time 0 with
 * each rasterizer into a target of `target`'s size and that path's samples
 * (one warm-up draw, then the least of 5, GL timestamps around the whole
 * draw), keeps the faster (hardware when compute fell back) and returns
 * true for compute; ms gets the hardware and compute times, wall_ms (when
 * non-NULL) the wall ms the measure took. Clears the pass timers'
 * statistics. */
bool app_world_raster_auto(app_world_t *w, const cam_t *cam, const gfx_target_t *target, double ms[2],
                           double *wall_ms);

#endif

/* world_harness: the world as the evaluation harness (src/bench, src/measure)
 * and the tests drive it, beside world_frame: knobs that are not scene
 * keys, the set-up of an offscreen session's world, one step or one draw
 * alone, a step with the harness's own blade sphere proxies, the colliders
 * as they stand, and the billboard field swapped for another placement
 * (the seam's noise floor). The program (src/app) does not use these. */
#ifndef MEADOW_WORLD_HARNESS_H
#define MEADOW_WORLD_HARNESS_H

#include "world/world.h"

#include "collide/collide_set.h"
#include "grass/grass_tuning.h"
#include "ground/ground_match.h"

/* What an offscreen session changes between world_load and world_make_gpu.
 * Zero = keep what the scene and options say. */
typedef struct world_setup_t {
    scene_mode_t mode;
    bool mode_set;
    int msaa;       /* 0 = the scene's */
    bool reference; /* the reference rendering (world_info_t.reference) */
    grass_tuning_t tuning;
    void (*tweak)(scene_desc_t *s, void *user); /* scene parameter overrides */
    void *user;
} world_setup_t;
/* Applies `setup`; a tweak that changes a heightfield terrain rebuilds it.
 * Returns false after one error line when that fails. */
bool world_setup(world_t *w, const world_setup_t *setup);
/* The seed of where grass stands: tuning.placement_seed, else the scene's. */
uint32_t world_placement_seed(const world_t *w);

/* Simulates one fixed step at simulated time t (what world_frame's steps do). */
void world_update(world_t *w, float t, float dt);
/* Draws into `target` (bound by the caller): opaque objects first, then
 * the grass (its occlusion tests read their depth). */
void world_draw(world_t *w, const grass_view_t *v, const gfx_target_t *target);
/* Binds and clears t, then draws the view in `mode`, with no grass at all
 * when !grass; the world's systems are used as they are (nothing is built
 * or simulated) and keep their state. The grass's depth is in t's depth on
 * either path (a frame of world_frame on the compute path has the opaque
 * scene's alone). */
void world_draw_as(world_t *w, const grass_view_t *v, const gfx_target_t *t, scene_mode_t mode, bool grass);
/* As world_draw_as with no grass, the ground shaded as the canopy from the
 * camera on (no canopy table: the plain ground): the reference of the seam
 * where the blades end in the canopy. */
void world_draw_canopy(world_t *w, const grass_view_t *v, const gfx_target_t *t);
/* The canopy match's state (grass_canopy_match). */
bool world_canopy_match(world_t *w, ground_match_state_t *out);
void world_canopy_match_reset(world_t *w);
/* The camera the tiles stream and activate around until the next draw
 * sets it (a step without drawing). */
void world_set_camera(world_t *w, const float camera[3]);

/* Blade sphere proxies that replace the world's: writes at most max, returns
 * the count. */
typedef int (*world_spheres_fn)(world_t *w, collide_sphere_t *out, int max, void *user);
/* world_update of a world with blades only (no billboards, characters or
 * tiles) with the spheres of `spheres` in place of the world's (same order:
 * colliders, then one blade step). */
void world_update_spheres(world_t *w, float t, float dt, world_spheres_fn spheres, void *user);

/* One analytic collider (scene "colliders") as it stands this step. */
typedef struct world_collider_info_t {
    scene_collider_t desc;
    float position[3];
    float bound_radius;
} world_collider_info_t;
int world_collider_count(const world_t *w);
world_collider_info_t world_collider(const world_t *w, int i);

/* A billboard field as the world builds its own, for placement seed
 * `placement_seed` (0: the scene seed); NULL when it cannot be made. */
typedef struct bb_field_t bb_field_t; /* billboard/bb.h */
bb_field_t *world_build_billboards(const world_t *w, uint32_t placement_seed);
/* Puts `field` in the world's place (NULL: none) and returns the field it
 * held; the caller owns what it gets back. */
bb_field_t *world_swap_billboards(world_t *w, bb_field_t *field);
/* The last frame drawn again (as world_draw_as in the world's mode, grass
 * depth written) with blades out to `distance` m and the canopy beyond: a
 * tiles field made for it (grass_build_tiles: every tile idle) in place of
 * the world's for this draw, then destroyed. False (nothing drawn) without
 * tiles or when it cannot be made. */
bool world_draw_tiles_to(world_t *w, const grass_view_t *v, const gfx_target_t *t, float distance);

#endif

/* grass_harness: what in-tree hosts (src/world) and the evaluation
 * harness (src/measure, the tests) take from a grass_t beyond grass.h: a
 * resolved scene and terrain at grass_make, knobs that are not scene
 * keys, the drivers it holds for the measures, and draws or steps that
 * the program does not use. Not part of the installed library. */
#ifndef MEADOW_GRASS_HARNESS_H
#define MEADOW_GRASS_HARNESS_H

#include "grass/grass.h"
#include "grass/grass_tuning.h"

#include "admit/admit.h"
#include "billboard/bb.h"
#include "blade/blade.h"
#include "blade/blade_tiles.h"
#include "collide/collide_set.h"
#include "gfx/gfx.h"
#include "ground/ground_match.h"
#include "raster/raster.h"
#include "scene/scene.h"
#include "terrain/terrain.h"

/* grass_desc_t.host: the scene and terrain the host resolved (both
 * borrowed for the grass's life; the grass applies grass.lod_table and
 * run-time mode and rasterizer switches to scene), the knobs, the
 * reference rendering, and the compute rasterizer's samples. */
typedef struct grass_host_t {
    scene_desc_t *scene;
    const terrain_mesh_t *terrain;
    const char *scene_path;
    grass_tuning_t tuning;
    bool reference; /* blades everywhere, maximum tessellation, no culling */
    int raster_samples; /* 0: the scene's */
} grass_host_t;

/* grass.lod_table (scene_lod_apply, scene_lod.h) of a hybrid scene on the
 * current GL's renderer: the table's distances into s and, where s says
 * `raster: auto`, the path the table chose; note gets what was chosen and
 * why ("" without a table). grass_make runs it on a scene of its own; a
 * host runs it on the scene it hands in. */
void grass_lod_table_apply(scene_desc_t *s, char *note, size_t note_size);

/* Resource admission (admit.h) of a field once the GL's limits are known,
 * before any of it is made: the grass's own rules with the host's
 * colliders and characters. grass_make runs it with desc's colliders when
 * there is no host; a host runs it itself (again once its characters are
 * loaded). False after filling err: the field does not fit (bad input). */
typedef struct grass_admit_t {
    const scene_desc_t *scene;
    const terrain_mesh_t *terrain;
    scene_mode_t mode;
    bool reference, size_option;
    int target_samples;
    float collider_radius;
    int objects;                  /* colliders and characters */
    const int *collider_spheres;  /* sphere proxies per scene collider (NULL: none) */
    const int *character_spheres; /* per character (NULL: none) */
    int characters;
} grass_admit_t;
bool grass_admit(const grass_admit_t *a, admit_t *out, char *err, size_t err_size);

/* Starts building the programs the host's field will take (the compute
 * rasterizer's, the tiles') on the driver's threads, before the host loads
 * what it needs of its own (its characters); grass_make takes them. */
void grass_prefetch(const grass_host_t *host);

/* The drivers a grass_t holds (NULL when it has none), for the measures. */
typedef struct grass_drivers_t {
    bb_field_t *billboards;
    blade_gpu_t *blades;
    blade_tiles_t *tiles;
    raster_t *raster; /* the compute rasterizer's buffers (vis.id 0: none yet) */
    const blade_env_t *blade_env;
    const collide_set_t *collide; /* the latest step's */
    const float *camera;          /* the camera the latest step steered by */
} grass_drivers_t;
grass_drivers_t grass_drivers(grass_t *g);

/* The samples per pixel of a target for g's path: the scene's msaa with
 * the hardware path, 1 with the compute rasterizer. */
int grass_target_samples(const grass_t *g);
/* The canopy match's state (ground_match.h; a read-back): false when the
 * grass has no ground canopy. */
bool grass_canopy_match(const grass_t *g, ground_match_state_t *out);
/* The canopy match's gain back to 1 (ground_match_reset). */
void grass_canopy_match_reset(grass_t *g);
/* The camera the tiles stream and activate around until the next draw. */
void grass_set_camera(grass_t *g, const float camera[3]);
/* As grass_draw into an in-tree target, in `mode`, with no grass at all
 * when !grass (the ground only) and the ground shaded as canopy from the
 * camera on when canopy_all; depth: the grass writes its depth on the
 * compute path too (measures read it back); tiles_distance > 0: the tiles
 * held end there (a field of grass_build_tiles swapped in), not at the
 * scene's distance, and the canopy beyond. */
typedef struct grass_draw_as_t {
    scene_mode_t mode;
    bool no_grass, canopy_all, depth;
    unsigned parts; /* grass_part_t: 0 all, else the ground or the grass alone */
    float tiles_distance;
} grass_draw_as_t;
void grass_draw_target(grass_t *g, const grass_view_t *v, const gfx_target_t *t, const grass_draw_as_t *as);
/* The collider a character instance is to the grass: its proxy spheres
 * and its skinned mesh (grass_character_collider; the world's characters). */
struct character_instance_t;
grass_collider_t grass_character_collider_of(const struct character_instance_t *inst);
/* Takes colliders as where they stood before the next grass_update (its
 * sweep), without a step; otherwise the first step sweeps nothing. */
void grass_prime_colliders(grass_t *g, const grass_collider_t *colliders, int count);
/* One blade step with the spheres given in place of the colliders' (the
 * full field alone: no billboards, no tiles). */
void grass_update_spheres(grass_t *g, const collide_sphere_t *spheres, int count, float t, float dt);
/* A billboard field as g builds its own, for placement seed `placement`
 * (0: the scene seed); NULL when it cannot be made. */
bb_field_t *grass_build_billboards(const grass_t *g, uint32_t placement);
/* Puts `field` in g's place (NULL: none) and returns the field it held. */
bb_field_t *grass_swap_billboards(grass_t *g, bb_field_t *field);
/* A tiles field as g builds its own, but with blades out to `distance` m
 * (its switch), streamed in and posed at the camera and time of g's latest
 * step with nothing pushing it (every tile idle); NULL when g has no tiles
 * or it cannot be made. Drawn swapped in, with grass_draw_as_t's
 * tiles_distance. */
blade_tiles_t *grass_build_tiles(grass_t *g, float distance);
/* Puts `tiles` (not NULL) in g's place and returns the field it held. */
blade_tiles_t *grass_swap_tiles(grass_t *g, blade_tiles_t *tiles);

#endif

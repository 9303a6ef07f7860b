/* world_local: the world's struct and what its files share (world.c,
 * world_frame.c, world_colliders.c, world_harness.c): the analytic
 * colliders. Not included outside src/world; world.h is the module's
 * interface. */
#ifndef MEADOW_WORLD_LOCAL_H
#define MEADOW_WORLD_LOCAL_H

#include "world/world.h"
#include "world/world_harness.h"

#include "collide/collide_shape.h"
#include "core/core.h"
#include "grass/grass_harness.h"
#include "grass/grass_pass.h"

/* ---- analytic colliders (scene "colliders") ---------------------------------- */
typedef struct world_collider_t {
    scene_collider_t desc;
    collide_mesh_t mesh;
    gfx_buffer_t vbo, ibo;
    GLuint vao;
    vec3 position, velocity; /* this frame */
    float bound_radius;
} world_collider_t;

typedef struct world_colliders_t {
    world_collider_t items[SCENE_MAX_COLLIDERS];
    int count;
    gfx_program_t prog;
} world_colliders_t;

bool world_colliders_make(world_colliders_t *c, const scene_desc_t *s);
void world_colliders_destroy(world_colliders_t *c);
/* Places every collider at time t on its path. Path y is the height of the
 * collider's centre above the ground under it (heightfield terrains), so a
 * ball rolls over hills; on mesh terrains y is absolute. */
void world_colliders_update(world_colliders_t *c, const terrain_mesh_t *terrain, float t);
void world_colliders_draw(const world_colliders_t *c, const grass_view_t *v);

/* ---- the world ------------------------------------------------------------------ */
struct world_t {
    scene_desc_t scene; /* resolved, CLI overrides applied */
    char scene_path[1024];
    terrain_mesh_t terrain_mesh;
    world_colliders_t colliders;
    /* What the grass is made with, kept before it is made and passed on to
     * it after (world_set_mode, world_set_raster). */
    scene_mode_t mode;
    bool reference; /* blades everywhere, maximum tessellation, no culling */
    grass_tuning_t tuning;
    bool raster_compute;
    int raster_samples; /* --raster-samples, else the scene key raster_samples (1 or 4) */
    bool gpu_ready;
    grass_t *grass; /* NULL until world_make_gpu */
    /* Walking characters (scene "characters" or --character). */
    character_set_t chars;
    bool have_chars;
    const char *character_override, *clip_override;
    float character_height; /* --character-height; 0 = the scene's */
    bool size_option;       /* the size is --size's (admission names the option) */
    bool input_error; /* a model file failed to load: exit code 2 */
    char lod_note[512]; /* grass.lod_table: what was chosen and why (summary.txt); "" without one */
    admit_t admitted; /* the memory and work estimate the run was admitted with (admit.h) */
    bool stepped;          /* world_update ran (its first step primes the colliders at t - dt) */
    float time;
    double stage_ms[WORLD_STAGES]; /* start-up, see WORLD_STAGE_* */
    double update_ms[WORLD_UPDATE_PARTS]; /* world_info_t.update_ms */
};

/* The ground (the grass's first part, the largest occluder), the world's
 * opaque objects (colliders, characters), then the grass, drawn as `as`
 * says (NULL: the world's mode, all of it). */
void world_draw_objects(world_t *w, const grass_view_t *v, const gfx_target_t *target, const grass_draw_as_t *as);

/* Capsules per character for the blade proxies: 8 keeps a humanoid near 35
 * spheres (see character_proxy_spheres). */
#define WORLD_CHARACTER_CAPSULES 8

#endif

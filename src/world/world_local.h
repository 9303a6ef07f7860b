/* world_local: the world's struct and what its files share (world.c,
 * world_frame.c, world_colliders.c, world_gi.c, world_harness.c): the
 * analytic colliders. Not included outside src/world; world.h is the
 * module's interface. */
#ifndef MEADOW_WORLD_LOCAL_H
#define MEADOW_WORLD_LOCAL_H

#include "world/world.h"
#include "world/world_harness.h"

#include "blade/blade_canopy.h"
#include "collide/collide_shape.h"
#include "core/core.h"
#include "gi/gi.h"
#include "ground/ground.h"
#include "scene/terrain_clipmap.h"

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
void world_colliders_draw(const world_colliders_t *c, const world_view_t *v);

/* ---- the world ------------------------------------------------------------------ */
struct world_t {
    scene_desc_t scene; /* resolved, CLI overrides applied */
    char scene_path[1024];
    terrain_mesh_t terrain_mesh;
    core_image_t clearings_image; /* grass.clearings.image (type image), 1 channel */
    ground_t *ground; /* the terrain as drawn, the sky, the ground canopy */
    world_colliders_t colliders;
    scene_mode_t mode;
    bool reference; /* blades everywhere, maximum tessellation, no culling */
    world_tuning_t tuning;
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
    gfx_texture_t blade_extent; /* blade mode on a heightfield: the extent map that thinned
                                   its blades, for the grass-shaded ground (R8; 0: none) */
    /* Grass through the compute rasterizer (scene "raster" compute, or auto
     * when it measured faster); the visibility buffer follows the target's
     * size. Wireframe and debug overlays always use the hardware path. */
    bool raster_compute;
    bool canopy_all;  /* world_draw_canopy: the ground canopy from the camera on */
    bool grass_depth; /* the compute path's composite writes the grass's depth
                         too (raster_end; world_draw_as): else colour alone
                         (raster_end_color), the target's depth keeping the
                         opaque scene */
    int raster_samples; /* --raster-samples, else the scene key raster_samples (1 or 4) */
    raster_t raster;
    /* Hybrid mode on heightfields: tiled blades (Fan et al. 2015) with
     * per-blade state only for tiles objects touch. */
    blade_tiles_t *tiles; /* NULL until made */
    bool have_tiles;
    float camera[3]; /* of the last draw (activation and representation) */
    bool drawn;      /* camera holds a draw's camera */
    /* The colliders of the latest step (world_update), taken by the
     * billboards, the blades and the tiles. */
    collide_set_t collide;
    /* Walking characters (scene "characters" or --character). */
    character_set_t chars;
    bool have_chars;
    const char *character_override, *clip_override;
    float character_height; /* --character-height; 0 = the scene's */
    bool size_option;       /* the size is --size's (admission names the option) */
    bool input_error; /* a model file failed to load: exit code 2 */
    /* Global illumination (scene grass.gi, world_gi.c): the volumes, made at
     * start-up; gi.ao.id 0 when off. */
    gi_gpu_t gi;
    gi_bind_t gi_bind; /* gi's bind for every draw (the ground's, the grass's) */
    char lod_note[512]; /* grass.lod_table: what was chosen and why (summary.txt); "" without one */
    admit_t admitted; /* the memory and work estimate the run was admitted with (admit.h) */
    bool stepped;          /* world_update ran (its first step seeds the collide set at t - dt) */
    float time;
    double stage_ms[WORLD_STAGES]; /* start-up, see WORLD_STAGE_* */
    double update_ms[WORLD_UPDATE_PARTS]; /* world_info_t.update_ms */
};

/* Module-internal (world.c, world_gi.c): the extent map of the layout both
 * grass models share (bb_layout_free it). */
bool world_extent_layout(const world_t *w, bb_layout_t *lay, bb_gen_desc_t *gen);
/* World terrains (world_ring.c): in billboard mode the ground canopy
 * beyond the billboard ring (true when there is nothing to make). */
bool world_ring_make_canopy(world_t *w);
/* The global illumination volumes of w's scene into w->gi and the
 * terrain's bind; false (logged) when they cannot be made. */
bool world_gi_make(world_t *w);

#endif

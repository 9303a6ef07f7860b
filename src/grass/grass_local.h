/* grass_local: the grass_t struct and what the files of src/grass share
 * (grass.c, grass_build.c, grass_update.c, grass_draw.c, grass_gi.c). Not
 * included outside src/grass. */
#ifndef MEADOW_GRASS_LOCAL_H
#define MEADOW_GRASS_LOCAL_H

#include "grass/grass_harness.h"
#include "grass/grass_pass.h"

#include "billboard/bb_layout.h"
#include "blade/blade_canopy.h"
#include "core/core.h"
#include "gi/gi.h"
#include "ground/ground.h"

struct grass_t {
    gfx_ctx_t *gfx; /* its own gfx context (a host of the library), else NULL: the current one */
    scene_desc_t *scene;           /* the host's, or own_scene */
    const terrain_mesh_t *terrain; /* the host's, or own_terrain */
    scene_desc_t own_scene;
    terrain_mesh_t own_terrain;
    char scene_path[1024];
    core_image_t clearings_image; /* grass.clearings.image (type image), 1 channel */
    scene_mode_t mode;
    bool reference;
    grass_tuning_t tuning;
    float collider_radius;
    int objects;
    grass_io_t io;
    ground_t *ground; /* the terrain as drawn, the sky, the ground canopy */
    /* Billboards (Orthmann et al. 2009), built for billboard and hybrid
     * modes (and on the first switch to them); NULL while there are none. */
    bb_field_t *bb;
    /* Blades (Jahrmann & Wimmer 2017), built for blade and hybrid modes. */
    blade_gpu_t *blades; /* NULL until made */
    bool have_blades;
    blade_env_t blade_env; /* winds fixed at load */
    int cube_res;          /* collision cube-map side (cube_resolution_for) */
    GLuint blade_cubes;    /* blade mode's CPU cube maps of the colliders
                              (blade_gpu_upload_cubes; owned by blades) */
    gfx_texture_t blade_extent; /* blade mode on a heightfield: the extent map that thinned
                                   its blades, for the grass-shaded ground (R8; 0: none) */
    /* Hybrid mode on heightfields: tiled blades (Fan et al. 2015) with
     * per-blade state only for tiles objects touch. */
    blade_tiles_t *tiles; /* NULL until made */
    bool have_tiles;
    /* The compute rasterizer (scene "raster" compute, or auto when it
     * measured faster); its visibility buffer follows the target's size.
     * Wireframe and debug overlays always use the hardware path. */
    bool raster_compute;
    int raster_samples;
    raster_t raster;
    /* A host framebuffer's depth copy for the occlusion tests (grass_draw
     * with an MSAA or renderbuffer depth). */
    gfx_target_t host_depth;
    gi_gpu_t gi;       /* global illumination (scene grass.gi); gi.ao.id 0 when off */
    gi_bind_t gi_bind; /* gi's bind for every draw (the ground's, the grass's) */
    char lod_note[512];
    /* The camera the last step steered by (the tiles' activation, the
     * billboards' hidden band, the collider reach), and the first view
     * drawn since that step, which steers the next. */
    float camera[3], view_camera[3];
    int views;
    bool drawn;
    /* The colliders of the latest step, taken by every grass system. */
    collide_set_t collide;
    bool stepped;
    int colliders_warned; /* the collider count last warned past GRASS_MAX_COLLIDERS; 0: none */
    double update_ms[3], make_ms[3]; /* grass_stats_t's */
    /* In-tree draws (grass_draw_as_t): the ground as canopy from the
     * camera on; the compute path's composite writes the grass's depth;
     * a frame's own draw, which steps the canopy match (measures' draws
     * do not). */
    bool canopy_all, grass_depth, match_frame;
    float tiles_reach; /* grass_draw_as_t.tiles_distance (0: the scene's) */
};

/* grass_build.c: what grass_make and grass_set_mode make. */
bool grass_make_billboards(grass_t *g);
bool grass_make_blades(grass_t *g);
bool grass_make_tiles(grass_t *g);
void grass_make_blade_env(grass_t *g);
int grass_cube_resolution(const grass_t *g);
/* The extent map of the layout both grass models share (bb_layout_free it). */
bool grass_extent_layout(const grass_t *g, bb_layout_t *lay, bb_gen_desc_t *gen);
/* A world terrain in billboard mode: the ground canopy beyond the ring. */
bool grass_ring_make_canopy(grass_t *g);
/* grass_gi.c: the global illumination volumes into g->gi and the ground's bind. */
bool grass_gi_make(grass_t *g);

/* Binds g's own gfx context around a call of the API: grass_enter returns
 * the context to give back to grass_leave. */
gfx_ctx_t *grass_enter(const grass_t *g);
void grass_leave(gfx_ctx_t *prev);

grass_ground_t grass_ground_of(const grass_t *g);
bool grass_uses_tiles(const grass_t *g);
float grass_tiles_distance(const grass_t *g);
uint32_t grass_placement_seed(const grass_t *g);
/* On a world, the horizontal distance from the camera within which a
 * collider can touch the tile window (docs/WORLD.md); 0 elsewhere (all). */
float grass_collider_reach(const grass_t *g);

#endif

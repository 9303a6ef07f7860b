/* world_pass: the frame's grass passes as data (GL-free). world_pass_list
 * turns the scene mode, the ground, the rasterizer and the reference flag
 * (with what the world could make) into the ordered passes world_draw
 * runs; the same rules decide what the world makes (world_make_gpu,
 * world_set_mode). Tested by test_world_pass without a GL context.
 * Order: terrain (with the colliders), characters, the compute
 * rasterizer's start (it takes the opaque depth), then at most one blade
 * pass (the tiles or the whole field), the billboards, the composite.
 * docs/DESIGN.md "Frame structure". */
#ifndef MEADOW_WORLD_PASS_H
#define MEADOW_WORLD_PASS_H

#include <stdbool.h>

#include "scene/scene.h"

typedef enum world_pass_kind_t {
    WORLD_PASS_TERRAIN,      /* terrain, sky and colliders */
    WORLD_PASS_CHARACTERS,
    WORLD_PASS_RASTER_BEGIN, /* compute rasterizer: the frame starts from the opaque depth */
    WORLD_PASS_TILES,        /* the streamed blades (hybrid's near ones; blade mode on a world) */
    WORLD_PASS_BLADES,       /* the whole blade field (blade mode, the reference, hybrid on a mesh) */
    WORLD_PASS_BILLBOARDS,
    WORLD_PASS_RASTER_END,   /* compute rasterizer: the composite into the target */
    WORLD_PASS_KINDS
} world_pass_kind_t;

typedef struct world_pass_t {
    world_pass_kind_t kind;
    bool compute; /* a grass pass drawn by the compute rasterizer */
} world_pass_t;

/* The ground under the grass (terrain_mesh_t): a heightfield (grid_res > 0),
 * another mesh, or a world terrain streamed around the camera. */
typedef enum world_ground_t {
    WORLD_GROUND_HEIGHTFIELD = 0,
    WORLD_GROUND_MESH,
    WORLD_GROUND_WORLD,
} world_ground_t;

/* What decides the list; zero: hybrid on a heightfield, hardware path,
 * nothing made. A pass whose object the world lacks is left out; the
 * whole field stands in for missing tiles when the world has it. */
typedef struct world_pass_desc_t {
    scene_mode_t mode;
    world_ground_t ground;
    bool compute;   /* the compute rasterizer draws the grass this frame */
    bool reference; /* every blade of the field, no culling, no billboards */
    bool have_tiles, have_blades, have_billboards, have_characters;
    scene_hybrid_billboards_t billboards; /* the hybrid's (grass.billboards) */
} world_pass_desc_t;

/* The passes in order into out (room for WORLD_PASS_KINDS); their count. */
int world_pass_list(const world_pass_desc_t *d, world_pass_t out[WORLD_PASS_KINDS]);
/* Whether the list holds a pass of kind k. */
bool world_pass_has(const world_pass_t *passes, int n, world_pass_kind_t k);
/* "terrain", "characters", "raster_begin", "tiles", "blades",
 * "billboards", "raster_end". */
const char *world_pass_name(world_pass_kind_t k);

/* The rules behind the list, also what the world makes: billboards in
 * billboard and hybrid modes (a world's streamed around the camera:
 * bb_ring.h); blades in blade and hybrid modes; the blades from tiles for the
 * hybrid on a heightfield and for blade and hybrid modes on a world, never
 * for the reference. The hybrid has no billboards with grass.billboards
 * none: its blades end in the ground canopy. */
bool world_pass_wants_billboards(scene_mode_t mode, scene_hybrid_billboards_t hybrid_bb);
bool world_pass_wants_blades(scene_mode_t mode);
bool world_pass_uses_tiles(scene_mode_t mode, world_ground_t ground, bool reference);

#endif

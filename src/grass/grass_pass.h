/* grass_pass: grass_draw's passes as data (GL-free). grass_pass_list turns
 * the mode, the ground, the rasterizer and the reference flag (with what
 * the grass could make) into the ordered passes grass_draw runs; the same
 * rules decide what grass_make and grass_set_mode make. Tested by
 * test_grass_pass without a GL context. Order, after the host's opaque
 * objects: the ground (terrain and sky), the compute rasterizer's start
 * (it takes the opaque depth), then at most one blade pass (the tiles or
 * the whole field), the billboards, the composite. docs/LIBRARY.md. */
#ifndef MEADOW_GRASS_PASS_H
#define MEADOW_GRASS_PASS_H

#include <stdbool.h>

#include "scene/scene.h"

typedef enum grass_pass_kind_t {
    GRASS_PASS_GROUND,       /* terrain and sky */
    GRASS_PASS_RASTER_BEGIN, /* compute rasterizer: the frame starts from the opaque depth */
    GRASS_PASS_TILES,        /* the streamed blades (hybrid's near ones; blade mode on a world) */
    GRASS_PASS_BLADES,       /* the whole blade field (blade mode, the reference, hybrid on a mesh) */
    GRASS_PASS_BILLBOARDS,
    GRASS_PASS_RASTER_END,   /* compute rasterizer: the composite into the target */
    GRASS_PASS_KINDS
} grass_pass_kind_t;

typedef struct grass_pass_t {
    grass_pass_kind_t kind;
    bool compute; /* a grass pass drawn by the compute rasterizer */
} grass_pass_t;

/* The ground under the grass (terrain_mesh_t): a heightfield (grid_res > 0),
 * another mesh, or a world terrain streamed around the camera. */
typedef enum grass_ground_t {
    GRASS_GROUND_HEIGHTFIELD = 0,
    GRASS_GROUND_MESH,
    GRASS_GROUND_WORLD,
} grass_ground_t;

/* The ground kind of a terrain mesh. */
grass_ground_t grass_pass_ground(const terrain_mesh_t *t);

/* What decides the list; zero: hybrid on a heightfield, hardware path,
 * nothing made. A pass whose object the grass lacks is left out; the
 * whole field stands in for missing tiles when the grass has it. */
typedef struct grass_pass_desc_t {
    scene_mode_t mode;
    grass_ground_t ground;
    bool compute;   /* the compute rasterizer draws the grass this frame */
    bool reference; /* every blade of the field (a world's to GRASS_REFERENCE_REACH), no culling,
                       no billboards */
    bool have_tiles, have_blades, have_billboards;
    scene_hybrid_billboards_t billboards; /* the hybrid's (grass.billboards) */
} grass_pass_desc_t;

/* The passes in order into out (room for GRASS_PASS_KINDS); their count. */
int grass_pass_list(const grass_pass_desc_t *d, grass_pass_t out[GRASS_PASS_KINDS]);
/* Whether the list holds a pass of kind k. */
bool grass_pass_has(const grass_pass_t *passes, int n, grass_pass_kind_t k);
/* "ground", "raster_begin", "tiles", "blades", "billboards", "raster_end". */
const char *grass_pass_name(grass_pass_kind_t k);

/* The rules behind the list, also what the grass makes: billboards in
 * billboard and hybrid modes (a world's streamed around the camera:
 * bb_ring.h); blades in blade and hybrid modes; the blades from tiles for the
 * hybrid on a heightfield and for blade and hybrid modes on a world, for
 * the reference only on a world (GRASS_REFERENCE_REACH). The hybrid has no
 * billboards with grass.billboards none: its blades end in the ground
 * canopy. */
bool grass_pass_wants_billboards(scene_mode_t mode, scene_hybrid_billboards_t hybrid_bb);
bool grass_pass_wants_blades(scene_mode_t mode);
bool grass_pass_uses_tiles(scene_mode_t mode, grass_ground_t ground, bool reference);
/* How far the tiles draw blades (m): grass.switch_distance, or on a world
 * in blade mode grass.blade_distance (default GRASS_BLADE_DISTANCE), or
 * for the reference GRASS_REFERENCE_REACH. */
float grass_pass_tiles_distance(const scene_grass_desc_t *g, scene_mode_t mode, grass_ground_t ground,
                                bool reference);

#endif

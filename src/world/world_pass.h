/* app_pass: the frame's grass passes as data (GL-free). app_pass_list
 * turns the scene mode, the ground, the rasterizer and the reference flag
 * (with what the world could make) into the ordered passes app_world_draw
 * runs; the same rules decide what the world makes (app_world_make_gpu,
 * app_world_set_mode). Tested by test_app_pass without a GL context.
 * Order: terrain (with the colliders), characters, the compute
 * rasterizer's start (it takes the opaque depth), then at most one blade
 * pass (the tiles or the whole field), the billboards, the composite.
 * docs/DESIGN.md "Frame structure". */
#ifndef MEADOW_APP_PASS_H
#define MEADOW_APP_PASS_H

#include <stdbool.h>

#include "scene/scene.h"

typedef enum app_pass_kind_t {
    APP_PASS_TERRAIN,      /* terrain, sky and colliders */
    APP_PASS_CHARACTERS,
    APP_PASS_RASTER_BEGIN, /* compute rasterizer: the frame starts from the opaque depth */
    APP_PASS_TILES,        /* the streamed blades (hybrid's near ones; blade mode on a world) */
    APP_PASS_BLADES,       /* the whole blade field (blade mode, the reference, hybrid on a mesh) */
    APP_PASS_BILLBOARDS,
    APP_PASS_RASTER_END,   /* compute rasterizer: the composite into the target */
    APP_PASS_KINDS
} app_pass_kind_t;

typedef struct app_pass_t {
    app_pass_kind_t kind;
    bool compute; /* a grass pass drawn by the compute rasterizer */
} app_pass_t;

/* The ground under the grass (terrain_mesh_t): a heightfield (grid_res > 0),
 * another mesh, or a world terrain streamed around the camera. */
typedef enum app_ground_t {
    APP_GROUND_HEIGHTFIELD = 0,
    APP_GROUND_MESH,
    APP_GROUND_WORLD,
} app_ground_t;

/* What decides the list; zero: hybrid on a heightfield, hardware path,
 * nothing made. A pass whose object the world lacks is left out; the
 * whole field stands in for missing tiles when the world has it. */
typedef struct app_pass_desc_t {
    scene_mode_t mode;
    app_ground_t ground;
    bool compute;   /* the compute rasterizer draws the grass this frame */
    bool reference; /* every blade of the field, no culling, no billboards */
    bool have_tiles, have_blades, have_billboards, have_characters;
} app_pass_desc_t;

/* The passes in order into out (room for APP_PASS_KINDS); their count. */
int app_pass_list(const app_pass_desc_t *d, app_pass_t out[APP_PASS_KINDS]);
/* Whether the list holds a pass of kind k. */
bool app_pass_has(const app_pass_t *passes, int n, app_pass_kind_t k);
/* "terrain", "characters", "raster_begin", "tiles", "blades",
 * "billboards", "raster_end". */
const char *app_pass_name(app_pass_kind_t k);

/* The rules behind the list, also what the world makes: billboards in
 * billboard and hybrid modes, except the hybrid on a world (not streamed
 * yet); blades in blade and hybrid modes; the blades from tiles for the
 * hybrid on a heightfield and for blade and hybrid modes on a world, never
 * for the reference. */
bool app_pass_wants_billboards(scene_mode_t mode, app_ground_t ground);
bool app_pass_wants_blades(scene_mode_t mode);
bool app_pass_uses_tiles(scene_mode_t mode, app_ground_t ground, bool reference);

#endif

/* bindings_blade.glsl: the blade module's binding numbers, one #define
 * each for blade.c / blade_tiles.c (through blade_local.h) and for
 * shaders/blade; only #define lines and comments, so the same file is C
 * and GLSL (docs/DESIGN.md "Layout"). BLADE_ names the full field's
 * programs, BLADE_TILES_ the tiles'; a number is reused where no program
 * binds both. blade.tesc/tese read the blades at BLADE_BIND_BLADES in both
 * (the tiles bind their drawn list there on the tessellated path). The
 * hand-over's slope buffers are hybrid's (bindings_hybrid.glsl). */
#ifndef BINDINGS_BLADE_GLSL
#define BINDINGS_BLADE_GLSL

/* The full field: seeding, physics, patch test, cull, draw (tess, pull), raster */
#define BLADE_BIND_BLADES 0
#define BLADE_BIND_ETA 1       /* physics */
#define BLADE_BIND_WINDS 2     /* physics */
#define BLADE_BIND_SPHERES 3   /* physics */
#define BLADE_BIND_CUBES 4     /* physics: the colliders' cube-map records */
#define BLADE_BIND_SURVIVORS 1 /* cull out; tess / pull draws in */
#define BLADE_BIND_COMMAND 2   /* cull: the indirect draw */
#define BLADE_BIND_COUNTERS 3  /* cull and patch test (blade_patch.glsl) */
#define BLADE_BIND_PATCHES 4   /* patch test out; cull in */
#define BLADE_BIND_PATCH_BOXES 5 /* patch test: the patch boxes */
#define BLADE_BIND_PATCH_KEYS 6  /* patch test: each patch's bucket and place in it */
#define BLADE_BIND_RASTER_IDS 1
#define BLADE_BIND_RASTER_COUNT 2
#define BLADE_TEX_CUBES 0 /* physics: the colliders' depth cube maps */
#define BLADE_TEX_DEPTH 0 /* cull: the previous frame's depth */
/* The field seeded on the GPU (blade_seed.comp: BLADE_BIND_BLADES and
 * BLADE_BIND_ETA out; blade_seed_boxes.comp: BLADE_BIND_BLADES in,
 * BLADE_BIND_PATCH_BOXES out) */
#define BLADE_SEED_BIND_POSITIONS 2
#define BLADE_SEED_BIND_NORMALS 3
#define BLADE_SEED_BIND_INDICES 4
#define BLADE_SEED_BIND_ORDER 5
#define BLADE_SEED_BIND_OFFSETS 6
#define BLADE_SEED_BIND_THINNED 7
#define BLADE_SEED_TEX_EXTENT 0

/* The tiles: init, physics, hand-over, resolve, cull, draw */
#define BLADE_TILES_BIND_TEMPLATES 0
#define BLADE_TILES_BIND_POOL 1
#define BLADE_TILES_BIND_ETA 2
#define BLADE_TILES_BIND_WINDS 3
#define BLADE_TILES_BIND_SPHERES 4
#define BLADE_TILES_BIND_SLOT_SPHERES 5
#define BLADE_TILES_BIND_LIST 6 /* the tiles or slots a dispatch covers */
#define BLADE_TILES_BIND_MOTION 7
#define BLADE_TILES_BIND_DRAWN 8
#define BLADE_TILES_BIND_COMMAND 9
#define BLADE_TILES_BIND_DRAWN_IDS 10
#define BLADE_TILES_BIND_TILE_INFO 11 /* tiles_draw.vert: the overlay's states */
#define BLADE_TILES_BIND_DRAW_ETA 12  /* tiles_draw.vert: the pool's eta */
#define BLADE_TILES_TEX_GROUND 0
#define BLADE_TILES_TEX_EXTENT 1
#define BLADE_TILES_TEX_DEPTH 2

#endif

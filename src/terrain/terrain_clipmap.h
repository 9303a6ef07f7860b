/* terrain_clipmap: the levels of detail a world terrain (terrain_world.h) is
 * drawn with: a geometry clipmap of nested square grids around the camera,
 * level l of cell `cell * 2^l`, the finest a full grid of ring_cells^2
 * cells, each coarser one a ring around the next finer (its hole the finer
 * level's square). A clipmap rather than CDLOD's quadtree: the height is a
 * function, so nothing is paged and no per-node selection is needed; the
 * whole terrain is `levels` draws of one vertex grid and five index ranges,
 * the same bytes and triangles for a 1 km or an 8 km world.
 * Each level's origin snaps (floor) to twice its cell, so a level's square
 * sits in the coarser level's grid at one of 4 offsets: 4 ring index ranges.
 * Geomorphing as in CDLOD (Strugar 2009): a vertex slides from its own grid
 * position to the coarser grid's (odd indices onto the even one below) as
 * its Chebyshev distance to the camera goes from morph_start to morph_end;
 * the outer two rows of every level are fully morphed, so level borders
 * share their vertices exactly (no cracks, no T-junctions) and the morph is
 * continuous in the camera position (no popping). The height is sampled at
 * the morphed position. terrain_clipmap_vertex is the CPU twin of
 * shaders/ground/terrain_world.vert. GL-free. */
#ifndef MEADOW_TERRAIN_CLIPMAP_H
#define MEADOW_TERRAIN_CLIPMAP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define TERRAIN_CLIPMAP_LEVELS_MAX 16
#define TERRAIN_CLIPMAP_RANGES 5 /* the full grid, then rings by hole offset x + 2 z */

/* Zero means default. */
typedef struct terrain_clipmap_desc_t {
    float cell;       /* finest cell (m), a power of two; default 0.5 */
    int ring_cells;   /* cells per level side, a multiple of 8 in [32, 1024]; default 128 */
    int levels;       /* default 7: 0.5 m to 32 m cells, the coarsest reaching 2048 m from the camera */
    int morph_cells;  /* width of the morph band in the level's cells; default ring_cells / 8 */
} terrain_clipmap_desc_t;

typedef struct terrain_clipmap_t {
    terrain_clipmap_desc_t desc; /* resolved */
    uint16_t *grid;              /* (i, j) per vertex, (ring_cells + 1)^2 vertices, i fastest */
    uint32_t vertex_count;
    uint32_t *indices;           /* triangles of the TERRAIN_CLIPMAP_RANGES ranges, ccw from +y */
    uint32_t index_count;
    uint32_t first[TERRAIN_CLIPMAP_RANGES], count[TERRAIN_CLIPMAP_RANGES]; /* index ranges */
} terrain_clipmap_t;

/* Where a level is drawn this frame. */
typedef struct terrain_clipmap_level_t {
    float origin[2];   /* world xz of grid vertex (0, 0) */
    float cell;        /* metres per grid step */
    float morph[2];    /* Chebyshev distance where the morph starts, 1 / (end - start) */
    int range;         /* index range: 0 for level 0, else 1 + hole offset x + 2 * z */
} terrain_clipmap_level_t;

/* The desc with zero fields resolved; false when a field is out of range. */
bool terrain_clipmap_resolve(const terrain_clipmap_desc_t *in, terrain_clipmap_desc_t *out);
/* Builds the grid and index ranges; false (logged) for a bad desc or out of memory. */
bool terrain_clipmap_make(terrain_clipmap_t *c, const terrain_clipmap_desc_t *desc);
void terrain_clipmap_free(terrain_clipmap_t *c);
/* Bytes of the grid and indices (what the GPU holds). */
size_t terrain_clipmap_bytes(const terrain_clipmap_t *c);
/* The same for a desc, without building it (0 for a bad desc). */
size_t terrain_clipmap_estimate_bytes(const terrain_clipmap_desc_t *desc);
/* Level `level` placed around the camera at (camera_x, camera_z). */
terrain_clipmap_level_t terrain_clipmap_place(const terrain_clipmap_t *c, int level, float camera_x, float camera_z);
/* World xz of grid vertex (i, j) of a placed level, morphed for the camera
 * (the vertex shader's computation). */
void terrain_clipmap_vertex(const terrain_clipmap_level_t *l, int i, int j, float camera_x, float camera_z,
                            float out_xz[2]);

#endif

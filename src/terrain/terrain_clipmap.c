/* terrain_clipmap: the clipmap's vertex grid, its five index ranges, the
 * per-frame placement of each level and the morphed vertex position (the
 * CPU twin of shaders/ground/terrain_world.vert). See terrain_clipmap.h. */
#include "terrain/terrain_clipmap.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"

#define DEFAULT_CELL 0.5f
#define DEFAULT_RING_CELLS 128
#define DEFAULT_LEVELS 7

bool terrain_clipmap_resolve(const terrain_clipmap_desc_t *in, terrain_clipmap_desc_t *out)
{
    terrain_clipmap_desc_t d = *in;
    if (d.cell <= 0.0f) d.cell = DEFAULT_CELL;
    if (d.ring_cells <= 0) d.ring_cells = DEFAULT_RING_CELLS;
    if (d.levels <= 0) d.levels = DEFAULT_LEVELS;
    if (d.morph_cells <= 0) d.morph_cells = d.ring_cells / 8;
    *out = d;
    int e;
    bool pow2 = frexpf(d.cell, &e) == 0.5f;
    /* The coarser level must not morph at its hole: ring_cells / 2 >= 8 + 2 morph_cells. */
    return pow2 && d.ring_cells % 8 == 0 && d.ring_cells >= 32 && d.ring_cells <= 1024 &&
           d.levels <= TERRAIN_CLIPMAP_LEVELS_MAX && d.morph_cells <= d.ring_cells / 4 - 4;
}

/* Appends the two triangles of cell (i, j). */
static uint32_t *cell_tris(uint32_t *ix, int n, int i, int j)
{
    uint32_t side = (uint32_t)n + 1, v00 = (uint32_t)j * side + (uint32_t)i, v10 = v00 + 1, v01 = v00 + side,
             v11 = v01 + 1;
    *ix++ = v00;
    *ix++ = v01;
    *ix++ = v11;
    *ix++ = v00;
    *ix++ = v11;
    *ix++ = v10;
    return ix;
}

bool terrain_clipmap_make(terrain_clipmap_t *c, const terrain_clipmap_desc_t *desc)
{
    memset(c, 0, sizeof *c);
    if (!terrain_clipmap_resolve(desc, &c->desc)) {
        core_log_error("terrain_clipmap: bad desc (cell %g, ring_cells %d, levels %d, morph_cells %d)",
                       (double)c->desc.cell, c->desc.ring_cells, c->desc.levels, c->desc.morph_cells);
        return false;
    }
    int n = c->desc.ring_cells, q = n / 4, hole = n / 2;
    uint32_t side = (uint32_t)n + 1, full = (uint32_t)(n * n) * 6, ring = (uint32_t)(n * n - hole * hole) * 6;
    c->vertex_count = side * side;
    c->index_count = full + 4 * ring;
    c->grid = malloc(sizeof(uint16_t) * 2 * c->vertex_count);
    c->indices = malloc(sizeof(uint32_t) * c->index_count);
    if (!c->grid || !c->indices) {
        core_log_error("terrain_clipmap: out of memory");
        terrain_clipmap_free(c);
        return false;
    }
    for (uint32_t j = 0; j < side; j++)
        for (uint32_t i = 0; i < side; i++) {
            c->grid[2 * (j * side + i) + 0] = (uint16_t)i;
            c->grid[2 * (j * side + i) + 1] = (uint16_t)j;
        }
    uint32_t *ix = c->indices;
    for (int r = 0; r < TERRAIN_CLIPMAP_RANGES; r++) {
        c->first[r] = (uint32_t)(ix - c->indices);
        int ox = (r - 1) & 1, oz = (r - 1) >> 1;
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                bool in_hole = r > 0 && i >= q + ox && i < q + ox + hole && j >= q + oz && j < q + oz + hole;
                if (!in_hole) ix = cell_tris(ix, n, i, j);
            }
        c->count[r] = (uint32_t)(ix - c->indices) - c->first[r];
    }
    return true;
}

void terrain_clipmap_free(terrain_clipmap_t *c)
{
    free(c->grid);
    free(c->indices);
    memset(c, 0, sizeof *c);
}

size_t terrain_clipmap_bytes(const terrain_clipmap_t *c)
{
    return sizeof(uint16_t) * 2 * c->vertex_count + sizeof(uint32_t) * c->index_count;
}

size_t terrain_clipmap_estimate_bytes(const terrain_clipmap_desc_t *desc)
{
    terrain_clipmap_desc_t d;
    if (!terrain_clipmap_resolve(desc, &d)) return 0;
    size_t n = (size_t)d.ring_cells, hole = n / 2;
    return sizeof(uint16_t) * 2 * (n + 1) * (n + 1) + sizeof(uint32_t) * 6 * (n * n + 4 * (n * n - hole * hole));
}

/* Index of the cell of side 2 * cell holding x (the level's snap). */
static double snap_index(float x, float cell) { return floor((double)x / (2.0 * (double)cell)); }

terrain_clipmap_level_t terrain_clipmap_place(const terrain_clipmap_t *c, int level, float camera_x, float camera_z)
{
    const terrain_clipmap_desc_t *d = &c->desc;
    terrain_clipmap_level_t l = {.cell = ldexpf(d->cell, level)};
    float half = (float)(d->ring_cells / 2) * l.cell;
    double qx = snap_index(camera_x, l.cell), qz = snap_index(camera_z, l.cell);
    l.origin[0] = (float)(qx * 2.0 * l.cell) - half;
    l.origin[1] = (float)(qz * 2.0 * l.cell) - half;
    float end = half - 3.0f * l.cell, start = end - (float)d->morph_cells * l.cell;
    l.morph[0] = start;
    l.morph[1] = 1.0f / (end - start);
    if (level > 0) {
        float finer = ldexpf(d->cell, level - 1);
        int ox = (int)(snap_index(camera_x, finer) - 2.0 * qx), oz = (int)(snap_index(camera_z, finer) - 2.0 * qz);
        l.range = 1 + ox + 2 * oz;
    }
    return l;
}

void terrain_clipmap_vertex(const terrain_clipmap_level_t *l, int i, int j, float camera_x, float camera_z,
                            float out_xz[2])
{
    float gx = (float)i, gz = (float)j;
    float px = l->origin[0] + gx * l->cell, pz = l->origin[1] + gz * l->cell;
    float dist = fmaxf(fabsf(px - camera_x), fabsf(pz - camera_z));
    float k = fminf(fmaxf((dist - l->morph[0]) * l->morph[1], 0.0f), 1.0f);
    out_xz[0] = l->origin[0] + (gx - (float)(i & 1) * k) * l->cell;
    out_xz[1] = l->origin[1] + (gz - (float)(j & 1) * k) * l->cell;
}

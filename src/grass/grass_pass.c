/* grass_pass: grass_draw's passes from the mode, the ground, the
 * rasterizer and the reference flag (grass_pass.h). GL-free. */
#include "grass/grass_pass.h"

#include "grass/grass.h"

bool grass_pass_wants_billboards(scene_mode_t mode, scene_hybrid_billboards_t hybrid_bb)
{
    /* a world streams its billboards too (bb_ring.h) */
    if (mode == SCENE_MODE_HYBRID) return hybrid_bb == SCENE_HYBRID_BILLBOARDS_RING;
    return mode == SCENE_MODE_BILLBOARD;
}

bool grass_pass_wants_blades(scene_mode_t mode) { return mode == SCENE_MODE_BLADE || mode == SCENE_MODE_HYBRID; }

bool grass_pass_uses_tiles(scene_mode_t mode, grass_ground_t ground, bool reference)
{
    if (reference) return ground == GRASS_GROUND_WORLD;
    if (ground == GRASS_GROUND_WORLD) return grass_pass_wants_blades(mode);
    return mode == SCENE_MODE_HYBRID && ground == GRASS_GROUND_HEIGHTFIELD;
}

grass_ground_t grass_pass_ground(const terrain_mesh_t *t)
{
    if (t->type == TERRAIN_WORLD) return GRASS_GROUND_WORLD;
    return t->grid_res > 0 ? GRASS_GROUND_HEIGHTFIELD : GRASS_GROUND_MESH;
}

float grass_pass_tiles_distance(const scene_grass_desc_t *g, scene_mode_t mode, grass_ground_t ground,
                                bool reference)
{
    if (reference) return GRASS_REFERENCE_REACH;
    if (ground != GRASS_GROUND_WORLD || mode != SCENE_MODE_BLADE) return g->switch_distance;
    return g->blade_distance > 0.0f ? g->blade_distance : GRASS_BLADE_DISTANCE;
}

int grass_pass_list(const grass_pass_desc_t *d, grass_pass_t out[GRASS_PASS_KINDS])
{
    int n = 0;
    out[n++] = (grass_pass_t){.kind = GRASS_PASS_GROUND};
    if (d->compute) out[n++] = (grass_pass_t){.kind = GRASS_PASS_RASTER_BEGIN};
    if (d->have_tiles && grass_pass_uses_tiles(d->mode, d->ground, d->reference))
        out[n++] = (grass_pass_t){.kind = GRASS_PASS_TILES, .compute = d->compute};
    else if (d->have_blades && (grass_pass_wants_blades(d->mode) || d->reference))
        out[n++] = (grass_pass_t){.kind = GRASS_PASS_BLADES, .compute = d->compute};
    if (d->have_billboards && grass_pass_wants_billboards(d->mode, d->billboards) && !d->reference)
        out[n++] = (grass_pass_t){.kind = GRASS_PASS_BILLBOARDS, .compute = d->compute};
    if (d->compute) out[n++] = (grass_pass_t){.kind = GRASS_PASS_RASTER_END};
    return n;
}

bool grass_pass_has(const grass_pass_t *passes, int n, grass_pass_kind_t k)
{
    for (int i = 0; i < n; i++)
        if (passes[i].kind == k) return true;
    return false;
}

const char *grass_pass_name(grass_pass_kind_t k)
{
    switch (k) {
    case GRASS_PASS_GROUND: return "ground";
    case GRASS_PASS_RASTER_BEGIN: return "raster_begin";
    case GRASS_PASS_TILES: return "tiles";
    case GRASS_PASS_BLADES: return "blades";
    case GRASS_PASS_BILLBOARDS: return "billboards";
    case GRASS_PASS_RASTER_END: return "raster_end";
    case GRASS_PASS_KINDS: break;
    }
    return "?";
}

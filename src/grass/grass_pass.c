/* world_pass: the frame's passes from the mode, the ground, the rasterizer
 * and the reference flag (world_pass.h). GL-free. */
#include "world/world_pass.h"

bool world_pass_wants_billboards(scene_mode_t mode, scene_hybrid_billboards_t hybrid_bb)
{
    /* a world streams its billboards too (bb_ring.h) */
    if (mode == SCENE_MODE_HYBRID) return hybrid_bb == SCENE_HYBRID_BILLBOARDS_RING;
    return mode == SCENE_MODE_BILLBOARD;
}

bool world_pass_wants_blades(scene_mode_t mode) { return mode == SCENE_MODE_BLADE || mode == SCENE_MODE_HYBRID; }

bool world_pass_uses_tiles(scene_mode_t mode, world_ground_t ground, bool reference)
{
    if (reference) return false;
    if (ground == WORLD_GROUND_WORLD) return world_pass_wants_blades(mode);
    return mode == SCENE_MODE_HYBRID && ground == WORLD_GROUND_HEIGHTFIELD;
}

int world_pass_list(const world_pass_desc_t *d, world_pass_t out[WORLD_PASS_KINDS])
{
    int n = 0;
    out[n++] = (world_pass_t){.kind = WORLD_PASS_TERRAIN};
    if (d->have_characters) out[n++] = (world_pass_t){.kind = WORLD_PASS_CHARACTERS};
    if (d->compute) out[n++] = (world_pass_t){.kind = WORLD_PASS_RASTER_BEGIN};
    if (d->have_tiles && world_pass_uses_tiles(d->mode, d->ground, d->reference))
        out[n++] = (world_pass_t){.kind = WORLD_PASS_TILES, .compute = d->compute};
    else if (d->have_blades && (world_pass_wants_blades(d->mode) || d->reference))
        out[n++] = (world_pass_t){.kind = WORLD_PASS_BLADES, .compute = d->compute};
    if (d->have_billboards && world_pass_wants_billboards(d->mode, d->billboards) && !d->reference)
        out[n++] = (world_pass_t){.kind = WORLD_PASS_BILLBOARDS, .compute = d->compute};
    if (d->compute) out[n++] = (world_pass_t){.kind = WORLD_PASS_RASTER_END};
    return n;
}

bool world_pass_has(const world_pass_t *passes, int n, world_pass_kind_t k)
{
    for (int i = 0; i < n; i++)
        if (passes[i].kind == k) return true;
    return false;
}

const char *world_pass_name(world_pass_kind_t k)
{
    switch (k) {
    case WORLD_PASS_TERRAIN: return "terrain";
    case WORLD_PASS_CHARACTERS: return "characters";
    case WORLD_PASS_RASTER_BEGIN: return "raster_begin";
    case WORLD_PASS_TILES: return "tiles";
    case WORLD_PASS_BLADES: return "blades";
    case WORLD_PASS_BILLBOARDS: return "billboards";
    case WORLD_PASS_RASTER_END: return "raster_end";
    case WORLD_PASS_KINDS: break;
    }
    return "?";
}

/* app_pass: the frame's passes from the mode, the ground, the rasterizer
 * and the reference flag (app_pass.h). GL-free. */
#include "app/app_pass.h"

bool app_pass_wants_billboards(scene_mode_t mode, app_ground_t ground)
{
    if (mode == SCENE_MODE_BILLBOARD) return true;
    return mode == SCENE_MODE_HYBRID && ground != APP_GROUND_WORLD;
}

bool app_pass_wants_blades(scene_mode_t mode) { return mode == SCENE_MODE_BLADE || mode == SCENE_MODE_HYBRID; }

bool app_pass_uses_tiles(scene_mode_t mode, app_ground_t ground, bool reference)
{
    if (reference) return false;
    if (ground == APP_GROUND_WORLD) return app_pass_wants_blades(mode);
    return mode == SCENE_MODE_HYBRID && ground == APP_GROUND_HEIGHTFIELD;
}

int app_pass_list(const app_pass_desc_t *d, app_pass_t out[APP_PASS_KINDS])
{
    int n = 0;
    out[n++] = (app_pass_t){.kind = APP_PASS_TERRAIN};
    if (d->have_characters) out[n++] = (app_pass_t){.kind = APP_PASS_CHARACTERS};
    if (d->compute) out[n++] = (app_pass_t){.kind = APP_PASS_RASTER_BEGIN};
    if (d->have_tiles && app_pass_uses_tiles(d->mode, d->ground, d->reference))
        out[n++] = (app_pass_t){.kind = APP_PASS_TILES, .compute = d->compute};
    else if (d->have_blades && (app_pass_wants_blades(d->mode) || d->reference))
        out[n++] = (app_pass_t){.kind = APP_PASS_BLADES, .compute = d->compute};
    if (d->have_billboards && app_pass_wants_billboards(d->mode, d->ground) && !d->reference)
        out[n++] = (app_pass_t){.kind = APP_PASS_BILLBOARDS, .compute = d->compute};
    if (d->compute) out[n++] = (app_pass_t){.kind = APP_PASS_RASTER_END};
    return n;
}

bool app_pass_has(const app_pass_t *passes, int n, app_pass_kind_t k)
{
    for (int i = 0; i < n; i++)
        if (passes[i].kind == k) return true;
    return false;
}

const char *app_pass_name(app_pass_kind_t k)
{
    switch (k) {
    case APP_PASS_TERRAIN: return "terrain";
    case APP_PASS_CHARACTERS: return "characters";
    case APP_PASS_RASTER_BEGIN: return "raster_begin";
    case APP_PASS_TILES: return "tiles";
    case APP_PASS_BLADES: return "blades";
    case APP_PASS_BILLBOARDS: return "billboards";
    case APP_PASS_RASTER_END: return "raster_end";
    case APP_PASS_KINDS: break;
    }
    return "?";
}

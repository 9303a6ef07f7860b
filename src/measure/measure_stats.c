/* measure_stats: the counts of the last frame of a world (blades, culling,
 * billboards, tiles, characters, triangles) read from its systems, for
 * summary.txt and the bench's perf and papers tables (measure.h). */
#include "measure/measure.h"

#include <string.h>

void measure_stats(world_t *w, measure_stats_t *st)
{
    memset(st, 0, sizeof *st);
    world_info_t wi = world_info(w);
    if (wi.blades) {
        blade_gpu_stats_t b = blade_gpu_stats(wi.blades, true);
        st->blades = b.total;
        st->blade_survivors = b.survivors;
        memcpy(st->blade_culled, b.culled, sizeof st->blade_culled);
        st->blade_patch_culled = b.patch_culled;
        st->triangles += b.triangles_max;
    }
    if (wi.billboards) {
        bb_stats_t s;
        bb_field_stats(wi.billboards, true, &s);
        st->billboards = s.billboards;
        st->bb_deformed = s.deformed;
        st->bb_generate_ms = s.generate_ms;
        st->bb_make_ms = s.make_ms;
        for (int k = 0; k < BB_MAKE_STAGES; k++) st->bb_make_stage_ms[k] = s.make_stage_ms[k];
        st->triangles += s.triangles;
    }
    if (wi.tiles) {
        blade_tiles_stats_t ts = blade_tiles_stats(wi.tiles, true);
        st->blades += (long)ts.blades_drawn;
        st->blade_survivors += (long)ts.blades_drawn;
        st->tiles_active = ts.active;
        st->tiles_recovering = ts.recovering;
        st->tiles_blade = ts.blade_tiles;
        st->tile_slots_used = ts.slots_used;
        st->tile_slots_total = ts.slots_total;
        st->tile_blades_simulated = (long)ts.blades_dispatched;
        st->tile_handovers = ts.handovers_total;
        st->tile_seeded = ts.seeded_total;
        memcpy(st->tiles_culled, ts.culled, sizeof st->tiles_culled);
        st->tiles_tile_culled = ts.tile_culled;
        st->triangles += ts.triangles_max;
    }
    st->characters = wi.characters ? character_set_count(wi.characters) : 0;
}

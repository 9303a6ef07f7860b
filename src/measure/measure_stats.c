/* measure_stats: the counts of the last frame of a world (blades, culling,
 * billboards, tiles, characters, triangles) read from its grass, for
 * summary.txt and the bench's perf and papers tables; the sizes and the
 * tiles' work the harness and the frame log read (measure_grass); the
 * summary's lines on the ring, the tile window and the rasterizer
 * (measure.h). */
#include "measure/measure.h"

#include <stdio.h>
#include <string.h>

grass_drivers_t measure_drivers(world_t *w)
{
    grass_t *g = world_info(w).grass;
    return g ? grass_drivers(g) : (grass_drivers_t){0};
}

const char *measure_bb_stage_name(int k) { return bb_make_stage_name(k); }

void measure_stats(world_t *w, measure_stats_t *st)
{
    memset(st, 0, sizeof *st);
    world_info_t info = world_info(w);
    grass_drivers_t wi = measure_drivers(w);
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
    st->characters = info.characters ? character_set_count(info.characters) : 0;
}

void measure_grass(world_t *w, unsigned parts, bool wait, measure_grass_t *out)
{
    memset(out, 0, sizeof *out);
    grass_drivers_t d = measure_drivers(w);
    if (d.blades && (parts & MEASURE_GRASS_SIZES)) {
        blade_gpu_info_t bi = blade_gpu_info(d.blades);
        out->blade_padded = bi.padded_count;
        out->blades_total = bi.blade_count;
    }
    if (d.billboards && (parts & MEASURE_GRASS_SIZES)) {
        bb_field_info_t fi;
        bb_field_info(d.billboards, &fi);
        out->bb_billboards = fi.billboards;
        out->bb_mesh_vertices = fi.mesh_vertices;
    }
    if (d.billboards && (parts & MEASURE_GRASS_LEAVES)) {
        bb_stats_t s;
        bb_field_stats(d.billboards, false, &s);
        out->bb_leaves_colliding = s.leaves[BB_NODE_COLLIDING];
        out->bb_leaves_recovering = s.leaves[BB_NODE_RECOVERING];
    }
    if (d.tiles && (parts & MEASURE_GRASS_TILES)) {
        blade_tiles_stats_t ts = blade_tiles_stats(d.tiles, wait);
        out->tiles_active = ts.active;
        out->tiles_recovering = ts.recovering;
        out->tile_slots_dispatched = ts.slots_dispatched;
        out->tile_blades_dispatched = (long)ts.blades_dispatched;
        out->tiles_streamed_total = ts.streamed_total;
    }
}

int measure_grass_lines(world_t *w, char *buf, size_t size)
{
    world_info_t wi = world_info(w);
    grass_drivers_t d = measure_drivers(w);
    bool world = wi.terrain->type == TERRAIN_WORLD;
    int n = 0;
    if (world && d.billboards) {
        bb_field_info_t fi;
        bb_field_info(d.billboards, &fi);
        float cell = (float)fi.ring_cand * fi.gen.spacing;
        n += snprintf(buf + n, size - (size_t)n,
                      "billboard ring: %d x %d cells of %.2f m (%d x %d candidates) around the camera, to %.1f m; "
                      "%d billboards, %.1f MiB; cells generated %ld\n",
                      fi.ring_side, fi.ring_side, (double)cell, fi.ring_cand, fi.ring_cand,
                      (double)fi.desc.ring_reach, fi.capacity,
                      (double)fi.capacity * (double)sizeof(bb_point_t) / 1048576.0, fi.ring_generated);
    }
    if (world && d.tiles && n < (int)size) {
        blade_tiles_info_t ti = blade_tiles_info(d.tiles);
        blade_tiles_stats_t ts = blade_tiles_stats(d.tiles, false);
        n += snprintf(buf + n, size - (size_t)n,
                      "world: %.0f m, a window of %d x %d tiles of %.0f m around the camera (blades to %.1f m); "
                      "tiles streamed in %ld; touched tiles that left it recovering %ld, back %ld\n",
                      wi.terrain->world.size, ti.desc.window, ti.desc.window, ti.desc.tile_size,
                      ti.desc.switch_distance, ts.streamed_total, ts.detached_total, ts.reattached_total);
    }
    raster_t *r = d.raster;
    if (r && r->vis.id && n < (int)size) {
        raster_stats_t rs;
        raster_read_stats(r, &rs);
        n += snprintf(buf + n, size - (size_t)n,
                      "raster_buffers_mb: %.1f (visibility %dx%d x %d samples, %s; triangle queues)\n"
                      "raster_queued (last draw): medium %u, large %u, not drawn (queue full) %u\n",
                      (double)(r->vis.size + r->queue.size + r->args.size) / (1024.0 * 1024.0), r->desc.w, r->desc.h,
                      r->desc.samples, r->atomic64 ? "64-bit atomics" : "two-pass 32-bit", rs.medium, rs.large,
                      rs.overflow);
    }
    return n < (int)size ? n : (int)size - 1;
}

/* app_bb_world: what the program adds around the billboard ring of a world
 * terrain (bb_ring.h, docs/WORLD.md "Streaming: the billboard ring"): the
 * ground canopy beyond it in billboard mode (the hybrid's comes with its
 * tiles) and the ring's line in summary.txt. */
#include "app/app_world.h"

#include <stdio.h>

bool app_ring_make_canopy(app_world_t *w)
{
    if (w->terrain_mesh.type != TERRAIN_WORLD || !w->bb || w->have_tiles) return true;
    blade_canopy_t canopy;
    if (!blade_canopy_make(&canopy, &(blade_canopy_desc_t){.population = w->scene.grass.population,
                                                           .seed = w->scene.seed,
                                                           .sun = APP_SUN_DIR}))
        return false;
    bb_field_info_t fi;
    bb_field_info(w->bb, &fi);
    app_terrain_set_canopy(&w->terrain, &canopy, fi.extent_texture, fi.gen.origin,
                           fi.gen.spacing * (float)fi.gen.cells_per_texel);
    return true;
}

int app_ring_summary(const app_world_t *w, char *buf, size_t size)
{
    if (w->terrain_mesh.type != TERRAIN_WORLD || !w->bb) return 0;
    bb_field_info_t fi;
    bb_field_info(w->bb, &fi);
    float cell = (float)fi.ring_cand * fi.gen.spacing;
    int n = snprintf(buf, size,
                     "billboard ring: %d x %d cells of %.2f m (%d x %d candidates) around the camera, to %.1f m; "
                     "%d billboards, %.1f MiB; cells generated %ld\n",
                     fi.ring_side, fi.ring_side, (double)cell, fi.ring_cand, fi.ring_cand,
                     (double)fi.desc.ring_reach, fi.capacity,
                     (double)fi.capacity * (double)sizeof(bb_point_t) / 1048576.0, fi.ring_generated);
    return n < 0 ? 0 : (n < (int)size ? n : (int)size - 1);
}

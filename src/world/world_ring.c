/* world_ring: what the world adds around the billboard ring of a world
 * terrain (bb_ring.h, docs/WORLD.md "Streaming: the billboard ring"): the
 * ground canopy beyond it in billboard mode (the hybrid's comes with its
 * tiles). The ring's line in summary.txt is app_run.c's. */
#include "world/world_local.h"

bool world_ring_make_canopy(world_t *w)
{
    if (w->terrain_mesh.type != TERRAIN_WORLD || !w->bb || w->have_tiles) return true;
    blade_canopy_t canopy;
    if (!blade_canopy_make(&canopy, &(blade_canopy_desc_t){.population = w->scene.grass.population,
                                                           .seed = w->scene.seed,
                                                           .sun = WORLD_SUN_DIR}))
        return false;
    bb_field_info_t fi;
    bb_field_info(w->bb, &fi);
    ground_set_canopy(w->ground, &canopy, fi.extent_texture, fi.gen.origin,
                      fi.gen.spacing * (float)fi.gen.cells_per_texel);
    return true;
}

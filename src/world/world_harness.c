/* world_harness: what world.h and world_harness.h read of the world
 * (world_info, the colliders), the set-up of an offscreen session's world,
 * a step with the harness's own blade sphere proxies, a draw in another
 * mode or without grass, and the billboard field swapped for another
 * placement, or the tiles for blades drawn farther. */
#include "world/world_local.h"

#include <string.h>

world_info_t world_info(world_t *w)
{
    world_info_t i = {.scene = &w->scene,
                      .scene_path = w->scene_path,
                      .terrain = &w->terrain_mesh,
                      .mode = w->mode,
                      .reference = w->reference,
                      .raster_compute = w->raster_compute,
                      .raster_samples = w->raster_samples,
                      .input_error = w->input_error,
                      .stage_ms = w->stage_ms,
                      .update_ms = w->update_ms,
                      .admitted = &w->admitted,
                      .lod_note = w->lod_note,
                      .characters = w->have_chars ? &w->chars : NULL};
    if (!w->grass) return i;
    grass_stats_t st = grass_stats(w->grass);
    grass_drivers_t d = grass_drivers(w->grass);
    i.raster_compute = st.compute;
    i.canopy = st.canopy;
    i.billboards = d.billboards != NULL;
    i.blades = d.blades != NULL;
    i.tiles = d.tiles != NULL;
    i.grass = w->grass;
    return i;
}

uint32_t world_placement_seed(const world_t *w)
{
    return w->tuning.placement_seed ? w->tuning.placement_seed : w->scene.seed;
}

int world_collider_count(const world_t *w) { return w->colliders.count; }

world_collider_info_t world_collider(const world_t *w, int i)
{
    const world_collider_t *c = &w->colliders.items[i];
    return (world_collider_info_t){.desc = c->desc,
                                   .position = {c->position[0], c->position[1], c->position[2]},
                                   .bound_radius = c->bound_radius};
}

void world_set_camera(world_t *w, const float camera[3]) { grass_set_camera(w->grass, camera); }

bb_field_t *world_build_billboards(const world_t *w, uint32_t placement)
{
    return grass_build_billboards(w->grass, placement);
}

bb_field_t *world_swap_billboards(world_t *w, bb_field_t *field) { return grass_swap_billboards(w->grass, field); }

/* world_draw_as and world_draw_canopy: the target bound and cleared, the
 * world's objects, then the grass as `as` says. */
static void draw_as(world_t *w, const grass_view_t *v, const gfx_target_t *t, const grass_draw_as_t *as)
{
    gfx_target_bind(t);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    world_draw_objects(w, v, t, as);
}

void world_draw_as(world_t *w, const grass_view_t *v, const gfx_target_t *t, scene_mode_t mode, bool grass)
{
    draw_as(w, v, t, &(grass_draw_as_t){.mode = mode, .no_grass = !grass, .depth = true});
}

void world_draw_canopy(world_t *w, const grass_view_t *v, const gfx_target_t *t)
{
    draw_as(w, v, t, &(grass_draw_as_t){.mode = w->mode, .no_grass = true, .canopy_all = true, .depth = true});
}

bool world_draw_tiles_to(world_t *w, const grass_view_t *v, const gfx_target_t *t, float distance)
{
    blade_tiles_t *tiles = w->grass ? grass_build_tiles(w->grass, distance) : NULL;
    if (!tiles) return false;
    blade_tiles_t *keep = grass_swap_tiles(w->grass, tiles);
    draw_as(w, v, t, &(grass_draw_as_t){.mode = w->mode, .depth = true, .tiles_distance = distance});
    grass_swap_tiles(w->grass, keep);
    blade_tiles_destroy(tiles);
    return true;
}

bool world_canopy_match(world_t *w, ground_match_state_t *out)
{
    return w->grass && grass_canopy_match(w->grass, out);
}

void world_canopy_match_reset(world_t *w)
{
    if (w->grass) grass_canopy_match_reset(w->grass);
}

bool world_setup(world_t *w, const world_setup_t *setup)
{
    scene_desc_t *s = &w->scene;
    if (setup->mode_set) world_set_mode(w, setup->mode);
    if (setup->msaa) s->msaa = setup->msaa;
    w->reference = setup->reference;
    w->tuning = setup->tuning;
    terrain_desc_t terrain_before = s->terrain;
    if (setup->tweak) setup->tweak(s, setup->user);
    /* A tweak of a heightfield rebuilds the terrain world_load made. */
    if (memcmp(&terrain_before, &s->terrain, sizeof terrain_before) != 0 && s->terrain.type == TERRAIN_HEIGHTFIELD) {
        terrain_free(&w->terrain_mesh);
        if (!terrain_make_heightfield(&w->terrain_mesh, &s->terrain, s->seed)) {
            core_log_error("session: cannot build the tweaked heightfield of %s", w->scene_path);
            return false;
        }
    }
    return true;
}

void world_update_spheres(world_t *w, float t, float dt, world_spheres_fn spheres, void *user)
{
    static collide_sphere_t proxies[BLADE_MAX_SPHERES];
    w->time = t;
    world_colliders_update(&w->colliders, &w->terrain_mesh, t);
    grass_update_spheres(w->grass, proxies, spheres(w, proxies, BLADE_MAX_SPHERES, user), t, dt);
}

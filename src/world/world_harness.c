/* world_harness: what world.h and world_harness.h read of the world
 * (world_info, the colliders, the tuning), the set-up of an offscreen
 * session's world, a step with the harness's own blade sphere proxies, a
 * draw in another mode or without grass, and the billboard field swapped
 * for another placement. */
#include "world/world_local.h"

#include <string.h>

world_info_t world_info(world_t *w)
{
    return (world_info_t){.scene = &w->scene,
                          .scene_path = w->scene_path,
                          .terrain = &w->terrain_mesh,
                          .mode = w->mode,
                          .reference = w->reference,
                          .raster_compute = w->raster_compute,
                          .raster_samples = w->raster_samples,
                          .canopy = w->ground && ground_has_canopy(w->ground),
                          .input_error = w->input_error,
                          .stage_ms = w->stage_ms,
                          .update_ms = w->update_ms,
                          .admitted = &w->admitted,
                          .lod_note = w->lod_note,
                          .blade_env = &w->blade_env,
                          .billboards = w->bb,
                          .blades = w->have_blades ? w->blades : NULL,
                          .tiles = w->have_tiles ? w->tiles : NULL,
                          .characters = w->have_chars ? &w->chars : NULL,
                          .raster = &w->raster};
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

void world_set_camera(world_t *w, const float camera[3]) { memcpy(w->camera, camera, sizeof w->camera); }

bb_field_t *world_swap_billboards(world_t *w, bb_field_t *field)
{
    bb_field_t *old = w->bb;
    w->bb = field;
    return old;
}

void world_draw_as(world_t *w, const world_view_t *v, const gfx_target_t *t, scene_mode_t mode, bool grass)
{
    scene_mode_t keep = w->mode;
    bb_field_t *bb = w->bb;
    bool blades = w->have_blades, tiles = w->have_tiles;
    w->mode = mode;
    if (!grass) {
        w->bb = NULL;
        w->have_blades = w->have_tiles = false;
    }
    gfx_target_bind(t);
    glClearColor(0, 0, 0, 1);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    w->grass_depth = true; /* measures read the depth back */
    world_draw(w, v, t, false);
    w->grass_depth = false;
    w->mode = keep;
    w->bb = bb;
    w->have_blades = blades;
    w->have_tiles = tiles;
}

void world_draw_canopy(world_t *w, const world_view_t *v, const gfx_target_t *t)
{
    w->canopy_all = true;
    world_draw_as(w, v, t, w->mode, false);
    w->canopy_all = false;
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
    w->time = t;
    world_colliders_update(&w->colliders, &w->terrain_mesh, t);
    blade_env_t *env = &w->blade_env;
    env->dt = dt;
    env->time = t;
    collide_begin_set(&w->collide);
    w->collide.sphere_count = spheres(w, w->collide.spheres, BLADE_MAX_SPHERES, user);
    blade_gpu_update(w->blades, env, &w->collide);
}

/* app_world_access: the world as the evaluation harness (src/bench) sees it:
 * read access to its scene, terrain, colliders and grass systems, the
 * set-up of an offscreen session's world, and an update with the harness's
 * own blade sphere proxies. */
#include "app/app_world.h"

#include <string.h>

const scene_desc_t *app_world_scene(const app_world_t *w) { return &w->scene; }
const char *app_world_scene_path(const app_world_t *w) { return w->scene_path; }
const terrain_mesh_t *app_world_terrain(const app_world_t *w) { return &w->terrain_mesh; }
const app_colliders_t *app_world_colliders(const app_world_t *w) { return &w->colliders; }
scene_mode_t app_world_mode(const app_world_t *w) { return w->mode; }
bool app_world_is_reference(const app_world_t *w) { return w->reference; }
bool app_world_input_error(const app_world_t *w) { return w->input_error; }
blade_gpu_t *app_world_blades(app_world_t *w) { return w->have_blades ? w->blades : NULL; }
bb_field_t *app_world_billboards(app_world_t *w) { return w->bb; }
blade_tiles_t *app_world_tiles(app_world_t *w) { return w->have_tiles ? w->tiles : NULL; }
character_set_t *app_world_characters(app_world_t *w) { return w->have_chars ? &w->chars : NULL; }

bool app_world_setup(app_world_t *w, const app_world_setup_t *setup)
{
    scene_desc_t *s = &w->scene;
    if (setup->mode_set) app_world_set_mode(w, setup->mode);
    if (setup->msaa) s->msaa = setup->msaa;
    w->reference = setup->reference;
    w->tuning = setup->tuning;
    terrain_desc_t terrain_before = s->terrain;
    if (setup->tweak) setup->tweak(s, setup->user);
    /* A tweak of a heightfield rebuilds the terrain app_world_load made. */
    if (memcmp(&terrain_before, &s->terrain, sizeof terrain_before) != 0 && s->terrain.type == TERRAIN_HEIGHTFIELD) {
        terrain_free(&w->terrain_mesh);
        if (!terrain_make_heightfield(&w->terrain_mesh, &s->terrain, s->seed)) {
            core_log_error("session: cannot build the tweaked heightfield of %s", w->scene_path);
            return false;
        }
    }
    return true;
}

void app_world_update_spheres(app_world_t *w, float t, float dt, app_world_spheres_fn spheres, void *user)
{
    w->time = t;
    app_colliders_update(&w->colliders, &w->terrain_mesh, t);
    blade_env_t *env = &w->blade_env;
    env->dt = dt;
    env->time = t;
    collide_begin_set(&w->collide);
    w->collide.sphere_count = spheres(w, w->collide.spheres, BLADE_MAX_SPHERES, user);
    blade_gpu_simulate(w->blades, env, &w->collide);
}

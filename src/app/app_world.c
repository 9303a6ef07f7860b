/* app_world: loads the scene and builds, updates and draws every system it
 * needs (terrain, colliders, characters, billboards, blades). Used by the
 * main loop, `meadow bench` and `meadow compare` alike. */
#include "app/app_world.h"

#include <stdio.h>
#include <string.h>

#include "core/core.h"

static scene_mode_t mode_from_cli(app_mode_t m, scene_mode_t scene_mode)
{
    switch (m) {
    case APP_MODE_BILLBOARD: return SCENE_MODE_BILLBOARD;
    case APP_MODE_BLADE: return SCENE_MODE_BLADE;
    case APP_MODE_HYBRID: return SCENE_MODE_HYBRID;
    default: return scene_mode;
    }
}

int app_world_load(app_world_t *w, const app_options_t *o)
{
    memset(w, 0, sizeof *w);
    char err[1024];
    if (o->scene) snprintf(w->scene_path, sizeof w->scene_path, "%s", o->scene);
    else core_fs_resolve("scenes/meadow.json", w->scene_path, sizeof w->scene_path);
    if (!scene_load(&w->scene, w->scene_path, err, sizeof err)) return 2;
    scene_desc_t *s = &w->scene;
    if (o->seed_set) s->seed = (uint32_t)o->seed;
    if (o->width) {
        s->size[0] = o->width;
        s->size[1] = o->height;
    }
    s->mode = mode_from_cli(o->mode, s->mode);
    w->mode = s->mode;
    if (s->terrain.type == TERRAIN_MESH) {
        char mesh[1024];
        if (!core_fs_resolve(s->terrain.mesh, mesh, sizeof mesh)) snprintf(mesh, sizeof mesh, "%s", s->terrain.mesh);
        if (!terrain_load_mesh(&w->terrain_mesh, mesh, s->terrain.scale, err, sizeof err)) {
            core_log_error("%s: terrain.mesh: %s", w->scene_path, err);
            return 2;
        }
    } else if (!terrain_make_heightfield(&w->terrain_mesh, &s->terrain, s->seed)) {
        core_log_error("%s: cannot build the heightfield terrain", w->scene_path);
        return 2;
    }
    return 0;
}

bool app_world_make_gpu(app_world_t *w)
{
    w->gpu_ready = app_terrain_make(&w->terrain, &w->terrain_mesh) && app_colliders_make(&w->colliders, &w->scene);
    return w->gpu_ready;
}

void app_world_update(app_world_t *w, float t, float dt)
{
    (void)dt;
    app_colliders_update(&w->colliders, t);
}

void app_world_draw(app_world_t *w, const app_view_t *v, bool wireframe)
{
    glPolygonMode(GL_FRONT_AND_BACK, wireframe ? GL_LINE : GL_FILL);
    gfx_timer_begin("terrain");
    app_terrain_draw(&w->terrain, v);
    app_colliders_draw(&w->colliders, v);
    gfx_timer_end();
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

void app_world_set_mode(app_world_t *w, scene_mode_t mode)
{
    w->mode = mode;
    w->scene.mode = mode;
}

void app_world_destroy(app_world_t *w)
{
    app_colliders_destroy(&w->colliders);
    app_terrain_destroy(&w->terrain);
    terrain_free(&w->terrain_mesh);
}

void app_view_make(app_view_t *v, const cam_t *cam_in, int width, int height, float time, float dt)
{
    cam_t cam = *cam_in;
    cam.aspect = (float)width / (float)height;
    cam_view(&cam, v->view);
    cam_proj(&cam, v->proj);
    glm_mat4_mul(v->proj, v->view, v->viewproj);
    glm_mat4_inv(v->viewproj, v->inv_viewproj);
    cam_frustum_planes(v->viewproj, v->planes);
    glm_vec3_copy(cam.position, v->camera);
    glm_vec3_normalize_to((vec3){0.45f, 0.8f, 0.35f}, v->sun_dir);
    v->width = width;
    v->height = height;
    v->time = time;
    v->dt = dt;
}

void app_world_metrics(app_world_t *w, app_metrics_t *m)
{
    (void)w;
    (void)m;
}

/* world: loads the scene and builds, steps and draws what a run holds: the
 * terrain, the analytic colliders, the characters, and the grass (one
 * grass_t, src/grass) they bend. Used by the main loop, `meadow bench` and
 * `meadow compare` alike (world.h). */
#include "world/world_local.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "admit/admit.h"
#include "collide/collide_shape.h"
#include "core/core.h"
#include "platform/plat.h"

const char *world_stage_name(int stage)
{
    static const char *const names[WORLD_STAGES] = {"scene",      "terrain",    "context", "terrain_gpu",
                                                  "characters", "billboards", "blades",  "first_frame"};
    return stage >= 0 && stage < WORLD_STAGES ? names[stage] : "?";
}

/* Adds the wall time since *mark to the world's stage and moves the mark. */
static void stage_done(world_t *w, int stage, double *mark)
{
    double now = plat_time();
    w->stage_ms[stage] += (now - *mark) * 1e3;
    *mark = now;
}

/* world_load's work on a zeroed world. */
static int load(world_t *w, const world_options_t *o)
{
    double mark = plat_time();
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
    if (o->mode_set) s->mode = o->mode;
    w->mode = s->mode;
    if (o->blade_render) s->grass.blade_render = (scene_blade_render_t)(o->blade_render - 1);
    w->tuning.view_cards = o->view_cards;
    if (o->raster) s->raster = (scene_raster_t)(o->raster - 1);
    w->raster_compute = s->raster == SCENE_RASTER_COMPUTE;
    w->raster_samples = o->raster_samples ? o->raster_samples : s->raster_samples;
    w->character_override = o->character;
    w->clip_override = o->clip;
    w->character_height = o->character_height;
    w->size_option = o->width != 0;
    float canopy_min = s->grass.switch_distance + GRASS_SWITCH_FADE + GRASS_CANOPY_FADE;
    /* Without billboards the canopy starts where the blades end (grass.billboards none). */
    if (s->grass.billboards == SCENE_HYBRID_BILLBOARDS_RING && s->grass.canopy_distance < canopy_min) {
        core_log_error("%s: grass.canopy_distance %g is less than grass.switch_distance + %g (%g): the blades' and "
                       "the canopy's fade bands would overlap",
                       w->scene_path, s->grass.canopy_distance, GRASS_SWITCH_FADE + GRASS_CANOPY_FADE, canopy_min);
        return 2;
    }
    stage_done(w, WORLD_STAGE_SCENE, &mark);
    /* Before the heightfield is built: its host and GPU copies, the targets
     * (admit; the rest is checked once the GL is up, which takes some
     * memory of its own: ADMIT_GL_RESERVE). */
    if (!admit_check(s, &(admit_world_t){.raster = s->raster != SCENE_RASTER_HW, .size_option = w->size_option},
                         &(admit_limits_t){.host_bytes = admit_host_bytes() - ADMIT_GL_RESERVE}, err,
                         sizeof err)) {
        core_log_error("%s: %s", w->scene_path, err);
        return 2;
    }
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
    stage_done(w, WORLD_STAGE_TERRAIN, &mark);
    if (admit_tiles_check(s, &w->terrain_mesh, err, sizeof err)) return 0;
    core_log_error("%s: %s", w->scene_path, err);
    return 2;
}

int world_load(const world_options_t *o, world_t **out)
{
    world_t *w = calloc(1, sizeof *w);
    *out = NULL;
    if (!w) return 1;
    int rc = load(w, o);
    if (rc) world_destroy(w);
    else *out = w;
    return rc;
}

/* Largest bounding radius of a collider or character (grass.cube_texel). */
static float largest_object_radius(world_t *w)
{
    float r = 0.0f;
    for (int i = 0; i < w->scene.collider_count; i++) {
        collide_shape_t s = scene_collider_shape(&w->scene.colliders[i]);
        r = fmaxf(r, collide_bounding_radius(&s));
    }
    if (w->have_chars) {
        character_object_t co[COLLIDE_MAX_OBJECTS];
        int n = character_set_objects(&w->chars, co, COLLIDE_MAX_OBJECTS);
        for (int i = 0; i < n && i < COLLIDE_MAX_OBJECTS; i++) r = fmaxf(r, co[i].radius);
    }
    return r;
}

/* grass.lod_table (scene_lod_apply) in hybrid mode, the reference aside. */
static void apply_lod_table(world_t *w)
{
    if (w->reference) return;
    grass_lod_table_apply(&w->scene, w->lod_note, sizeof w->lod_note);
    w->raster_compute = w->scene.raster == SCENE_RASTER_COMPUTE;
}

/* Resource admission (grass_admit) once the GL's limits are known, before
 * any grass is allocated, and again with the characters: a scene that
 * does not fit is bad input. */
static bool admit(world_t *w)
{
    static int spheres[SCENE_MAX_COLLIDERS];
    static float packed[BLADE_MAX_SPHERES][4];
    for (int i = 0; i < w->scene.collider_count; i++) {
        collide_shape_t s = scene_collider_shape(&w->scene.colliders[i]);
        spheres[i] = collide_pack_spheres(&s, (float[3]){0}, packed, BLADE_MAX_SPHERES);
    }
    /* On a world only the characters near the camera pack spheres (see
     * grass_collider_reach): the sphere limit is not a static one there. */
    static int char_spheres[SCENE_MAX_CHARACTERS];
    int characters = 0;
    bool counted = w->have_chars && grass_pass_ground(&w->terrain_mesh) != GRASS_GROUND_WORLD;
    for (int i = 0; counted && i < w->chars.count && i < SCENE_MAX_CHARACTERS; i++)
        char_spheres[characters++] = w->chars.items[i].sphere_count;
    grass_admit_t a = {.scene = &w->scene,
                       .terrain = &w->terrain_mesh,
                       .mode = w->mode,
                       .reference = w->reference,
                       .size_option = w->size_option,
                       .target_samples = world_target_samples(w),
                       .collider_radius = largest_object_radius(w),
                       .objects = w->scene.collider_count +
                                  (w->scene.character_count ? w->scene.character_count : w->character_override != NULL),
                       .collider_spheres = spheres,
                       .character_spheres = char_spheres,
                       .characters = characters};
    char err[1024];
    if (grass_admit(&a, &w->admitted, err, sizeof err)) return true;
    core_log_error("%s: %s", w->scene_path, err);
    w->input_error = true;
    return false;
}

/* The grass of the scene, on the world's scene and terrain. */
static bool make_grass(world_t *w, double *mark)
{
    grass_host_t host = {.scene = &w->scene, .terrain = &w->terrain_mesh, .scene_path = w->scene_path,
                         .tuning = w->tuning, .reference = w->reference, .raster_samples = w->raster_samples};
    int objects = w->colliders.count + (w->have_chars ? character_set_count(&w->chars) : 0);
    w->grass = grass_make(&(grass_desc_t){.host = &host, .mode = (grass_mode_t)(w->mode + 1),
                                          .collider_radius = largest_object_radius(w),
                                          .max_colliders = objects > 0 ? objects : 1});
    if (!w->grass) {
        w->input_error = grass_last_error() == 2;
        return false;
    }
    /* The grass's start-up stages: the ground with the terrain's GPU side. */
    grass_stats_t st = grass_stats(w->grass);
    w->stage_ms[WORLD_STAGE_TERRAIN_GPU] += st.make_ms[0];
    w->stage_ms[WORLD_STAGE_BILLBOARDS] += st.make_ms[1];
    w->stage_ms[WORLD_STAGE_BLADES] += st.make_ms[2];
    *mark = plat_time();
    return true;
}

bool world_make_gpu(world_t *w)
{
    double mark = plat_time();
    apply_lod_table(w);
    w->gpu_ready = admit(w) && world_colliders_make(&w->colliders, &w->scene);
    stage_done(w, WORLD_STAGE_TERRAIN_GPU, &mark);
    /* The grass's programs build on the driver's threads while the
     * characters are loaded: made there, on a fresh H100 they were 2.5 s
     * of the world's first frame. */
    if (w->gpu_ready)
        grass_prefetch(&(grass_host_t){.scene = &w->scene, .terrain = &w->terrain_mesh, .reference = w->reference,
                                       .raster_samples = w->raster_samples});
    if (w->gpu_ready && !w->scene.character_count && !w->character_override &&
        (w->clip_override || w->character_height > 0.0f)) {
        core_log_error("%s: the scene has no characters and there is no --character",
                       w->clip_override ? "--clip" : "--character-height");
        w->input_error = true;
        w->gpu_ready = false;
    }
    if (w->gpu_ready && (w->scene.character_count || w->character_override)) {
        w->have_chars = character_set_make(&w->chars, &(character_set_desc_t){
                                                          .characters = w->scene.characters,
                                                          .count = w->scene.character_count,
                                                          .terrain = &w->terrain_mesh,
                                                          .capsules = WORLD_CHARACTER_CAPSULES,
                                                          .model_override = w->character_override,
                                                          .clip_override = w->clip_override,
                                                          .height_override = w->character_height,
                                                      });
        w->input_error = !w->have_chars;
        w->gpu_ready = w->have_chars;
    }
    stage_done(w, WORLD_STAGE_CHARACTERS, &mark);
    /* Again with the characters: their size (grass.cube_texel scales the
     * cube maps by it) and their sphere proxies in the blade physics. */
    if (w->gpu_ready && w->have_chars) w->gpu_ready = admit(w);
    if (w->gpu_ready) w->gpu_ready = make_grass(w, &mark);
    return w->gpu_ready;
}

/* Metres beyond every reach of the grass at which a world's characters
 * start to be posed less often: twice a tall character's bounding radius
 * and a step of a running one at 30 fps, many times over. */
#define WORLD_CHARACTER_LOD_MARGIN 16.0f

/* On a world, the characters beyond the reach of the tile window's
 * spheres and of the billboard ring, with WORLD_CHARACTER_LOD_MARGIN to
 * spare, are posed less often (character_set_view); elsewhere every
 * character at every step. */
static float character_lod_distance(const world_t *w)
{
    if (grass_pass_ground(&w->terrain_mesh) != GRASS_GROUND_WORLD) return 0.0f;
    float reach = grass_stats(w->grass).reach;
    if (grass_drivers(w->grass).billboards) reach = fmaxf(reach, w->scene.grass.canopy_distance + GRASS_CANOPY_FADE);
    return reach + WORLD_CHARACTER_LOD_MARGIN;
}

/* The step's colliders as the grass takes them: every analytic collider
 * (its mesh's vertex array has position at attribute 0 and normal at 1),
 * then every character as its proxy spheres and skinned mesh. */
static int grass_colliders(world_t *w, grass_collider_t *out, int max)
{
    static const grass_shape_t shapes[] = {[SCENE_COLLIDER_SPHERE] = GRASS_SHAPE_SPHERE,
                                           [SCENE_COLLIDER_CAPSULE] = GRASS_SHAPE_CAPSULE,
                                           [SCENE_COLLIDER_BOX] = GRASS_SHAPE_BOX};
    int n = 0;
    for (int i = 0; i < w->colliders.count && n < max; i++, n++) {
        const world_collider_t *c = &w->colliders.items[i];
        grass_collider_t *g = &out[n];
        *g = (grass_collider_t){.shape = shapes[c->desc.type], .radius = c->desc.radius, .length = c->desc.length,
                                .vao = c->vao, .index_type = GL_UNSIGNED_INT,
                                .index_count = (int32_t)c->mesh.index_count};
        memcpy(g->position, c->position, sizeof g->position);
        memcpy(g->half_extents, c->desc.half_extents, sizeof g->half_extents);
        mat4 m;
        glm_translate_make(m, (float *)c->position);
        memcpy(g->model, m, sizeof g->model);
    }
    for (int i = 0; w->have_chars && i < w->chars.count && n < max; i++, n++)
        out[n] = grass_character_collider_of(&w->chars.items[i]);
    return n;
}

/* Adds the CPU ms since *mark to update part k and restarts the mark. */
static void update_part(world_t *w, int k, double *mark)
{
    double now = plat_time();
    w->update_ms[k] += (now - *mark) * 1e3;
    *mark = now;
}

/* One step: colliders and characters move, then the grass takes them. */
void world_update(world_t *w, float t, float dt)
{
    static grass_collider_t colliders[COLLIDE_MAX_OBJECTS];
    w->time = t;
    double mark = plat_time();
    if (w->have_chars) {
        character_set_view(&w->chars, grass_drivers(w->grass).camera, character_lod_distance(w));
        character_set_update(&w->chars, t, dt);
    }
    if (!w->stepped && dt > 0.0f) {
        /* The first step sweeps too: the colliders on paths stood at t - dt
         * before it (a fast ball's first step would skip its path
         * otherwise: stability cases tunnelling, tunnelling_bb). */
        world_colliders_update(&w->colliders, &w->terrain_mesh, t - dt);
        grass_prime_colliders(w->grass, colliders, grass_colliders(w, colliders, COLLIDE_MAX_OBJECTS));
    }
    w->stepped = true;
    world_colliders_update(&w->colliders, &w->terrain_mesh, t);
    int n = grass_colliders(w, colliders, COLLIDE_MAX_OBJECTS);
    update_part(w, 0, &mark);
    grass_update(w->grass, colliders, n, t, dt);
    grass_stats_t st = grass_stats(w->grass);
    for (int k = 0; k < 3; k++) w->update_ms[1 + k] += st.update_ms[k];
    mark = plat_time();
}

void world_draw_objects(world_t *w, const grass_view_t *v, const gfx_target_t *target, const grass_draw_as_t *as)
{
    grass_draw_as_t part = as ? *as : (grass_draw_as_t){.mode = w->mode};
    part.parts = GRASS_PART_GROUND;
    grass_draw_target(w->grass, v, target, &part);
    world_colliders_draw(&w->colliders, v);
    if (w->have_chars) character_set_draw(&w->chars, v->viewproj, v->camera, v->sun);
    part.parts = GRASS_PART_GRASS;
    grass_draw_target(w->grass, v, target, &part);
}

void world_draw(world_t *w, const grass_view_t *v, const gfx_target_t *target)
{
    world_draw_objects(w, v, target, NULL);
}

void world_set_raster(world_t *w, bool compute)
{
    w->raster_compute = compute;
    w->scene.raster = compute ? SCENE_RASTER_COMPUTE : SCENE_RASTER_HW;
    if (w->grass) grass_set_raster(w->grass, compute);
}

int world_target_samples(const world_t *w)
{
    return w->grass ? grass_target_samples(w->grass) : (w->raster_compute ? 1 : w->scene.msaa);
}

bool world_fit_target(const world_t *w, gfx_target_t *t, const char *label)
{
    int samples = world_target_samples(w);
    if (t->fbo && t->samples == gfx_target_samples(samples)) return true;
    int tw = t->w, th = t->h;
    gfx_target_destroy(t);
    *t = gfx_target_make(&(gfx_target_desc_t){.w = tw, .h = th, .samples = samples, .label = label});
    if (!t->fbo) core_log_error("cannot make the %dx%d target '%s' with %d samples", tw, th, label, samples);
    return t->fbo != 0;
}

void world_set_mode(world_t *w, scene_mode_t mode)
{
    w->mode = mode;
    w->scene.mode = mode;
    if (w->grass) grass_set_mode(w->grass, (grass_mode_t)(mode + 1));
}

void world_destroy(world_t *w)
{
    if (!w) return;
    grass_destroy(w->grass);
    if (w->have_chars) character_set_destroy(&w->chars);
    world_colliders_destroy(&w->colliders);
    terrain_free(&w->terrain_mesh);
    free(w);
}

void world_view_make(grass_view_t *v, const cam_t *cam_in, int width, int height, float time, float dt)
{
    cam_t cam = *cam_in;
    cam.aspect = (float)width / (float)height;
    mat4 view, proj;
    cam_view(&cam, view);
    cam_proj(&cam, proj);
    grass_view_make(v, (const float *)view, (const float *)proj, width, height, time);
    /* the camera's own position and far plane, not their round trip through the matrices */
    glm_vec3_copy(cam.position, v->camera);
    v->far = cam.far;
    v->dt = dt;
}

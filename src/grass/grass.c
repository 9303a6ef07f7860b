/* grass: a field's lifecycle (grass.h): its scene and terrain (the host's
 * or its own), admission, what each mode makes and in which order, run-time
 * switches, the view, the stats, and what grass_harness.h hands in-tree
 * hosts and measures. */
#include "grass/grass_local.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "platform/plat.h"
#include "scene/scene_lod.h"

_Static_assert(ADMIT_RASTER_QUEUE_LAYERS == RASTER_QUEUE_LAYERS, "admit's raster queue estimate");
_Static_assert(ADMIT_MAX_OBJECTS == COLLIDE_MAX_OBJECTS, "admit's object count is a collide set's");
_Static_assert(GRASS_MAX_COLLIDERS == COLLIDE_MAX_OBJECTS, "grass.h's collider count is a collide set's");
_Static_assert(ADMIT_MAX_SPHERES == BLADE_MAX_SPHERES, "admit's sphere count is the blade physics'");
_Static_assert(SCENE_MAX_WIND <= BLADE_MAX_WINDS, "every scene wind reaches the blade physics");

static _Thread_local int last_error;
int grass_last_error(void) { return last_error; }

gfx_ctx_t *grass_enter(const grass_t *g)
{
    gfx_ctx_t *prev = gfx_ctx_current();
    if (g->gfx) gfx_ctx_bind(g->gfx);
    return prev;
}

void grass_leave(gfx_ctx_t *prev) { gfx_ctx_bind(prev); }

grass_ground_t grass_ground_of(const grass_t *g) { return grass_pass_ground(g->terrain); }

bool grass_uses_tiles(const grass_t *g) { return grass_pass_uses_tiles(g->mode, grass_ground_of(g), g->reference); }

float grass_tiles_distance(const grass_t *g)
{
    return grass_pass_tiles_distance(&g->scene->grass, g->mode, grass_ground_of(g), g->reference);
}

uint32_t grass_placement_seed(const grass_t *g)
{
    return g->tuning.placement_seed ? g->tuning.placement_seed : g->scene->seed;
}

float grass_collider_reach(const grass_t *g)
{
    if (grass_ground_of(g) != GRASS_GROUND_WORLD || !g->tiles) return 0.0f;
    blade_tiles_info_t ti = blade_tiles_info(g->tiles);
    return (0.5f * (float)ti.desc.window + 1.0f) * ti.desc.tile_size * 1.4142136f + ti.reach;
}

bool grass_admit(const grass_admit_t *a, admit_t *out, char *err, size_t err_size)
{
    gfx_limits_t gl = gfx_limits();
    admit_limits_t lim = {.max_texture_size = gl.max_texture_size,
                          .max_renderbuffer_size = gl.max_renderbuffer_size,
                          .max_gs_vertices = gl.max_gs_vertices,
                          .max_gs_components = gl.max_gs_components,
                          .max_compute_groups = gl.max_compute_groups,
                          .gpu_bytes = 0.9 * gl.gpu_bytes,
                          .host_bytes = admit_host_bytes()};
    grass_ground_t ground = grass_pass_ground(a->terrain);
    bool tiles = grass_pass_uses_tiles(a->mode, ground, a->reference);
    bool blades = grass_pass_wants_blades(a->mode);
    admit_world_t aw = {.terrain = a->terrain,
                        .terrain_area = admit_terrain_area(a->terrain),
                        .billboards = grass_pass_wants_billboards(a->mode, a->scene->grass.billboards) &&
                                      !a->reference,
                        .tiles = tiles,
                        .tiles_distance = grass_pass_tiles_distance(&a->scene->grass, a->mode, ground,
                                                                    a->reference),
                        .full_field = !tiles && (blades || a->reference),
                        .raster = a->scene->raster != SCENE_RASTER_HW,
                        .target_samples = gfx_target_samples(a->target_samples),
                        .size_option = a->size_option,
                        .collider_radius = a->collider_radius,
                        .max_texture_size = gl.max_texture_size,
                        .objects = a->objects,
                        .collider_spheres = a->collider_spheres,
                        .character_spheres = a->character_spheres,
                        .characters = a->characters};
    admit_estimate(a->scene, &aw, out);
    return admit_check(a->scene, &aw, &lim, err, err_size);
}

void grass_lod_table_apply(scene_desc_t *s, char *note, size_t note_size)
{
    bool compute = s->raster == SCENE_RASTER_COMPUTE;
    if (s->grass.lod_table[0] && s->mode == SCENE_MODE_HYBRID &&
        scene_lod_apply(s, (const char *)glGetString(GL_RENDERER), &compute, note, note_size) &&
        s->raster == SCENE_RASTER_AUTO)
        s->raster = compute ? SCENE_RASTER_COMPUTE : SCENE_RASTER_HW;
}

/* A field of its own: the scene file (default scenes/meadow.json) with
 * desc's overrides, its terrain, grass.lod_table and admission. Returns 0,
 * 1 or 2 as grass_last_error. */
static int load_own(grass_t *g, const grass_desc_t *d)
{
    char err[1024];
    const char *scene = d->scene ? d->scene : "scenes/meadow.json";
    if (scene[0] == '/' || !core_fs_resolve(scene, g->scene_path, sizeof g->scene_path))
        snprintf(g->scene_path, sizeof g->scene_path, "%s", scene);
    scene_desc_t *s = &g->own_scene;
    if (!scene_load(s, g->scene_path, err, sizeof err)) return 2; /* logged */
    if (d->seed) s->seed = d->seed;
    if (d->mode) s->mode = (scene_mode_t)(d->mode - 1);
    if (d->raster) s->raster = d->raster == 2 ? SCENE_RASTER_COMPUTE : SCENE_RASTER_HW;
    if (d->width > 0 && d->height > 0) {
        s->size[0] = d->width;
        s->size[1] = d->height;
    }
    g->scene = s;
    bool ok = s->terrain.type == TERRAIN_MESH
                  ? terrain_load_mesh(&g->own_terrain, s->terrain.mesh, s->terrain.scale, err, sizeof err)
                  : terrain_make_heightfield(&g->own_terrain, &s->terrain, s->seed);
    if (!ok) {
        core_log_error("%s: terrain: %s", g->scene_path, s->terrain.type == TERRAIN_MESH ? err : "cannot build it");
        return 2;
    }
    g->terrain = &g->own_terrain;
    grass_lod_table_apply(s, g->lod_note, sizeof g->lod_note);
    /* `raster: auto` is the program's measure at start-up; a host that
     * does not choose (desc.raster) gets the hardware path. */
    if (s->raster == SCENE_RASTER_AUTO) s->raster = SCENE_RASTER_HW;
    g->collider_radius = d->collider_radius > 0.0f ? d->collider_radius : 2.0f;
    g->objects = d->max_colliders > 0 ? d->max_colliders : 8;
    admit_t admitted;
    grass_admit_t a = {.scene = s, .terrain = g->terrain, .mode = s->mode, .target_samples = s->msaa,
                       .collider_radius = g->collider_radius, .objects = g->objects};
    if (admit_tiles_check(s, g->terrain, err, sizeof err) && grass_admit(&a, &admitted, err, sizeof err)) return 0;
    core_log_error("%s: %s", g->scene_path, err);
    return 2;
}

/* What every mode needs: the scene's clearings image, the ground, the
 * global illumination; then the grass of g's mode. stage_ms: ground,
 * billboards, blades. */
static bool make_gpu(grass_t *g, double stage_ms[3])
{
    double mark = plat_time();
    const scene_desc_t *s = g->scene;
    const scene_clearings_desc_t *cl = &s->grass.clearings;
    if (cl->type == SCENE_CLEARINGS_IMAGE) {
        char image[1024];
        if (!core_fs_resolve(cl->image, image, sizeof image)) {
            core_log_error("%s: grass.clearings.image: cannot find \"%s\"", g->scene_path, cl->image);
            last_error = 2;
            return false;
        }
        if (!core_image_load(&g->clearings_image, image, 1)) { /* logged: the file and why */
            last_error = 2;
            return false;
        }
    }
    g->raster_compute = s->raster == SCENE_RASTER_COMPUTE;
    if (!(g->ground = ground_make(g->terrain))) return false;
    if (s->grass.gi && !grass_gi_make(g)) return false;
    g->cube_res = grass_cube_resolution(g);
    stage_ms[0] = (plat_time() - mark) * 1e3;
    mark = plat_time();
    if (grass_pass_wants_billboards(g->mode, s->grass.billboards) && !g->reference &&
        !(grass_make_billboards(g) && grass_ring_make_canopy(g)))
        return false;
    stage_ms[1] = (plat_time() - mark) * 1e3;
    mark = plat_time();
    grass_make_blade_env(g);
    bool ok = true;
    if (grass_uses_tiles(g)) ok = grass_make_tiles(g);
    else if (grass_pass_wants_blades(g->mode) || g->reference) ok = grass_make_blades(g);
    stage_ms[2] = (plat_time() - mark) * 1e3;
    return ok;
}

void grass_prefetch(const grass_host_t *h)
{
    const scene_desc_t *s = h->scene;
    grass_ground_t ground = grass_pass_ground(h->terrain);
    bool tiles = grass_pass_uses_tiles(s->mode, ground, h->reference);
    raster_desc_t rd = {.samples = h->raster_samples ? h->raster_samples : s->raster_samples};
    bool raster = s->raster != SCENE_RASTER_HW;
    if (raster && (tiles || grass_pass_wants_blades(s->mode) || h->reference)) blade_raster_prefetch(&rd, s->grass.gi);
    if (tiles) blade_tiles_prefetch(h->terrain);
}

static void log_to_host(int severity, const char *line, void *user)
{
    const grass_io_t *io = user;
    io->log(severity, line, io->user);
}

grass_t *grass_make(const grass_desc_t *d)
{
    last_error = 1;
    grass_t *g = calloc(1, sizeof *g);
    if (!g) return NULL;
    g->io = d->io;
    if (g->io.log) core_log_set_sink(log_to_host, &g->io);
    const grass_host_t *h = d->host;
    if (h) {
        g->scene = h->scene;
        g->terrain = h->terrain;
        snprintf(g->scene_path, sizeof g->scene_path, "%s", h->scene_path ? h->scene_path : "scene");
        g->tuning = h->tuning;
        g->reference = h->reference;
        g->collider_radius = d->collider_radius;
        g->objects = d->max_colliders > 0 ? d->max_colliders : 1;
    } else {
        /* A host of the library: gfx state of its own, not the host's. */
        if (!(g->gfx = gfx_ctx_make(NULL))) {
            free(g);
            return NULL;
        }
        gfx_ctx_t *prev = grass_enter(g);
        int rc = load_own(g, d);
        grass_leave(prev);
        if (rc) {
            grass_destroy(g);
            last_error = rc;
            return NULL;
        }
    }
    if (h && d->mode) g->scene->mode = (scene_mode_t)(d->mode - 1);
    g->mode = g->scene->mode;
    g->raster_samples = h && h->raster_samples ? h->raster_samples : g->scene->raster_samples;
    double stage_ms[3] = {0};
    gfx_ctx_t *prev = grass_enter(g);
    bool made = make_gpu(g, stage_ms);
    grass_leave(prev);
    if (!made) {
        int rc = last_error;
        grass_destroy(g);
        last_error = rc;
        return NULL;
    }
    memcpy(g->make_ms, stage_ms, sizeof g->make_ms);
    /* Until the first draw, the scene's camera at t = 0 decides which
     * tiles are near. */
    cam_t cam;
    scene_camera_init(g->scene, &cam);
    memcpy(g->camera, cam.position, sizeof g->camera);
    last_error = 0;
    return g;
}

void grass_destroy(grass_t *g)
{
    if (!g) return;
    if (g->io.log) core_log_set_sink(NULL, NULL);
    gfx_ctx_t *prev = grass_enter(g);
    bb_field_destroy(g->bb);
    blade_gpu_destroy(g->blades);
    gfx_texture_destroy(&g->blade_extent);
    blade_tiles_destroy(g->tiles);
    raster_destroy(&g->raster);
    gfx_target_destroy(&g->host_depth);
    gi_gpu_destroy(&g->gi);
    ground_destroy(g->ground);
    if (g->terrain == &g->own_terrain) terrain_free(&g->own_terrain);
    core_image_free(&g->clearings_image);
    grass_leave(prev);
    gfx_ctx_destroy(g->gfx, false);
    free(g);
}

void grass_set_mode(grass_t *g, grass_mode_t mode)
{
    if (mode == GRASS_MODE_SCENE) return;
    gfx_ctx_t *prev = grass_enter(g);
    g->mode = g->scene->mode = (scene_mode_t)(mode - 1);
    if (grass_pass_wants_billboards(g->mode, g->scene->grass.billboards) && !g->bb && !g->reference &&
        grass_make_billboards(g))
        grass_ring_make_canopy(g);
    if (grass_uses_tiles(g) && !g->have_tiles) grass_make_tiles(g);
    else if (grass_pass_wants_blades(g->mode) && !grass_uses_tiles(g) && !g->have_blades) grass_make_blades(g);
    grass_leave(prev);
}

void grass_set_raster(grass_t *g, bool compute)
{
    g->raster_compute = compute;
    g->scene->raster = compute ? SCENE_RASTER_COMPUTE : SCENE_RASTER_HW;
}

grass_stats_t grass_stats(const grass_t *g)
{
    grass_stats_t s = {.mode = (grass_mode_t)(g->mode + 1),
                       .compute = g->raster_compute,
                       .canopy = g->ground && ground_has_canopy(g->ground),
                       .reach = grass_collider_reach(g),
                       .lod_note = g->lod_note};
    memcpy(s.update_ms, g->update_ms, sizeof s.update_ms);
    memcpy(s.make_ms, g->make_ms, sizeof s.make_ms);
    return s;
}

void grass_view_make(grass_view_t *v, const float view[16], const float proj[16], int width, int height, float time)
{
    *v = (grass_view_t){.width = width, .height = height, .time = time};
    memcpy(v->view, view, sizeof v->view);
    memcpy(v->proj, proj, sizeof v->proj);
    mat4 vw, pr, vp, inv;
    memcpy(vw, view, sizeof vw);
    memcpy(pr, proj, sizeof pr);
    glm_mat4_mul(pr, vw, vp);
    glm_mat4_inv(vp, inv);
    memcpy(v->viewproj, vp, sizeof v->viewproj);
    memcpy(v->inv_viewproj, inv, sizeof v->inv_viewproj);
    vec4 planes[6]; /* cglm's aligned vectors */
    cam_frustum_planes(vp, planes);
    memcpy(v->planes, planes, sizeof v->planes);
    mat4 eye;
    glm_mat4_inv(vw, eye);
    memcpy(v->camera, eye[3], sizeof v->camera);
    /* perspective: proj[2][2] = -(f + n) / (f - n), proj[3][2] = -2 f n / (f - n) */
    v->far = pr[3][2] / (pr[2][2] + 1.0f);
    glm_vec3_normalize_to((vec3)GRASS_SUN_DIR, v->sun);
}

grass_drivers_t grass_drivers(grass_t *g)
{
    return (grass_drivers_t){.billboards = g->bb,
                             .blades = g->have_blades ? g->blades : NULL,
                             .tiles = g->have_tiles ? g->tiles : NULL,
                             .raster = &g->raster,
                             .blade_env = &g->blade_env,
                             .collide = &g->collide,
                             .camera = g->camera};
}

int grass_target_samples(const grass_t *g) { return g->raster_compute ? 1 : g->scene->msaa; }
void grass_set_camera(grass_t *g, const float camera[3]) { memcpy(g->camera, camera, sizeof g->camera); }

bool grass_canopy_match(const grass_t *g, ground_match_state_t *out)
{
    if (!g->ground || !ground_has_canopy(g->ground)) return false;
    ground_match_state(g->ground, out);
    return true;
}

void grass_canopy_match_reset(grass_t *g)
{
    if (g->ground) ground_match_reset(g->ground);
}

blade_tiles_t *grass_swap_tiles(grass_t *g, blade_tiles_t *tiles)
{
    blade_tiles_t *old = g->tiles;
    g->tiles = tiles;
    return old;
}

bb_field_t *grass_swap_billboards(grass_t *g, bb_field_t *field)
{
    bb_field_t *old = g->bb;
    g->bb = field;
    return old;
}

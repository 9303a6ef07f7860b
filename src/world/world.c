/* world: loads the scene and builds, updates and draws every system it
 * needs (terrain, colliders, characters, billboards, blades). Used by the
 * main loop, `meadow bench` and `meadow compare` alike (world.h). */
#include "world/world_local.h"

#include <math.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "admit/admit.h"
#include "core/core.h"
#include "platform/plat.h"
#include "scene/scene_lod.h"
#include "world/world_pass.h"

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
    float canopy_min = s->grass.switch_distance + WORLD_SWITCH_FADE + WORLD_CANOPY_FADE;
    /* Without billboards the canopy starts where the blades end (grass.billboards none). */
    if (s->grass.billboards == SCENE_HYBRID_BILLBOARDS_RING && s->grass.canopy_distance < canopy_min) {
        core_log_error("%s: grass.canopy_distance %g is less than grass.switch_distance + %g (%g): the blades' and "
                       "the canopy's fade bands would overlap",
                       w->scene_path, s->grass.canopy_distance, WORLD_SWITCH_FADE + WORLD_CANOPY_FADE, canopy_min);
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
    const scene_clearings_desc_t *cl = &s->grass.clearings;
    if (cl->type == SCENE_CLEARINGS_IMAGE) {
        char image[1024];
        if (!core_fs_resolve(cl->image, image, sizeof image)) {
            core_log_error("%s: grass.clearings.image: cannot find \"%s\"", w->scene_path, cl->image);
            return 2;
        }
        if (!core_image_load(&w->clearings_image, image, 1)) return 2; /* logged: the file and why */
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

/* The layout shared by both grass models (so hybrid tiles cover the same
 * ground): one layout texel per billboard candidate cell over the terrain,
 * so the extent map's clearings are sized relative to the field. */
static int layout_for(const world_t *w, bb_gen_desc_t *gen)
{
    const scene_grass_desc_t *g = &w->scene.grass;
    float extent = fmaxf(w->terrain_mesh.aabb_max[0] - w->terrain_mesh.aabb_min[0],
                         w->terrain_mesh.aabb_max[2] - w->terrain_mesh.aabb_min[2]);
    int cells = (int)ceilf(extent * sqrtf(g->billboard_density));
    int layout_size = ((cells + 15) / 16) * 16;
    layout_size = layout_size < 32 ? 32 : (layout_size > 1024 ? 1024 : layout_size);
    *gen = bb_gen_desc_defaults(&(bb_gen_desc_t){.spacing = 1.0f / sqrtf(g->billboard_density),
                                                 .origin = {w->terrain_mesh.aabb_min[0], w->terrain_mesh.aabb_min[2]},
                                                 .seed = w->scene.seed});
    return layout_size;
}

/* The extent map's clearings (grass.clearings) on the layout of gen's
 * cells: the blob size in texels, the image stretched over the terrain's
 * xz box (the layout's origin is its corner). */
static bb_extent_desc_t extent_desc(const world_t *w, const bb_gen_desc_t *gen)
{
    static const bb_clearings_t kinds[] = {[SCENE_CLEARINGS_NOISE] = BB_CLEARINGS_NOISE,
                                           [SCENE_CLEARINGS_NONE] = BB_CLEARINGS_NONE,
                                           [SCENE_CLEARINGS_IMAGE] = BB_CLEARINGS_IMAGE};
    const scene_clearings_desc_t *c = &w->scene.grass.clearings;
    const float *lo = w->terrain_mesh.aabb_min, *hi = w->terrain_mesh.aabb_max;
    float texel = gen->spacing * (float)gen->cells_per_texel;
    bool image = c->type == SCENE_CLEARINGS_IMAGE;
    return (bb_extent_desc_t){.clearings = kinds[c->type],
                              .fraction = c->fraction,
                              .feature = c->size / texel,
                              .image = image ? &w->clearings_image : NULL,
                              .image_texels = {image ? (hi[0] - lo[0]) / texel : 0.0f,
                                               image ? (hi[2] - lo[2]) / texel : 0.0f}};
}

/* The shared layout's extent map alone (the clump texture is the billboard
 * field's business): one tiny clump layer is enough for bb_layout. */
bool world_extent_layout(const world_t *w, bb_layout_t *lay, bb_gen_desc_t *gen)
{
    int size = layout_for(w, gen);
    return bb_layout_generate(lay, &(bb_layout_desc_t){.seed = w->scene.seed, .size = size, .clump_layers = 1,
                                                        .clump_size = 8, .blades = 1, .extent_only = true,
                                                        .extent = extent_desc(w, gen)});
}

/* Thins seeded blades by the extent map with the billboards' acceptance
 * rule (accept with probability E/255, see bb_layout.h), so both
 * representations share clearings and density ratio. A rejected blade gets
 * height and width 0: the physics and culling skip it like patch padding,
 * and the patch layout stays intact. */
static size_t thin_blades_by_extent(const world_t *w, const bb_layout_t *lay, const bb_gen_desc_t *g,
                                    blade_field_t *field)
{
    bb_gen_desc_t gen = *g;
    const core_image_t *ex = &lay->extent;
    size_t dropped = 0;
    for (size_t i = 0; i < field->blade_count; i++) {
        blade_t *b = &field->blades[i];
        int ix = (int)floorf((b->v0[0] - gen.origin[0]) / gen.spacing);
        int iz = (int)floorf((b->v0[2] - gen.origin[1]) / gen.spacing);
        int tx = ((ix / gen.cells_per_texel) % ex->w + ex->w) % ex->w;
        int tz = ((iz / gen.cells_per_texel) % ex->h + ex->h) % ex->h;
        uint32_t e = ex->px[(size_t)tz * (size_t)ex->w + (size_t)tx];
        if (core_hash_u32((uint32_t)i ^ core_hash_u32(world_placement_seed(w) ^ 0x5bd1e995u)) % 255u >= e) {
            b->v1[3] = 0.0f;
            b->v2[3] = 0.0f;
            dropped++;
        }
    }
    return dropped;
}

/* Blade mode's grass-shaded ground (ground_set_lod): the canopy table and
 * the extent map that thinned the blades (NULL: none, the ground canopy
 * unthinned). */
static void blade_mode_canopy(world_t *w, const bb_layout_t *lay, const bb_gen_desc_t *gen)
{
    blade_canopy_t canopy;
    if (!blade_canopy_make(&canopy, &(blade_canopy_desc_t){.population = w->scene.grass.population,
                                                           .seed = w->scene.seed,
                                                           .sun = WORLD_SUN_DIR}))
        return;
    float origin[2] = {0.0f, 0.0f}, spacing = 1.0f;
    if (lay) {
        w->blade_extent = gfx_texture_make(&(gfx_texture_desc_t){.w = lay->extent.w, .h = lay->extent.h,
                                                                 .format = GL_R8, .filter = GL_NEAREST,
                                                                 .data = lay->extent.px, .upload_format = GL_RED,
                                                                 .label = "blades.extent"});
        memcpy(origin, gen->origin, sizeof origin);
        spacing = gen->spacing * (float)gen->cells_per_texel;
    }
    ground_set_canopy(w->ground, &canopy, w->blade_extent.id, origin, spacing);
}

/* Largest bounding radius of a collider or character (grass.cube_texel). */
static float largest_object_radius(world_t *w)
{
    float r = 0.0f;
    for (int i = 0; i < w->scene.collider_count; i++) r = fmaxf(r, collide_bounding_radius(&w->scene.colliders[i]));
    if (w->have_chars) {
        character_object_t co[COLLIDE_MAX_OBJECTS];
        int n = character_set_objects(&w->chars, co, COLLIDE_MAX_OBJECTS);
        for (int i = 0; i < n && i < COLLIDE_MAX_OBJECTS; i++) r = fmaxf(r, co[i].radius);
    }
    return r;
}

/* The collision cube-map side: grass.cube_resolution, raised (grass.cube_texel
 * > 0) until the largest collider or character, of bounding radius r, has
 * texels 2 r / res no larger than cube_texel (large_bb in the stability
 * suite: a 4 m ball at 16 texels had 0.5 m texels). Capped where the cube
 * render target (res x 6 res) exceeds the GL's texture size, with a warning. */
static int cube_resolution_for(world_t *w)
{
    const scene_grass_desc_t *g = &w->scene.grass;
    int res = g->cube_resolution;
    if (g->cube_texel <= 0.0f) return res;
    float r = largest_object_radius(w);
    int want = (int)ceilf(2.0f * r / g->cube_texel);
    GLint max_size = 4096;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    int cap = max_size / 6;
    if (want > cap) {
        core_log_warn("grass.cube_texel %g m needs %d texels per cube face for a collider of radius %g m; the GL "
                      "allows %d: texels stay %g m",
                      (double)g->cube_texel, want, (double)r, cap, (double)(2.0f * r / (float)cap));
        want = cap;
    }
    if (want > res) {
        core_log_info("collision cube maps: %d texels per face (grass.cube_texel %g m, largest collider radius "
                      "%g m; grass.cube_resolution %d)",
                      want, (double)g->cube_texel, (double)r, res);
        res = want;
    }
    return res;
}

/* The billboard field's desc (world_build_billboards; placement: its
 * placement seed). */
static bb_field_desc_t billboard_desc(const world_t *w, uint32_t placement)
{
    const scene_desc_t *s = &w->scene;
    const scene_grass_desc_t *g = &s->grass;
    bb_wind_desc_t wind = {0};
    float wind_strength = 0.0f; /* the clump bakes' blades settle under its mean */
    if (s->wind_count && s->wind[0].type == SCENE_WIND_DIRECTIONAL) {
        const scene_wind_t *sw = &s->wind[0];
        wind = bb_wind_from_wave(sw->direction[0], sw->direction[1], sw->strength, sw->wavelength, sw->speed);
        wind_strength = sw->strength;
    }
    bb_gen_desc_t gen;
    int layout_size = layout_for(w, &gen);
    int objects = w->colliders.count + (w->have_chars ? character_set_count(&w->chars) : 0);
    if (objects > BB_MAX_OBJECTS) objects = BB_MAX_OBJECTS;
    return (bb_field_desc_t){
        .terrain = &w->terrain_mesh,
        .seed = s->seed,
        .placement_seed = placement,
        .density = g->billboard_density,
        .size = {g->billboard_size[0], g->billboard_size[1]},
        .subdiv = {g->subdiv[0], g->subdiv[1]},
        .gi = g->gi,
        .occlusion = g->bb_occlusion,
        .iterations = g->spring_iterations,
        .paper = w->tuning.paper,
        .max_deformed = g->deformed_pool,
        .cube_res = w->cube_res,
        .recover_time = g->recover_time,
        .max_objects = objects > 0 ? objects : 1,
        /* a world's ring (bb_ring.h) holds billboards out to the canopy's band */
        .ring_reach = g->canopy_distance + WORLD_CANOPY_FADE,
        .wind = wind,
        .layout = {.size = layout_size,
                   .blades = bb_clump_blades(g->population.density, g->billboard_density),
                   .clump = {.population = g->population,
                             .wind = wind_strength,
                             .wind_dir = {wind.dir[0], wind.dir[1]}},
                   .extent = extent_desc(w, &gen),
                   .views = {.on = w->tuning.view_cards}},
    };
}

bb_field_t *world_build_billboards(const world_t *w, uint32_t placement)
{
    bb_field_desc_t d = billboard_desc(w, placement);
    return bb_field_make(&d);
}

static bool make_bb(world_t *w)
{
    w->bb = world_build_billboards(w, w->tuning.placement_seed);
    return w->bb != NULL;
}

static bool on_world(const world_t *w) { return w->terrain_mesh.type == TERRAIN_WORLD; }
static world_ground_t ground_of(const world_t *w)
{
    if (on_world(w)) return WORLD_GROUND_WORLD;
    return w->terrain_mesh.grid_res > 0 ? WORLD_GROUND_HEIGHTFIELD : WORLD_GROUND_MESH;
}
/* What the world makes and draws: the rules of world_pass.h for its ground
 * (a world streams tiles and the billboard ring, the canopy beyond; blade
 * mode off a world and the reference
 * simulate every blade of the field, as the paper). */
static bool wants_bb(const world_t *w, scene_mode_t m)
{
    return world_pass_wants_billboards(m, w->scene.grass.billboards);
}
static bool wants_blades(scene_mode_t m) { return world_pass_wants_blades(m); }
static bool uses_tiles(const world_t *w) { return world_pass_uses_tiles(w->mode, ground_of(w), w->reference); }

/* How far the tiles draw blades: the switch distance, or on a world in
 * blade mode grass.blade_distance (default WORLD_BLADE_DISTANCE). */
static float tiles_distance(const world_t *w)
{
    const scene_grass_desc_t *g = &w->scene.grass;
    if (!on_world(w) || w->mode != SCENE_MODE_BLADE) return g->switch_distance;
    return g->blade_distance > 0.0f ? g->blade_distance : WORLD_BLADE_DISTANCE;
}

static bool make_blades(world_t *w)
{
    const scene_desc_t *s = &w->scene;
    const scene_grass_desc_t *g = &s->grass;
    const terrain_mesh_t *t = &w->terrain_mesh;
    blade_field_t field;
    blade_mesh_t mesh = {.positions = t->positions, .normals = t->normals, .vertex_count = t->vertex_count,
                         .indices = t->indices, .index_count = t->index_count};
    blade_seed_desc_t sd = {.seed = world_placement_seed(w),
                            .population = g->population,
                            .max_blades = ADMIT_MAX_FIELD_BLADES};
    if (!blade_seed_mesh(&mesh, &sd, &field)) return false;
    bb_gen_desc_t gen;
    bb_layout_t lay;
    bool have_layout = w->scene.terrain.type == TERRAIN_HEIGHTFIELD && world_extent_layout(w, &lay, &gen);
    size_t dropped = have_layout ? thin_blades_by_extent(w, &lay, &gen, &field) : 0;
    if (!w->reference && !ground_has_canopy(w->ground)) blade_mode_canopy(w, have_layout ? &lay : NULL, &gen);
    if (have_layout) bb_layout_free(&lay);
    blade_gpu_desc_t gd = {.field = &field, .shape = g->population.shape, .label = "blades",
                           .displacement = g->displacement, .width_correction = g->width_correction,
                           .path = g->blade_render == SCENE_BLADE_RENDER_TESS ? BLADE_PATH_TESSELLATION
                                                                              : BLADE_PATH_PULLING};
    if (w->tuning.tess_max) gd.max_tess_level = w->tuning.tess_max;
    if (w->reference) {
        gd.max_tess_level = 16;
        gd.no_patch_cull = true;
    }
    w->blades = blade_gpu_make(&gd);
    w->have_blades = w->blades != NULL;
    core_log_info("blades: %zu blades in %zu patches (%zu in clearings of the extent map)",
                  field.blade_count - dropped, field.patch_count, dropped);
    blade_field_free(&field);
    return w->have_blades;
}

_Static_assert(SCENE_MAX_WIND <= BLADE_MAX_WINDS, "every scene wind reaches the blade physics");

/* The blade environment shared by the full field and the tiles. */
static void make_blade_env(world_t *w)
{
    const scene_desc_t *s = &w->scene;
    const scene_grass_desc_t *g = &s->grass;
    /* A push of a tenth of the mean height counts fully towards eta, and
     * eta decays over the scene's recover time: a trail stays down about
     * that long, like the billboards' (departure from the paper's k = 1,
     * see blade_env_t.collision_gain). */
    blade_population_t pop = blade_population_defaults(&g->population);
    float h = 0.5f * (pop.height[0] + pop.height[1]);
    w->blade_env = (blade_env_t){.gravity = pop.gravity,
                                 .collision_gain = 1.0f / (0.01f * h * h),
                                 .collision_decay = 1.0f / g->recover_time};
    if (w->tuning.paper) {
        w->blade_env.paper = true;
        w->blade_env.length_mode = BLADE_LENGTH_PAPER;
        w->blade_env.collision_gain = 1.0f;
    }
    for (int i = 0; i < s->wind_count && i < BLADE_MAX_WINDS; i++) {
        const scene_wind_t *sw = &s->wind[i];
        w->blade_env.winds[w->blade_env.wind_count++] =
            sw->type == SCENE_WIND_POINT
                ? blade_wind_point(sw->position, sw->strength, sw->radius)
                : blade_wind_wave(sw->direction[0], sw->direction[1], sw->strength, sw->wavelength, sw->speed);
    }
}

/* Billboards -> blades hand-over: the deformed billboards of the moment
 * seed the blades of tiles turning to blades (blade_tiles.h). */
static void bb_slope_source(void *user, const hybrid_slope_grid_t *grid, gfx_buffer_t sums)
{
    world_t *w = user;
    if (w->bb) bb_field_add_slopes(w->bb, grid, sums);
}

/* The canopy table (GL-free; its rows computed in parallel, 211 ms on 2
 * cores) runs on a thread of its own while the layout and the tiles are
 * made. */
typedef struct canopy_job_t {
    blade_canopy_desc_t desc;
    blade_canopy_t canopy;
    bool ok;
} canopy_job_t;

static void *canopy_thread(void *user)
{
    canopy_job_t *job = user;
    job->ok = blade_canopy_make(&job->canopy, &job->desc);
    return NULL;
}

static bool make_tiles(world_t *w)
{
    const scene_desc_t *s = &w->scene;
    const scene_grass_desc_t *g = &s->grass;
    canopy_job_t job = {.desc = {.population = g->population,
                                 .seed = s->seed,
                                 .sun = WORLD_SUN_DIR}};
    pthread_t thread;
    bool threaded = pthread_create(&thread, NULL, canopy_thread, &job) == 0;
    blade_tiles_desc_t td = {.terrain = &w->terrain_mesh,
                             .tile_size = g->tile_size,
                             .population = g->population,
                             .seed = s->seed,
                             .switch_distance = tiles_distance(w),
                             .pool_slots = g->tile_pool,
                             .displacement = g->displacement,
                             .width_correction = g->width_correction,
                             .tessellate = g->blade_render == SCENE_BLADE_RENDER_TESS,
                             .wind_count = w->blade_env.wind_count,
                             .cull = {.max_distance = tiles_distance(w) + 1.0f, .lod = g->lod,
                                      .focal_px = scene_focal(s)},
                             .slope_recover = g->recover_time,
                             .label = "tiles"};
    memcpy(td.winds, w->blade_env.winds, sizeof td.winds);
    /* The billboards' extent map thins the tiles too (same clearings). */
    bb_gen_desc_t gen;
    bb_layout_t lay;
    bool have_layout = world_extent_layout(w, &lay, &gen);
    if (have_layout) {
        td.extent = &lay.extent;
        memcpy(td.extent_origin, gen.origin, sizeof td.extent_origin);
        td.extent_spacing = gen.spacing * (float)gen.cells_per_texel;
        td.extent_seed = s->seed;
    }
    w->tiles = blade_tiles_make(&td);
    w->have_tiles = w->tiles != NULL;
    if (w->have_tiles) blade_tiles_set_slope_source(w->tiles, bb_slope_source, w);
    /* The ground canopy beyond the billboards, thinned by the tiles' extent
     * map (its texture). */
    if (threaded) pthread_join(thread, NULL);
    else canopy_thread(&job);
    if (w->have_tiles && job.ok)
        ground_set_canopy(w->ground, &job.canopy, blade_tiles_info(w->tiles).extent_texture,
                               td.extent_origin, td.extent_spacing);
    if (have_layout) bb_layout_free(&lay);
    return w->have_tiles;
}

/* Collider i's sweep (previous - current centre) from this step's collide
 * set: the colliders are its first objects (add_objects) and only
 * translate, so every sphere of their proxies moves by the same vector. */
static void collider_sweep(const world_t *w, int i, float out[4])
{
    const collide_object_t *o = i < w->collide.object_count ? &w->collide.objects[i] : NULL;
    for (int k = 0; k < 3; k++) out[k] = o ? o->prev_position[k] - o->position[k] : 0.0f;
    out[3] = 0.0f;
}

/* On a world, the horizontal distance from the camera within which a
 * character's proxy spheres can touch the tile window: the window's half
 * diagonal and the blades' reach (docs/WORLD.md); 0 elsewhere (all). */
static float tiles_sphere_reach(const world_t *w)
{
    if (!on_world(w) || !w->tiles) return 0.0f;
    blade_tiles_info_t ti = blade_tiles_info(w->tiles);
    return (0.5f * (float)ti.desc.window + 1.0f) * ti.desc.tile_size * 1.4142136f + ti.reach;
}

/* The characters' proxy spheres (already swept by character_set_update:
 * each holds its previous and current pose) appended to out[n..max); on a
 * world only those within tiles_sphere_reach. */
static int character_spheres(world_t *w, blade_sphere_t *out, int n, int max)
{
    static float packed[BLADE_MAX_SPHERES][4];
    float reach = tiles_sphere_reach(w);
    int room = max - n, want = character_set_spheres_near(&w->chars, w->camera, reach, packed, room);
    for (int k = 0; k < room && k < want; k++)
        out[n + k] = (blade_sphere_t){.centre_radius = {packed[k][0], packed[k][1], packed[k][2], packed[k][3]}};
    return want;
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
    if (!on_world(w)) return 0.0f;
    float reach = tiles_sphere_reach(w);
    if (w->bb) reach = fmaxf(reach, w->scene.grass.canopy_distance + WORLD_CANOPY_FADE);
    return reach + WORLD_CHARACTER_LOD_MARGIN;
}

/* Sphere proxies for the blade physics (collide_pack_spheres per collider,
 * with its sweep, then the characters'). Admission (admit) keeps them
 * within BLADE_MAX_SPHERES. */
static int blade_spheres(world_t *w, blade_sphere_t *out, int max)
{
    static float packed[BLADE_MAX_SPHERES][4];
    int n = 0;
    bool full = false;
    for (int i = 0; i < w->colliders.count && !full; i++) {
        const world_collider_t *c = &w->colliders.items[i];
        int want = collide_pack_spheres(&c->desc, c->position, packed, max - n);
        full = want > max - n;
        int got = full ? max - n : want;
        for (int k = 0; k < got; k++) {
            memcpy(out[n + k].centre_radius, packed[k], sizeof packed[k]);
            collider_sweep(w, i, out[n + k].sweep);
        }
        n += got;
    }
    if (w->have_chars && !full) {
        int want = character_spheres(w, out, n, max);
        full = want > max - n;
        n += full ? max - n : want;
    }
    return n;
}

/* Capsules per character for the blade proxies: 8 keeps a humanoid near 35
 * spheres (see character_proxy_spheres). */
#define WORLD_CHARACTER_CAPSULES 8

/* grass.lod_table (scene_lod_apply) in hybrid mode, the reference aside. */
static void apply_lod_table(world_t *w)
{
    if (!w->scene.grass.lod_table[0] || w->mode != SCENE_MODE_HYBRID || w->reference) return;
    bool compute = w->raster_compute;
    if (scene_lod_apply(&w->scene, (const char *)glGetString(GL_RENDERER), &compute, w->lod_note, sizeof w->lod_note) &&
        w->scene.raster == SCENE_RASTER_AUTO)
        world_set_raster(w, compute);
}

_Static_assert(ADMIT_RASTER_QUEUE_LAYERS == RASTER_QUEUE_LAYERS, "admit's raster queue estimate");
_Static_assert(ADMIT_MAX_OBJECTS == COLLIDE_MAX_OBJECTS, "admit's object count is a collide set's");
_Static_assert(ADMIT_MAX_SPHERES == BLADE_MAX_SPHERES, "admit's sphere count is the blade physics'");

/* Resource admission (admit.h) once the GL's limits are known, before
 * any grass is allocated: a scene that does not fit is bad input. */
static bool admit(world_t *w)
{
    gfx_limits_t gl = gfx_limits();
    admit_limits_t lim = {.max_texture_size = gl.max_texture_size,
                              .max_renderbuffer_size = gl.max_renderbuffer_size,
                              .max_gs_vertices = gl.max_gs_vertices,
                              .max_gs_components = gl.max_gs_components,
                              .max_compute_groups = gl.max_compute_groups,
                              .gpu_bytes = 0.9 * gl.gpu_bytes,
                              .host_bytes = admit_host_bytes()};
    admit_world_t aw = {.terrain = &w->terrain_mesh,
                            .terrain_area = admit_terrain_area(&w->terrain_mesh),
                            .billboards = wants_bb(w, w->mode) && !w->reference,
                            .tiles = uses_tiles(w),
                            .tiles_distance = tiles_distance(w),
                            .full_field = (wants_blades(w->mode) && !uses_tiles(w)) || w->reference,
                            .raster = w->scene.raster != SCENE_RASTER_HW,
                            .target_samples = gfx_target_samples(world_target_samples(w)),
                            .size_option = w->size_option,
                            .collider_radius = largest_object_radius(w),
                            .max_texture_size = gl.max_texture_size,
                            .objects = w->scene.collider_count +
                                       (w->scene.character_count ? w->scene.character_count
                                                                 : w->character_override != NULL)};
    static int spheres[SCENE_MAX_COLLIDERS];
    static float packed[BLADE_MAX_SPHERES][4];
    for (int i = 0; i < w->scene.collider_count; i++)
        spheres[i] = collide_pack_spheres(&w->scene.colliders[i], (float[3]){0}, packed, BLADE_MAX_SPHERES);
    aw.collider_spheres = spheres;
    /* On a world only the characters near the camera pack spheres (see
     * character_spheres): the sphere limit is not a static one there. */
    static int char_spheres[SCENE_MAX_CHARACTERS];
    for (int i = 0; w->have_chars && !on_world(w) && i < w->chars.count && i < SCENE_MAX_CHARACTERS; i++)
        char_spheres[aw.characters++] = w->chars.items[i].sphere_count;
    aw.character_spheres = char_spheres;
    char err[1024];
    admit_estimate(&w->scene, &aw, &w->admitted);
    if (admit_check(&w->scene, &aw, &lim, err, sizeof err)) return true;
    core_log_error("%s: %s", w->scene_path, err);
    w->input_error = true;
    return false;
}

bool world_make_gpu(world_t *w)
{
    double mark = plat_time();
    apply_lod_table(w);
    w->gpu_ready = admit(w) && (w->ground = ground_make(&w->terrain_mesh)) != NULL &&
                   world_colliders_make(&w->colliders, &w->scene);
    if (w->gpu_ready && w->scene.grass.gi) w->gpu_ready = world_gi_make(w);
    stage_done(w, WORLD_STAGE_TERRAIN_GPU, &mark);
    /* The compute rasterizer's programs build on the driver's threads while
     * the rest is made, and the first frame takes them: made there, on a
     * fresh H100 they were 2.5 s of the world's first frame. */
    raster_desc_t rd = {.samples = w->raster_samples};
    bool raster = w->scene.raster != SCENE_RASTER_HW;
    if (w->gpu_ready && raster && (uses_tiles(w) || wants_blades(w->mode) || w->reference))
        blade_raster_prefetch(&rd, w->gi_bind.ao != 0);
    /* The tiles' programs build while the characters and the billboards
     * are made. */
    if (w->gpu_ready && uses_tiles(w)) blade_tiles_prefetch(&w->terrain_mesh);
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
    if (w->gpu_ready) w->cube_res = cube_resolution_for(w);
    if (w->gpu_ready && wants_bb(w, w->mode) && !w->reference) {
        /* its programs build during its layout (and the raster's during the
         * rest) */
        bb_field_desc_t bd = billboard_desc(w, w->tuning.placement_seed);
        bb_field_prefetch(&bd, raster ? &rd : NULL);
        w->gpu_ready = (w->bb = bb_field_make(&bd)) != NULL && world_ring_make_canopy(w);
    }
    stage_done(w, WORLD_STAGE_BILLBOARDS, &mark);
    make_blade_env(w);
    if (w->gpu_ready && uses_tiles(w)) w->gpu_ready = make_tiles(w);
    else if (w->gpu_ready && (wants_blades(w->mode) || w->reference)) w->gpu_ready = make_blades(w);
    stage_done(w, WORLD_STAGE_BLADES, &mark);
    if (!w->drawn) {
        /* Until the first draw, the scene's camera at t = 0 decides which
         * tiles are near (the first frame drew no grass near the camera
         * when the tiles took the origin for it). */
        cam_t cam;
        scene_camera_init(&w->scene, &cam);
        glm_vec3_copy(cam.position, w->camera);
    }
    return w->gpu_ready;
}

/* This step's objects of the collide set: every analytic collider (its
 * mesh VAO has position at attribute 0 and normal at 1), then every
 * character. Admission (admit) keeps them within the set. */
static void add_objects(world_t *w, collide_set_t *set, float dt)
{
    bool full = false;
    for (int i = 0; i < w->colliders.count && !full; i++) {
        const world_collider_t *c = &w->colliders.items[i];
        collide_object_t o = {.radius = c->bound_radius, .vao = c->vao,
                              .index_count = (int32_t)c->mesh.index_count, .index_type = GL_UNSIGNED_INT};
        mat4 m;
        glm_translate_make(m, (float *)c->position);
        memcpy(o.model, m, sizeof o.model);
        full = !collide_add_object(set, &o, dt);
    }
    if (w->have_chars && !full) {
        character_object_t co[COLLIDE_MAX_OBJECTS];
        int room = COLLIDE_MAX_OBJECTS - set->object_count;
        int want = character_set_objects(&w->chars, co, room);
        for (int i = 0; i < want && i < room; i++) {
            collide_object_t o = {.radius = co[i].radius, .vao = co[i].vao, .index_count = co[i].index_count,
                                  .index_type = co[i].index_type};
            memcpy(o.model, co[i].model, sizeof o.model);
            /* the set's centre is in object space, the character's in the world */
            mat4 model, inv;
            memcpy(model, co[i].model, sizeof model);
            glm_mat4_inv(model, inv);
            glm_mat4_mulv3(inv, co[i].centre, 1.0f, o.centre);
            collide_add_object(set, &o, dt);
        }
    }
}

/* Cube-map proxies of the blade physics (tuning.blade_cube_proxies; beyond
 * both papers), into the collide set. With the billboard field: its cube
 * maps of the set's objects as rendered by this step's bb_field_update
 * (bb_field_lend_cubes). Blade mode (no field): the analytic colliders
 * rasterised once on the CPU (collide_render_shape) at the scene's cube
 * resolution, the first BLADE_MAX_CUBES of them; further colliders by
 * their bounding sphere and characters by their proxy spheres. */
static void blade_cube_proxies(world_t *w, collide_set_t *set)
{
    if (w->bb) {
        bb_field_lend_cubes(w->bb, set);
        return;
    }
    int nc = w->colliders.count < BLADE_MAX_CUBES ? w->colliders.count : BLADE_MAX_CUBES;
    if (nc > 0 && !w->blade_cubes) {
        collide_cubemap_t cubes[BLADE_MAX_CUBES];
        bool ok = true;
        for (int k = 0; k < nc; k++) {
            const world_collider_t *c = &w->colliders.items[k];
            ok = ok && collide_init_cubemap(&cubes[k], w->cube_res, (vec3){0, 0, 0}, c->bound_radius);
            if (!ok) {
                nc = k;
                break;
            }
            collide_render_shape(&cubes[k], &c->desc);
        }
        if (ok && nc > 0) w->blade_cubes = blade_gpu_upload_cubes(w->blades, cubes, nc);
        for (int k = 0; k < nc; k++) collide_free_cubemap(&cubes[k]);
    }
    if (!w->blade_cubes) nc = 0;
    for (int k = 0; k < nc; k++) {
        const world_collider_t *c = &w->colliders.items[k];
        mat4 model;
        glm_translate_make(model, (float *)c->position);
        collide_make_cube_proxy((const float *)model, (vec3){0, 0, 0}, c->bound_radius, &set->cubes[set->cube_count++]);
    }
    set->cube_texture = w->blade_cubes;
    set->cube_res = w->cube_res;
    for (int k = nc; k < w->colliders.count && set->sphere_count < BLADE_MAX_SPHERES; k++) {
        const world_collider_t *c = &w->colliders.items[k];
        collide_sphere_t *s = &set->spheres[set->sphere_count++];
        *s = (collide_sphere_t){.centre_radius = {c->position[0], c->position[1], c->position[2], c->bound_radius}};
        collider_sweep(w, k, s->sweep);
    }
    if (w->have_chars) {
        int room = BLADE_MAX_SPHERES - set->sphere_count;
        int want = character_spheres(w, set->spheres, set->sphere_count, BLADE_MAX_SPHERES);
        set->sphere_count += want < room ? want : room;
    }
}

/* One step: colliders and characters move, the collide set is built from
 * them, and every grass system takes it. */
/* Adds the CPU ms since *mark to update part k and restarts the mark. */
static void update_part(world_t *w, int k, double *mark)
{
    double now = plat_time();
    w->update_ms[k] += (now - *mark) * 1e3;
    *mark = now;
}

void world_update(world_t *w, float t, float dt)
{
    w->time = t;
    double mark = plat_time();
    world_colliders_update(&w->colliders, &w->terrain_mesh, t);
    if (w->have_chars) {
        character_set_view(&w->chars, w->camera, character_lod_distance(w));
        character_set_update(&w->chars, t, dt);
    }
    collide_set_t *set = &w->collide;
    if (!w->stepped && dt > 0.0f) {
        /* The first step sweeps too: the colliders on paths stood at t - dt
         * before it (a fast ball's first step would skip its path
         * otherwise: stability cases tunnelling, tunnelling_bb). */
        world_colliders_update(&w->colliders, &w->terrain_mesh, t - dt);
        collide_begin_set(set);
        add_objects(w, set, 0.0f);
        world_colliders_update(&w->colliders, &w->terrain_mesh, t);
    }
    w->stepped = true;
    collide_begin_set(set);
    add_objects(w, set, dt);
    /* The papers' colliders stand where they are at each step (no sweep). */
    for (int i = 0; i < set->object_count && w->tuning.paper; i++)
        memcpy(set->objects[i].prev_position, set->objects[i].position, sizeof set->objects[i].prev_position);
    update_part(w, 0, &mark);
    if (w->bb) {
        /* The hybrid draws no billboard nearer than its fade band: objects
         * there bend the blades alone (unless the blades borrow the
         * billboards' cube maps). */
        bool hide = w->mode == SCENE_MODE_HYBRID && !w->reference && w->drawn && !w->tuning.blade_cube_proxies;
        bb_field_set_hidden(w->bb, w->camera, hide ? w->scene.grass.switch_distance - WORLD_SWITCH_FADE : 0.0f);
        bb_field_update(w->bb, set, t, dt);
    }
    update_part(w, 1, &mark);
    if (w->have_blades || w->have_tiles) {
        blade_env_t *env = &w->blade_env;
        env->dt = dt;
        env->time = t;
        if (w->tuning.blade_cube_proxies && w->have_blades) blade_cube_proxies(w, set);
        else set->sphere_count = blade_spheres(w, set->spheres, BLADE_MAX_SPHERES);
        update_part(w, 2, &mark);
        if (w->have_blades) blade_gpu_update(w->blades, env, set);
        if (w->have_tiles) blade_tiles_update(w->tiles, w->camera, set, env);
    }
    update_part(w, 3, &mark);
}

/* The visibility buffer at the target's size (made or remade here). */
static raster_t *frame_raster(world_t *w, const gfx_target_t *target)
{
    raster_t *r = &w->raster;
    if (r->vis.id && r->desc.w == target->w && r->desc.h == target->h) return r;
    raster_destroy(r);
    if (!raster_make(r, &(raster_desc_t){.w = target->w, .h = target->h, .samples = w->raster_samples})) {
        core_log_warn("compute rasterizer unavailable; drawing grass with the hardware path");
        w->raster_compute = false;
        return NULL;
    }
    return r;
}

/* One frame's draw state shared by its passes (world_draw). */
typedef struct frame_draw_t {
    const world_view_t *v;
    const gfx_target_t *target;
    raster_t *raster;       /* NULL: the hardware path */
    bool tiles;             /* the frame draws tiles (and the canopy beyond) */
    float fade_lo, fade_hi; /* the blades' fade band (hybrid) */
    float far_lo, far_hi;   /* the canopy's fade band */
    /* The frame's thinning (frame_lod), shared by the blades, the tiles and
     * the ground under them: grass.lod, the focal length of the target,
     * and the distance where the blades end. */
    blade_lod_t lod;
    float focal, cull;
    bool raster_ok;
} frame_draw_t;

/* Where the switch band's dithered fade ends the blades (the tiles, the
 * hybrid's whole field) they end at its far edge with no end fade of
 * their own; blade mode's field ends at grass.blade_distance (default:
 * the field's edge or the far plane). */
static void frame_lod(const world_t *w, frame_draw_t *f)
{
    const world_view_t *v = f->v;
    bool switch_ends = f->tiles || w->mode == SCENE_MODE_HYBRID;
    f->lod = w->scene.grass.lod;
    f->lod.no_fade = f->lod.no_fade || switch_ends;
    f->focal = blade_lod_focal(v->frame.viewproj, f->target->h);
    f->cull = switch_ends ? f->fade_hi
                          : scene_blade_distance(&w->scene.grass, v->frame.camera, v->far, w->terrain_mesh.aabb_min,
                                                 w->terrain_mesh.aabb_max);
}

static void draw_tiles(world_t *w, frame_draw_t *f)
{
    const world_view_t *v = f->v;
    blade_draw_desc_t dd = {.view = v->frame, .focal_px = f->focal, .fade_start = f->fade_lo, .fade_end = f->fade_hi,
                            .gi = w->gi_bind};
    blade_tiles_set_overlay(w->tiles, v->overlay);
    blade_tiles_set_lod(w->tiles, &f->lod, f->focal);
    /* Occlusion culling reads the opaque depth, as blade mode's below. */
    if (f->raster) {
        f->raster_ok = blade_tiles_raster(w->tiles, f->raster, &dd, f->raster->opaque_depth.id) && f->raster_ok;
    } else {
        gfx_target_resolve_depth(f->target);
        blade_tiles_draw(w->tiles, &dd, f->target->resolve_depth.id);
    }
}

static void draw_blades(world_t *w, frame_draw_t *f)
{
    const world_view_t *v = f->v;
    const gfx_target_t *target = f->target;
    /* Occlusion culling reads the resolved depth of the opaque pass (the
     * compute path: the farthest opaque sample, from raster_begin). */
    if (!f->raster) gfx_target_resolve_depth(target);
    /* Thinned by the scene's grass.lod to the frame's cull distance
     * (frame_lod, docs/BLADES.md). */
    bool hybrid = w->mode == SCENE_MODE_HYBRID;
    blade_cull_desc_t cd = {.view = v->frame,
                            .max_distance = f->cull,
                            .disable = w->reference ? 0xffu : w->tuning.cull_disable,
                            .lod = f->lod,
                            .focal_px = f->focal};
    GLuint depth = f->raster ? f->raster->opaque_depth.id : target->resolve_depth.id;
    blade_gpu_cull(w->blades, &cd, w->reference ? 0 : depth);
    glBindFramebuffer(GL_FRAMEBUFFER, target->fbo);
    glViewport(0, 0, target->w, target->h);
    blade_draw_desc_t dd = {.view = v->frame, .focal_px = cd.focal_px, .gi = w->gi_bind};
    if (hybrid && !w->reference) {
        dd.fade_start = f->fade_lo;
        dd.fade_end = f->fade_hi;
    }
    if (f->raster) f->raster_ok = blade_gpu_raster(w->blades, f->raster, &dd) && f->raster_ok;
    else blade_gpu_draw(w->blades, &dd);
}

static void draw_billboards(world_t *w, frame_draw_t *f)
{
    const world_view_t *v = f->v;
    bb_draw_desc_t d = {.view = v->frame, .overlay = v->overlay == 1, .gi = w->gi_bind};
    if (w->mode == SCENE_MODE_HYBRID) {
        d.fade_start = f->fade_lo;
        d.fade_end = f->fade_hi;
    }
    if (f->tiles || on_world(w)) { /* a world's ring ends at the canopy in every mode */
        d.far_start = f->far_lo;
        d.far_end = f->far_hi;
    }
    if (f->tiles) blade_tiles_slope(w->tiles, &d.slope_map, &d.slope_grid, &d.slope_recover);
    if (f->raster) f->raster_ok = bb_field_raster(w->bb, f->raster, &d) && f->raster_ok;
    else bb_field_draw(w->bb, &d);
}

static void run_pass(world_t *w, frame_draw_t *f, world_pass_kind_t kind)
{
    switch (kind) {
    case WORLD_PASS_TERRAIN:
        gfx_timer_begin("terrain");
        ground_draw(w->ground, &f->v->frame, (const float *)f->v->inv_viewproj);
        world_colliders_draw(&w->colliders, f->v);
        gfx_timer_end();
        break;
    case WORLD_PASS_CHARACTERS:
        character_set_draw(&w->chars, f->v->frame.viewproj, f->v->frame.camera, f->v->frame.sun_dir);
        break;
    /* raster_begin takes the opaque depth (also read by occlusion culling). */
    case WORLD_PASS_RASTER_BEGIN: raster_begin(f->raster, f->target); break;
    case WORLD_PASS_TILES: draw_tiles(w, f); break;
    case WORLD_PASS_BLADES: draw_blades(w, f); break;
    case WORLD_PASS_BILLBOARDS: draw_billboards(w, f); break;
    case WORLD_PASS_RASTER_END:
        if (w->grass_depth) raster_end(f->raster, f->target);
        else raster_end_color(f->raster, f->target);
        break;
    case WORLD_PASS_KINDS: break;
    }
}

/* The grass-shaded ground under the frame's thinned blades: the tiles' (to
 * their switch; with billboards beyond, nearer than them) or blade mode's
 * whole field (to its cull distance); none under billboards alone. */
static void set_ground_lod(world_t *w, const frame_draw_t *f, bool ring, bool field)
{
    if (!f->tiles && !field) {
        ground_set_lod(w->ground, NULL, 0.0f, 0.0f, 0.0f, 0.0f);
        return;
    }
    blade_population_t pop = blade_population_defaults(&w->scene.grass.population);
    float width = 0.5f * (pop.width[0] + pop.width[1]);
    ground_set_lod(w->ground, &f->lod, width, f->focal, f->cull, ring ? f->fade_lo : INFINITY);
}

/* The passes of world_pass_list, in order. */
void world_draw(world_t *w, const world_view_t *v, const gfx_target_t *target, bool wireframe)
{
    glPolygonMode(GL_FRONT_AND_BACK, wireframe ? GL_LINE : GL_FILL);
    glm_vec3_copy((float *)v->frame.camera, w->camera);
    w->drawn = true;
    frame_draw_t f = {.v = v, .target = target, .raster_ok = true};
    f.raster = w->raster_compute && !wireframe && v->overlay == 0 ? frame_raster(w, target) : NULL;
    world_pass_t passes[WORLD_PASS_KINDS];
    int n = world_pass_list(&(world_pass_desc_t){.mode = w->mode, .ground = ground_of(w), .compute = f.raster != NULL,
                                             .reference = w->reference, .have_tiles = w->have_tiles,
                                             .have_blades = w->have_blades, .have_billboards = w->bb != NULL,
                                             .have_characters = w->have_chars,
                                             .billboards = w->scene.grass.billboards},
                          passes);
    f.tiles = world_pass_has(passes, n, WORLD_PASS_TILES); /* the hybrid's near blades, and its canopy */
    f.fade_lo = tiles_distance(w) - WORLD_SWITCH_FADE;
    f.fade_hi = tiles_distance(w) + WORLD_SWITCH_FADE;
    /* The canopy fades in beyond the billboards of the hybrid (or of a
     * world), or, without them (grass.billboards none, blade mode on a
     * world), where the blades fade out. */
    bool ring = (f.tiles || on_world(w)) && world_pass_has(passes, n, WORLD_PASS_BILLBOARDS);
    f.far_lo = !ring ? f.fade_lo : w->scene.grass.canopy_distance - WORLD_CANOPY_FADE;
    f.far_hi = !ring ? f.fade_hi : w->scene.grass.canopy_distance + WORLD_CANOPY_FADE;
    ground_set_canopy_fade(w->ground, f.tiles || ring ? f.far_lo : 0.0f, f.tiles || ring ? f.far_hi : 0.0f);
    frame_lod(w, &f);
    set_ground_lod(w, &f, ring, world_pass_has(passes, n, WORLD_PASS_BLADES) && !w->reference);
    if (w->canopy_all) ground_set_canopy_fade(w->ground, 0.0f, 1e-3f);
    for (int i = 0; i < n; i++) run_pass(w, &f, passes[i].kind);
    if (!f.raster_ok) {
        core_log_warn("compute rasterizer shaders unavailable (see above); drawing grass with the hardware path");
        w->raster_compute = false;
    }
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

void world_set_raster(world_t *w, bool compute)
{
    w->raster_compute = compute;
    w->scene.raster = compute ? SCENE_RASTER_COMPUTE : SCENE_RASTER_HW;
}

int world_target_samples(const world_t *w)
{
    return w->raster_compute ? 1 : w->scene.msaa;
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
    if (w->gpu_ready && wants_bb(w, mode) && !w->bb && !w->reference && make_bb(w)) world_ring_make_canopy(w);
    if (w->gpu_ready && uses_tiles(w) && !w->have_tiles) make_tiles(w);
    else if (w->gpu_ready && wants_blades(mode) && !uses_tiles(w) && !w->have_blades) make_blades(w);
}

void world_destroy(world_t *w)
{
    if (!w) return;
    bb_field_destroy(w->bb);
    blade_gpu_destroy(w->blades);
    gfx_texture_destroy(&w->blade_extent);
    blade_tiles_destroy(w->tiles);
    if (w->have_chars) character_set_destroy(&w->chars);
    raster_destroy(&w->raster);
    world_colliders_destroy(&w->colliders);
    gi_gpu_destroy(&w->gi);
    ground_destroy(w->ground);
    terrain_free(&w->terrain_mesh);
    core_image_free(&w->clearings_image);
    free(w);
}

void world_view_make(world_view_t *v, const cam_t *cam_in, int width, int height, float time, float dt)
{
    cam_t cam = *cam_in;
    cam.aspect = (float)width / (float)height;
    *v = (world_view_t){0};
    mat4 vp;
    vec4 planes[6]; /* cglm's aligned vectors; core_view_t holds plain floats */
    cam_view(&cam, v->view);
    cam_proj(&cam, v->proj);
    glm_mat4_mul(v->proj, v->view, vp);
    glm_mat4_inv(vp, v->inv_viewproj);
    cam_frustum_planes(vp, planes);
    memcpy(v->frame.viewproj, vp, sizeof v->frame.viewproj);
    memcpy(v->frame.planes, planes, sizeof v->frame.planes);
    glm_vec3_copy(cam.position, v->frame.camera);
    v->far = cam.far;
    glm_vec3_normalize_to((vec3)WORLD_SUN_DIR, v->frame.sun_dir); /* the clump bakes and the canopy light with it */
    v->width = width;
    v->height = height;
    v->frame.time = time;
    v->dt = dt;
}

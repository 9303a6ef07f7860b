/* grass_build: what grass_make and grass_set_mode make: the layout and
 * extent map both grass models share, the billboard field, the blade
 * field or its tiles, the blades' environment, the ground canopy and the
 * collision cube maps' size. */
#include "grass/grass_local.h"

#include <math.h>
#include <pthread.h>
#include <string.h>

#include "admit/admit.h"
#include "platform/plat.h"
#include "scene/scene_lod.h"

/* The layout shared by both grass models (so hybrid tiles cover the same
 * ground): one layout texel per billboard candidate cell over the terrain,
 * so the extent map's clearings are sized relative to the field. */
static int layout_for(const grass_t *gr, bb_gen_desc_t *gen)
{
    const scene_grass_desc_t *g = &gr->scene->grass;
    float extent = fmaxf(gr->terrain->aabb_max[0] - gr->terrain->aabb_min[0],
                         gr->terrain->aabb_max[2] - gr->terrain->aabb_min[2]);
    int cells = (int)ceilf(extent * sqrtf(g->billboard_density));
    int layout_size = ((cells + 15) / 16) * 16;
    layout_size = layout_size < 32 ? 32 : (layout_size > 1024 ? 1024 : layout_size);
    *gen = bb_gen_desc_defaults(&(bb_gen_desc_t){.spacing = 1.0f / sqrtf(g->billboard_density),
                                                 .origin = {gr->terrain->aabb_min[0], gr->terrain->aabb_min[2]},
                                                 .seed = gr->scene->seed});
    return layout_size;
}

/* The extent map's clearings (grass.clearings) on the layout of gen's
 * cells: the blob size in texels, the image stretched over the terrain's
 * xz box (the layout's origin is its corner). */
static bb_extent_desc_t extent_desc(const grass_t *gr, const bb_gen_desc_t *gen)
{
    static const bb_clearings_t kinds[] = {[SCENE_CLEARINGS_NOISE] = BB_CLEARINGS_NOISE,
                                           [SCENE_CLEARINGS_NONE] = BB_CLEARINGS_NONE,
                                           [SCENE_CLEARINGS_IMAGE] = BB_CLEARINGS_IMAGE};
    const scene_clearings_desc_t *c = &gr->scene->grass.clearings;
    const float *lo = gr->terrain->aabb_min, *hi = gr->terrain->aabb_max;
    float texel = gen->spacing * (float)gen->cells_per_texel;
    bool image = c->type == SCENE_CLEARINGS_IMAGE;
    return (bb_extent_desc_t){.clearings = kinds[c->type],
                              .fraction = c->fraction,
                              .feature = c->size / texel,
                              .image = image ? &gr->clearings_image : NULL,
                              .image_texels = {image ? (hi[0] - lo[0]) / texel : 0.0f,
                                               image ? (hi[2] - lo[2]) / texel : 0.0f}};
}

/* The shared layout's extent map alone (the clump texture is the billboard
 * field's business): one tiny clump layer is enough for bb_layout. */
bool grass_extent_layout(const grass_t *gr, bb_layout_t *lay, bb_gen_desc_t *gen)
{
    int size = layout_for(gr, gen);
    return bb_layout_generate(lay, &(bb_layout_desc_t){.seed = gr->scene->seed, .size = size, .clump_layers = 1,
                                                        .clump_size = 8, .blades = 1, .extent_only = true,
                                                        .extent = extent_desc(gr, gen)});
}

/* The canopy tables this process made, by their desc (bytes; a desc that
 * differs only in padding is made again): a bench or a test makes many
 * worlds of one scene, and a table with wind poses takes 0.6 s on 2 cores,
 * seconds under the sanitizers. The least recently used goes first. */
#define CANOPY_CACHE 4
static struct {
    blade_canopy_desc_t desc;
    blade_canopy_t table;
    uint64_t used; /* 0: empty */
} canopy_cache[CANOPY_CACHE];
static uint64_t canopy_cache_tick;
static pthread_mutex_t canopy_cache_lock = PTHREAD_MUTEX_INITIALIZER;

/* *out = a deep copy of c (its wind poses copied); false: out of memory. */
static bool canopy_copy(blade_canopy_t *out, const blade_canopy_t *c)
{
    *out = *c;
    if (!c->windy) return true;
    size_t size = sizeof *c->windy * (size_t)(c->poses - 1);
    out->windy = malloc(size);
    if (out->windy) memcpy(out->windy, c->windy, size);
    return out->windy != NULL;
}

/* blade_canopy_make through the cache. */
static bool canopy_make(blade_canopy_t *out, const blade_canopy_desc_t *d)
{
    bool hit = false;
    pthread_mutex_lock(&canopy_cache_lock);
    for (int i = 0; i < CANOPY_CACHE && !hit; i++)
        if (canopy_cache[i].used && memcmp(&canopy_cache[i].desc, d, sizeof *d) == 0) {
            hit = canopy_copy(out, &canopy_cache[i].table);
            canopy_cache[i].used = ++canopy_cache_tick;
        }
    pthread_mutex_unlock(&canopy_cache_lock);
    if (hit) return true;
    if (!blade_canopy_make(out, d)) return false;
    pthread_mutex_lock(&canopy_cache_lock);
    int slot = 0;
    for (int i = 1; i < CANOPY_CACHE; i++)
        if (canopy_cache[i].used < canopy_cache[slot].used) slot = i;
    blade_canopy_free(&canopy_cache[slot].table);
    canopy_cache[slot].used = canopy_copy(&canopy_cache[slot].table, out) ? ++canopy_cache_tick : 0;
    canopy_cache[slot].desc = *d;
    pthread_mutex_unlock(&canopy_cache_lock);
    return true;
}

/* The canopy table (GL-free; its rows computed in parallel, 211 ms on 2
 * cores) runs on a thread of its own while the layout and the blades or
 * the tiles are made. */
typedef struct canopy_job_t {
    blade_canopy_desc_t desc;
    blade_canopy_t canopy;
    bool ok;
} canopy_job_t;

static void *canopy_thread(void *user)
{
    canopy_job_t *job = user;
    job->ok = canopy_make(&job->canopy, &job->desc);
    return NULL;
}

/* The scene's canopy table desc, its blades cut into `segments` quads (0:
 * the default): its population, seed and sun, and as its largest wind the
 * scene's winds' strengths summed. Zeroed first, padding too: the cache
 * compares bytes. */
static void canopy_desc(const scene_desc_t *s, int segments, blade_canopy_desc_t *out)
{
    memset(out, 0, sizeof *out);
    out->population = s->grass.population;
    out->seed = s->seed;
    memcpy(out->sun, (float[3])GRASS_SUN_DIR, sizeof out->sun);
    out->segments = segments;
    for (int i = 0; i < s->wind_count; i++) out->wind += fmaxf(s->wind[i].strength, 0.0f);
}

/* Starts the scene's canopy table on a thread (canopy_desc); false: it was
 * not started (canopy_finish then computes it). */
static bool canopy_start(const grass_t *gr, int segments, canopy_job_t *job, pthread_t *thread)
{
    memset(job, 0, sizeof *job);
    canopy_desc(gr->scene, segments, &job->desc);
    return pthread_create(thread, NULL, canopy_thread, job) == 0;
}

static void canopy_finish(canopy_job_t *job, pthread_t thread, bool threaded)
{
    if (threaded) pthread_join(thread, NULL);
    else canopy_thread(job);
}

/* The collision cube-map side: grass.cube_resolution, raised (grass.cube_texel
 * > 0) until the largest collider or character, of bounding radius r, has
 * texels 2 r / res no larger than cube_texel (large_bb in the stability
 * suite: a 4 m ball at 16 texels had 0.5 m texels). Capped where the cube
 * render target (res x 6 res) exceeds the GL's texture size, with a warning. */
int grass_cube_resolution(const grass_t *gr)
{
    const scene_grass_desc_t *g = &gr->scene->grass;
    int res = g->cube_resolution;
    if (g->cube_texel <= 0.0f) return res;
    float r = gr->collider_radius;
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

/* The billboard field's desc (grass_build_billboards; placement: its
 * placement seed). */
static bb_field_desc_t billboard_desc(const grass_t *gr, uint32_t placement)
{
    const scene_desc_t *s = gr->scene;
    const scene_grass_desc_t *g = &s->grass;
    bb_wind_desc_t wind = {0};
    float wind_strength = 0.0f; /* the clump bakes' blades settle under its mean */
    if (s->wind_count && s->wind[0].type == SCENE_WIND_DIRECTIONAL) {
        const scene_wind_t *sw = &s->wind[0];
        wind = bb_wind_from_wave(sw->direction[0], sw->direction[1], sw->strength, sw->wavelength, sw->speed);
        wind_strength = sw->strength;
    }
    bb_gen_desc_t gen;
    int layout_size = layout_for(gr, &gen);
    int objects = gr->objects;
    if (objects > BB_MAX_OBJECTS) objects = BB_MAX_OBJECTS;
    return (bb_field_desc_t){
        .terrain = gr->terrain,
        .seed = s->seed,
        .placement_seed = placement,
        .density = g->billboard_density,
        .size = {g->billboard_size[0], g->billboard_size[1]},
        .subdiv = {g->subdiv[0], g->subdiv[1]},
        .gi = g->gi,
        .occlusion = g->bb_occlusion,
        .iterations = g->spring_iterations,
        .paper = gr->tuning.paper,
        .max_deformed = g->deformed_pool,
        .cube_res = gr->cube_res,
        .recover_time = g->recover_time,
        .max_objects = objects > 0 ? objects : 1,
        /* a world's ring (bb_ring.h) holds billboards out to the canopy's band */
        .ring_reach = g->canopy_distance + GRASS_CANOPY_FADE,
        .wind = wind,
        .layout = {.size = layout_size,
                   .blades = bb_clump_blades(g->population.density, g->billboard_density),
                   .clump = {.population = g->population,
                             .wind = wind_strength,
                             .wind_dir = {wind.dir[0], wind.dir[1]}},
                   .extent = extent_desc(gr, &gen),
                   .views = {.on = gr->tuning.view_cards}},
    };
}

bb_field_t *grass_build_billboards(const grass_t *gr, uint32_t placement)
{
    bb_field_desc_t d = billboard_desc(gr, placement);
    return bb_field_make(&d);
}

bool grass_make_billboards(grass_t *gr)
{
    /* its programs build during its layout (and the raster's during the rest) */
    bb_field_desc_t bd = billboard_desc(gr, gr->tuning.placement_seed);
    raster_desc_t rd = {.samples = gr->raster_samples};
    bb_field_prefetch(&bd, gr->scene->raster != SCENE_RASTER_HW ? &rd : NULL);
    gr->bb = bb_field_make(&bd);
    return gr->bb != NULL;
}

/* Blade mode's field, seeded on the GPU (blade_seed_plan.h) and thinned by
 * the extent map with the billboards' acceptance rule (accept with
 * probability E/255, bb_layout.h), so both representations share clearings
 * and density ratio. A thinned blade has height and width 0: the physics
 * and culling skip it like patch padding, and the patches stay intact. */
bool grass_make_blades(grass_t *gr)
{
    const scene_desc_t *s = gr->scene;
    const scene_grass_desc_t *g = &s->grass;
    const terrain_mesh_t *t = gr->terrain;
    blade_mesh_t mesh = {.positions = t->positions, .normals = t->normals, .vertex_count = t->vertex_count,
                         .indices = t->indices, .index_count = t->index_count};
    blade_seed_desc_t sd = {.seed = grass_placement_seed(gr),
                            .population = g->population,
                            .max_blades = ADMIT_MAX_FIELD_BLADES};
    double mark[4];
    mark[0] = plat_time();
    /* blade mode's grass-shaded ground (ground_set_lod): the canopy table,
     * thinned by the extent map that thins the blades */
    bool shade = !gr->reference && !ground_has_canopy(gr->ground);
    canopy_job_t job;
    pthread_t thread;
    bool threaded = shade && canopy_start(gr, 0, &job, &thread);
    blade_seed_plan_t plan;
    bool planned = blade_seed_plan_make(&mesh, &sd, &plan);
    bb_gen_desc_t gen;
    bb_layout_t lay;
    bool have_layout = gr->scene->terrain.type == TERRAIN_HEIGHTFIELD && grass_extent_layout(gr, &lay, &gen);
    blade_gpu_seed_t seed = {.plan = &plan, .mesh = &mesh, .extent_spacing = 1.0f,
                             .extent_key = grass_placement_seed(gr)};
    gfx_texture_destroy(&gr->blade_extent);
    if (have_layout) {
        gr->blade_extent = gfx_texture_make(&(gfx_texture_desc_t){.w = lay.extent.w, .h = lay.extent.h,
                                                                 .format = GL_R8, .filter = GL_NEAREST,
                                                                 .data = lay.extent.px, .upload_format = GL_RED,
                                                                 .label = "blades.extent"});
        seed.extent_texture = gr->blade_extent.id;
        memcpy(seed.extent_origin, gen.origin, sizeof seed.extent_origin);
        seed.extent_spacing = gen.spacing * (float)gen.cells_per_texel;
        bb_layout_free(&lay);
    }
    mark[1] = plat_time();
    blade_gpu_desc_t gd = {.seed = &seed, .shape = g->population.shape, .label = "blades",
                           .displacement = g->displacement, .width_correction = g->width_correction,
                           .width_printed = {g->width_printed[0], g->width_printed[1]},
                           .path = g->blade_render == SCENE_BLADE_RENDER_TESS ? BLADE_PATH_TESSELLATION
                                                                              : BLADE_PATH_PULLING};
    if (gr->tuning.tess_max) gd.max_tess_level = gr->tuning.tess_max;
    if (gr->reference) {
        gd.max_tess_level = 16;
        gd.no_patch_cull = true;
    }
    gr->blades = planned ? blade_gpu_make(&gd) : NULL;
    gr->have_blades = gr->blades != NULL;
    mark[2] = plat_time();
    if (shade) {
        canopy_finish(&job, thread, threaded);
        if (job.ok) ground_set_canopy(gr->ground, &job.canopy, seed.extent_texture, seed.extent_origin,
                                      seed.extent_spacing);
        blade_canopy_free(&job.canopy);
    }
    mark[3] = plat_time();
    if (gr->blades) {
        blade_gpu_info_t info = blade_gpu_info(gr->blades);
        core_log_info("blades: %u blades in %u patches (%u in clearings of the extent map), seeded on the GPU; "
                      "plan and extent map %.1f ms, programs and seeding %.1f ms, then the canopy table %.1f ms",
                      info.blade_count - info.thinned, info.patch_count, info.thinned, (mark[1] - mark[0]) * 1e3,
                      (mark[2] - mark[1]) * 1e3, (mark[3] - mark[2]) * 1e3);
    }
    blade_seed_plan_free(&plan);
    return gr->have_blades;
}

_Static_assert(SCENE_MAX_WIND <= BLADE_MAX_WINDS, "every scene wind reaches the blade physics");

/* The blade environment shared by the full field and the tiles. */
void grass_make_blade_env(grass_t *gr)
{
    const scene_desc_t *s = gr->scene;
    const scene_grass_desc_t *g = &s->grass;
    /* A push of a tenth of the mean height counts fully towards eta, and
     * eta decays over the scene's recover time: a trail stays down about
     * that long, like the billboards' (departure from the paper's k = 1,
     * see blade_env_t.collision_gain). */
    blade_population_t pop = blade_population_defaults(&g->population);
    float h = 0.5f * (pop.height[0] + pop.height[1]);
    gr->blade_env = (blade_env_t){.gravity = pop.gravity,
                                 .collision_gain = 1.0f / (0.01f * h * h),
                                 .collision_decay = 1.0f / g->recover_time};
    if (gr->tuning.paper) {
        gr->blade_env.paper = true;
        gr->blade_env.length_mode = BLADE_LENGTH_PAPER;
        gr->blade_env.collision_gain = 1.0f;
    }
    for (int i = 0; i < s->wind_count && i < BLADE_MAX_WINDS; i++) {
        const scene_wind_t *sw = &s->wind[i];
        gr->blade_env.winds[gr->blade_env.wind_count++] =
            sw->type == SCENE_WIND_POINT
                ? blade_wind_point(sw->position, sw->strength, sw->radius)
                : blade_wind_wave(sw->direction[0], sw->direction[1], sw->strength, sw->wavelength, sw->speed);
    }
    if (gr->ground) ground_set_winds(gr->ground, gr->blade_env.winds, gr->blade_env.wind_count);
}

/* Billboards -> blades hand-over: the deformed billboards of the moment
 * seed the blades of tiles turning to blades (blade_tiles.h). */
static void bb_slope_source(void *user, const hybrid_slope_grid_t *grid, gfx_buffer_t sums)
{
    grass_t *gr = user;
    if (gr->bb) bb_field_add_slopes(gr->bb, grid, sums);
}

/* The reference's tiles (a world's) take their templates from the
 * placement seed xor this: another placement, another reference (the
 * image error's noise floor), none of them the drawn tiles' own. */
#define GRASS_REFERENCE_TILES_SEED 0x27d4eb2fu

/* The tiles' desc with blades to `distance` (m), without its extent map. */
static void tiles_desc(const grass_t *gr, float distance, blade_tiles_desc_t *td)
{
    const scene_desc_t *s = gr->scene;
    const scene_grass_desc_t *g = &s->grass;
    *td = (blade_tiles_desc_t){.terrain = gr->terrain,
                               .tile_size = g->tile_size,
                               .population = g->population,
                               .seed = s->seed,
                               .switch_distance = distance,
                               .pool_slots = g->tile_pool,
                               .displacement = g->displacement,
                               .width_correction = g->width_correction,
                               .width_printed = {g->width_printed[0], g->width_printed[1]},
                               .tessellate = g->blade_render == SCENE_BLADE_RENDER_TESS,
                               .wind_count = gr->blade_env.wind_count,
                               .cull = {.max_distance = distance + 1.0f, .lod = g->lod, .focal_px = scene_focal(s)},
                               .slope_recover = g->recover_time,
                               .label = "tiles"};
    memcpy(td->winds, gr->blade_env.winds, sizeof td->winds);
    if (gr->reference) { /* a world's (GRASS_REFERENCE_REACH) */
        td->seed = grass_placement_seed(gr) ^ GRASS_REFERENCE_TILES_SEED;
        td->max_level = 16;
        td->lod_distance = distance;
        td->cull.lod = (blade_lod_t){.rule = BLADE_LOD_OFF};
        td->cull.disable = BLADE_CULL_ORIENTATION | BLADE_CULL_OCCLUSION;
        td->label = "tiles.reference";
    }
}

/* The billboards' extent map thins the tiles too (same clearings): the
 * shared layout's, made into *lay when it returns true (bb_layout_free it). */
static bool tiles_extent(const grass_t *gr, blade_tiles_desc_t *td, bb_layout_t *lay)
{
    bb_gen_desc_t gen;
    if (!grass_extent_layout(gr, lay, &gen)) return false;
    td->extent = &lay->extent;
    memcpy(td->extent_origin, gen.origin, sizeof td->extent_origin);
    td->extent_spacing = gen.spacing * (float)gen.cells_per_texel;
    td->extent_seed = gr->scene->seed;
    return true;
}

bool grass_make_tiles(grass_t *gr)
{
    const scene_grass_desc_t *g = &gr->scene->grass;
    blade_tiles_desc_t td;
    tiles_desc(gr, grass_tiles_distance(gr), &td);
    /* Without billboards the canopy continues the tiles' blades where they
     * end: its blades have the segments the tiles draw there (the hardware
     * path's level of detail; docs/HYBRID.md "Ground canopy"). */
    bool ring = grass_pass_wants_billboards(gr->mode, g->billboards);
    canopy_job_t job;
    pthread_t thread;
    bool threaded = canopy_start(gr, ring ? 0 : blade_tiles_segments_at(&td, td.switch_distance), &job, &thread);
    bb_layout_t lay;
    bool have_layout = tiles_extent(gr, &td, &lay);
    gr->tiles = blade_tiles_make(&td);
    gr->have_tiles = gr->tiles != NULL;
    if (gr->have_tiles) blade_tiles_set_slope_source(gr->tiles, bb_slope_source, gr);
    /* The ground canopy beyond the billboards, thinned by the tiles' extent
     * map (its texture); without billboards the canopy match's programs
     * compile meanwhile, on the tiles' ground. */
    blade_tiles_info_t ti = gr->have_tiles ? blade_tiles_info(gr->tiles) : (blade_tiles_info_t){0};
    ground_set_grid(gr->ground, ti.ground_texture, ti.grid_res, 0.5f * ti.field_size);
    if (gr->have_tiles && !ring && gr->mode == SCENE_MODE_HYBRID && g->canopy_match == SCENE_CANOPY_MATCH_ON)
        ground_match_prefetch(gr->ground);
    canopy_finish(&job, thread, threaded);
    if (gr->have_tiles && job.ok)
        ground_set_canopy(gr->ground, &job.canopy, ti.extent_texture, td.extent_origin, td.extent_spacing);
    blade_canopy_free(&job.canopy);
    if (have_layout) bb_layout_free(&lay);
    return gr->have_tiles;
}

blade_tiles_t *grass_build_tiles(grass_t *gr, float distance)
{
    if (!gr->have_tiles || !(distance > 0.0f)) return NULL;
    gfx_ctx_t *prev = grass_enter(gr);
    blade_tiles_desc_t td;
    tiles_desc(gr, distance, &td);
    bb_layout_t lay;
    bool have_layout = tiles_extent(gr, &td, &lay);
    td.label = "tiles.reach";
    blade_tiles_t *t = blade_tiles_make(&td);
    if (have_layout) bb_layout_free(&lay);
    /* streamed in and posed at the latest step's time, with nothing to push */
    if (t) blade_tiles_update(t, gr->camera, NULL, &gr->blade_env);
    grass_leave(prev);
    return t;
}

/* A world terrain in billboard mode: the ground canopy beyond the
 * billboard ring (bb_ring.h; the hybrid's comes with its tiles); true
 * when there is nothing to make. */
bool grass_ring_make_canopy(grass_t *gr)
{
    if (gr->terrain->type != TERRAIN_WORLD || !gr->bb || gr->have_tiles) return true;
    blade_canopy_t *canopy = malloc(sizeof *canopy); /* 0.4 MB: not on the stack */
    blade_canopy_desc_t desc;
    canopy_desc(gr->scene, 0, &desc);
    if (!canopy || !canopy_make(canopy, &desc)) {
        free(canopy);
        return false;
    }
    bb_field_info_t fi;
    bb_field_info(gr->bb, &fi);
    ground_set_canopy(gr->ground, canopy, fi.extent_texture, fi.gen.origin,
                      fi.gen.spacing * (float)fi.gen.cells_per_texel);
    blade_canopy_free(canopy);
    free(canopy);
    return true;
}

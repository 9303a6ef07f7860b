/* blade_tiles: tiled blade field of Fan et al. 2015 over the Jahrmann &
 * Wimmer 2017 blades (eq. 3-16 physics on active slots only, eq. 17-20
 * culling, eq. 21 drawing): template seeding, ground texture, slot pool,
 * activation through src/hybrid, motion readback, per-tile CPU frustum
 * test, cull (occlusion included) + vertex-pulled or tessellated draw.
 * See blade_tiles.h. GL objects come from
 * gfx only. */
#include "blade/blade_local.h"

#include <assert.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* t->slot_spheres, uint words: per slot its list's first word and length
 * (2 slot, 2 slot + 1), then the dispatched slots' lists end to end: every
 * sphere of its tile's object list (hybrid), however many. The buffer holds
 * 2 S + SLOT_LISTS_FIRST words at make time and doubles to what a step
 * needs (fit_slot_lists). */
#define SLOT_LISTS_FIRST 2048
#define NO_SLOT 0xffffffffu
/* t->command, uint words: the solid blades' draw (count, instanceCount,
 * first, baseInstance), appends past the capacity, appends tried, the
 * fading blades' draw, and the blades culled per test (orientation,
 * frustum, distance, occlusion; tiles_cull.comp's Command). A draw counts
 * its blades in word t->count_word: instanceCount for the pulled strips,
 * count (patch vertices) for tessellation. */
enum { CMD_SOLID = 0, CMD_OVERFLOW = 4, CMD_TOTAL = 5, CMD_FADE = 8, CMD_CULLED = 12, TILES_COMMAND_WORDS = 16 };
/* t->draw_ring, uint words: appends tried, past the capacity, culled per test. */
enum { RING_TOTAL = 0, RING_OVERFLOW = 1, RING_CULLED = 2, RING_WORDS = 6 };
#define RECOVERING_BIT 0x80000000u
#define SLOT_AWAY (-2) /* t->slot_owner of a slot kept by a tile away from the window */
#define HYSTERESIS 1.0f /* hybrid's default dead band, used for the draw capacity */
#define TILES_POSE_ITERATIONS 6 /* tiles_common.glsl */
#define TILES_POSE_RELAX 0.7f
#define TILES_POSE_STEPS 24

blade_tiles_desc_t blade_tiles_desc_defaults(const blade_tiles_desc_t *desc)
{
    blade_tiles_desc_t d = *desc;
    if (d.tile_size <= 0.0f) d.tile_size = BLADE_TILES_DEFAULT_TILE_SIZE;
    if (d.template_count <= 0) d.template_count = 4;
    d.population = blade_population_defaults(&d.population);
    if (d.pool_slots <= 0) d.pool_slots = 64;
    if (d.switch_distance <= 0.0f) d.switch_distance = BLADE_TILES_DEFAULT_SWITCH_DISTANCE;
    if (d.recover_timeout <= 0.0f) d.recover_timeout = 5.0f;
    if (d.motion_epsilon <= 0.0f) d.motion_epsilon = BLADE_TILES_DEFAULT_MOTION_EPSILON;
    if (d.max_level == 0) d.max_level = 8;
    if (d.lod_distance <= 0.0f) d.lod_distance = 30.0f;
    d.cull = blade_cull_desc_defaults(&d.cull);
    d.cull.eye_distance = true; /* the hybrid's one switch distance (tiles_cull.comp) */
    /* Half-metre cells, finer where a cell would hold more blades than
     * HYBRID_SLOPE_MAX_PER_CELL (dense grass on large tiles). */
    if (d.slope_cells_per_tile <= 0)
        d.slope_cells_per_tile =
            (int)fmaxf(fmaxf(1.0f, roundf(d.tile_size / 0.5f)),
                       ceilf(d.tile_size * sqrtf(d.population.density / (float)HYBRID_SLOPE_MAX_PER_CELL)));
    if (d.slope_recover <= 0.0f) d.slope_recover = BLADE_TILES_DEFAULT_RECOVER_TIME;
    if (!d.label) d.label = "tiles";
    assert(d.template_count <= BLADE_TILES_MAX_TEMPLATES);
    assert(d.wind_count >= 0 && d.wind_count <= BLADE_MAX_WINDS);
    assert(d.max_level >= 1 && d.max_level <= 64);
    return d;
}

/* Blades per template before padding (blade_seed UNIFORM: round(density *
 * area)), padded to the seeding patch size. */
static uint32_t template_blades(const blade_tiles_desc_t *d)
{
    uint32_t n = (uint32_t)lroundf(d->population.density * d->tile_size * d->tile_size);
    uint32_t p = (uint32_t)blade_seed_desc_defaults(&(blade_seed_desc_t){0}).patch_size;
    return (n + p - 1) / p * p;
}

/* Most tiles whose nearest point can be within r of one camera position:
 * offsets (di, dj) from the camera's tile whose gap T * max(|d| - 1, 0)
 * per axis stays below r. Offsets past twice the grid's larger side are not
 * visited: a reach that long already counts more offsets than the grid has
 * tiles, the cap below (a 1 km reach over 4 cm tiles looped 2.5e9 times). */
static int max_tiles_within(float r, float tile, int nx, int nz)
{
    int k = (int)fminf(ceilf(r / tile) + 1.0f, 2.0f * (float)(nx > nz ? nx : nz) + 2.0f), count = 0;
    for (int dj = -k; dj <= k; dj++)
        for (int di = -k; di <= k; di++) {
            float gx = tile * fmaxf((float)abs(di) - 1.0f, 0.0f), gz = tile * fmaxf((float)abs(dj) - 1.0f, 0.0f);
            count += gx * gx + gz * gz < r * r;
        }
    return count < nx * nz ? count : nx * nz;
}

/* Blades the distance test and the thinning (tiles_cull.comp, the eye
 * distance) can keep of the tiles within r of one camera position: per
 * tile offset, the blades of one template times the share the thinning
 * keeps at its nearest point, over blade widths drawn evenly from `width`
 * (blade_seed): u (1 + shrink) for WIDTH (the blades of the shrink window
 * too), u for the other rules, u of blade_lod_kept at the cull desc's
 * focal length (0: BLADE_TILES_CAPACITY_FOCAL). The draw buffer's default
 * where it is below every blade of the tiles in reach. */
static double max_blades_within(float r, float tile, uint32_t blades, const blade_cull_desc_t *c,
                                const float width[2])
{
    enum { WIDTHS = 8 };
    int k = (int)ceilf(r / tile) + 1;
    blade_lod_t lod = blade_lod_defaults(&c->lod);
    float focal = c->focal_px > 0.0f ? c->focal_px : BLADE_TILES_CAPACITY_FOCAL;
    float window = lod.rule == BLADE_LOD_WIDTH ? lod.shrink : 0.0f;
    double sum = 0.0;
    for (int dj = -k; dj <= k; dj++)
        for (int di = -k; di <= k; di++) {
            float gx = tile * fmaxf((float)abs(di) - 1.0f, 0.0f), gz = tile * fmaxf((float)abs(dj) - 1.0f, 0.0f);
            float d = sqrtf(gx * gx + gz * gz);
            if (d >= r) continue;
            double keep = 1.0;
            if ((c->disable & BLADE_CULL_DISTANCE) == 0 && c->max_distance > 0.0f) {
                keep = 0.0;
                for (int w = 0; w < WIDTHS; w++) {
                    float wd = width[0] + (width[1] - width[0]) * ((float)w + 0.5f) / (float)WIDTHS;
                    keep += fmin(1.0, blade_lod_kept(&lod, d, wd, focal, c->max_distance) * (1.0f + window)) / WIDTHS;
                }
            }
            sum += keep * blades;
        }
    return sum;
}

typedef struct layout_t {
    uint32_t blades; /* per template, padded */
    int tiles_x, tiles_z, draw_tiles;
    uint32_t draw_capacity;
    size_t bytes;
} layout_t;

/* The default window (blade_tiles_desc_t.window): every tile whose box can
 * be within the switch distance plus the hysteresis of the camera, and a
 * tile of margin for the camera's tile. */
static int default_window(const blade_tiles_desc_t *d)
{
    return 2 * (int)ceilf((d->switch_distance + HYSTERESIS) / d->tile_size) + 3;
}

/* grid_res 0: a world terrain, no ground texture. */
static layout_t layout_of(const blade_tiles_desc_t *d, float field_size, int grid_res)
{
    layout_t l = {.blades = template_blades(d)};
    l.tiles_x = l.tiles_z = d->window > 0 ? d->window : (int)ceilf(field_size / d->tile_size);
    l.draw_tiles = max_tiles_within(d->switch_distance + HYSTERESIS, d->tile_size, l.tiles_x, l.tiles_z);
    l.draw_capacity = d->draw_capacity ? d->draw_capacity : (uint32_t)l.draw_tiles * l.blades;
    if (!d->draw_capacity)
        l.draw_capacity = (uint32_t)fmin(
            (double)l.draw_capacity,
            ceil(max_blades_within(d->switch_distance + HYSTERESIS, d->tile_size, l.blades, &d->cull,
                                   d->population.width)));
    size_t S = (size_t)d->pool_slots, B = l.blades, side = grid_res > 0 ? (size_t)grid_res + 1 : 0;
    l.bytes = (size_t)d->template_count * B * sizeof(blade_t)          /* templates */
              + S * B * (sizeof(blade_t) + sizeof(float))              /* pool + eta */
              + S * sizeof(uint32_t) * (1 + 2 + 1 + 2)                 /* motion, list heads, slot / init lists */
              + SLOT_LISTS_FIRST * sizeof(uint32_t)                    /* per-slot sphere lists (grow) */
              + BLADE_MAX_WINDS * sizeof(blade_wind_t) + BLADE_SPHERES_FIRST * sizeof(blade_sphere_t)
              + (size_t)l.draw_tiles * 2 * sizeof(uint32_t)            /* tile list */
              + (size_t)l.draw_capacity * (sizeof(blade_t) + sizeof(uint32_t)) /* drawn blades + ids */
              + TILES_COMMAND_WORDS * sizeof(uint32_t)                  /* draw commands */
              + (size_t)BLADE_TILES_READBACK_SLOTS * (S + RING_WORDS) * sizeof(uint32_t) /* readback rings */
              + side * side * 4 * sizeof(float)                        /* ground texture */
              + (size_t)l.tiles_x * l.tiles_z * (size_t)d->slope_cells_per_tile * d->slope_cells_per_tile *
                    (sizeof(hybrid_slope_cell_t) + 2 * sizeof(hybrid_slope_sum_t)); /* slope cells + sums */
    return l;
}

/* The field's side, and the window resolved (0: none). */
static float field_side(const blade_tiles_desc_t *d, const terrain_mesh_t *m, int *window)
{
    bool world = m->type == TERRAIN_WORLD;
    *window = d->window > 0 ? d->window : world ? default_window(d) : 0;
    return world ? m->world.size : m->grid_size;
}

int blade_tiles_segments_at(const blade_tiles_desc_t *desc, float distance)
{
    blade_tiles_desc_t d = blade_tiles_desc_defaults(desc);
    float f = fminf(fmaxf(distance / d.lod_distance, 0.0f), 1.0f);
    float hi = (float)d.max_level, lo = (float)(d.max_level / 4 > 1 ? d.max_level / 4 : 1);
    return (int)floorf(hi + f * (lo - hi) + 0.5f);
}

size_t blade_tiles_estimate_bytes(const blade_tiles_desc_t *desc, uint32_t *template_blades_out)
{
    assert(desc->terrain && (desc->terrain->grid_res > 0 || desc->terrain->type == TERRAIN_WORLD));
    blade_tiles_desc_t d = blade_tiles_desc_defaults(desc);
    float side = field_side(&d, desc->terrain, &d.window);
    layout_t l = layout_of(&d, side, desc->terrain->grid_res);
    if (template_blades_out) *template_blades_out = l.blades;
    return l.bytes;
}

void blade_tiles_instance(const blade_tiles_t *t, int tile, int *template_index, int *symmetry)
{
    const int32_t *cell = t->grid.tiles[tile].coord;
    int wi = cell[0] + t->tile_offset[0], wj = cell[1] + t->tile_offset[1];
    uint32_t h = core_hash_u32((uint32_t)wi * 0x8da6b343u ^
                               core_hash_u32((uint32_t)wj ^ (uint32_t)(t->desc.seed * 0x9e3779b9u)));
    *template_index = (int)(h % (uint32_t)t->desc.template_count);
    *symmetry = (int)((h >> 8) & 7u);
}

void blade_tiles_root(const blade_tiles_t *t, int tile, const float local_xz[2], float root[3], float up[3])
{
    int tmpl, sym;
    blade_tiles_instance(t, tile, &tmpl, &sym);
    float half_tile = 0.5f * t->desc.tile_size, x = local_xz[0] - half_tile, z = local_xz[1] - half_tile;
    for (int r = 0; r < (sym & 3); r++) {
        float nx = -z;
        z = x;
        x = nx;
    }
    if (sym & 4) x = -x;
    const int32_t *at = t->grid.tiles[tile].coord;
    float half = 0.5f * t->field_size;
    root[0] = x + half_tile + (-half + (float)at[0] * t->desc.tile_size);
    root[2] = z + half_tile + (-half + (float)at[1] * t->desc.tile_size);
    if (t->world) {
        root[1] = terrain_world_height(&t->world_fn, root[0], root[2], up);
        return;
    }
    /* ground: the height of terrain_height_at, the normal interpolated
     * from the vertex normals with the same weights */
    const float *g = t->ground_cpu;
    int res = t->grid_res, side = res + 1;
    float cell = (2.0f * half) / (float)res;
    float fx = (fminf(fmaxf(root[0], -half), half) + half) / cell;
    float fz = (fminf(fmaxf(root[2], -half), half) + half) / cell;
    int i = (int)floorf(fx), j = (int)floorf(fz);
    i = i < 0 ? 0 : i > res - 1 ? res - 1 : i;
    j = j < 0 ? 0 : j > res - 1 ? res - 1 : j;
    float u = fx - (float)i, v = fz - (float)j;
    const float *p00 = &g[4 * (j * side + i)], *p10 = p00 + 4, *p01 = p00 + 4 * side, *p11 = p01 + 4;
    float r4[4];
    for (int c = 0; c < 4; c++)
        r4[c] = v >= u ? p00[c] + u * (p11[c] - p01[c]) + v * (p01[c] - p00[c])
                       : p00[c] + u * (p10[c] - p00[c]) + v * (p11[c] - p10[c]);
    float l = sqrtf(r4[0] * r4[0] + r4[1] * r4[1] + r4[2] * r4[2]);
    for (int c = 0; c < 3; c++) up[c] = r4[c] / l;
    root[1] = r4[3];
}

void blade_tiles_pose(const blade_tiles_t *t, int tile, uint32_t k, blade_t *out)
{
    int tmpl, sym;
    blade_tiles_instance(t, tile, &tmpl, &sym);
    const blade_t *src = &t->template_cpu[(size_t)tmpl * t->template_blades + k];
    float a = src->v0[3];
    for (int r = 0; r < (sym & 3); r++) a = a + 1.57079633f;
    if (sym & 4) a = 3.14159265f - a;
    float root[3], up[3], local[2] = {src->v0[0], src->v0[2]};
    blade_tiles_root(t, tile, local, root, up);
    float half = 0.5f * t->field_size, h = src->v1[3];
    if (root[0] > half || root[2] > half) h = 0.0f;
    blade_t b = {.v0 = {root[0], root[1], root[2], a}, .up = {up[0], up[1], up[2], src->up[3]}};
    for (int c = 0; c < 3; c++) b.v1[c] = b.v2[c] = root[c] + up[c] * h;
    b.v1[3] = h;
    b.v2[3] = src->v2[3];
    if (h > 0.0f) {
        blade_env_t e = t->env;
        e.time = t->time;
        float s = fmaxf(b.up[3], BLADE_STIFFNESS_MIN);
        float relax = fminf(1.0f - expf(-s * (e.dt > 0.0f ? e.dt : 1.0f / 60.0f)), TILES_POSE_RELAX), g[3], w[3];
        blade_ref_gravity(&b, &e, g);
        for (int it = 0; it < TILES_POSE_ITERATIONS + TILES_POSE_STEPS; it++) {
            blade_ref_wind(&b, &e, w);
            for (int c = 0; c < 3; c++) {
                float target = root[c] + up[c] * h + (g[c] + w[c]) / s;
                b.v2[c] += (target - b.v2[c]) * (it < TILES_POSE_ITERATIONS ? TILES_POSE_RELAX : relax);
            }
            blade_ref_validate(&b, e.length_mode);
        }
    }
    *out = b;
}

static gfx_buffer_t make_buffer(const blade_tiles_t *t, const char *what, size_t size, const void *data)
{
    char label[128];
    snprintf(label, sizeof label, "%s.%s", t->desc.label, what);
    return gfx_buffer_make(&(gfx_buffer_desc_t){
        .size = size ? size : 16, .data = data, .dynamic = true, .label = label});
}

/* The compute programs with the tiles' defines (TILES_WORLD on world
 * terrains), labelled by what they do. */
#define TILE_PROGRAMS 5
static void tile_programs(const char *defines, gfx_program_desc_t out[TILE_PROGRAMS])
{
    out[0] = (gfx_program_desc_t){.cs = "blade/tiles_handover.comp", .defines = defines, .label = "handover"};
    out[1] = (gfx_program_desc_t){.cs = "blade/tiles_slope_resolve.comp", .label = "slope_resolve"};
    out[2] = (gfx_program_desc_t){.cs = "blade/tiles_init.comp", .defines = defines, .label = "init"};
    out[3] = (gfx_program_desc_t){.cs = "blade/tiles_physics.comp", .defines = defines, .label = "physics"};
    out[4] = (gfx_program_desc_t){.cs = "blade/tiles_cull.comp", .defines = defines, .label = "cull"};
}

static const char *tile_defines(bool world) { return world ? "#define TILES_WORLD 1\n" : ""; }

void blade_tiles_prefetch(const terrain_mesh_t *terrain)
{
    gfx_program_desc_t pds[TILE_PROGRAMS];
    tile_programs(tile_defines(terrain->type == TERRAIN_WORLD), pds);
    gfx_programs_prefetch(TILE_PROGRAMS, pds);
}

static bool seed_templates(blade_tiles_t *t)
{
    const blade_tiles_desc_t *d = &t->desc;
    float s = d->tile_size;
    float pos[] = {0, 0, 0, s, 0, 0, s, 0, s, 0, 0, s};
    static const uint32_t idx[] = {0, 2, 1, 0, 3, 2};
    blade_mesh_t mesh = {pos, NULL, 4, idx, 6};
    uint32_t B = t->template_blades;
    t->template_cpu = calloc((size_t)d->template_count * B, sizeof(blade_t));
    if (!t->template_cpu) return false;
    for (int k = 0; k < d->template_count; k++) {
        blade_field_t f;
        blade_seed_desc_t sd = {.seed = d->seed + (uint64_t)k, .population = d->population};
        if (!blade_seed_mesh(&mesh, &sd, &f)) return false;
        if (f.padded_count != B) {
            core_log_error("blade_tiles: template %d has %zu blades, expected %u", k,
                           f.padded_count, B);
            blade_field_free(&f);
            return false;
        }
        memcpy(&t->template_cpu[(size_t)k * B], f.blades, B * sizeof(blade_t));
        t->template_real[k] = (uint32_t)f.blade_count;
        blade_field_free(&f);
    }
    return true;
}

/* The GL objects of t (tiles_init's second half): buffers, readback rings,
 * textures, slope cells and programs; false (one logged error) on failure. */
static bool make_objects(blade_tiles_t *t, const layout_t *l)
{
    const blade_tiles_desc_t *d = &t->desc;
    int ntiles = t->grid.nx * t->grid.nz;
    size_t side = (size_t)t->grid_res + 1;
    uint32_t B = t->template_blades;
    size_t S = (size_t)d->pool_slots;
    t->templates = make_buffer(t, "templates", (size_t)d->template_count * B * sizeof(blade_t), t->template_cpu);
    t->pool = make_buffer(t, "pool", S * B * sizeof(blade_t), NULL);
    t->eta = make_buffer(t, "eta", S * B * sizeof(float), NULL);
    t->motion = make_buffer(t, "motion", S * sizeof(uint32_t), NULL);
    t->slot_words_capacity = 2 * (int)S + SLOT_LISTS_FIRST;
    t->slot_spheres = make_buffer(t, "slot_spheres", (size_t)t->slot_words_capacity * sizeof(uint32_t), NULL);
    t->slot_words = malloc((size_t)t->slot_words_capacity * sizeof(uint32_t));
    t->slot_list = make_buffer(t, "slot_list", S * sizeof(uint32_t), NULL);
    t->init_list = make_buffer(t, "init_list", S * 2 * sizeof(uint32_t), NULL);
    t->winds = make_buffer(t, "winds", BLADE_MAX_WINDS * sizeof(blade_wind_t), NULL);
    t->sphere_capacity = BLADE_SPHERES_FIRST;
    t->spheres = make_buffer(t, "spheres", (size_t)t->sphere_capacity * sizeof(blade_sphere_t), NULL);
    t->tile_list = make_buffer(t, "tile_list", (size_t)l->draw_tiles * 2 * sizeof(uint32_t), NULL);
    t->drawn = make_buffer(t, "drawn", (size_t)t->draw_capacity * sizeof(blade_t), NULL);
    t->drawn_ids = make_buffer(t, "drawn_ids", (size_t)t->draw_capacity * sizeof(uint32_t), NULL);
    uint32_t cmd[TILES_COMMAND_WORDS] = {0};
    t->count_word = d->tessellate ? 0 : 1;
    for (int k = 0; k < 2; k++) {
        uint32_t *c = &cmd[k ? CMD_FADE : CMD_SOLID];
        if (d->tessellate) c[1] = 1u; /* one instance of `count` patches */
        else c[0] = blade_strip_vertices(d->max_level, d->displacement); /* vertices of one strip */
    }
    t->command = make_buffer(t, "command", sizeof cmd, cmd);
    bool ok = t->templates.id && t->pool.id && t->eta.id && t->motion.id && t->slot_spheres.id && t->slot_words &&
              t->slot_list.id &&
              t->init_list.id && t->winds.id && t->spheres.id && t->tile_list.id && t->drawn.id &&
              t->drawn_ids.id && t->command.id;
    char label[128];
    snprintf(label, sizeof label, "%s.motion_readback", d->label);
    t->motion_ring = gfx_readback_make(S * sizeof(uint32_t), BLADE_TILES_READBACK_SLOTS, label);
    snprintf(label, sizeof label, "%s.draw_readback", d->label);
    t->draw_ring = gfx_readback_make(RING_WORDS * sizeof(uint32_t), BLADE_TILES_READBACK_SLOTS, label);
    ok = ok && t->motion_ring.depth && t->draw_ring.depth;
    snprintf(label, sizeof label, "%s.ground", d->label);
    if (!t->world)
        t->ground = gfx_texture_make(&(gfx_texture_desc_t){.w = (int)side, .h = (int)side, .format = GL_RGBA32F,
                                                       .filter = GL_NEAREST, .data = t->ground_cpu,
                                                       .upload_format = GL_RGBA, .upload_type = GL_FLOAT,
                                                       .label = label});
    if (d->extent) {
        snprintf(label, sizeof label, "%s.extent", d->label);
        t->extent = gfx_texture_make(&(gfx_texture_desc_t){.w = d->extent->w, .h = d->extent->h, .format = GL_R8,
                                                           .filter = GL_NEAREST, .data = d->extent->px,
                                                           .upload_format = GL_RED, .label = label});
        ok = ok && t->extent.id;
    }
    int cpt = d->slope_cells_per_tile;
    t->slope_grid = hybrid_slope_grid(t->field_min[0], t->field_min[1], d->tile_size, t->grid.nx, t->grid.nz, cpt);
    float per_cell = d->population.density * t->slope_grid.cell * t->slope_grid.cell;
    if (per_cell > (float)HYBRID_SLOPE_MAX_PER_CELL) {
        core_log_error("blade_tiles_make: %.0f blades per slope cell, at most %d (the default "
                       "blade_tiles_desc_t.slope_cells_per_tile keeps within it)",
                       per_cell, HYBRID_SLOPE_MAX_PER_CELL);
        return false;
    }
    size_t cells = (size_t)t->slope_grid.nx * (size_t)t->slope_grid.nz;
    t->slope_map = make_buffer(t, "slope_map", cells * sizeof(hybrid_slope_cell_t), NULL);
    t->slope_sums = make_buffer(t, "slope_sums", cells * sizeof(hybrid_slope_sum_t), NULL);
    t->bb_sums = make_buffer(t, "bb_slope_sums", cells * sizeof(hybrid_slope_sum_t), NULL);
    ok = ok && t->slope_map.id && t->slope_sums.id && t->bb_sums.id;
    /* the compute programs, built side by side */
    char labels[TILE_PROGRAMS][128];
    gfx_program_desc_t pds[TILE_PROGRAMS];
    tile_programs(t->defines, pds);
    for (int k = 0; k < TILE_PROGRAMS; k++) {
        snprintf(labels[k], sizeof labels[k], "%s.%s", d->label, pds[k].label);
        pds[k].label = labels[k];
    }
    gfx_program_t progs[TILE_PROGRAMS];
    ok = gfx_programs_make(TILE_PROGRAMS, pds, progs) && ok;
    t->handover = progs[0];
    t->resolve = progs[1];
    t->init = progs[2];
    t->physics = progs[3];
    t->cull = progs[4];
    if (t->world) {
        /* tiles_common.glsl's ground: the world's height function */
        gfx_program_t world_progs[] = {t->handover, t->init, t->physics, t->cull};
        terrain_world_gpu_t w = terrain_world_gpu(&t->world_fn);
        for (size_t k = 0; k < sizeof world_progs / sizeof world_progs[0]; k++)
            gfx_world_height_uniforms(world_progs[k], w.keys, TERRAIN_WORLD_LAYERS, w.height);
    }
    t->tile_info = make_buffer(t, "tile_info", (size_t)t->grid.nx * (size_t)t->grid.nz * sizeof(uint32_t), NULL);
    ok = ok && t->tile_info.id;
    snprintf(label, sizeof label, "%s.vao", d->label);
    t->vao = gfx_vertex_array_make(label);
    ok = ok && (t->world || t->ground.id) && t->init.id && t->physics.id && t->cull.id && t->vao;
    if (!ok) {
        core_log_error("blade_tiles_make: could not create the GL objects of '%s'", d->label);
        return false;
    }
    uint32_t zero = 0;
    glClearNamedBufferData(t->pool.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearNamedBufferData(t->eta.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearNamedBufferData(t->slope_map.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearNamedBufferData(t->slope_sums.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glClearNamedBufferData(t->bb_sums.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    t->stats.gpu_bytes = l->bytes;
    t->stats.slots_total = d->pool_slots;
    t->stats.blades_per_template = B;
    t->stats.tiles = ntiles;
    return true;
}

/* hybrid_desc_t.tile_range for a window: the ground's range under a tile
 * from 5 x 5 samples, padded by half the sample spacing times the steepest
 * slope seen (the ground between samples may rise that much). */
static void tile_range(void *user, const float min_xz[2], const float max_xz[2], float y[2])
{
    const terrain_mesh_t *m = user;
    enum { N = 5 };
    float lo = FLT_MAX, hi = -FLT_MAX, slope = 0.0f;
    float step = fmaxf(max_xz[0] - min_xz[0], max_xz[1] - min_xz[1]) / (float)(N - 1);
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            vec3 n;
            float x = fminf(min_xz[0] + step * (float)i, max_xz[0]);
            float z = fminf(min_xz[1] + step * (float)j, max_xz[1]);
            float h = terrain_height_at(m, x, z, n);
            lo = fminf(lo, h);
            hi = fmaxf(hi, h);
            slope = fmaxf(slope, sqrtf(n[0] * n[0] + n[2] * n[2]) / fmaxf(n[1], 0.05f));
        }
    float pad = 0.5f * step * slope + 0.05f;
    y[0] = lo - pad;
    y[1] = hi + pad;
}

/* Fills the zeroed t; false (one logged error) on failure, the caller
 * releases. */
static bool tiles_init(blade_tiles_t *t, const blade_tiles_desc_t *desc)
{
    t->desc = blade_tiles_desc_defaults(desc);
    const terrain_mesh_t *m = desc->terrain;
    t->desc.terrain = NULL;
    t->desc.cull.depth = NULL;
    if (!m || (m->grid_res <= 0 && m->type != TERRAIN_WORLD)) {
        core_log_error("blade_tiles_make: the terrain must be a heightfield or a world (mesh terrains: use "
                       "blade_gpu)");
        return false;
    }
    const blade_tiles_desc_t *d = &t->desc;
    t->world = m->type == TERRAIN_WORLD;
    t->field_size = field_side(d, m, &t->desc.window);
    t->field_min[0] = t->field_min[1] = -0.5f * t->field_size;
    t->grid_res = t->world ? 0 : m->grid_res;
    if (t->world) t->world_fn = m->world;
    snprintf(t->defines, sizeof t->defines, "%s", tile_defines(t->world));
    t->reach = d->population.height[1] + 0.5f * d->population.width[1];
    t->tile_offset[0] = t->tile_offset[1] = (int)lroundf(t->field_min[0] / d->tile_size);
    layout_t l = layout_of(d, t->field_size, t->grid_res);
    t->template_blades = l.blades;
    t->draw_capacity = l.draw_capacity;
    t->max_draw_tiles = l.draw_tiles;
    t->env = blade_env_defaults(&(blade_env_t){0});
    memcpy(t->env.winds, d->winds, sizeof d->winds);
    t->env.wind_count = d->wind_count;

    bool ok = hybrid_grid_make(&t->grid, &(hybrid_desc_t){.min_x = t->field_min[0],
                                                          .min_z = t->field_min[1],
                                                          .size_x = t->field_size,
                                                          .size_z = t->field_size,
                                                          .min_y = m->aabb_min[1],
                                                          .max_y = m->aabb_max[1],
                                                          .tile_size = d->tile_size,
                                                          .grass_height = t->reach,
                                                          .switch_distance = d->switch_distance,
                                                          .hysteresis = HYSTERESIS,
                                                          .recover_timeout = d->recover_timeout,
                                                          .motion_epsilon = d->motion_epsilon,
                                                          .pool_slots = d->pool_slots,
                                                          .memory = d->slope_recover,
                                                          .keep_state = d->keep_state || d->window > 0,
                                                          .window = d->window,
                                                          .tile_range = tile_range,
                                                          .range_user = (void *)m});
    int ntiles = t->grid.nx * t->grid.nz;
    size_t side = t->world ? 0 : (size_t)t->grid_res + 1; /* the ground texture's; none on a world */
    t->slot_owner = malloc((size_t)d->pool_slots * sizeof(int));
    t->slot_epoch = calloc((size_t)d->pool_slots, sizeof(uint32_t));
    t->away_mark = calloc((size_t)d->pool_slots, 1);
    t->slot_motion = malloc((size_t)d->pool_slots * sizeof(float));
    t->tile_motion = malloc((size_t)(ntiles > 0 ? ntiles : 1) * sizeof(float));
    t->scratch = malloc((size_t)(d->pool_slots * 5 + 2 * l.draw_tiles) * sizeof(uint32_t));
    t->order = malloc((size_t)(l.draw_tiles > 0 ? l.draw_tiles : 1) * sizeof(blade_order_key_t));
    t->ground_cpu = t->world ? NULL : malloc(side * side * 4 * sizeof(float));
    for (int i = 0; i < BLADE_TILES_READBACK_SLOTS; i++) {
        t->motion_owner[i] = malloc((size_t)d->pool_slots * sizeof(int));
        t->motion_epoch[i] = malloc((size_t)d->pool_slots * sizeof(uint32_t));
        ok = ok && t->motion_owner[i] && t->motion_epoch[i];
    }
    ok = ok && t->slot_owner && t->slot_epoch && t->away_mark && t->slot_motion && t->tile_motion && t->scratch &&
         t->order && (t->world || t->ground_cpu);
    if (!ok || !seed_templates(t)) {
        core_log_error("blade_tiles_make: out of memory or seeding failed");
        return false;
    }
    for (int s = 0; s < d->pool_slots; s++) t->slot_owner[s] = -1, t->slot_motion[s] = 0.0f;
    for (int i = 0; i < ntiles; i++) t->tile_motion[i] = FLT_MAX;
    for (size_t v = 0; v < side * side; v++) {
        memcpy(&t->ground_cpu[4 * v], &m->normals[3 * v], 3 * sizeof(float));
        t->ground_cpu[4 * v + 3] = m->positions[3 * v + 1];
    }
    if (!make_objects(t, &l)) return false;
    t->desc.extent = NULL; /* borrowed during make only, as the terrain */
    return true;
}

/* Every object and allocation of t (members without one are zero). */
static void release(blade_tiles_t *t)
{
    gfx_buffer_t *bufs[] = {&t->templates, &t->pool, &t->eta, &t->motion, &t->winds, &t->spheres,
                            &t->slot_spheres, &t->slot_list, &t->init_list, &t->tile_list, &t->drawn,
                            &t->drawn_ids, &t->command, &t->slope_map, &t->slope_sums, &t->bb_sums};
    for (size_t i = 0; i < sizeof bufs / sizeof bufs[0]; i++)
        if (bufs[i]->id) gfx_buffer_destroy(bufs[i]);
    gfx_readback_destroy(&t->motion_ring);
    gfx_readback_destroy(&t->draw_ring);
    raster_program_destroy(&t->raster);
    gfx_program_t *progs[] = {&t->init, &t->physics, &t->cull, &t->draw, &t->draw_fade, &t->handover, &t->resolve};
    for (size_t i = 0; i < sizeof progs / sizeof progs[0]; i++)
        if (progs[i]->id) gfx_program_destroy(progs[i]);
    if (t->ground.id) gfx_texture_destroy(&t->ground);
    if (t->extent.id) gfx_texture_destroy(&t->extent);
    if (t->tile_info.id) gfx_buffer_destroy(&t->tile_info);
    if (t->vao) gfx_vertex_array_destroy(&t->vao);
    hybrid_grid_free(&t->grid);
    for (int i = 0; i < BLADE_TILES_READBACK_SLOTS; i++) free(t->motion_owner[i]), free(t->motion_epoch[i]);
    free(t->slot_owner);
    free(t->slot_epoch);
    free(t->away_mark);
    free(t->slot_motion);
    free(t->tile_motion);
    free(t->scratch);
    free(t->slot_words);
    free(t->order);
    free(t->template_cpu);
    free(t->ground_cpu);
}

blade_tiles_t *blade_tiles_make(const blade_tiles_desc_t *desc)
{
    blade_tiles_t *t = calloc(1, sizeof *t);
    if (!t) {
        core_log_error("blade_tiles_make: out of memory");
        return NULL;
    }
    if (!tiles_init(t, desc)) {
        blade_tiles_destroy(t);
        return NULL;
    }
    return t;
}

void blade_tiles_destroy(blade_tiles_t *t)
{
    if (!t) return;
    release(t);
    free(t);
}

blade_tiles_info_t blade_tiles_info(const blade_tiles_t *t)
{
    blade_tiles_info_t info = {.desc = t->desc,
                               .grid = &t->grid,
                               .slope_grid = t->slope_grid,
                               .template_blades = t->template_blades,
                               .draw_capacity = t->draw_capacity,
                               .max_draw_tiles = t->max_draw_tiles,
                               .reach = t->reach,
                               .env = t->env,
                               .time = t->time,
                               .extent_texture = t->extent.id,
                               .ground_texture = t->ground.id,
                               .grid_res = t->grid_res,
                               .field_size = t->field_size};
    memcpy(info.template_real, t->template_real, sizeof info.template_real);
    return info;
}

/* Uniforms of slope.glsl. */
static void set_slope_grid(gfx_program_t p, const hybrid_slope_grid_t *g)
{
    glUniform2fv(gfx_uniform(p, "u_slope_origin"), 1, g->origin);
    glUniform1f(gfx_uniform(p, "u_slope_cell"), g->cell);
    glUniform2i(gfx_uniform(p, "u_slope_dims"), g->nx, g->nz);
}

/* Uniforms of tiles_common.glsl, and the shared bindings. */
static void set_common(const blade_tiles_t *t, gfx_program_t p)
{
    const blade_env_t *e = &t->env;
    glUseProgram(p.id);
    glUniform1ui(gfx_uniform(p, "u_template_blades"), t->template_blades);
    glUniform1ui(gfx_uniform(p, "u_template_count"), (GLuint)t->desc.template_count);
    glUniform1ui(gfx_uniform(p, "u_seed_hash"), (uint32_t)(t->desc.seed * 0x9e3779b9u));
    glUniform1i(gfx_uniform(p, "u_tiles_x"), t->grid.nx);
    glUniform2i(gfx_uniform(p, "u_tile_offset"), t->tile_offset[0], t->tile_offset[1]);
    int w = t->desc.window;
    glUniform1i(gfx_uniform(p, "u_window"), w);
    glUniform2i(gfx_uniform(p, "u_window_base"), t->grid.base[0], t->grid.base[1]);
    if (w > 0)
        glUniform2i(gfx_uniform(p, "u_window_shift"), ((-t->grid.base[0]) % w + w) % w,
                    ((-t->grid.base[1]) % w + w) % w);
    glUniform1f(gfx_uniform(p, "u_tile_size"), t->desc.tile_size);
    glUniform1f(gfx_uniform(p, "u_half"), 0.5f * t->field_size);
    glUniform1i(gfx_uniform(p, "u_grid_res"), t->grid_res);
    glUniform1f(gfx_uniform(p, "u_time"), t->time);
    glUniform4f(gfx_uniform(p, "u_gravity"), e->gravity_dir[0], e->gravity_dir[1], e->gravity_dir[2], e->gravity);
    glUniform4f(gfx_uniform(p, "u_gravity_centre"), e->gravity_centre[0], e->gravity_centre[1],
                e->gravity_centre[2], e->gravity_centre_mix);
    glUniform1i(gfx_uniform(p, "u_wind_count"), e->wind_count);
    glUniform1i(gfx_uniform(p, "u_length_mode"), e->length_mode);
    glUniform1f(gfx_uniform(p, "u_pose_dt"), e->dt > 0.0f ? e->dt : 1.0f / 60.0f);
    set_slope_grid(p, &t->slope_grid);
    glBindTextureUnit(BLADE_TILES_TEX_GROUND, t->ground.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_TEMPLATES, t->templates.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_POOL, t->pool.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_ETA, t->eta.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_WINDS, t->winds.id);
}

/* Applies every completed motion readback, oldest first: a value counts
 * only for the tile that still owns the slot it was measured on. */
static void poll_motion(blade_tiles_t *t)
{
    int S = t->desc.pool_slots, r;
    uint32_t *bits = t->scratch;
    while ((r = gfx_readback_poll(&t->motion_ring, false)) >= 0) {
        gfx_readback_read(&t->motion_ring, r, 0, (size_t)S * sizeof(uint32_t), bits);
        for (int s = 0; s < S; s++) {
            int owner = t->motion_owner[r][s];
            float v;
            memcpy(&v, &bits[s], sizeof v);
            if (owner == SLOT_AWAY) { /* a tile away from the window (hybrid_grid_settle_away) */
                if (t->slot_owner[s] == SLOT_AWAY) t->slot_motion[s] = v;
                continue;
            }
            if (owner < 0 || t->slot_owner[s] != owner || t->slot_epoch[s] != t->motion_epoch[r][s]) continue;
            t->slot_motion[s] = v;
            if (t->grid.tiles[owner].state == HYBRID_RECOVERING) t->tile_motion[owner] = v;
        }
    }
}

/* Blades -> billboards: sums of the handed-over slots' tilt offsets per
 * slope cell, then the cells of their tiles (entries: slot, tile). Runs
 * before this update's initialisations, which may reuse the slots. */
static void hand_over(blade_tiles_t *t, const uint32_t *entries, int n)
{
    uint32_t B = t->template_blades;
    GLuint per = (GLuint)(t->desc.slope_cells_per_tile * t->desc.slope_cells_per_tile);
    gfx_buffer_update(t->init_list, 0, (size_t)n * 2 * sizeof(uint32_t), entries);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    set_common(t, t->handover);
    glUniform1ui(gfx_uniform(t->handover, "u_count"), (GLuint)n * B);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_LIST, t->init_list.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HYBRID_BIND_SLOPE_SUMS, t->slope_sums.id);
    glDispatchCompute(((GLuint)n * B + 255u) / 256u, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    gfx_program_t p = t->resolve;
    glUseProgram(p.id);
    set_slope_grid(p, &t->slope_grid);
    glUniform1ui(gfx_uniform(p, "u_count"), (GLuint)n * per);
    glUniform1i(gfx_uniform(p, "u_cells_per_tile"), t->desc.slope_cells_per_tile);
    glUniform1i(gfx_uniform(p, "u_tiles_x"), t->grid.nx);
    glUniform1f(gfx_uniform(p, "u_time"), t->time);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HYBRID_BIND_SLOPE_MAP, t->slope_map.id);
    glDispatchCompute(((GLuint)n * per + 63u) / 64u, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* Initialises the blades of the slots that changed owner (entries: slot,
 * tile | RECOVERING_BIT when seeded); nseed of them are seeded from the
 * billboards' slope sums, which the source callback fills first. */
static void init_slots(blade_tiles_t *t, const uint32_t *entries, int n, int nseed)
{
    uint32_t B = t->template_blades;
    if (nseed && t->source) {
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        t->source(t->source_user, &t->slope_grid, t->bb_sums);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
    gfx_buffer_update(t->init_list, 0, (size_t)n * 2 * sizeof(uint32_t), entries);
    set_common(t, t->init);
    glUniform1ui(gfx_uniform(t->init, "u_count"), (GLuint)n * B);
    glUniform1f(gfx_uniform(t->init, "u_slope_recover"), t->desc.slope_recover);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_LIST, t->init_list.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HYBRID_BIND_SLOPE_MAP, t->slope_map.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HYBRID_BIND_SLOPE_BB_SUMS, t->bb_sums.id);
    glDispatchCompute(((GLuint)n * B + 255u) / 256u, 1, 1);
    gfx_count_add("tiles.initialised", (double)n * B);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    if (nseed && t->source) {
        uint32_t zero = 0;
        glClearNamedBufferData(t->bb_sums.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    }
}

/* Makes t->slot_spheres and its CPU twin t->slot_words hold `words`:
 * past their capacity both are remade, doubled until they fit. False
 * (logged, every time) when the GL or the heap cannot; they are then
 * unchanged. */
static bool fit_slot_lists(blade_tiles_t *t, int words)
{
    if (words <= t->slot_words_capacity) return true;
    int cap = t->slot_words_capacity;
    while (cap < words) cap *= 2;
    uint32_t *cpu = malloc((size_t)cap * sizeof *cpu);
    gfx_buffer_t grown = cpu ? make_buffer(t, "slot_spheres", (size_t)cap * sizeof(uint32_t), NULL) : (gfx_buffer_t){0};
    if (!grown.id) {
        free(cpu);
        core_log_error("%s: cannot grow the per-slot sphere lists to %d words", t->desc.label, cap);
        return false;
    }
    gfx_buffer_destroy(&t->slot_spheres);
    free(t->slot_words);
    t->slot_spheres = grown;
    t->slot_words = cpu;
    t->slot_words_capacity = cap;
    return true;
}

void blade_tiles_update(blade_tiles_t *t, const float camera[3], const collide_set_t *colliders,
                        const blade_env_t *env)
{
    static const collide_set_t none;
    const collide_set_t *c = colliders ? colliders : &none;
    const collide_sphere_t *spheres = c->spheres;
    int sphere_count = c->sphere_count;
    assert(sphere_count >= 0 && sphere_count <= BLADE_MAX_SPHERES);
    if (!blade_sphere_buffer_fit(&t->spheres, &t->sphere_capacity, sphere_count, t->desc.label))
        sphere_count = t->sphere_capacity;
    blade_env_t e = blade_env_defaults(env);
    if (e.wind_count == 0) {
        memcpy(e.winds, t->env.winds, sizeof e.winds);
        e.wind_count = t->env.wind_count;
    }
    t->env = e;
    t->time = e.time;
    poll_motion(t);

    /* activation bound: spheres grown by the blade reach (see the header);
     * a swept sphere by the bounding sphere of its capsule */
    static hybrid_object_t objs[BLADE_MAX_SPHERES];
    for (int k = 0; k < sphere_count; k++) {
        const float *cr = spheres[k].centre_radius, *d = spheres[k].sweep;
        for (int a = 0; a < 3; a++) objs[k].sphere[a] = cr[a] + 0.5f * d[a];
        objs[k].sphere[3] = cr[3] + 0.5f * sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) + t->reach;
    }
    hybrid_grid_settle_away(&t->grid, t->slot_motion);
    hybrid_grid_update(&t->grid, camera, objs, sphere_count, t->tile_motion, e.dt);
    t->stats.streamed_total += t->grid.stats.streamed;
    t->stats.detached_total += t->grid.stats.detached;
    t->stats.reattached_total += t->grid.stats.reattached;

    const int S = t->desc.pool_slots, ntiles = t->grid.nx * t->grid.nz;
    for (int s = 0; s < S; s++) {
        int o = t->slot_owner[s];
        if (o >= 0 && (t->grid.tiles[o].slot != s || t->grid.tiles[o].epoch != t->slot_epoch[s]))
            t->slot_owner[s] = -1;
        t->away_mark[s] = 0;
    }
    for (int k = 0; k < t->grid.away_count; k++) t->away_mark[t->grid.away[k].slot] = 1;
    for (int s = 0; s < S; s++) {
        if (t->slot_owner[s] == SLOT_AWAY && !t->away_mark[s]) t->slot_owner[s] = -1; /* freed or back */
        if (t->away_mark[s] && t->slot_owner[s] != SLOT_AWAY) {
            t->slot_owner[s] = SLOT_AWAY; /* newly away: its motion is measured anew */
            t->slot_motion[s] = FLT_MAX;
        }
    }
    /* the slots' sphere lists: heads, then each slotted tile's whole list */
    int words = 2 * S;
    for (int i = 0; i < ntiles; i++)
        if (t->grid.tiles[i].slot >= 0) words += t->grid.tiles[i].object_count;
    if (!fit_slot_lists(t, words)) gfx_count_add("tiles.spheres_unlisted", words - t->slot_words_capacity);
    uint32_t *slot_spheres = t->slot_words, *init = t->scratch;
    uint32_t *list = init + 2 * S, *handover = list + S;
    memset(slot_spheres, 0, 2 * (size_t)S * sizeof *slot_spheres);
    int ninit = 0, nslots = 0, nhand = 0, nseed = 0, at = 2 * S;
    for (int i = 0; i < ntiles; i++) {
        hybrid_tile_t *tile = &t->grid.tiles[i];
        if (tile->handover_slot >= 0) {
            handover[2 * nhand] = (uint32_t)tile->handover_slot;
            handover[2 * nhand + 1] = (uint32_t)i;
            nhand++;
        }
        if (tile->state != HYBRID_RECOVERING) t->tile_motion[i] = FLT_MAX;
        if (tile->slot < 0) continue;
        int s = tile->slot;
        if (t->slot_owner[s] != i && tile->reattached) {
            t->slot_owner[s] = i; /* back from away: its state goes on */
            t->slot_epoch[s] = tile->epoch;
        } else if (t->slot_owner[s] != i) {
            t->slot_owner[s] = i;
            t->slot_epoch[s] = tile->epoch;
            t->slot_motion[s] = FLT_MAX;
            t->tile_motion[i] = FLT_MAX;
            init[2 * ninit] = (uint32_t)s;
            init[2 * ninit + 1] = (uint32_t)i | (tile->seed ? RECOVERING_BIT : 0u);
            ninit++;
            nseed += tile->seed;
        }
        list[nslots++] = (uint32_t)s | (tile->state == HYBRID_RECOVERING ? RECOVERING_BIT : 0u);
        int n = tile->object_count < t->slot_words_capacity - at ? tile->object_count : t->slot_words_capacity - at;
        slot_spheres[2 * s] = (uint32_t)at;
        slot_spheres[2 * s + 1] = (uint32_t)n;
        memcpy(&slot_spheres[at], &t->grid.objects[tile->object_first], (size_t)n * sizeof *slot_spheres);
        at += n;
    }
    /* tiles away from the camera recover on, with no objects */
    for (int k = 0; k < t->grid.away_count; k++) {
        int s = t->grid.away[k].slot;
        list[nslots++] = (uint32_t)s | RECOVERING_BIT;
    }
    uint32_t B = t->template_blades;
    t->stats.slots_dispatched = nslots;
    t->stats.blades_dispatched = (uint32_t)nslots * B;
    t->stats.handovers = nhand;
    t->stats.seeded = nseed;
    t->stats.handovers_total += nhand;
    t->stats.seeded_total += nseed;

    gfx_timer_begin(GFX_PASS_TILES_PHYSICS);
    if (e.wind_count) gfx_buffer_update(t->winds, 0, (size_t)e.wind_count * sizeof(blade_wind_t), e.winds);
    if (sphere_count) gfx_buffer_update(t->spheres, 0, (size_t)sphere_count * sizeof(collide_sphere_t), spheres);
    t->sphere_count = sphere_count;
    if (nhand) hand_over(t, handover, nhand);
    if (ninit) init_slots(t, init, ninit, nseed);
    uint32_t zero = 0;
    glClearNamedBufferData(t->motion.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    if (nslots) {
        gfx_buffer_update(t->slot_spheres, 0, (size_t)at * sizeof(uint32_t), slot_spheres);
        gfx_buffer_update(t->slot_list, 0, (size_t)nslots * sizeof(uint32_t), list);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        gfx_program_t p = t->physics;
        set_common(t, p);
        glUniform1ui(gfx_uniform(p, "u_count"), (GLuint)nslots * B);
        glUniform1f(gfx_uniform(p, "u_dt"), e.dt);
        glUniform1f(gfx_uniform(p, "u_collision_decay"), e.collision_decay);
        glUniform1f(gfx_uniform(p, "u_collision_gain"), e.collision_gain);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_SPHERES, t->spheres.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_SLOT_SPHERES, t->slot_spheres.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_LIST, t->slot_list.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_MOTION, t->motion.id);
        glDispatchCompute(((GLuint)nslots * B + 255u) / 256u, 1, 1);
        gfx_count_add("tiles.simulated", (double)nslots * B);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        gfx_readback_copy(&t->motion_ring, t->motion, 0, 0, (size_t)S * 4);
        int r = gfx_readback_fence(&t->motion_ring);
        for (int s = 0; s < S; s++) {
            int o = t->slot_owner[s];
            t->motion_owner[r][s] = o >= 0 && t->grid.tiles[o].state == HYBRID_RECOVERING ? o
                                    : o == SLOT_AWAY                                      ? SLOT_AWAY
                                                                                          : -1;
            t->motion_epoch[r][s] = t->slot_epoch[s];
        }
    }
    glBindTextureUnit(BLADE_TILES_TEX_GROUND, 0);
    gfx_timer_end();
}

/* The CPU tile frustum test and tiles_cull.comp: appends the drawn blades
 * to t->drawn and their count to the draw commands (timer "tiles.cull").
 * With `split` (the hardware path's fade) blades whose roots lie beyond
 * the fade start go to the end of t->drawn and the fade command, the rest
 * to the front and the solid one; without it all go to the front. The
 * tile list goes nearest first (blade_order_sort), so the blades are
 * appended roughly front to back and the depth test rejects more of the
 * hidden ones (docs/PERFORMANCE.md). With `grouped` (the compute
 * rasterizer's cull) each workgroup places its survivors together, in
 * order (tiles_cull.comp, u_group_append). */
static void cull_tiles(blade_tiles_t *t, const blade_draw_desc_t *desc, bool split, bool grouped, GLuint depth)
{
    const blade_cull_desc_t *c = &t->desc.cull;
    uint32_t B = t->template_blades;
    gfx_timer_begin(GFX_PASS_TILES_CULL);
    int ntiles = t->grid.nx * t->grid.nz, n = 0;
    uint32_t *list = t->scratch, tile_culled = 0;
    for (int i = 0; i < ntiles; i++) {
        const hybrid_tile_t *tile = &t->grid.tiles[i];
        if (tile->rep != HYBRID_REP_BLADE) continue;
        float mn[3] = {tile->min[0] - t->reach, tile->min[1], tile->min[2] - t->reach};
        float mx[3] = {tile->max[0] + t->reach, tile->max[1], tile->max[2] + t->reach};
        if ((c->disable & BLADE_CULL_FRUSTUM) == 0 && blade_ref_box_outside(mn, mx, desc->view.viewproj, c->frustum_tolerance)) {
            int tmpl, sym;
            blade_tiles_instance(t, i, &tmpl, &sym);
            tile_culled += t->template_real[tmpl];
            continue;
        }
        if (n == t->max_draw_tiles) {
            core_log_warn("blade_tiles: more than %d blade tiles in view; the rest are not drawn", n);
            break;
        }
        t->order[n++] = (blade_order_key_t){.dist2 = core_box_dist2(desc->view.camera, tile->min, tile->max),
                                            .id = (uint32_t)i};
    }
    blade_order_sort(t->order, (size_t)n);
    for (int k = 0; k < n; k++) {
        const hybrid_tile_t *tile = &t->grid.tiles[t->order[k].id];
        list[2 * k] = t->order[k].id;
        list[2 * k + 1] = tile->slot >= 0 ? (uint32_t)tile->slot : NO_SLOT;
    }
    t->stats.tiles_drawn = n;
    uint32_t zero = 0;
    const int counted[] = {CMD_SOLID + t->count_word, CMD_OVERFLOW, CMD_TOTAL, CMD_FADE + t->count_word};
    for (int k = 0; k < 4; k++)
        glClearNamedBufferSubData(t->command.id, GL_R32UI, 4 * counted[k], 4, GL_RED_INTEGER, GL_UNSIGNED_INT,
                                  &zero);
    glClearNamedBufferSubData(t->command.id, GL_R32UI, 4 * CMD_CULLED, 16, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    if (n) gfx_buffer_update(t->tile_list, 0, (size_t)n * 2 * sizeof(uint32_t), list);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_program_t p = t->cull;
    set_common(t, p);
    glUniform1ui(gfx_uniform(p, "u_count"), (GLuint)n * B);
    glUniform1ui(gfx_uniform(p, "u_capacity"), t->draw_capacity);
    glUniform3fv(gfx_uniform(p, "u_cam_pos"), 1, desc->view.camera);
    glUniformMatrix4fv(gfx_uniform(p, "u_view_proj"), 1, GL_FALSE, desc->view.viewproj);
    glUniform1f(gfx_uniform(p, "u_max_distance"), c->max_distance);
    blade_lod_uniforms(p, &c->lod, c->focal_px, c->max_distance);
    glUniform1f(gfx_uniform(p, "u_orientation_threshold"), c->orientation_threshold);
    glUniform1f(gfx_uniform(p, "u_frustum_tolerance"), c->frustum_tolerance);
    glUniform1ui(gfx_uniform(p, "u_disable"), c->disable);
    glUniform1i(gfx_uniform(p, "u_split"), split);
    glUniform1i(gfx_uniform(p, "u_group_append"), grouped);
    glUniform1f(gfx_uniform(p, "u_fade_start"), desc->fade_start);
    glUniform1ui(gfx_uniform(p, "u_count_word"), (GLuint)t->count_word);
    glUniform1i(gfx_uniform(p, "u_use_depth"), depth != 0);
    glUniform1f(gfx_uniform(p, "u_depth_bias"), c->depth_bias);
    glBindTextureUnit(BLADE_TILES_TEX_DEPTH, depth);
    glUniform1i(gfx_uniform(p, "u_extent_on"), t->extent.id != 0);
    glUniform2fv(gfx_uniform(p, "u_extent_origin"), 1, t->desc.extent_origin);
    glUniform1f(gfx_uniform(p, "u_extent_spacing"), t->desc.extent_spacing);
    glUniform1ui(gfx_uniform(p, "u_extent_seed"), t->desc.extent_seed);
    glBindTextureUnit(BLADE_TILES_TEX_EXTENT, t->extent.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_LIST, t->tile_list.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_DRAWN, t->drawn.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_COMMAND, t->command.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_DRAWN_IDS, t->drawn_ids.id);
    if (n) glDispatchCompute(((GLuint)n * B + 255u) / 256u, 1, 1);
    gfx_count_add("tiles.cull_tested", (double)n * B);
    glBindTextureUnit(BLADE_TILES_TEX_GROUND, 0);
    glBindTextureUnit(BLADE_TILES_TEX_EXTENT, 0);
    glBindTextureUnit(BLADE_TILES_TEX_DEPTH, 0);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    /* appends tried, those past the capacity, and the culled counts */
    gfx_readback_copy(&t->draw_ring, t->command, 4 * CMD_TOTAL, 4 * RING_TOTAL, 4);
    gfx_readback_copy(&t->draw_ring, t->command, 4 * CMD_OVERFLOW, 4 * RING_OVERFLOW, 4);
    gfx_readback_copy(&t->draw_ring, t->command, 4 * CMD_CULLED, 4 * RING_CULLED, 16);
    t->ring_tile_culled[gfx_readback_fence(&t->draw_ring)] = tile_culled;
    t->culled_once = true;
    gfx_timer_end();
}

static blade_surface_t tiles_surface(const blade_tiles_t *t)
{
    return (blade_surface_t){.shape = t->desc.population.shape,
                             .displacement = t->desc.displacement,
                             .width_correction = t->desc.width_correction,
                             .width_printed = {t->desc.width_printed[0], t->desc.width_printed[1]},
                             .max_level = t->desc.max_level,
                             .lod_distance = t->desc.lod_distance};
}

/* Blades nearer than the fade start are opaque: drawn without the fade's
 * discard and sample mask, so the depth test runs before the fragment
 * shader (blade.frag); the fading ones after them with both. */
/* The hardware path's draw programs, made by the first blade_tiles_draw:
 * tiles drawn by the compute rasterizer alone never compile them. False
 * (logged) when they do not build; the draw then shows nothing. */
static bool draw_programs(blade_tiles_t *t)
{
    if (t->draw.id) return true;
    if (t->programs_failed) return false;
    gfx_program_desc_t pds[2];
    char labels[2][128];
    for (int fade = 0; fade < 2; fade++) {
        /* the pulled strips carry the debug overlays; the tessellation
         * stages are blade mode's (blade.tesc, blade.tese) */
        pds[fade] = (gfx_program_desc_t){.vs = "blade/tiles_draw.vert", .fs = "blade/blade.frag",
                                         .defines = fade ? "#define BLADE_OVERLAY 1\n#define BLADE_FADE 1\n"
                                                         : "#define BLADE_OVERLAY 1\n"};
        if (t->desc.tessellate) {
            pds[fade] = (gfx_program_desc_t){.vs = "blade/tiles_tess.vert", .tcs = "blade/blade.tesc",
                                             .tes = "blade/blade.tese", .fs = "blade/blade.frag",
                                             .defines = fade ? "#define BLADE_FADE 1\n" : NULL};
        }
        snprintf(labels[fade], sizeof labels[fade], "%s.draw_%s%s", t->desc.label,
                 t->desc.tessellate ? "tess" : "pull", fade ? "_fade" : "");
        pds[fade].label = labels[fade];
    }
    gfx_program_t progs[2];
    gfx_programs_make(2, pds, progs);
    t->draw = progs[0];
    t->draw_fade = progs[1];
    if (t->draw.id && t->draw_fade.id) return true;
    gfx_program_destroy(&t->draw);
    gfx_program_destroy(&t->draw_fade);
    t->programs_failed = true;
    return false;
}

void blade_tiles_draw(blade_tiles_t *t, const blade_draw_desc_t *desc, GLuint depth_texture)
{
    if (!draw_programs(t)) return;
    bool fade = desc->fade_end > desc->fade_start, tess = t->desc.tessellate;
    cull_tiles(t, desc, fade, false, depth_texture);
    uint32_t B = t->template_blades;
    gfx_timer_begin(GFX_PASS_TILES_DRAW);
    if (t->overlay) {
        int ntiles_all = t->grid.nx * t->grid.nz;
        uint32_t *info = malloc((size_t)ntiles_all * sizeof(uint32_t));
        for (int i = 0; info && i < ntiles_all; i++) {
            const hybrid_tile_t *tile = &t->grid.tiles[i];
            info[i] = (uint32_t)tile->state | ((tile->slot >= 0 ? (uint32_t)tile->slot : 0xffffu) << 2);
        }
        if (info) gfx_buffer_update(t->tile_info, 0, (size_t)ntiles_all * sizeof(uint32_t), info);
        free(info);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, tess ? BLADE_BIND_BLADES : BLADE_TILES_BIND_DRAWN, t->drawn.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_DRAWN_IDS, t->drawn_ids.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_TILE_INFO, t->tile_info.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_TILES_BIND_DRAW_ETA, t->eta.id);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, t->command.id);
    glBindVertexArray(t->vao);
    glEnable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    blade_surface_t surf = tiles_surface(t);
    if (tess) glPatchParameteri(GL_PATCH_VERTICES, 1);
    for (int pass = 0; pass < (fade ? 2 : 1); pass++) {
        gfx_program_t p = pass ? t->draw_fade : t->draw;
        glUseProgram(p.id);
        blade_set_surface_uniforms(p, &surf, desc);
        glUniform1ui(gfx_uniform(p, "u_capacity"), t->draw_capacity);
        glUniform1i(gfx_uniform(p, "u_from_end"), pass);
        glUniform1i(gfx_uniform(p, "u_overlay"), t->overlay);
        glUniform1ui(gfx_uniform(p, "u_template_blades"), B);
        glDrawArraysIndirect(tess ? GL_PATCHES : GL_TRIANGLE_STRIP,
                             (const void *)(uintptr_t)(4 * (pass ? CMD_FADE : CMD_SOLID)));
    }
    glBindVertexArray(0);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    gfx_timer_end();
}

void blade_tiles_cull(blade_tiles_t *t, const blade_draw_desc_t *desc, GLuint depth_texture, bool grouped)
{
    cull_tiles(t, desc, !grouped && desc->fade_end > desc->fade_start, grouped, depth_texture);
}

bool blade_tiles_raster(blade_tiles_t *t, raster_t *r, const blade_draw_desc_t *desc, GLuint depth_texture)
{
    cull_tiles(t, desc, false, true, depth_texture);
    gfx_timer_begin(GFX_PASS_TILES_RASTER);
    blade_surface_t surf = tiles_surface(t);
    bool ok = blade_raster_list(r, &t->raster, &surf, desc, t->drawn, (gfx_buffer_t){0}, t->command,
                                CMD_SOLID + (uint32_t)t->count_word, t->draw_capacity);
    gfx_timer_end();
    return ok;
}

blade_tiles_stats_t blade_tiles_stats(blade_tiles_t *t, bool wait)
{
    int r;
    while ((r = gfx_readback_poll(&t->draw_ring, wait)) >= 0) {
        uint32_t v[RING_WORDS];
        gfx_readback_read(&t->draw_ring, r, 0, sizeof v, v);
        uint32_t total = v[RING_TOTAL], over = v[RING_OVERFLOW];
        t->stats.blades_drawn = total < t->draw_capacity ? total : t->draw_capacity;
        t->stats.draw_overflow = over;
        memcpy(t->stats.culled, &v[RING_CULLED], sizeof t->stats.culled);
        t->stats.tile_culled = t->ring_tile_culled[r];
        if (over && !t->warned_overflow)
            core_log_warn("blade_tiles: %u blades did not fit the draw buffer (%u, blade_tiles_desc_t.draw_capacity; "
                          "its default holds every blade of the tiles in reach)", over,
                          t->draw_capacity);
        t->warned_overflow = t->warned_overflow || over;
    }
    const hybrid_stats_t *h = &t->grid.stats;
    t->stats.idle = h->idle;
    t->stats.active = h->active;
    t->stats.recovering = h->recovering;
    t->stats.blade_tiles = h->blade_tiles;
    t->stats.slots_used = h->slots_used;
    t->stats.pool_denied = h->pool_denied;
    t->stats.triangles_max = (long)t->stats.blades_drawn * 2 * t->desc.max_level;
    return t->stats;
}

void blade_tiles_slope(const blade_tiles_t *t, gfx_buffer_t *map, hybrid_slope_grid_t *grid, float *recover)
{
    *map = t->slope_map;
    *grid = t->slope_grid;
    *recover = t->desc.slope_recover;
}

void blade_tiles_read_slot(const blade_tiles_t *t, int slot, blade_t *out, float *eta_out)
{
    size_t B = t->template_blades;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (out) gfx_buffer_read(t->pool, (size_t)slot * B * sizeof(blade_t), B * sizeof(blade_t), out);
    if (eta_out) gfx_buffer_read(t->eta, (size_t)slot * B * sizeof(float), B * sizeof(float), eta_out);
}

void blade_tiles_read_pool(const blade_tiles_t *t, blade_t *out)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_buffer_read(t->pool, 0, (size_t)t->desc.pool_slots * t->template_blades * sizeof(blade_t), out);
}

uint32_t blade_tiles_read_drawn(const blade_tiles_t *t, blade_t *out, uint32_t *ids)
{
    uint32_t solid, fade;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_buffer_read(t->command, 4 * (CMD_SOLID + (size_t)t->count_word), sizeof solid, &solid);
    gfx_buffer_read(t->command, 4 * (CMD_FADE + (size_t)t->count_word), sizeof fade, &fade);
    uint32_t cap = t->draw_capacity, first_fade = cap - fade;
    if (solid && out) gfx_buffer_read(t->drawn, 0, solid * sizeof(blade_t), out);
    if (solid && ids) gfx_buffer_read(t->drawn_ids, 0, solid * sizeof(uint32_t), ids);
    if (fade && out) gfx_buffer_read(t->drawn, first_fade * sizeof(blade_t), fade * sizeof(blade_t), out + solid);
    if (fade && ids)
        gfx_buffer_read(t->drawn_ids, first_fade * sizeof(uint32_t), fade * sizeof(uint32_t), ids + solid);
    return solid + fade;
}

int blade_tiles_read_tile_list(const blade_tiles_t *t, uint32_t *out)
{
    int n = t->stats.tiles_drawn;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (n) gfx_buffer_read(t->tile_list, 0, (size_t)n * 2 * sizeof(uint32_t), out);
    return n;
}

void blade_tiles_read_template(const blade_tiles_t *t, int index, blade_t *out)
{
    assert(index >= 0 && index < t->desc.template_count);
    memcpy(out, &t->template_cpu[(size_t)index * t->template_blades], t->template_blades * sizeof *out);
}

int blade_tiles_slot_owner(const blade_tiles_t *t, int slot) { return t->slot_owner[slot]; }

void blade_tiles_set_cull(blade_tiles_t *t, const blade_cull_desc_t *cull)
{
    t->desc.cull = *cull;
    t->desc.cull.depth = NULL;
}

void blade_tiles_set_lod(blade_tiles_t *t, const blade_lod_t *lod, float focal_px)
{
    blade_cull_desc_t c = t->desc.cull;
    c.lod = *lod;
    c.focal_px = focal_px;
    t->desc.cull = blade_cull_desc_defaults(&c);
}

float blade_tiles_slot_motion(const blade_tiles_t *t, int slot)
{
    return t->slot_motion[slot];
}

void blade_tiles_set_overlay(blade_tiles_t *t, int overlay) { t->overlay = overlay; }

void blade_tiles_set_slope_source(blade_tiles_t *t, blade_tiles_slope_source_fn fn, void *user)
{
    t->source = fn;
    t->source_user = user;
}

int blade_tiles_read_spheres(const blade_tiles_t *t, blade_sphere_t *out, int max)
{
    int n = t->sphere_count < max ? t->sphere_count : max;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    if (n > 0) gfx_buffer_read(t->spheres, 0, (size_t)n * sizeof(blade_sphere_t), out);
    return t->sphere_count;
}

void blade_tiles_read_slopes(const blade_tiles_t *t, hybrid_slope_cell_t *out)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_buffer_read(t->slope_map, 0,
                    (size_t)t->slope_grid.nx * (size_t)t->slope_grid.nz * sizeof(hybrid_slope_cell_t), out);
}

void blade_tiles_write_slopes(blade_tiles_t *t, const hybrid_slope_cell_t *cells)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_buffer_update(t->slope_map, 0,
                      (size_t)t->slope_grid.nx * (size_t)t->slope_grid.nz * sizeof(hybrid_slope_cell_t), cells);
}

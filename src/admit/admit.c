/* admit: the memory and work estimate of a run and the check against
 * the GL's limits and the machine's memory (see admit.h). A scene that
 * does not fit names the key of the largest part that deviates most from
 * its default and the largest (or smallest) value of it that fits, found by
 * bisecting the same estimate. */
#include "admit/admit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include <cglm/cglm.h>

#include "billboard/bb_ring.h"
#include "blade/blade_tiles.h"
#include "hybrid/hybrid.h"
#include "scene/scene_fields.h"
#include "terrain/terrain_clipmap.h"

#define MIB (1024.0 * 1024.0)
#define BLADE_BYTES 64.0   /* sizeof(blade_t) */
#define BB_POINT_BYTES 64.0 /* sizeof(bb_point_t) */
#define CUBE_TEXEL_BYTES 16.0 /* GL_RGBA32F */

const char *admit_part_name(int part)
{
    static const char *const names[ADMIT_PARTS] = {"fixed",  "render targets", "compute rasterizer", "terrain",
                                                       "blades", "blade tiles",    "billboards",         "cube maps"};
    return part >= 0 && part < ADMIT_PARTS ? names[part] : "?";
}

/* Side (m) of the ground: terrain.size for heightfields, the mesh's box. */
static void ground_extent(const scene_desc_t *s, const admit_world_t *w, double ext[2])
{
    const terrain_mesh_t *t = w->terrain;
    if (s->terrain.type == TERRAIN_HEIGHTFIELD || !t) {
        ext[0] = ext[1] = s->terrain.size;
        return;
    }
    ext[0] = t->aabb_max[0] - t->aabb_min[0];
    ext[1] = t->aabb_max[2] - t->aabb_min[2];
}

/* Ground surface at the scene's terrain.size: the loaded terrain's area,
 * scaled with terrain.size for heightfields (the bisection changes it). */
static double ground_area(const scene_desc_t *s, const admit_world_t *w)
{
    double ext[2];
    ground_extent(s, w, ext);
    if (!w->terrain || w->terrain_area <= 0.0) return ext[0] * ext[1];
    if (s->terrain.type != TERRAIN_HEIGHTFIELD) return w->terrain_area;
    double loaded = w->terrain->grid_size > 0.0f ? w->terrain->grid_size : ext[0];
    return w->terrain_area * (ext[0] / loaded) * (ext[0] / loaded);
}

/* cube_resolution_for's side: raised by grass.cube_texel, capped where a
 * cube's 6 faces side by side exceed the GL's texture size. */
static int cube_res(const scene_desc_t *s, const admit_world_t *w)
{
    const scene_grass_desc_t *g = &s->grass;
    int res = g->cube_resolution;
    if (g->cube_texel <= 0.0f) return res;
    double want = ceil(2.0 * w->collider_radius / g->cube_texel);
    int cap = (w->max_texture_size > 0 ? w->max_texture_size : 16384) / 6;
    if (want > cap) want = cap;
    return want > res ? (int)want : res;
}

static double tiles_bytes(const scene_desc_t *s, const admit_world_t *w)
{
    const scene_grass_desc_t *g = &s->grass;
    terrain_mesh_t t = *w->terrain;
    t.grid_size = t.world.size = s->terrain.size;
    double tiles = ceil(t.grid_size / g->tile_size) * ceil(t.grid_size / g->tile_size);
    if (t.type == TERRAIN_WORLD) tiles = 0; /* a window of tiles, whatever the size */
    if (tiles > HYBRID_MAX_TILES || g->population.density * g->tile_size * g->tile_size < 1.0f) return INFINITY;
    float distance = w->tiles_distance > 0.0f ? w->tiles_distance : g->switch_distance;
    blade_tiles_desc_t d = {.terrain = &t, .tile_size = g->tile_size, .population = g->population,
                            .switch_distance = distance, .pool_slots = g->tile_pool,
                            .cull = {.max_distance = distance + 1.0f, .lod = g->lod, .focal_px = scene_focal(s)}};
    return (double)blade_tiles_estimate_bytes(&d, NULL);
}

/* A world's billboard ring (bb_ring.h) out to the canopy's band (its
 * reach in world.c make_bb: canopy_distance + GRASS_CANOPY_FADE, 4 m),
 * generation tiles of 2 x 2: W^2 K^2 points, whatever the world's size;
 * *scratch: its collide scratch, 32 slots of K^2 (bb_ring.c). */
static double ring_candidates(const scene_desc_t *s, double spacing, double *scratch)
{
    int cand = bb_ring_cand(BB_RING_CELL_DEFAULT, (float)spacing, 2);
    double side = bb_ring_side(s->grass.canopy_distance + 4.0f, (float)(cand * spacing));
    *scratch = fmin(side * side, 32.0) * cand * cand;
    return side * side * cand * cand;
}

void admit_estimate(const scene_desc_t *s, const admit_world_t *w, admit_t *e)
{
    memset(e, 0, sizeof *e);
    const scene_grass_desc_t *g = &s->grass;
    double px = (double)s->size[0] * s->size[1], ts = w->target_samples > 0 ? w->target_samples : 1;
    e->gpu[ADMIT_FIXED] = 9.0 * MIB; /* the upload ring (8 MiB), programs, small buffers */
    e->gpu[ADMIT_TARGETS] = px * 8.0 * (ts > 1 ? ts + 1.0 : 1.0);
    if (w->raster) {
        double rs = s->raster_samples > 0 ? s->raster_samples : SCENE_DEFAULT_RASTER_SAMPLES;
        double queue = fmin(fmax(px * rs * ADMIT_RASTER_QUEUE_LAYERS / 64.0, (double)(1 << 20)), (double)(1 << 26));
        e->raster_vis = px * rs * 8.0;
        e->gpu[ADMIT_RASTER] = e->raster_vis + px * 4.0 + 16.0 * queue; /* visibility, depth, triangle queues */
        if (s->raster == SCENE_RASTER_AUTO) e->transient = px * 8.0 * (ts > 1 ? ts + 2.0 : 2.0);
    }
    double verts, indices;
    if (s->terrain.type == TERRAIN_WORLD) {
        verts = indices = 0.0; /* a function: the clipmap's bytes below, the same for any size */
    } else if (s->terrain.type == TERRAIN_HEIGHTFIELD || !w->terrain) {
        double r = s->terrain.resolution;
        verts = (r + 1.0) * (r + 1.0);
        indices = 6.0 * r * r;
    } else {
        verts = w->terrain->vertex_count;
        indices = w->terrain->index_count;
    }
    e->gpu[ADMIT_TERRAIN] = verts * 32.0 + indices * 4.0 + (w->billboards ? verts * 4.0 : 0.0) +
                                (s->terrain.type == TERRAIN_WORLD
                                     ? (double)terrain_clipmap_estimate_bytes(&(terrain_clipmap_desc_t){0})
                                     : 0.0);
    e->host = verts * 32.0 + indices * 4.0 + indices / 3.0 * 4.0; /* the mesh and its cell grid */
    double area = ground_area(s, w), ext[2];
    ground_extent(s, w, ext);
    if (w->full_field) {
        e->blades = area * g->population.density;
        e->gpu[ADMIT_BLADES] = e->blades * (BLADE_BYTES + 12.0) + MIB; /* eta, survivor (id, width factor) */
        e->host += e->blades * (BLADE_BYTES + 4.0); /* seeded on the CPU, then uploaded */
    }
    if (w->tiles && w->terrain) {
        e->gpu[ADMIT_TILES] = tiles_bytes(s, w);
        e->blades = (double)g->tile_pool * g->population.density * g->tile_size * g->tile_size;
    }
    if (w->billboards) {
        double spacing = 1.0 / sqrt(g->billboard_density), scratch = 0.0;
        e->bb_candidates = s->terrain.type == TERRAIN_HEIGHTFIELD ? ceil(ext[0] / spacing) * ceil(ext[1] / spacing)
                           : s->terrain.type == TERRAIN_WORLD     ? ring_candidates(s, spacing, &scratch)
                                                                  : 1.3 * area * g->billboard_density;
        double layout = fmin(fmax(ceil(fmax(ext[0], ext[1]) / spacing), 32.0), 1024.0);
        /* points and the collide passes' scratch copy (a ring's holds 32 cells) */
        if (s->terrain.type != TERRAIN_WORLD) scratch = e->bb_candidates;
        e->gpu[ADMIT_BILLBOARDS] = (e->bb_candidates + scratch) * BB_POINT_BYTES + e->bb_candidates * 8.0 +
                                       (double)g->deformed_pool * g->subdiv[0] * g->subdiv[1] * 16.0 +
                                       layout * layout * 5.0 + 0.5 * MIB;
        double res = cube_res(s, w);
        e->gpu[ADMIT_CUBES] = res * res * 6.0 * (w->objects > 1 ? w->objects : 1) * CUBE_TEXEL_BYTES;
    }
    for (int k = 0; k < ADMIT_PARTS; k++) e->gpu_total += e->gpu[k];
}

/* ---- the check ------------------------------------------------------------ */

/* A key the bisection may change: +1 when larger values cost more. */
typedef struct knob_t {
    scene_section_t section;
    const char *key;
    int sign;
} knob_t;

static void *field_at(scene_desc_t *s, const scene_field_t *f)
{
    char *base = f->section == SCENE_SEC_TERRAIN ? (char *)&s->terrain
                 : f->section == SCENE_SEC_GRASS ? (char *)&s->grass
                                                 : (char *)s;
    return base + f->offset;
}

/* The knob's value(s) times k (integers rounded towards the cheaper side). */
static void knob_scale(scene_desc_t *s, const knob_t *kn, const scene_desc_t *from, double k)
{
    const scene_field_t *f = scene_field_find(kn->section, kn->key);
    int n = f->type == SCENE_FIELD_INTS || f->type == SCENE_FIELD_FLOATS ? f->n : 1;
    for (int c = 0; c < n; c++) {
        if (f->type == SCENE_FIELD_INT || f->type == SCENE_FIELD_INTS) {
            double v = ((const int *)field_at((scene_desc_t *)from, f))[c] * k;
            v = kn->sign > 0 ? floor(v) : ceil(v);
            ((int *)field_at(s, f))[c] = (int)fmin(fmax(v, fmax(f->lo, 1.0)), f->hi);
        } else {
            double v = ((const float *)field_at((scene_desc_t *)from, f))[c] * k;
            ((float *)field_at(s, f))[c] = (float)fmin(fmax(v, 1e-9), f->hi);
        }
    }
}

static double knob_ratio(const scene_desc_t *s, const knob_t *kn)
{
    const scene_field_t *f = scene_field_find(kn->section, kn->key);
    const void *at = field_at((scene_desc_t *)s, f);
    bool ints = f->type == SCENE_FIELD_INT || f->type == SCENE_FIELD_INTS;
    double v = ints ? ((const int *)at)[0] : ((const float *)at)[0];
    double d = f->def[0] > 0.0f ? f->def[0] : 1.0;
    return kn->sign > 0 ? v / d : d / fmax(v, 1e-12);
}

/* size given as --size: named as the option, WxH (knob_format). */
static bool size_option(const admit_world_t *w, const knob_t *kn)
{
    return w->size_option && kn->section == SCENE_SEC_ROOT && strcmp(kn->key, "size") == 0;
}

static int knob_format(char *buf, size_t size, const scene_desc_t *s, const admit_world_t *w, const knob_t *kn)
{
    const scene_field_t *f = scene_field_find(kn->section, kn->key);
    const void *at = field_at((scene_desc_t *)s, f);
    if (size_option(w, kn)) return snprintf(buf, size, "%dx%d", ((const int *)at)[0], ((const int *)at)[1]);
    if (f->type == SCENE_FIELD_INTS) return snprintf(buf, size, "[%d, %d]", ((const int *)at)[0], ((const int *)at)[1]);
    if (f->type == SCENE_FIELD_INT) return snprintf(buf, size, "%d", ((const int *)at)[0]);
    return snprintf(buf, size, "%.6g", (double)((const float *)at)[0]);
}

/* The part that does not fit (-1: all fit); *why: what it exceeds, *count
 * how many of the items a count limit counts (0: memory). */
static int misfit(const scene_desc_t *s, const admit_world_t *w, const admit_limits_t *lim, admit_t *e,
                  const char **why, double *count)
{
    admit_estimate(s, w, e);
    *count = e->blades;
    if (e->blades > ADMIT_MAX_FIELD_BLADES && w->full_field) {
        *why = "blades, more than the 50000000 a full blade field holds (use mode hybrid for larger fields)";
        return ADMIT_BLADES;
    }
    double groups = lim->max_compute_groups > 0 ? (double)lim->max_compute_groups * 256.0 : INFINITY;
    if (e->blades > groups) {
        *why = "blades simulated per frame, more than one compute dispatch of this GL reaches";
        return w->full_field ? ADMIT_BLADES : ADMIT_TILES;
    }
    if (e->bb_candidates > ADMIT_MAX_BB_CANDIDATES) {
        *why = "billboard candidates, more than the 67108864 a billboard field holds";
        *count = e->bb_candidates;
        return ADMIT_BILLBOARDS;
    }
    double gpu = lim->gpu_bytes > 0.0 ? lim->gpu_bytes : INFINITY;
    double host = lim->host_bytes > 0.0 ? lim->host_bytes : INFINITY;
    bool shared = lim->gpu_bytes <= 0.0;
    double peak = e->gpu_total + e->transient;
    if (peak <= gpu && (shared ? peak + e->host : e->host) <= host) {
        if (e->raster_vis <= ADMIT_MAX_BUFFER_BYTES) return -1;
        *why = "bytes in the compute rasterizer's visibility buffer, more than the 4294967295 one GL buffer holds "
               "(Mesa's limit)";
        *count = e->raster_vis;
        return ADMIT_RASTER;
    }
    *why = shared ? "of memory (GPU storage and host, one pool here)" : "of memory";
    *count = 0.0;
    int worst = ADMIT_TERRAIN;
    for (int k = ADMIT_TARGETS; k < ADMIT_PARTS; k++)
        if (e->gpu[k] > e->gpu[worst]) worst = k;
    return worst;
}

static const knob_t *knobs_of(int part, int *count)
{
    static const knob_t targets[] = {{SCENE_SEC_ROOT, "size", 1}};
    static const knob_t terrain[] = {{SCENE_SEC_TERRAIN, "resolution", 1}};
    static const knob_t blades[] = {{SCENE_SEC_GRASS, "density", 1}, {SCENE_SEC_TERRAIN, "size", 1}};
    static const knob_t tiles[] = {{SCENE_SEC_GRASS, "density", 1},  {SCENE_SEC_GRASS, "tile_size", 1},
                                   {SCENE_SEC_GRASS, "switch_distance", 1}, {SCENE_SEC_GRASS, "tile_pool", 1},
                                   {SCENE_SEC_TERRAIN, "size", 1}};
    static const knob_t bb[] = {{SCENE_SEC_GRASS, "billboard_density", 1}, {SCENE_SEC_GRASS, "deformed_pool", 1},
                                {SCENE_SEC_TERRAIN, "size", 1}};
    static const knob_t cubes[] = {{SCENE_SEC_GRASS, "cube_resolution", 1}, {SCENE_SEC_GRASS, "cube_texel", -1}};
    static const struct {
        const knob_t *k;
        int n;
    } by_part[ADMIT_PARTS] = {[ADMIT_TARGETS] = {targets, 1}, [ADMIT_RASTER] = {targets, 1},
                                  [ADMIT_TERRAIN] = {terrain, 1}, [ADMIT_BLADES] = {blades, 2},
                                  [ADMIT_TILES] = {tiles, 5},     [ADMIT_BILLBOARDS] = {bb, 3},
                                  [ADMIT_CUBES] = {cubes, 2}};
    *count = by_part[part].n;
    return by_part[part].k;
}

/* The largest scale k of kn's value (sign > 0; the smallest above 1 when
 * sign < 0) with which the scene fits; false when even the cheap end does
 * not fit. */
static bool bisect(const scene_desc_t *s, const admit_world_t *w, const admit_limits_t *lim, const knob_t *kn,
                   scene_desc_t *fit)
{
    const scene_field_t *f = scene_field_find(kn->section, kn->key);
    const void *at = field_at((scene_desc_t *)s, f);
    bool ints = f->type == SCENE_FIELD_INT || f->type == SCENE_FIELD_INTS;
    double v = ints ? ((const int *)at)[0] : ((const float *)at)[0];
    /* The cheap end: the key's default when that is cheaper, else the end
     * of its range (tile_size: tiles too small are refused, not cheap). */
    double def = f->def[0] > 0.0f ? f->def[0] / fmax(v, 1e-12) : 0.0;
    double ends[2] = {(kn->sign > 0) == (def < 1.0) ? def : 0.0, kn->sign > 0 ? 1e-9 : f->hi / fmax(v, 1e-12)};
    double good = 0.0, bad = 1.0;
    admit_t e;
    const char *why;
    double count;
    *fit = *s;
    for (int i = 0; i < 2 && good == 0.0; i++) {
        if (ends[i] <= 0.0) continue;
        knob_scale(fit, kn, s, ends[i]);
        if (misfit(fit, w, lim, &e, &why, &count) < 0) good = ends[i];
    }
    if (good == 0.0) return false;
    for (int i = 0; i < 60; i++) {
        double mid = sqrt(good * bad);
        knob_scale(fit, kn, s, mid);
        if (misfit(fit, w, lim, &e, &why, &count) >= 0) bad = mid;
        else good = mid;
    }
    knob_scale(fit, kn, s, good);
    /* Three significant digits, rounded towards the cheap side (still fits). */
    if (!ints) {
        float *x = field_at(fit, f);
        int n = f->type == SCENE_FIELD_FLOATS ? f->n : 1;
        for (int c = 0; c < n; c++) {
            double unit = pow(10.0, floor(log10(fmax(x[c], 1e-30))) - 2.0);
            double r = (kn->sign > 0 ? floor(x[c] / unit) : ceil(x[c] / unit)) * unit;
            x[c] = (float)(kn->sign > 0 ? r : fmin(r, f->hi));
        }
    }
    return true;
}

static bool gl_limits(const scene_desc_t *s, const admit_world_t *w, const admit_limits_t *lim, char *err,
                      size_t size)
{
    int side = lim->max_texture_size;
    if (lim->max_renderbuffer_size > 0 && (side <= 0 || lim->max_renderbuffer_size < side))
        side = lim->max_renderbuffer_size;
    if (side > 0 && (s->size[0] > side || s->size[1] > side)) {
        double k = (double)side / fmax(s->size[0], s->size[1]);
        const char *fmt = w->size_option ? "--size %dx%d: this GL's render targets are at most %d px a side: the "
                                           "largest --size of this shape that fits is %dx%d"
                                         : "size [%d, %d]: this GL's render targets are at most %d px a side: the "
                                           "largest size of this shape that fits is [%d, %d]";
        snprintf(err, size, fmt, s->size[0], s->size[1], side, (int)floor(s->size[0] * k), (int)floor(s->size[1] * k));
        return false;
    }
    int n = s->grass.subdiv[0], m = s->grass.subdiv[1];
    int verts = (m - 1) * 2 * n > 4 ? (m - 1) * 2 * n : 4;
    int max_verts = lim->max_gs_vertices, max_comps = lim->max_gs_components;
    if (w->billboards && max_verts > 0 && max_comps > 0 && (verts > max_verts || verts * 16 > max_comps)) {
        int fm = m;
        while (fm > BB_SUBDIV_MIN && ((fm - 1) * 2 * n > max_verts || (fm - 1) * 2 * n * 16 > max_comps)) fm--;
        snprintf(err, size, "grass.subdiv [%d, %d] needs %d geometry-shader output vertices (%d components), this GL "
                 "allows %d (%d): the largest that fits is [%d, %d]", n, m, verts, verts * 16, max_verts, max_comps,
                 n, fm);
        return false;
    }
    return true;
}

/* How many of counts[0..n), taken in order after `used`, stay within `most`. */
static int fit_count(long long used, const int *counts, int n, long long most)
{
    int fit = 0;
    for (; fit < n && used + counts[fit] <= most; fit++) used += counts[fit];
    return fit;
}

/* The blade physics' sphere proxies: a capsule takes 1 + ceil(length /
 * radius) (collide_pack_spheres), so one thin capsule can take them all; a
 * humanoid takes 38, 16 of them (the scene's most) 608. The physics'
 * buffers grow to what a step packs; the collide set holds at most
 * ADMIT_MAX_SPHERES. Counted in long long: a capsule of radius 0 needs
 * COLLIDE_PACK_SATURATED. On a world the host packs only the characters
 * near the tile window and may leave them out here (the grass counts and
 * warns what a step cannot take). */
static bool sphere_limit(const scene_desc_t *s, const admit_world_t *w, char *err, size_t size)
{
    if (!w->full_field && !w->tiles) return true;
    long long colliders = 0, characters = 0;
    int worst = -1;
    for (int i = 0; w->collider_spheres && i < s->collider_count; i++) {
        colliders += w->collider_spheres[i];
        if (worst < 0 || w->collider_spheres[i] > w->collider_spheres[worst]) worst = i;
    }
    for (int i = 0; w->character_spheres && i < w->characters; i++) characters += w->character_spheres[i];
    long long total = colliders + characters, most = ADMIT_MAX_SPHERES;
    if (total <= most) return true;
    if (characters > most || worst < 0) {
        int fit = fit_count(colliders, w->character_spheres, w->characters, most);
        snprintf(err, size, "characters: %d characters take %lld of the blade physics' sphere proxies, %lld with the "
                 "colliders', more than its %lld: the most characters that fit is %d", w->characters, characters,
                 total, most, fit);
        return false;
    }
    const scene_collider_t *c = &s->colliders[worst];
    long long room = most - (total - w->collider_spheres[worst]);
    if (c->type == SCENE_COLLIDER_CAPSULE && room >= 2) {
        snprintf(err, size, "colliders[%d].length %g over radius %g takes %d of the blade physics' sphere proxies, "
                 "%lld with the rest, more than its %lld: the largest colliders[%d].length that fits is %g", worst,
                 (double)c->length, (double)c->radius, w->collider_spheres[worst], total, most, worst,
                 floor((double)(room - 1) * (double)c->radius * 1e3) / 1e3);
        return false;
    }
    int fit = fit_count(characters, w->collider_spheres, s->collider_count, most);
    snprintf(err, size, "colliders: %d colliders and the characters need %lld sphere proxies in the blade physics "
             "(characters %lld), more than its %lld: the most colliders that fit is %d", s->collider_count, total,
             characters, most, fit);
    return false;
}

bool admit_world_supported(const scene_desc_t *s, const admit_world_t *w, char *err, size_t err_size)
{
    if (s->terrain.type != TERRAIN_WORLD) return true;
    const char *what = w->full_field ? "the full blade field (the bench's reference) needs the terrain's vertices"
                       : s->grass.gi   ? "grass.gi needs the terrain's vertices: set it false"
                                       : NULL;
    if (!what) return true;
    snprintf(err, err_size, "terrain.type \"world\": %s", what);
    return false;
}

bool admit_check(const scene_desc_t *s, const admit_world_t *w, const admit_limits_t *lim, char *err,
                     size_t err_size)
{
    if (!admit_world_supported(s, w, err, err_size)) return false;
    if (!sphere_limit(s, w, err, err_size)) return false;
    if (w->objects > ADMIT_MAX_OBJECTS) {
        int most = ADMIT_MAX_OBJECTS - (w->objects - s->collider_count);
        snprintf(err, err_size, "colliders: %d colliders and %d character(s) are %d objects, more than the %d that "
                 "bend grass: the most colliders that fit beside the characters is %d", s->collider_count,
                 w->objects - s->collider_count, w->objects, ADMIT_MAX_OBJECTS, most > 0 ? most : 0);
        return false;
    }
    if (!gl_limits(s, w, lim, err, err_size)) return false;
    admit_t e;
    const char *why = "";
    double items;
    int part = misfit(s, w, lim, &e, &why, &items);
    if (part < 0) return true;
    int count;
    const knob_t *knobs = knobs_of(part, &count);
    /* The key furthest from its default first, then the others. */
    int order[8];
    for (int i = 0; i < count; i++) order[i] = i;
    for (int i = 1; i < count; i++)
        for (int j = i; j > 0 && knob_ratio(s, &knobs[order[j]]) > knob_ratio(s, &knobs[order[j - 1]]); j--) {
            int t = order[j];
            order[j] = order[j - 1];
            order[j - 1] = t;
        }
    char need[160];
    if (items > 0.0)
        snprintf(need, sizeof need, "%.3g %s", items, why);
    else
        snprintf(need, sizeof need, "%.2f GB %s (%s %.2f GB), where %.2f GB is free",
                 (e.gpu_total + e.transient + e.host) / 1e9,
                 why, admit_part_name(part), e.gpu[part] / 1e9,
                 (lim->gpu_bytes > 0.0 ? lim->gpu_bytes : lim->host_bytes) / 1e9);
    scene_desc_t fit;
    for (int i = 0; i < count; i++) {
        const knob_t *kn = &knobs[order[i]];
        if (!bisect(s, w, lim, kn, &fit)) continue;
        char name[64], now[48], best[48];
        const char *sec = scene_section_name(kn->section);
        snprintf(name, sizeof name, "%s%s%s", size_option(w, kn) ? "--" : sec, sec[0] ? "." : "", kn->key);
        knob_format(now, sizeof now, s, w, kn);
        knob_format(best, sizeof best, &fit, w, kn);
        snprintf(err, err_size, "%s %s needs %s: the %s %s that fits is %s", name, now, need,
                 kn->sign > 0 ? "largest" : "smallest", name, best);
        return false;
    }
    snprintf(err, err_size, "the scene needs %s, and no single key of the %s makes it fit", need,
             admit_part_name(part));
    return false;
}

double admit_host_bytes(void)
{
    double avail = 0.0;
    FILE *f = fopen("/proc/meminfo", "r");
    if (f) {
        char line[256];
        double kb;
        while (fgets(line, sizeof line, f))
            if (sscanf(line, "MemAvailable: %lf kB", &kb) == 1) avail = kb * 1024.0;
        fclose(f);
    }
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
        double used = 0.0;
        if ((f = fopen("/proc/self/statm", "r"))) {
            double pages;
            if (fscanf(f, "%lf", &pages) == 1) used = pages * 4096.0;
            fclose(f);
        }
        double left = (double)rl.rlim_cur - used;
        avail = avail > 0.0 ? fmin(avail, left) : left;
    }
    avail = avail > 0.0 ? 0.8 * avail : 0.0;
    const char *cap = getenv("MEADOW_MEMORY_LIMIT_MB");
    double mb = cap ? atof(cap) : 0.0;
    if (mb > 0.0 && (avail <= 0.0 || mb * MIB < avail)) avail = mb * MIB;
    return avail;
}

bool admit_tiles_check(const scene_desc_t *s, const terrain_mesh_t *t, char *err, size_t err_size)
{
    const scene_grass_desc_t *g = &s->grass;
    const float density = g->population.density;
    if (s->terrain.type != TERRAIN_HEIGHTFIELD || g->tile_size <= 0.0f) return true;
    double sx = t->aabb_max[0] - t->aabb_min[0], sz = t->aabb_max[2] - t->aabb_min[2];
    double tiles = ceil(sx / g->tile_size) * ceil(sz / g->tile_size);
    double per_tile = (double)density * g->tile_size * g->tile_size;
    if (tiles <= HYBRID_MAX_TILES && (per_tile >= 1.0 || density <= 0.0f)) return true;
    if (tiles <= HYBRID_MAX_TILES && density < BLADE_DEFAULT_DENSITY) {
        snprintf(err, err_size,
                 "grass.density %g puts %.3g blades on a tile of grass.tile_size %g m, less than one: the smallest "
                 "grass.density that fits is %.3g (or a tile_size of %.3g m)",
                 density, per_tile, g->tile_size, ceil(1e3 / (g->tile_size * g->tile_size)) / 1e3,
                 ceil(1e3 / sqrt(density)) / 1e3);
        return false;
    }
    double smallest = fmax(sqrt(sx * sz / HYBRID_MAX_TILES), density > 0.0f ? 1.0 / sqrt(density) : 0.0);
    snprintf(err, err_size,
             "grass.tile_size %g m cuts the %.0f x %.0f m field into %.3g tiles of %.3g blades; the hybrid holds at "
             "most %d tiles of at least one blade: the smallest tile_size that fits is %.3g m",
             g->tile_size, sx, sz, tiles, per_tile, HYBRID_MAX_TILES, ceil(smallest * 1e3) / 1e3);
    return false;
}

double admit_terrain_area(const terrain_mesh_t *t)
{
    double area = 0;
    for (uint32_t i = 0; i + 2 < t->index_count; i += 3) {
        const float *a = t->positions + 3 * t->indices[i], *b = t->positions + 3 * t->indices[i + 1],
                    *c = t->positions + 3 * t->indices[i + 2];
        vec3 e1, e2, n;
        glm_vec3_sub((float *)b, (float *)a, e1);
        glm_vec3_sub((float *)c, (float *)a, e2);
        glm_vec3_cross(e1, e2, n);
        area += 0.5 * glm_vec3_norm(n);
    }
    return area;
}

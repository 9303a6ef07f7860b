/* bb_layout: procedural layout textures (extent, direction, messiness), the
 * grass-clump texture array (its layers baked by blade_clump from the blade
 * model of Jahrmann & Wimmer 2017), and the CPU twin of the billboard
 * generation rule of Orthmann et al. 2009 (sec. 3); see bb_layout.h. */
#include "billboard/bb_layout.h"

#include "billboard/bb_view.h"
#include "billboard/bb_defaults.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bb_extent_desc_t bb_extent_desc_defaults(const bb_extent_desc_t *e, int size)
{
    bb_extent_desc_t d = *e;
    if (d.image_texels[0] <= 0.0f) d.image_texels[0] = (float)size;
    if (d.image_texels[1] <= 0.0f) d.image_texels[1] = (float)size;
    assert(d.fraction >= 0.0f && d.fraction <= 1.0f && d.feature >= 0.0f);
    assert(d.clearings != BB_CLEARINGS_IMAGE || (d.image && d.image->w > 0 && d.image->h > 0));
    return d;
}

bb_layout_desc_t bb_layout_desc_defaults(const bb_layout_desc_t *desc)
{
    bb_layout_desc_t d = desc ? *desc : (bb_layout_desc_t){0};
    if (d.size == 0) d.size = 256;
    d.extent = bb_extent_desc_defaults(&d.extent, d.size);
    if (d.clump_size == 0) d.clump_size = 128;
    if (d.clump_layers == 0) d.clump_layers = 4;
    d.clump = blade_clump_desc_defaults(&d.clump);
    if (d.blades == 0) d.blades = bb_clump_blades(d.clump.population.density, BB_DEFAULT_DENSITY);
    d.views = bb_view_desc_defaults(&d.views);
    return d;
}

int bb_clump_blades(float blade_density, float billboard_density)
{
    assert(billboard_density > 0.0f);
    long n = lrintf(1.5707963f * blade_density / billboard_density);
    if (n > BLADE_CLUMP_MAX_BLADES)
        core_log_warn("billboards: %g blades/m^2 over %g billboards/m^2 asks %ld blades per clump layer; drawing "
                      "BLADE_CLUMP_MAX_BLADES = %d",
                      blade_density, billboard_density, n, BLADE_CLUMP_MAX_BLADES);
    return n < 1 ? 1 : (n > BLADE_CLUMP_MAX_BLADES ? BLADE_CLUMP_MAX_BLADES : (int)n);
}

bb_gen_desc_t bb_gen_desc_defaults(const bb_gen_desc_t *desc)
{
    bb_gen_desc_t d = desc ? *desc : (bb_gen_desc_t){0};
    if (d.spacing == 0.0f) d.spacing = 0.25f;
    if (d.cells_per_texel == 0) d.cells_per_texel = 1;
    if (d.width == 0.0f) d.width = 0.5f;
    if (d.height == 0.0f) d.height = 0.4f;
    if (d.layers == 0) d.layers = 4;
    return d;
}

/* ---- tileable value-noise fBm ----------------------------------------------- */

static float bb_lattice(int x, int y, int period, uint32_t seed)
{
    x = ((x % period) + period) % period;
    y = ((y % period) + period) % period;
    return core_hash_float((uint32_t)x + core_hash_u32((uint32_t)y ^ core_hash_u32(seed)));
}

static float bb_smooth(float t) { return t * t * (3.0f - 2.0f * t); }

/* Up to 5 octaves of periods base, 2 base, 4 base, ... lattice cells across
 * the unit square, gain 0.5. The lattice values of every octave are hashed
 * once into a table, so a sample costs 4 table reads per octave instead of
 * 12 hashes; the values and the arithmetic are the same as hashing each
 * time. The direction and messiness fields (and the default clearings) use
 * base 4, periods 4 to 64. */
enum { BB_OCTAVES = 5, BB_BASE_PERIOD = 4 };

typedef struct bb_fbm_t {
    int base, octaves;
    float *lattice; /* base^2 + (2 base)^2 + ... values, octave by octave */
} bb_fbm_t;

static bool bb_fbm_init(bb_fbm_t *n, uint32_t seed, int base, int octaves)
{
    size_t values = 0;
    for (int o = 0; o < octaves; o++) values += (size_t)(base << o) * (size_t)(base << o);
    *n = (bb_fbm_t){.base = base, .octaves = octaves, .lattice = malloc(values * sizeof(float))};
    if (!n->lattice) return false;
    float *t = n->lattice;
    for (int o = 0, period = base; o < octaves; o++, period *= 2) {
        uint32_t s = core_hash_u32(seed + (uint32_t)o);
        for (int y = 0; y < period; y++)
            for (int x = 0; x < period; x++) *t++ = bb_lattice(x, y, period, s);
    }
    return true;
}

/* Value noise with `period` lattice cells across the unit square; u, v >= 0. */
static float bb_value_noise(float u, float v, int period, const float *lattice)
{
    float x = u * (float)period, y = v * (float)period;
    int ix = (int)x, iy = (int)y; /* floorf without the libm call */
    ix -= x < (float)ix;
    iy -= y < (float)iy;
    float fx = bb_smooth(x - (float)ix), fy = bb_smooth(y - (float)iy);
    int x0 = ix % period, y0 = iy % period, x1 = (ix + 1) % period, y1 = (iy + 1) % period;
    float a = lattice[y0 * period + x0], b = lattice[y0 * period + x1];
    float c = lattice[y1 * period + x0], d = lattice[y1 * period + x1];
    return (a + (b - a) * fx) + ((c + (d - c) * fx) - (a + (b - a) * fx)) * fy;
}

/* Normalised to [0,1]. */
static float bb_fbm(float u, float v, const bb_fbm_t *n)
{
    float sum = 0.0f, amp = 0.5f, norm = 0.0f;
    const float *lattice = n->lattice;
    for (int o = 0, period = n->base; o < n->octaves; o++, period *= 2) {
        sum += amp * bb_value_noise(u, v, period, lattice);
        lattice += period * period;
        norm += amp;
        amp *= 0.5f;
    }
    return sum / norm;
}

static float bb_clamp01(float x) { return x < 0.0f ? 0.0f : (x > 1.0f ? 1.0f : x); }

static float bb_smoothstep(float e0, float e1, float x) { return bb_smooth(bb_clamp01((x - e0) / (e1 - e0))); }

static uint8_t bb_byte(float x) { return (uint8_t)lrintf(bb_clamp01(x) * 255.0f); }


/* Channel 0 of image texel (x, y), clamped to the edges, in [0, 1]. */
static float bb_image_at(const core_image_t *im, int x, int y)
{
    x = x < 0 ? 0 : (x >= im->w ? im->w - 1 : x);
    y = y < 0 ? 0 : (y >= im->h ? im->h - 1 : y);
    return (float)im->px[((size_t)y * (size_t)im->w + (size_t)x) * (size_t)im->channels] / 255.0f;
}

/* The image over image_texels of the map, bilinear between texel centres. */
static void bb_extent_image(core_image_t *ext, const bb_extent_desc_t *e)
{
    const core_image_t *im = e->image;
    for (int y = 0; y < ext->h; y++) {
        float sy = ((float)y + 0.5f) / e->image_texels[1] * (float)im->h - 0.5f;
        int iy = (int)floorf(sy);
        float fy = sy - (float)iy;
        for (int x = 0; x < ext->w; x++) {
            float sx = ((float)x + 0.5f) / e->image_texels[0] * (float)im->w - 0.5f;
            int ix = (int)floorf(sx);
            float fx = sx - (float)ix;
            float top = bb_image_at(im, ix, iy) + (bb_image_at(im, ix + 1, iy) - bb_image_at(im, ix, iy)) * fx;
            float bot =
                bb_image_at(im, ix, iy + 1) + (bb_image_at(im, ix + 1, iy + 1) - bb_image_at(im, ix, iy + 1)) * fx;
            ext->px[(size_t)y * (size_t)ext->w + (size_t)x] = bb_byte(top + (bot - top) * fy);
        }
    }
}

/* Noise clearings: the mask smoothstep(lo, hi, fbm) over a band 0.09 wide
 * (by default [0.42, 0.51]: bare where the field dips below ~0.45), times
 * 0.8 + 0.2 x a detail fBm at twice the frequency. With e->fraction the
 * band is centred on that quantile of the map's fBm values, so that share
 * of texels has a mask below one half. The clearing and detail fields
 * take e->feature's base period and stop before an octave's period
 * exceeds max(64, side): finer octaves than the texels add nothing. */
/* The k-th smallest of a[0..n) (k < n), a reordered: quickselect with a
 * median-of-three pivot, O(n) where a sort was O(n log n) (a 1024^2
 * layout's quantile: about 100 ms of start-up sorted). */
static float bb_select_float(float *a, size_t n, size_t k)
{
    size_t lo = 0, hi = n - 1;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        float x = a[lo], y = a[mid], z = a[hi];
        float pivot = x < y ? (y < z ? y : (x < z ? z : x)) : (x < z ? x : (y < z ? z : y));
        size_t i = lo, j = hi;
        while (i <= j) {
            while (a[i] < pivot) i++;
            while (a[j] > pivot) j--;
            if (i <= j) {
                float t = a[i];
                a[i] = a[j];
                a[j] = t;
                i++;
                if (j == 0) break;
                j--;
            }
        }
        if (k <= j) hi = j;
        else if (k >= i) lo = i;
        else return a[k];
    }
    return a[k];
}

/* The two passes of bb_extent_noise over rows [begin, end) (core_parallel_for):
 * the clearing field, then the cover from it and the detail noise. */
typedef struct extent_rows_t {
    core_image_t *ext;
    float *field;
    const bb_fbm_t *clear, *detail;
    float lo, hi;
} extent_rows_t;

static void extent_field_rows(void *user, int begin, int end)
{
    const extent_rows_t *r = user;
    int n = r->ext->w;
    for (int y = begin; y < end; y++)
        for (int x = 0; x < n; x++)
            r->field[(size_t)y * n + x] = bb_fbm(((float)x + 0.5f) / (float)n, ((float)y + 0.5f) / (float)n, r->clear);
}

static void extent_cover_rows(void *user, int begin, int end)
{
    const extent_rows_t *r = user;
    int n = r->ext->w;
    for (int y = begin; y < end; y++) {
        for (int x = 0; x < n; x++) {
            float u = ((float)x + 0.5f) / (float)n, v = ((float)y + 0.5f) / (float)n;
            size_t i = (size_t)y * n + x;
            float cover = bb_smoothstep(r->lo, r->hi, r->field[i]);
            cover *= 0.8f + 0.2f * bb_fbm(2.0f * u, 2.0f * v, r->detail);
            r->ext->px[i] = bb_byte(cover);
        }
    }
}

static bool bb_extent_noise(core_image_t *ext, uint32_t seed, const bb_extent_desc_t *e)
{
    int n = ext->w, base = BB_BASE_PERIOD, octaves = 0;
    size_t count = (size_t)n * (size_t)n;
    if (e->feature > 0.0f) {
        float cells = (float)n / e->feature;
        int most = n / 2 > 1 ? n / 2 : 1;
        base = cells >= (float)most ? most : (cells < 1.5f ? 1 : (int)lrintf(cells));
    }
    for (int period = base; octaves < BB_OCTAVES && period <= (n > 64 ? n : 64); period *= 2) octaves++;
    bb_fbm_t clear, detail;
    bool ok_clear = bb_fbm_init(&clear, core_hash_u32(seed ^ 0x1001u), base, octaves);
    bool ok_detail = bb_fbm_init(&detail, core_hash_u32(seed ^ 0x2002u), base, octaves);
    float *field = malloc(count * sizeof *field), *sorted = e->fraction > 0.0f ? malloc(count * sizeof *sorted) : NULL;
    bool ok = ok_clear && ok_detail && field && (sorted || e->fraction <= 0.0f);
    if (ok) {
        extent_rows_t rows = {.ext = ext, .field = field, .clear = &clear, .detail = &detail};
        core_parallel_for(n, extent_field_rows, &rows);
        float lo = 0.42f, hi = 0.51f;
        if (sorted) {
            memcpy(sorted, field, count * sizeof *sorted);
            size_t k = (size_t)lrintf(e->fraction * (float)count);
            float centre;
            if (k < count) {
                centre = bb_select_float(sorted, count, k);
            } else {
                centre = sorted[0];
                for (size_t i = 1; i < count; i++) centre = fmaxf(centre, sorted[i]);
                centre += 1.0f;
            }
            lo = centre - 0.045f;
            hi = centre + 0.045f;
        }
        rows.lo = lo;
        rows.hi = hi;
        core_parallel_for(n, extent_cover_rows, &rows);
    }
    free(clear.lattice);
    free(detail.lattice);
    free(field);
    free(sorted);
    return ok;
}

/* Rows [begin, end) of the direction and messiness maps (core_parallel_for). */
typedef struct view_rows_t {
    bb_layout_t *l;
    const bb_fbm_t *fields; /* direction x, direction z, messiness */
} view_rows_t;

static void direction_rows(void *user, int begin, int end)
{
    const view_rows_t *r = user;
    bb_layout_t *l = r->l;
    int n = l->extent.w;
    for (int y = begin; y < end; y++) {
        for (int x = 0; x < n; x++) {
            float u = ((float)x + 0.5f) / (float)n, v = ((float)y + 0.5f) / (float)n;
            size_t i = (size_t)y * n + x;
            float dir[3] = {(bb_fbm(u, v, &r->fields[0]) - 0.5f) * 0.8f, 1.0f,
                            (bb_fbm(u, v, &r->fields[1]) - 0.5f) * 0.8f};
            float len = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            for (int k = 0; k < 3; k++) l->direction.px[i * 3 + k] = bb_byte(0.5f + 0.5f * dir[k] / len);
            l->messiness.px[i] = bb_byte((bb_fbm(u, v, &r->fields[2]) - 0.5f) * 2.5f + 0.5f);
        }
    }
}

static bool bb_layout_maps(bb_layout_t *l, uint32_t seed, const bb_extent_desc_t *e, bool extent_only)
{
    int n = l->extent.w;
    bool ok = true;
    if (e->clearings == BB_CLEARINGS_NONE) memset(l->extent.px, 255, (size_t)n * (size_t)n);
    else if (e->clearings == BB_CLEARINGS_IMAGE) bb_extent_image(&l->extent, e);
    else ok = bb_extent_noise(&l->extent, seed, e);
    if (extent_only) return ok;
    static const uint32_t salts[3] = {0x3003u, 0x4004u, 0x5005u};
    bb_fbm_t fields[3];
    for (int k = 0; k < 3; k++)
        ok = bb_fbm_init(&fields[k], core_hash_u32(seed ^ salts[k]), BB_BASE_PERIOD, BB_OCTAVES) && ok;
    if (ok) core_parallel_for(n, direction_rows, &(view_rows_t){.l = l, .fields = fields});
    for (int k = 0; k < 3; k++) free(fields[k].lattice);
    return ok;
}

/* Every view of clump layer `layer` (images l->clumps[v L + layer] and
 * l->clump_light[...], L = l->clump_layers), baked by blade_clump. False
 * when out of memory. */
static bool bb_clump_draw(bb_layout_t *l, uint32_t seed, int layer, int blades, const blade_clump_desc_t *c)
{
    float angles[BB_VIEW_MAX][2];
    int views = l->views.elevations * l->views.azimuths;
    for (int v = 0; v < views; v++) bb_view_angles(&l->views, v, &angles[v][0], &angles[v][1]);
    return blade_clump_bake(c, &(blade_clump_bake_t){.seed = seed,
                                                     .layer = layer,
                                                     .blades = blades,
                                                     .views_on = l->views.on,
                                                     .views = views,
                                                     .angles = (const float(*)[2])angles,
                                                     .albedo = l->clumps + layer,
                                                     .light = l->clump_light + layer,
                                                     .stats = l->clump_stats + layer,
                                                     .stride = l->clump_layers});
}

bool bb_layout_generate(bb_layout_t *layout, const bb_layout_desc_t *desc)
{
    bb_layout_desc_t d = bb_layout_desc_defaults(desc);
    memset(layout, 0, sizeof *layout);
    int images = d.clump_layers * d.views.elevations * d.views.azimuths;
    layout->clumps = calloc((size_t)images, sizeof *layout->clumps);
    layout->clump_light = calloc((size_t)images, sizeof *layout->clump_light);
    layout->clump_stats = calloc((size_t)images, sizeof *layout->clump_stats);
    bool ok = layout->clumps && layout->clump_light && layout->clump_stats &&
              core_image_alloc(&layout->extent, d.size, d.size, 1) &&
              (d.extent_only || (core_image_alloc(&layout->direction, d.size, d.size, 3) &&
                                 core_image_alloc(&layout->messiness, d.size, d.size, 1)));
    if (ok) {
        layout->clump_layers = d.clump_layers;
        layout->views = d.views;
    }
    for (int k = 0; ok && k < images; k++)
        ok = core_image_alloc(&layout->clumps[k], d.clump_size, d.clump_size, 4) &&
             core_image_alloc(&layout->clump_light[k], d.clump_size, d.clump_size, 4);
    if (!ok) {
        core_log_error("out of memory for billboard layout textures");
        bb_layout_free(layout);
        return false;
    }
    if (!bb_layout_maps(layout, d.seed, &d.extent, d.extent_only)) {
        core_log_error("out of memory for the billboard layout's noise");
        bb_layout_free(layout);
        return false;
    }
    for (int k = 0; ok && k < d.clump_layers; k++) ok = bb_clump_draw(layout, d.seed, k, d.blades, &d.clump);
    if (!ok) {
        core_log_error("out of memory drawing the clump layers");
        bb_layout_free(layout);
    }
    return ok;
}

void bb_layout_free(bb_layout_t *layout)
{
    core_image_free(&layout->extent);
    core_image_free(&layout->direction);
    core_image_free(&layout->messiness);
    int images = layout->clump_layers * layout->views.elevations * layout->views.azimuths;
    for (int k = 0; layout->clumps && k < images; k++) core_image_free(&layout->clumps[k]);
    for (int k = 0; layout->clump_light && k < images; k++) core_image_free(&layout->clump_light[k]);
    free(layout->clumps);
    free(layout->clump_light);
    free(layout->clump_stats);
    memset(layout, 0, sizeof *layout);
}

bool bb_layout_write_pngs(const bb_layout_t *layout, const char *dir)
{
    if (!core_fs_mkdirs(dir)) return false;
    char path[1024];
    const char *names[3] = {"extent", "direction", "messiness"};
    const core_image_t *maps[3] = {&layout->extent, &layout->direction, &layout->messiness};
    for (int k = 0; k < 3; k++) {
        snprintf(path, sizeof path, "%s/%s.png", dir, names[k]);
        if (!core_image_write_png(maps[k], path)) return false;
    }
    int images = layout->clump_layers * layout->views.elevations * layout->views.azimuths;
    for (int k = 0; k < images; k++) {
        int layer = k % layout->clump_layers, view = k / layout->clump_layers;
        if (view)
            snprintf(path, sizeof path, "%s/clump_%d_view%d.png", dir, layer, view);
        else
            snprintf(path, sizeof path, "%s/clump_%d.png", dir, layer);
        if (!core_image_write_png(&layout->clumps[k], path)) return false;
        snprintf(path, sizeof path, "%s/clump_%d_view%d_light.png", dir, layer, view);
        if (!core_image_write_png(&layout->clump_light[k], path)) return false;
    }
    return true;
}

/* ---- generation rule (twin: bb_generate in shaders/common/bb.glsl) -------------- */

static int bb_floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

/* Written without % on negatives so the GLSL twin (where that is undefined) matches. */
static int bb_mod(int a, int b) { return a - b * bb_floor_div(a, b); }

/* What every rule shares: candidate h on layout texel (tx, tz) is kept
 * with the texel's extent as probability; a kept one gets every field but
 * its position (left to the caller). */
static bool bb_accept_point(const bb_layout_t *layout, const bb_gen_desc_t *d, uint32_t h, int tx, int tz,
                            bb_point_t *out)
{
    assert(layout->direction.px && "bb_layout_sample needs a layout made without extent_only");
    size_t ti = (size_t)tz * layout->extent.w + tx;
    uint32_t e = layout->extent.px[ti];
    if (!(core_hash_u32(h ^ 0x5bd1e995u) % 255u < e)) return false;
    memset(out, 0, sizeof *out);
    out->size[0] = d->width * (0.8f + 0.4f * core_hash_float(h + 3u));
    out->size[1] = d->height * (0.6f + 0.8f * core_hash_float(h + 4u)) * (0.5f + 0.5f * (float)e / 255.0f);
    out->angle = 6.2831853f * core_hash_float(h + 5u);
    out->layer = ((core_hash_u32(h + 6u) >> 8) * d->layers) >> 24;
    float g[3], len2 = 0.0f;
    for (int k = 0; k < 3; k++) {
        g[k] = (float)layout->direction.px[ti * 3 + k] / 255.0f * 2.0f - 1.0f;
        len2 += g[k] * g[k];
    }
    float inv = 1.0f / sqrtf(len2);
    for (int k = 0; k < 3; k++) out->growth[k] = g[k] * inv;
    out->messiness = (float)layout->messiness.px[ti] / 255.0f;
    out->seed = h;
    out->state = BB_STATE_IDLE;
    out->recover_time = 0.0f;
    return true;
}

bool bb_layout_sample(const bb_layout_t *layout, const bb_gen_desc_t *desc, int ix, int iz,
                      bb_point_t *out)
{
    bb_gen_desc_t d = bb_gen_desc_defaults(desc);
    assert(d.layers <= 256u && d.cells_per_texel > 0);
    uint32_t h = core_hash_u32((uint32_t)ix * 0x8da6b343u ^ core_hash_u32((uint32_t)iz ^ core_hash_u32(d.seed)));
    int tx = bb_mod(bb_floor_div(ix, d.cells_per_texel), layout->extent.w);
    int tz = bb_mod(bb_floor_div(iz, d.cells_per_texel), layout->extent.h);
    if (!bb_accept_point(layout, &d, h, tx, tz, out)) return false;
    out->position[0] = d.origin[0] + ((float)ix + core_hash_float(h + 1u)) * d.spacing;
    out->position[1] = 0.0f;
    out->position[2] = d.origin[1] + ((float)iz + core_hash_float(h + 2u)) * d.spacing;
    return true;
}

bool bb_gen_tri_make(const float a[3], const float b[3], const float c[3], float spacing, bb_gen_tri_t *out)
{
    memset(out, 0, sizeof *out);
    const float *p[3] = {a, b, c};
    float e[3][3], len2[3];
    for (int k = 0; k < 3; k++) {
        for (int q = 0; q < 3; q++) e[k][q] = p[(k + 1) % 3][q] - p[k][q];
        len2[k] = e[k][0] * e[k][0] + e[k][1] * e[k][1] + e[k][2] * e[k][2];
    }
    /* (b - a) x (c - a) = e[2] x e[0] (e[2] = a - c). */
    float n[3] = {e[2][1] * e[0][2] - e[2][2] * e[0][1], e[2][2] * e[0][0] - e[2][0] * e[0][2],
                  e[2][0] * e[0][1] - e[2][1] * e[0][0]};
    float nl = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(0.5f * nl >= 1e-12f) || !(n[1] / nl >= BB_GEN_TRI_MIN_UP)) return false;
    /* Rotate (a, b, c) so that edge k (p[k] -> p[k+1]) is the longest;
     * rotation keeps the winding. */
    int k = len2[0] >= len2[1] ? (len2[0] >= len2[2] ? 0 : 2) : (len2[1] >= len2[2] ? 1 : 2);
    const float *pa = p[k], *pc = p[(k + 2) % 3];
    out->length = sqrtf(len2[k]);
    float ac[3], d = 0.0f, h2 = 0.0f;
    for (int q = 0; q < 3; q++) {
        out->a[q] = pa[q];
        out->u[q] = e[k][q] / out->length;
        ac[q] = pc[q] - pa[q];
        d += ac[q] * out->u[q];
    }
    for (int q = 0; q < 3; q++) {
        out->v[q] = ac[q] - d * out->u[q];
        h2 += out->v[q] * out->v[q];
    }
    out->height = sqrtf(h2);
    for (int q = 0; q < 3; q++) out->v[q] /= out->height;
    out->foot = fminf(fmaxf(d, 0.0f), out->length);
    float an[3] = {fabsf(n[0]), fabsf(n[1]), fabsf(n[2])};
    out->plane = an[1] >= an[0] && an[1] >= an[2] ? 1 : (an[0] >= an[2] ? 0 : 2);
    out->cells[0] = (int32_t)ceilf(out->length / spacing);
    out->cells[1] = (int32_t)ceilf(out->height / spacing);
    return true;
}

/* Layout texel coordinate of world coordinate c (twin: bb_texel_of). */
static int bb_texel_of(float c, const bb_gen_desc_t *d, int side)
{
    return bb_mod(bb_floor_div((int)floorf(c / d->spacing), d->cells_per_texel), side);
}

bool bb_layout_sample_tri(const bb_layout_t *layout, const bb_gen_desc_t *desc, const bb_gen_tri_t *tri,
                          uint32_t t, int i, int j, bb_point_t *out)
{
    bb_gen_desc_t d = bb_gen_desc_defaults(desc);
    assert(d.layers <= 256u && d.cells_per_texel > 0);
    uint32_t h = core_hash_u32((uint32_t)i * 0x8da6b343u ^
                               core_hash_u32((uint32_t)j ^ core_hash_u32(t ^ core_hash_u32(d.seed))));
    float pu = ((float)i + core_hash_float(h + 1u)) * d.spacing;
    float pv = ((float)j + core_hash_float(h + 2u)) * d.spacing;
    if (!(tri->height * pu >= tri->foot * pv && tri->height * (tri->length - pu) >= (tri->length - tri->foot) * pv))
        return false;
    float pos[3];
    for (int q = 0; q < 3; q++) pos[q] = tri->a[q] + pu * tri->u[q] + pv * tri->v[q];
    float cx = pos[0] - d.origin[0], cz = pos[2] - d.origin[1];
    float s0 = tri->plane == 0 ? cz : cx, s1 = tri->plane == 1 ? cz : pos[1];
    int tx = bb_texel_of(s0, &d, layout->extent.w), tz = bb_texel_of(s1, &d, layout->extent.h);
    if (!bb_accept_point(layout, &d, h, tx, tz, out)) return false;
    memcpy(out->position, pos, sizeof pos);
    return true;
}

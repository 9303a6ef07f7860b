/* bb_layout: procedural layout textures (extent, direction, messiness), the
 * grass-clump texture array drawn from the blade model of Jahrmann & Wimmer
 * 2017 (eq. 3-13 settle the blades, eq. 21 shapes them), and the CPU twin
 * of the billboard generation rule of Orthmann et al. 2009 (sec. 3); see
 * bb_layout.h. */
#include "billboard/bb_layout.h"

#include "billboard/bb_view.h"
#include "blade/blade_ref.h"
#include "scene/scene_fields.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bool bb_zero3(const float v[3]) { return v[0] == 0.0f && v[1] == 0.0f && v[2] == 0.0f; }

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
    bb_clump_desc_t *c = &d.clump;
    c->population = blade_population_defaults(&c->population);
    if (d.blades == 0) d.blades = bb_clump_blades(c->population.density, SCENE_DEFAULT_BILLBOARD_DENSITY);
    if (c->size[0] <= 0.0f) c->size[0] = SCENE_DEFAULT_BILLBOARD_WIDTH;
    if (c->size[1] <= 0.0f) c->size[1] = SCENE_DEFAULT_BILLBOARD_HEIGHT;
    static const float sun[3] = BB_CLUMP_SUN;
    if (bb_zero3(c->sun)) memcpy(c->sun, sun, sizeof sun);
    if (c->wind_dir[0] == 0.0f && c->wind_dir[1] == 0.0f) c->wind_dir[0] = 1.0f;
    if (c->depth <= 0.0f) c->depth = 1.5707963f / (c->size[0] * SCENE_DEFAULT_BILLBOARD_DENSITY);
    d.views = bb_view_desc_defaults(&d.views);
    assert(c->population.shape >= BLADE_SHAPE_QUADRATIC && c->population.shape <= BLADE_SHAPE_DANDELION);
    assert(c->population.height[0] <= c->population.height[1] && c->population.width[0] <= c->population.width[1] &&
           c->population.stiffness[0] <= c->population.stiffness[1]);
    return d;
}

int bb_clump_blades(float blade_density, float billboard_density)
{
    assert(billboard_density > 0.0f);
    long n = lrintf(1.5707963f * blade_density / billboard_density);
    if (n > BB_CLUMP_MAX_BLADES)
        core_log_warn("billboards: %g blades/m^2 over %g billboards/m^2 asks %ld blades per clump layer; drawing "
                      "BB_CLUMP_MAX_BLADES = %d",
                      blade_density, billboard_density, n, BB_CLUMP_MAX_BLADES);
    return n < 1 ? 1 : (n > BB_CLUMP_MAX_BLADES ? BB_CLUMP_MAX_BLADES : (int)n);
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
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++)
                field[(size_t)y * n + x] = bb_fbm(((float)x + 0.5f) / (float)n, ((float)y + 0.5f) / (float)n, &clear);
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
        for (int y = 0; y < n; y++) {
            for (int x = 0; x < n; x++) {
                float u = ((float)x + 0.5f) / (float)n, v = ((float)y + 0.5f) / (float)n;
                size_t i = (size_t)y * n + x;
                float cover = bb_smoothstep(lo, hi, field[i]);
                cover *= 0.8f + 0.2f * bb_fbm(2.0f * u, 2.0f * v, &detail);
                ext->px[i] = bb_byte(cover);
            }
        }
    }
    free(clear.lattice);
    free(detail.lattice);
    free(field);
    free(sorted);
    return ok;
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
    const bb_fbm_t *s_dx = &fields[0], *s_dz = &fields[1], *s_mes = &fields[2];
    for (int y = 0; ok && y < n; y++) {
        for (int x = 0; x < n; x++) {
            float u = ((float)x + 0.5f) / (float)n, v = ((float)y + 0.5f) / (float)n;
            size_t i = (size_t)y * n + x;
            float dir[3] = {(bb_fbm(u, v, s_dx) - 0.5f) * 0.8f, 1.0f, (bb_fbm(u, v, s_dz) - 0.5f) * 0.8f};
            float len = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            for (int k = 0; k < 3; k++) l->direction.px[i * 3 + k] = bb_byte(0.5f + 0.5f * dir[k] / len);
            l->messiness.px[i] = bb_byte((bb_fbm(u, v, s_mes) - 0.5f) * 2.5f + 0.5f);
        }
    }
    for (int k = 0; k < 3; k++) free(fields[k].lattice);
    return ok;
}

/* ---- grass clumps (the blade model, seen from each view) ----------------------
 * Layer frame: x across the billboard (its `right`, the viewer's right), y
 * up (its growth direction), z horizontal towards the viewer; roots on
 * y = 0. Each blade is a blade_t of the blade model with root (x, 0, z),
 * z in [-depth, 0], and up +y, rasterised as the blade path draws it:
 * BB_CLUMP_SEGMENTS quads along v, each vertex from blade_ref_surface
 * (eq. 21 with the scene's width profile).
 *
 * Views (bb_view.h; beyond the paper): the blades settle once under
 * gravity and the scene's mean wind (blade_wind_wave's mean, half its
 * strength) blowing along -z; view (theta, phi) turns every blade about
 * its root by phi (the physics is invariant under the turn, so this is the
 * blade settled under a wind at azimuth phi) and projects it obliquely
 * along the view direction d = (0, sin theta, cos theta) onto the card
 * plane z = 0: image height y + (-z) tan theta, depth p . d. The slab is
 * as deep as the mean free path between cards (bb_clump_desc_t.depth), so
 * from above a card shows the blades up to the next card behind it. A
 * grid of BB_CLUMP_SS x BB_CLUMP_SS samples per texel with a depth test
 * (nearest wins); a texel's alpha is its covered fraction, its colour the
 * mean albedo mix(root, tip, v) of its covered samples (straight alpha),
 * and a second image their mean lit colour as blade_shade lights them
 * before fog: shade() (lighting.glsl) of the sample's albedo, its unit
 * normal turned towards d as blade_shade turns it towards the viewer,
 * ambient occlusion mix(0.45, 1, v), and the sun in the view's frame (the
 * scene's sun and wind fix it for each azimuth), linear, so the mip
 * levels average it as the pixels would (a square root kept more of the
 * dark colours' bits but darkened the minified cards: the mean of a root
 * squared is below the mean). A plain card shows that colour times its
 * tint, fogged.
 *
 * Coverage, calibrated (per view): a ray through the blade field meets
 * blade surface at the rate the layer's `blades` blades (bb_clump_blades:
 * per billboard as many as the field grows, times pi / 2) give counted
 * with their overlaps, a mean overlap count T per sample; through the
 * billboards it meets cards, each hit letting 1 - alpha through, and
 * random hits make the transmittance exp(-rate x mean alpha) (Campbell's
 * theorem). The blades of one layer overlap each other, so its mean alpha
 * (their union) falls short of T, and the cards let more ground through
 * than the blades they stand for. So the layer takes more blades, from the
 * same stream, until its mean alpha reaches the mean over sample rows of
 * min(T_row, 1) (a row already covered cannot be more opaque), at most
 * 4 x `blades` and BB_CLUMP_MAX_BLADES (bb_layout_t.clump_stats says how
 * many). */

static float bb_range(core_rng_t *rng, const float r[2]) { return core_rng_range(rng, r[0], r[1]); }

/* One blade of a layer, settled with its root at the origin; *x: its
 * draw for the root's place across the layer (bb_clump_place), *z: its
 * root's depth, in [-depth, 0] (front, views off: over the layer width,
 * as the front-only bake placed them). */
static void bb_clump_blade(blade_t *b, core_rng_t *rng, const bb_clump_desc_t *c, const blade_env_t *env, bool front,
                           float *x, float *z)
{
    const blade_population_t *pop = &c->population;
    float h = bb_range(rng, pop->height), w = bb_range(rng, pop->width), s = bb_range(rng, pop->stiffness);
    float angle = core_rng_range(rng, 0.0f, 6.2831853f);
    *x = core_rng_float(rng);
    float u = core_rng_float(rng);
    *z = front ? (u - 0.5f) * c->size[0] : -u * c->depth;
    *b = (blade_t){.v0 = {0.0f, 0.0f, 0.0f, angle}, .v1 = {0.0f, h, 0.0f, h}, .v2 = {0.0f, h, 0.0f, w},
                   .up = {0.0f, 1.0f, 0.0f, s}};
    float eta = 0.0f;
    for (int i = 0; i < BB_CLUMP_SETTLE_STEPS; i++) blade_ref_step_one(b, &eta, env, NULL);
}

/* Settled blade b (root at the origin) turned about its root by phi (the
 * wind's -z goes to (sin phi, 0, -cos phi)) and placed: root depth z, root
 * across at draw x of the range that keeps the turned blade's projection
 * `margin` metres off the layer's sides (no blade is cut). */
static blade_t bb_clump_place(const blade_t *b, const bb_clump_desc_t *c, float phi, float x, float z, float margin)
{
    blade_t t = *b;
    if (phi != 0.0f) {
        float cs = cosf(phi), sn = sinf(phi);
        float *pts[2] = {t.v1, t.v2};
        for (int k = 0; k < 2; k++) {
            float dx = pts[k][0], dz = pts[k][2];
            pts[k][0] = dx * cs - dz * sn;
            pts[k][2] = dx * sn + dz * cs;
        }
        t.v0[3] = b->v0[3] + phi;
    }
    float lo = 0.0f, hi = 0.0f;
    for (int i = 0; i <= BB_CLUMP_SEGMENTS; i++)
        for (int e = 0; e < 2; e++) {
            float p[3], n[3];
            blade_ref_surface(&t, c->population.shape, (float)e, (float)i / BB_CLUMP_SEGMENTS, p, n);
            lo = fminf(lo, p[0]);
            hi = fmaxf(hi, p[0]);
        }
    float half = 0.5f * c->size[0] - margin, x0 = -half - lo, x1 = half - hi;
    float root = x1 > x0 ? x0 + x * (x1 - x0) : 0.5f * (x0 + x1);
    float shift[3] = {root, 0.0f, z};
    for (int k = 0; k < 3; k++) {
        t.v0[k] += shift[k];
        t.v1[k] += shift[k];
        t.v2[k] += shift[k];
    }
    return t;
}

/* shade() of shaders/common/lighting.glsl (its twin: keep the constants
 * alike): Lambert sun and hemispheric sky ambient of albedo at unit normal
 * n under the unit sun direction, ambient occlusion ao. */
static void bb_shade_ref(const float albedo[3], const float n[3], const float sun[3], float ao, float out[3])
{
    static const float sun_color[3] = {1.0f, 0.95f, 0.85f}, down[3] = {0.18f, 0.17f, 0.14f},
                       up[3] = {0.35f, 0.42f, 0.55f};
    float ndl = fmaxf(n[0] * sun[0] + n[1] * sun[1] + n[2] * sun[2], 0.0f), t = n[1] * 0.5f + 0.5f;
    for (int k = 0; k < 3; k++)
        out[k] = albedo[k] * (sun_color[k] * ndl * 0.85f + (down[k] + (up[k] - down[k]) * t) * ao);
}

/* Sample buffer of one view: nearest depth, the blade parameter v and the
 * normal (attributes 1-4 of the triangles). */
#define BB_CLUMP_ATTRS 5 /* depth, v, normal xyz */
typedef struct bb_samples_t {
    int w, h; /* samples */
    float *z, *v, *n;
    uint16_t *hits; /* surfaces over each sample, overlaps counted; NULL: not counted */
    long covered;   /* samples some surface covers */
} bb_samples_t;

/* Rasterises the triangle (a, b, c) of sample-space x, y and the
 * BB_CLUMP_ATTRS attributes (depth z, blade parameter v, normal), either
 * winding: per sample row, the span of sample centres inside it (where the
 * row's centre line crosses its edges); attributes from the triangle's
 * plane; a sample takes them when nearer than what it holds. */
static void bb_clump_triangle(bb_samples_t *sb, const float *a, const float *b, const float *c)
{
    float area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (fabsf(area) < 1e-6f) return;
    /* Attribute k at (x, y): at[k] + dx[k] (x - a.x) + dy[k] (y - a.y). */
    float dx[BB_CLUMP_ATTRS], dy[BB_CLUMP_ATTRS];
    for (int k = 0; k < BB_CLUMP_ATTRS; k++) {
        float fb = b[2 + k] - a[2 + k], fc = c[2 + k] - a[2 + k];
        dx[k] = (fb * (c[1] - a[1]) - fc * (b[1] - a[1])) / area;
        dy[k] = (fc * (b[0] - a[0]) - fb * (c[0] - a[0])) / area;
    }
    const float *v[3] = {a, b, c};
    float ylo = fminf(a[1], fminf(b[1], c[1])), yhi = fmaxf(a[1], fmaxf(b[1], c[1]));
    int y0 = (int)ceilf(ylo - 0.5f), y1 = (int)floorf(yhi - 0.5f);
    y0 = y0 < 0 ? 0 : y0;
    y1 = y1 > sb->h - 1 ? sb->h - 1 : y1;
    for (int y = y0; y <= y1; y++) {
        float py = (float)y + 0.5f, xlo = INFINITY, xhi = -INFINITY;
        for (int e = 0; e < 3; e++) {
            const float *p = v[e], *q = v[(e + 1) % 3];
            if ((p[1] > py) == (q[1] > py)) continue;
            float x = p[0] + (py - p[1]) * (q[0] - p[0]) / (q[1] - p[1]);
            xlo = fminf(xlo, x);
            xhi = fmaxf(xhi, x);
        }
        int x0 = (int)ceilf(xlo - 0.5f), x1 = (int)floorf(xhi - 0.5f);
        x0 = x0 < 0 ? 0 : x0;
        x1 = x1 > sb->w - 1 ? sb->w - 1 : x1;
        size_t row = (size_t)y * (size_t)sb->w;
        float ry = py - a[1];
        for (int x = x0; x <= x1; x++) {
            float rx = (float)x + 0.5f - a[0];
            float z = a[2] + dx[0] * rx + dy[0] * ry;
            if (sb->hits) {
                uint16_t *hit = sb->hits + row + (size_t)x;
                *hit = *hit < UINT16_MAX ? (uint16_t)(*hit + 1) : *hit;
            }
            sb->covered += sb->z[row + (size_t)x] == -INFINITY;
            if (z <= sb->z[row + (size_t)x]) continue;
            sb->z[row + (size_t)x] = z;
            sb->v[row + (size_t)x] = fminf(fmaxf(a[3] + dx[1] * rx + dy[1] * ry, 0.0f), 1.0f);
            for (int k = 0; k < 3; k++)
                sb->n[(row + (size_t)x) * 3 + (size_t)k] = a[4 + k] + dx[2 + k] * rx + dy[2 + k] * ry;
        }
    }
}

/* The oblique projection of view elevation theta: image height and depth
 * of layer point p (see the banner). */
typedef struct bb_clump_proj_t {
    float tan_t, sin_t, cos_t;
} bb_clump_proj_t;

static float bb_proj_y(const bb_clump_proj_t *pr, const float p[3]) { return p[1] - p[2] * pr->tan_t; }

/* One blade into the sample buffer (sx, sy: samples per metre). */
static void bb_clump_raster(bb_samples_t *sb, const blade_t *b, const bb_clump_desc_t *c, const bb_clump_proj_t *pr,
                            float sx, float sy)
{
    float q[BB_CLUMP_SEGMENTS + 1][2][2 + BB_CLUMP_ATTRS];
    for (int i = 0; i <= BB_CLUMP_SEGMENTS; i++) {
        float v = (float)i / BB_CLUMP_SEGMENTS;
        for (int u = 0; u < 2; u++) {
            float p[3], nrm[3];
            blade_ref_surface(b, c->population.shape, (float)u, v, p, nrm);
            q[i][u][0] = (p[0] + 0.5f * c->size[0]) * sx;
            q[i][u][1] = (float)sb->h - bb_proj_y(pr, p) * sy;
            q[i][u][2] = p[1] * pr->sin_t + p[2] * pr->cos_t;
            q[i][u][3] = v;
            for (int k = 0; k < 3; k++) q[i][u][4 + k] = nrm[k];
        }
    }
    for (int i = 0; i < BB_CLUMP_SEGMENTS; i++) {
        bb_clump_triangle(sb, q[i][0], q[i][1], q[i + 1][0]);
        bb_clump_triangle(sb, q[i][1], q[i + 1][1], q[i + 1][0]);
    }
}

/* View (theta, phi) of one layer's settled blades b[0..pool) into img
 * (albedo, alpha) and light (the lit colour under sun, a unit direction in
 * the view's frame), placed by place[2n], place[2n + 1] (bb_clump_blade's
 * x and z) and margin, sy samples per metre up, calibrated as the banner
 * says; *stats: its blades, mean alpha and target. sb: the sample buffer
 * (its arrays allocated), turned: room for pool blades. False when out of
 * memory. */
static bool bb_clump_view(core_image_t *img, core_image_t *light, bb_samples_t *sb, const blade_t *b,
                          const float *place, blade_t *turned, int pool, int blades, int layer,
                          const bb_clump_desc_t *c, float theta, float phi, float sy, float margin, const float sun[3],
                          bb_clump_stats_t *stats)
{
    int w = img->w, h = img->h;
    size_t ns = (size_t)sb->w * (size_t)sb->h;
    for (size_t i = 0; i < ns; i++) sb->z[i] = -INFINITY;
    memset(sb->hits, 0, ns * sizeof *sb->hits);
    sb->covered = 0;
    bb_clump_proj_t pr = {tanf(theta), sinf(theta), cosf(theta)};
    for (int n = 0; n < pool; n++) turned[n] = bb_clump_place(&b[n], c, phi, place[2 * n], place[2 * n + 1], margin);
    float sx = (float)sb->w / c->size[0];
    uint16_t *hits = sb->hits;
    for (int n = 0; n < blades; n++) bb_clump_raster(sb, &turned[n], c, &pr, sx, sy);
    /* Target coverage: the mean over sample rows of min(T_row, 1). */
    double target = 0.0;
    for (int y = 0; y < sb->h; y++) {
        long row = 0;
        for (int x = 0; x < sb->w; x++) row += hits[(size_t)y * (size_t)sb->w + (size_t)x];
        target += fmin((double)row / sb->w, 1.0) / sb->h;
    }
    sb->hits = NULL;
    int n = blades;
    for (; (double)sb->covered / (double)ns < target && n < pool; n++) bb_clump_raster(sb, &turned[n], c, &pr, sx, sy);
    sb->hits = hits;
    *stats = (bb_clump_stats_t){
        .blades = n, .alpha = (float)((double)sb->covered / (double)ns), .target = (float)target};
    if (stats->alpha < target)
        core_log_warn("billboards: clump layer %d covers %.3f of its samples with %d blades (4 x %d, at most "
                      "BB_CLUMP_MAX_BLADES = %d), short of the %.3f its field's blades cover",
                      layer, stats->alpha, n, blades, BB_CLUMP_MAX_BLADES, target);
    /* Resolve: coverage, mean albedo and mean lit colour per texel;
     * transparent texels take the view's means. */
    const float *ra = c->population.albedo_root, *ta = c->population.albedo_tip;
    float d[3] = {0.0f, pr.sin_t, pr.cos_t};
    double mean[6] = {0}, wsum = 0.0;
    float *acc = malloc(sizeof(float) * 7 * (size_t)w * (size_t)h);
    if (!acc) return false;
    for (int ty = 0; ty < h; ty++)
        for (int tx = 0; tx < w; tx++) {
            float sum[6] = {0};
            int covered = 0;
            for (int sy0 = 0; sy0 < BB_CLUMP_SS; sy0++) {
                size_t row = (size_t)(ty * BB_CLUMP_SS + sy0) * (size_t)sb->w + (size_t)(tx * BB_CLUMP_SS);
                for (int sx0 = 0; sx0 < BB_CLUMP_SS; sx0++) {
                    size_t s = row + (size_t)sx0;
                    if (sb->z[s] == -INFINITY) continue;
                    covered++;
                    float v = sb->v[s], *sn = sb->n + s * 3;
                    float len = sqrtf(sn[0] * sn[0] + sn[1] * sn[1] + sn[2] * sn[2]), un[3], albedo[3], lit[3];
                    for (int k = 0; k < 3; k++) un[k] = len > 0.0f ? sn[k] / len : d[k];
                    if (un[0] * d[0] + un[1] * d[1] + un[2] * d[2] < 0.0f)
                        for (int k = 0; k < 3; k++) un[k] = -un[k];
                    for (int k = 0; k < 3; k++) albedo[k] = ra[k] + (ta[k] - ra[k]) * v;
                    bb_shade_ref(albedo, un, sun, 0.45f + 0.55f * v, lit);
                    for (int k = 0; k < 3; k++) {
                        sum[k] += albedo[k];
                        sum[3 + k] += lit[k];
                    }
                }
            }
            float *o = acc + ((size_t)ty * (size_t)w + (size_t)tx) * 7;
            o[6] = (float)covered / (float)(BB_CLUMP_SS * BB_CLUMP_SS);
            for (int k = 0; k < 6; k++) {
                o[k] = covered ? sum[k] / (float)covered : 0.0f;
                mean[k] += sum[k];
            }
            wsum += covered;
        }
    for (size_t i = 0; i < (size_t)w * (size_t)h; i++) {
        const float *o = acc + i * 7;
        float m[6];
        for (int k = 0; k < 6; k++) m[k] = o[6] > 0.0f ? o[k] : (wsum > 0.0 ? (float)(mean[k] / wsum) : 0.0f);
        for (int k = 0; k < 3; k++) {
            img->px[i * 4 + k] = bb_byte(m[k]);
            light->px[i * 4 + k] = bb_byte(m[3 + k]);
        }
        img->px[i * 4 + 3] = bb_byte(o[6]);
        light->px[i * 4 + 3] = 255;
    }
    free(acc);
    return true;
}

/* Every view of clump layer `layer` (images l->clumps[v L + layer] and
 * l->clump_light[...], L = l->clump_layers). False when out of memory. */
static bool bb_clump_draw(bb_layout_t *l, uint32_t seed, int layer, int blades, const bb_clump_desc_t *c)
{
    int w = l->clumps[layer].w;
    bb_samples_t sb = {.w = w * BB_CLUMP_SS, .h = l->clumps[layer].h * BB_CLUMP_SS};
    size_t ns = (size_t)sb.w * (size_t)sb.h;
    sb.z = malloc(sizeof(float) * ns);
    sb.v = malloc(sizeof(float) * ns);
    sb.n = malloc(sizeof(float) * 3 * ns);
    sb.hits = malloc(ns * sizeof *sb.hits);
    /* The calibration's blades come from the same stream: all are settled
     * first, so each view's vertical scale fits the tallest of them. */
    int pool = blades * 4 < BB_CLUMP_MAX_BLADES ? blades * 4 : BB_CLUMP_MAX_BLADES;
    pool = pool > blades ? pool : blades;
    blade_t *b = malloc(sizeof *b * (size_t)pool), *turned = malloc(sizeof *b * (size_t)pool);
    float *place = malloc(sizeof(float) * 2 * (size_t)pool);
    bool ok = sb.z && sb.v && sb.n && sb.hits && b && turned && place;
    core_rng_t rng;
    core_rng_seed(&rng, seed, 100u + (uint64_t)layer);
    blade_env_t env = {.dt = SCENE_DEFAULT_DT, .gravity = c->population.gravity};
    if (c->wind > 0.0f && !!l->views.on)
        env.winds[env.wind_count++] = blade_wind_wave(0.0f, -1.0f, c->wind, 1.0f, 0.0f);
    env = blade_env_defaults(&env);
    float margin = BB_CLUMP_MARGIN * c->size[0] / (float)w, top = 0.0f;
    for (int n = 0; ok && n < pool; n++) {
        bb_clump_blade(&b[n], &rng, c, &env, !l->views.on, &place[2 * n], &place[2 * n + 1]);
        for (int i = 0; i <= BB_CLUMP_SEGMENTS; i++) {
            float p[3], nrm[3];
            blade_ref_surface(&b[n], c->population.shape, 0.5f, (float)i / BB_CLUMP_SEGMENTS, p, nrm);
            top = fmaxf(top, p[1]);
        }
    }
    /* Metres to samples up: by size[1], or by what the tallest blade needs
     * when it would reach above 0.98 of it; every view alike (an elevated
     * view's blades rising above the card are cut: the card's frame is
     * its window on the field). */
    float sy = (float)sb.h / fmaxf(c->size[1], top / 0.98f);
    int views = l->views.elevations * l->views.azimuths;
    for (int v = 0; ok && v < views; v++) {
        float theta, phi;
        bb_view_angles(&l->views, v, &theta, &phi);
        int i = v * l->clump_layers + layer;
        /* The view's frame in the world: the wind W at azimuth phi, so
         * z = -cos phi W + sin phi W_perp, x = y cross z. */
        float cs = cosf(phi), sn = sinf(phi), wl = hypotf(c->wind_dir[0], c->wind_dir[1]);
        float W[2] = {c->wind_dir[0] / wl, c->wind_dir[1] / wl}, P[2] = {-W[1], W[0]};
        float z[2] = {-cs * W[0] + sn * P[0], -cs * W[1] + sn * P[1]}, x[2] = {z[1], -z[0]};
        float sl = sqrtf(c->sun[0] * c->sun[0] + c->sun[1] * c->sun[1] + c->sun[2] * c->sun[2]);
        float sun[3] = {(c->sun[0] * x[0] + c->sun[2] * x[1]) / sl, c->sun[1] / sl,
                        (c->sun[0] * z[0] + c->sun[2] * z[1]) / sl};
        ok = bb_clump_view(&l->clumps[i], &l->clump_light[i], &sb, b, place, turned, pool, blades, layer, c, theta,
                           phi, sy, margin, sun, &l->clump_stats[i]);
    }
    free(sb.z);
    free(sb.v);
    free(sb.n);
    free(sb.hits);
    free(b);
    free(turned);
    free(place);
    return ok;
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
              core_image_alloc(&layout->direction, d.size, d.size, 3) &&
              core_image_alloc(&layout->messiness, d.size, d.size, 1);
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

/* bb_layout: procedural layout textures (extent, direction, messiness), the
 * grass-clump texture array, and the CPU twin of the billboard generation
 * rule of Orthmann et al. 2009 (sec. 3); see bb_layout.h. */
#include "billboard/bb_layout.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

bb_layout_desc_t bb_layout_desc_defaults(const bb_layout_desc_t *desc)
{
    bb_layout_desc_t d = desc ? *desc : (bb_layout_desc_t){0};
    if (d.size == 0) d.size = 256;
    if (d.clump_size == 0) d.clump_size = 128;
    if (d.clump_layers == 0) d.clump_layers = 4;
    if (d.blades == 0) d.blades = 48;
    return d;
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

/* 5 octaves, base period 4, gain 0.5. The lattice values of every octave
 * are hashed once into a table (4^2 + 8^2 + ... + 64^2 values), so a sample
 * costs 20 table reads instead of 60 hashes; the values and the arithmetic
 * are the same as hashing each time. */
enum { BB_OCTAVES = 5, BB_BASE_PERIOD = 4, BB_LATTICE_VALUES = 16 + 64 + 256 + 1024 + 4096 };

typedef struct bb_fbm_t {
    float lattice[BB_LATTICE_VALUES];
} bb_fbm_t;

static void bb_fbm_init(bb_fbm_t *n, uint32_t seed)
{
    float *t = n->lattice;
    for (int o = 0, period = BB_BASE_PERIOD; o < BB_OCTAVES; o++, period *= 2) {
        uint32_t s = core_hash_u32(seed + (uint32_t)o);
        for (int y = 0; y < period; y++)
            for (int x = 0; x < period; x++) *t++ = bb_lattice(x, y, period, s);
    }
}

/* Value noise with `period` lattice cells across the unit square. */
static float bb_value_noise(float u, float v, int period, const float *lattice)
{
    float x = u * (float)period, y = v * (float)period;
    int ix = (int)x, iy = (int)y; /* floorf without the libm call */
    ix -= x < (float)ix;
    iy -= y < (float)iy;
    float fx = bb_smooth(x - (float)ix), fy = bb_smooth(y - (float)iy);
    int mask = period - 1; /* periods are powers of two */
    int x0 = ix & mask, y0 = iy & mask, x1 = (ix + 1) & mask, y1 = (iy + 1) & mask;
    float a = lattice[y0 * period + x0], b = lattice[y0 * period + x1];
    float c = lattice[y1 * period + x0], d = lattice[y1 * period + x1];
    return (a + (b - a) * fx) + ((c + (d - c) * fx) - (a + (b - a) * fx)) * fy;
}

/* Normalised to [0,1]. */
static float bb_fbm(float u, float v, const bb_fbm_t *n)
{
    float sum = 0.0f, amp = 0.5f, norm = 0.0f;
    const float *lattice = n->lattice;
    for (int o = 0, period = BB_BASE_PERIOD; o < BB_OCTAVES; o++, period *= 2) {
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

static void bb_layout_maps(bb_layout_t *l, uint32_t seed)
{
    int n = l->extent.w;
    static const uint32_t salts[5] = {0x1001u, 0x2002u, 0x3003u, 0x4004u, 0x5005u};
    bb_fbm_t *fields = malloc(sizeof *fields * 5);
    assert(fields);
    for (int k = 0; k < 5; k++) bb_fbm_init(&fields[k], core_hash_u32(seed ^ salts[k]));
    const bb_fbm_t *s_ext = &fields[0], *s_det = &fields[1], *s_dx = &fields[2], *s_dz = &fields[3];
    const bb_fbm_t *s_mes = &fields[4];
    for (int y = 0; y < n; y++) {
        for (int x = 0; x < n; x++) {
            float u = ((float)x + 0.5f) / (float)n, v = ((float)y + 0.5f) / (float)n;
            size_t i = (size_t)y * n + x;
            /* Clearings where the fBm field dips below ~0.45 (about a tenth to a
             * quarter of a field, depending on the seed). */
            float cover = bb_smoothstep(0.42f, 0.51f, bb_fbm(u, v, s_ext));
            cover *= 0.8f + 0.2f * bb_fbm(2.0f * u, 2.0f * v, s_det);
            l->extent.px[i] = bb_byte(cover);
            float dir[3] = {(bb_fbm(u, v, s_dx) - 0.5f) * 0.8f, 1.0f, (bb_fbm(u, v, s_dz) - 0.5f) * 0.8f};
            float len = sqrtf(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            for (int k = 0; k < 3; k++) l->direction.px[i * 3 + k] = bb_byte(0.5f + 0.5f * dir[k] / len);
            l->messiness.px[i] = bb_byte((bb_fbm(u, v, s_mes) - 0.5f) * 2.5f + 0.5f);
        }
    }
    free(fields);
}

/* ---- grass clumps ------------------------------------------------------------- */

enum { BB_BLADE_SAMPLES = 16 };

typedef struct bb_blade_t {
    float p[BB_BLADE_SAMPLES][2]; /* centre line, normalised coords (x right, y up) */
    float hw[BB_BLADE_SAMPLES];   /* half width at each sample */
    float col[3];
    float lo[2], hi[2];           /* bounding box */
} bb_blade_t;

static void bb_blade_make(bb_blade_t *b, core_rng_t *rng)
{
    float bx = 0.5f + (core_rng_float(rng) + core_rng_float(rng) - 1.0f) * 0.24f;
    float height = core_rng_range(rng, 0.45f, 0.96f);
    float lean = (bx - 0.5f) * 0.9f + core_rng_range(rng, -0.14f, 0.14f);
    bool droop = core_rng_float(rng) < 0.25f;
    float p0[2] = {bx, 0.0f};
    float p1[2] = {bx + lean * 0.15f, height * (droop ? 0.95f : 0.6f)};
    float p2[2] = {bx + lean * (droop ? 1.6f : 1.0f), height * (droop ? 0.75f : 1.0f)};
    /* Keep tips off the texture border so billboards never show a cut blade. */
    p1[0] = fminf(fmaxf(p1[0], 0.05f), 0.95f);
    p2[0] = fminf(fmaxf(p2[0], 0.05f), 0.95f);
    float w0 = core_rng_range(rng, 0.008f, 0.016f);
    float g = core_rng_range(rng, 0.42f, 0.72f);
    float yellow = core_rng_float(rng);
    b->col[0] = g * (0.35f + 0.45f * yellow * yellow);
    b->col[1] = g;
    b->col[2] = g * core_rng_range(rng, 0.15f, 0.35f);
    b->lo[0] = b->lo[1] = 1e9f;
    b->hi[0] = b->hi[1] = -1e9f;
    for (int s = 0; s < BB_BLADE_SAMPLES; s++) {
        float t = (float)s / (float)(BB_BLADE_SAMPLES - 1), it = 1.0f - t;
        for (int k = 0; k < 2; k++) {
            b->p[s][k] = it * it * p0[k] + 2.0f * it * t * p1[k] + t * t * p2[k];
            b->lo[k] = fminf(b->lo[k], b->p[s][k]);
            b->hi[k] = fmaxf(b->hi[k], b->p[s][k]);
        }
        b->hw[s] = w0 * powf(it, 0.7f);
    }
    for (int k = 0; k < 2; k++) {
        b->lo[k] -= w0 + 0.01f;
        b->hi[k] += w0 + 0.01f;
    }
}

/* Signed distance (pixels) from (x,y) to the tapered blade outline, and the
 * blade parameter t and the lateral fraction of the closest point. */
static float bb_blade_dist(const bb_blade_t *b, float x, float y, float px, float *t_out, float *side_out)
{
    float best = 1e9f;
    for (int s = 0; s < BB_BLADE_SAMPLES - 1; s++) {
        float ax = b->p[s][0], ay = b->p[s][1];
        float dx = b->p[s + 1][0] - ax, dy = b->p[s + 1][1] - ay;
        float den = dx * dx + dy * dy;
        float f = den > 0.0f ? bb_clamp01(((x - ax) * dx + (y - ay) * dy) / den) : 0.0f;
        float qx = x - ax - f * dx, qy = y - ay - f * dy;
        float dist = sqrtf(qx * qx + qy * qy);
        float hw = b->hw[s] + f * (b->hw[s + 1] - b->hw[s]);
        float sd = (dist - hw) * px;
        if (sd < best) {
            best = sd;
            *t_out = ((float)s + f) / (float)(BB_BLADE_SAMPLES - 1);
            *side_out = hw > 0.0f ? dist / hw : 1.0f;
        }
    }
    return best;
}

static void bb_clump_draw(core_image_t *img, uint32_t seed, int layer, int blades)
{
    int w = img->w, h = img->h;
    float *acc = calloc((size_t)w * h * 4, sizeof(float));
    core_rng_t rng;
    core_rng_seed(&rng, seed, 100u + (uint64_t)layer);
    for (int n = 0; n < blades; n++) {
        bb_blade_t b;
        bb_blade_make(&b, &rng);
        int x0 = (int)floorf(b.lo[0] * w), x1 = (int)ceilf(b.hi[0] * w);
        int y0 = (int)floorf((1.0f - b.hi[1]) * h), y1 = (int)ceilf((1.0f - b.lo[1]) * h);
        x0 = x0 < 0 ? 0 : x0;
        y0 = y0 < 0 ? 0 : y0;
        x1 = x1 > w ? w : x1;
        y1 = y1 > h ? h : y1;
        for (int py = y0; py < y1; py++) {
            for (int px = x0; px < x1; px++) {
                float x = ((float)px + 0.5f) / (float)w, y = 1.0f - ((float)py + 0.5f) / (float)h;
                float t = 0.0f, side = 1.0f;
                float sd = bb_blade_dist(&b, x, y, (float)w, &t, &side);
                float a = bb_clamp01(0.5f - sd);
                if (a <= 0.0f) continue;
                /* Dark base, lighter tip, a faint bright midrib. */
                float shade = (0.35f + 0.65f * bb_smoothstep(0.0f, 0.55f, t)) * (1.0f + 0.12f * t);
                shade *= 1.0f + 0.15f * (1.0f - bb_clamp01(side));
                float *dst = acc + ((size_t)py * w + px) * 4;
                for (int k = 0; k < 3; k++)
                    dst[k] = bb_clamp01(b.col[k] * shade) * a + dst[k] * (1.0f - a);
                dst[3] = a + dst[3] * (1.0f - a);
            }
        }
    }
    double mean[3] = {0, 0, 0}, wsum = 0.0;
    for (size_t i = 0; i < (size_t)w * h; i++) {
        for (int k = 0; k < 3; k++) mean[k] += acc[i * 4 + k];
        wsum += acc[i * 4 + 3];
    }
    for (size_t i = 0; i < (size_t)w * h; i++) {
        float a = acc[i * 4 + 3];
        for (int k = 0; k < 3; k++) {
            float c = a > 0.0f ? acc[i * 4 + k] / a : (wsum > 0.0 ? (float)(mean[k] / wsum) : 0.0f);
            img->px[i * 4 + k] = bb_byte(c);
        }
        img->px[i * 4 + 3] = bb_byte(a);
    }
    free(acc);
}

bool bb_layout_generate(bb_layout_t *layout, const bb_layout_desc_t *desc)
{
    bb_layout_desc_t d = bb_layout_desc_defaults(desc);
    memset(layout, 0, sizeof *layout);
    layout->clumps = calloc((size_t)d.clump_layers, sizeof *layout->clumps);
    bool ok = layout->clumps && core_image_alloc(&layout->extent, d.size, d.size, 1) &&
              core_image_alloc(&layout->direction, d.size, d.size, 3) &&
              core_image_alloc(&layout->messiness, d.size, d.size, 1);
    if (ok) layout->clump_layers = d.clump_layers;
    for (int k = 0; ok && k < d.clump_layers; k++)
        ok = core_image_alloc(&layout->clumps[k], d.clump_size, d.clump_size, 4);
    if (!ok) {
        core_log_error("%s:%d: out of memory for billboard layout textures", __FILE__, __LINE__);
        bb_layout_free(layout);
        return false;
    }
    bb_layout_maps(layout, d.seed);
    for (int k = 0; k < d.clump_layers; k++) bb_clump_draw(&layout->clumps[k], d.seed, k, d.blades);
    return true;
}

void bb_layout_free(bb_layout_t *layout)
{
    core_image_free(&layout->extent);
    core_image_free(&layout->direction);
    core_image_free(&layout->messiness);
    for (int k = 0; layout->clumps && k < layout->clump_layers; k++) core_image_free(&layout->clumps[k]);
    free(layout->clumps);
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
    for (int k = 0; k < layout->clump_layers; k++) {
        snprintf(path, sizeof path, "%s/clump_%d.png", dir, k);
        if (!core_image_write_png(&layout->clumps[k], path)) return false;
    }
    return true;
}

/* ---- generation rule (twin: bb_generate in shaders/common/bb.glsl) -------------- */

static int bb_floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

/* Written without % on negatives so the GLSL twin (where that is undefined) matches. */
static int bb_mod(int a, int b) { return a - b * bb_floor_div(a, b); }

bool bb_layout_sample(const bb_layout_t *layout, const bb_gen_desc_t *desc, int ix, int iz,
                      bb_point_t *out)
{
    bb_gen_desc_t d = bb_gen_desc_defaults(desc);
    assert(d.layers <= 256u && d.cells_per_texel > 0);
    uint32_t h = core_hash_u32((uint32_t)ix * 0x8da6b343u ^ core_hash_u32((uint32_t)iz ^ core_hash_u32(d.seed)));
    int tx = bb_mod(bb_floor_div(ix, d.cells_per_texel), layout->extent.w);
    int tz = bb_mod(bb_floor_div(iz, d.cells_per_texel), layout->extent.h);
    size_t ti = (size_t)tz * layout->extent.w + tx;
    uint32_t e = layout->extent.px[ti];
    if (!(core_hash_u32(h ^ 0x5bd1e995u) % 255u < e)) return false;
    memset(out, 0, sizeof *out);
    out->position[0] = d.origin[0] + ((float)ix + core_hash_float(h + 1u)) * d.spacing;
    out->position[1] = 0.0f;
    out->position[2] = d.origin[1] + ((float)iz + core_hash_float(h + 2u)) * d.spacing;
    out->size[0] = d.width * (0.8f + 0.4f * core_hash_float(h + 3u));
    out->size[1] = d.height * (0.6f + 0.8f * core_hash_float(h + 4u)) * (0.5f + 0.5f * (float)e / 255.0f);
    out->angle = 6.2831853f * core_hash_float(h + 5u);
    out->layer = ((core_hash_u32(h + 6u) >> 8) * d.layers) >> 24;
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

/* terrain_world: the open world's height function and its analytic normal
 * (see terrain_world.h). Every expression here has its twin, in the same
 * order of operations, in shaders/common/world_height.glsl; change both. */
#include "terrain/terrain_world.h"
#include "terrain/terrain.h"

#include <math.h>
#include <stdio.h>

#include "core/core.h"

/* Layer ids hashed into each octave's lattice key. */
enum { LAYER_MACRO = 0, LAYER_VALLEY = 3, LAYER_DETAIL = 5, LAYER_FLAT = 8 };

#define VALLEY_K 0.125f          /* smooth |n| = sqrt(n^2 + K^2) - K */
#define VALLEY_K2 0.015625f      /* K^2 */
#define VALLEY_MAX 0.88278222f   /* sqrt(1 + K^2) - K, the smooth |n| at |n| = 1 */

/* A noise value and its derivatives along x and z (per metre). */
typedef struct wnoise_t {
    float v, dx, dz;
} wnoise_t;

static uint32_t layer_key(const terrain_world_t *w, uint32_t layer)
{
    return core_hash_u32(w->seed[0] ^ core_hash_u32(w->seed[1] ^ layer));
}

/* Lattice value in [-1, 1) at integer (ix, iz). */
static float lattice(uint32_t key, int32_t ix, int32_t iz)
{
    return core_hash_float(core_hash_u32(key ^ (uint32_t)ix) ^ (uint32_t)iz) * 2.0f - 1.0f;
}

static float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
static float dfade(float t) { return 30.0f * t * t * (t * (t - 2.0f) + 1.0f); }

/* Value noise of one octave at frequency freq (1/m, a power of two). */
static wnoise_t noise(uint32_t key, float x, float z, float freq)
{
    float fx = x * freq, fz = z * freq;
    float x0 = floorf(fx), z0 = floorf(fz);
    int32_t ix = (int32_t)x0, iz = (int32_t)z0;
    float ux = fx - x0, uz = fz - z0;
    float u = fade(ux), v = fade(uz), du = dfade(ux), dv = dfade(uz);
    float a = lattice(key, ix, iz), b = lattice(key, ix + 1, iz);
    float c = lattice(key, ix, iz + 1), d = lattice(key, ix + 1, iz + 1);
    float k1 = b - a, k2 = c - a, k3 = ((a - b) - c) + d;
    wnoise_t n;
    n.v = ((a + k1 * u) + k2 * v) + (k3 * u) * v;
    n.dx = freq * (du * (k1 + k3 * v));
    n.dz = freq * (dv * (k2 + k3 * u));
    return n;
}

/* fBm of `octaves` octaves from wavelength 1/freq down, gain 0.5,
 * normalised to [-1, 1]. */
static wnoise_t fbm(const terrain_world_t *w, uint32_t layer, int octaves, float x, float z, float freq)
{
    wnoise_t s = {0.0f, 0.0f, 0.0f};
    float amp = 1.0f, norm = 0.0f;
    for (int o = 0; o < octaves; o++) {
        wnoise_t n = noise(layer_key(w, layer + (uint32_t)o), x, z, freq);
        s.v += amp * n.v;
        s.dx += amp * n.dx;
        s.dz += amp * n.dz;
        norm += amp;
        amp *= 0.5f;
        freq *= 2.0f;
    }
    float inv = 1.0f / norm;
    s.v *= inv;
    s.dx *= inv;
    s.dz *= inv;
    return s;
}

/* Height (m) and its gradient. */
static wnoise_t world_eval(const terrain_world_t *w, float x, float z)
{
    wnoise_t m = fbm(w, LAYER_MACRO, 3, x, z, 1.0f / 1024.0f);
    wnoise_t vn = fbm(w, LAYER_VALLEY, 2, x, z, 1.0f / 128.0f);
    wnoise_t d = fbm(w, LAYER_DETAIL, 3, x, z, 1.0f / 64.0f);
    wnoise_t f = noise(layer_key(w, LAYER_FLAT), x, z, 1.0f / 512.0f);
    /* valleys: smooth |n| mapped to [-1, 1] */
    float root = sqrtf(vn.v * vn.v + VALLEY_K2);
    float vs = 2.0f / VALLEY_MAX, dva = vs * (vn.v / root);
    float va = (root - VALLEY_K) * vs - 1.0f;
    /* meadow mask: smoothstep(0, 0.25, f) */
    float s = fminf(fmaxf(f.v * 4.0f, 0.0f), 1.0f);
    float flat = s * s * (3.0f - 2.0f * s);
    float dflat = s > 0.0f && s < 1.0f ? 24.0f * s * (1.0f - s) : 0.0f;
    float r = 0.35f * va + 0.12f * d.v, g = 1.0f - flat;
    float rdx = 0.35f * (dva * vn.dx) + 0.12f * d.dx, rdz = 0.35f * (dva * vn.dz) + 0.12f * d.dz;
    wnoise_t h;
    h.v = w->height * ((0.5f * m.v + g * r) + 0.03f * d.v);
    h.dx = w->height * (((0.5f * m.dx + g * rdx) - (dflat * f.dx) * r) + 0.03f * d.dx);
    h.dz = w->height * (((0.5f * m.dz + g * rdz) - (dflat * f.dz) * r) + 0.03f * d.dz);
    return h;
}

terrain_world_t terrain_world_make(const terrain_desc_t *desc, uint64_t seed)
{
    terrain_desc_t d = terrain_desc_defaults(desc);
    return (terrain_world_t){.size = d.size, .height = d.height, .seed = {(uint32_t)seed, (uint32_t)(seed >> 32)}};
}

float terrain_world_height(const terrain_world_t *w, float x, float z, vec3 normal_out)
{
    wnoise_t h = world_eval(w, x, z);
    if (normal_out) {
        normal_out[0] = -h.dx;
        normal_out[1] = 1.0f;
        normal_out[2] = -h.dz;
        glm_vec3_normalize(normal_out);
    }
    return h.v;
}

terrain_world_gpu_t terrain_world_gpu(const terrain_world_t *w)
{
    terrain_world_gpu_t g = {.height = w->height};
    for (uint32_t k = 0; k < TERRAIN_WORLD_LAYERS; k++) g.keys[k] = layer_key(w, k);
    return g;
}

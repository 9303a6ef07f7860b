/* world_height.glsl: the open world's height function, GLSL twin of
 * terrain_world_height (src/scene/terrain_world.c; the same expressions in
 * the same order, so heights agree to float rounding; test_terrain_world_gpu
 * checks it). Configured only by two uniforms (terrain_world_gpu; the
 * owner of the program sets them once, a program keeps them):
 * u_world_keys, the hash key of each noise layer, and u_world_height, the
 * amplitude (m). Not defines: one compiled program for every world.
 *   float world_height(vec2 xz)  height (m) in [-WORLD_HEIGHT, WORLD_HEIGHT]
 *   vec3  world_normal(vec2 xz)  unit analytic normal
 *   vec3  world_eval(vec2 xz)    (height, dh/dx, dh/dz) */
#ifndef WORLD_HEIGHT_GLSL
#define WORLD_HEIGHT_GLSL

#include "common/hash.glsl"

#define WORLD_LAYERS 9 /* TERRAIN_WORLD_LAYERS */
uniform uint u_world_keys[WORLD_LAYERS];
uniform float u_world_height;

#define WORLD_LAYER_MACRO 0u
#define WORLD_LAYER_VALLEY 3u
#define WORLD_LAYER_DETAIL 5u
#define WORLD_LAYER_FLAT 8u
#define WORLD_VALLEY_K 0.125
#define WORLD_VALLEY_K2 0.015625
#define WORLD_VALLEY_MAX 0.88278222

uint world_layer_key(uint layer) { return u_world_keys[layer]; }

float world_lattice(uint key, int ix, int iz)
{
    return hash_float(hash_u32(key ^ uint(ix)) ^ uint(iz)) * 2.0 - 1.0;
}

float world_fade(float t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
float world_dfade(float t) { return 30.0 * t * t * (t * (t - 2.0) + 1.0); }

/* One octave of value noise: (value, d/dx, d/dz). */
vec3 world_noise(uint key, vec2 p, float freq)
{
    float fx = p.x * freq, fz = p.y * freq;
    float x0 = floor(fx), z0 = floor(fz);
    int ix = int(x0), iz = int(z0);
    float ux = fx - x0, uz = fz - z0;
    float u = world_fade(ux), v = world_fade(uz), du = world_dfade(ux), dv = world_dfade(uz);
    float a = world_lattice(key, ix, iz), b = world_lattice(key, ix + 1, iz);
    float c = world_lattice(key, ix, iz + 1), d = world_lattice(key, ix + 1, iz + 1);
    float k1 = b - a, k2 = c - a, k3 = ((a - b) - c) + d;
    return vec3(((a + k1 * u) + k2 * v) + (k3 * u) * v, freq * (du * (k1 + k3 * v)), freq * (dv * (k2 + k3 * u)));
}

vec3 world_fbm(uint layer, int octaves, vec2 p, float freq)
{
    vec3 s = vec3(0.0);
    float amp = 1.0, norm = 0.0;
    for (int o = 0; o < octaves; o++) {
        s += amp * world_noise(world_layer_key(layer + uint(o)), p, freq);
        norm += amp;
        amp *= 0.5;
        freq *= 2.0;
    }
    return s * (1.0 / norm);
}

vec3 world_eval(vec2 p)
{
    vec3 m = world_fbm(WORLD_LAYER_MACRO, 3, p, 1.0 / 1024.0);
    vec3 vn = world_fbm(WORLD_LAYER_VALLEY, 2, p, 1.0 / 128.0);
    vec3 d = world_fbm(WORLD_LAYER_DETAIL, 3, p, 1.0 / 64.0);
    vec3 f = world_noise(world_layer_key(WORLD_LAYER_FLAT), p, 1.0 / 512.0);
    float root = sqrt(vn.x * vn.x + WORLD_VALLEY_K2);
    float vs = 2.0 / WORLD_VALLEY_MAX, dva = vs * (vn.x / root);
    float va = (root - WORLD_VALLEY_K) * vs - 1.0;
    float s = min(max(f.x * 4.0, 0.0), 1.0);
    float flat_ = s * s * (3.0 - 2.0 * s);
    float dflat = s > 0.0 && s < 1.0 ? 24.0 * s * (1.0 - s) : 0.0;
    float r = 0.35 * va + 0.12 * d.x, g = 1.0 - flat_;
    vec2 rd = 0.35 * (dva * vn.yz) + 0.12 * d.yz;
    float h = (0.5 * m.x + g * r) + 0.03 * d.x;
    vec2 dh = ((0.5 * m.yz + g * rd) - (dflat * f.yz) * r) + 0.03 * d.yz;
    return u_world_height * vec3(h, dh);
}

float world_height(vec2 xz) { return world_eval(xz).x; }

vec3 world_normal(vec2 xz)
{
    vec3 e = world_eval(xz);
    return normalize(vec3(-e.y, 1.0, -e.z));
}

#endif

/* lod.glsl: coverage-preserving thinning of blades with distance, the
 * twin of src/blade/blade_lod.c (blade_lod_ -> lod_; the rules, the rank,
 * the shrink window and the widening are documented in blade_lod.h).
 * Parameters travel as the u_lod_* uniforms below, which the host sets
 * from blade_lod_t with blade_lod_uniforms (src/blade: the terrain's
 * program, blade_cull.comp and tiles_cull.comp). */
#ifndef LOD_GLSL
#define LOD_GLSL

#include "common/hash.glsl"

#define LOD_WIDTH 0
#define LOD_LEVELS 1
#define LOD_PRINTED 2
#define LOD_OFF 3

/* The resolved blade_lod_t, the frame's focal length and cull distance. */
uniform int u_lod_rule;
uniform int u_lod_levels;
uniform vec4 u_lod_a;     /* start, width_px, level_distance (0: cull), max_scale */
uniform vec4 u_lod_b;     /* shrink, fade, compensation (0/1), focal_px */
uniform float u_lod_cull; /* cull distance (m) */

float lod_rank(uint index)
{
    uint rev = bitfieldReverse(index & 255u) >> 24;
    return (float(rev) + hash_float(index * 0x9e3779b9u ^ 0x68e31da4u)) * (1.0 / 256.0);
}

int lod_level_of(float d)
{
    float end = u_lod_a.z > 0.0 ? u_lod_a.z : u_lod_cull;
    float level = floor(float(u_lod_levels) * (1.0 - d / end));
    return int(clamp(level, 0.0, float(u_lod_levels - 1)));
}

float lod_kept(float d, float width)
{
    float n = float(u_lod_levels);
    if (u_lod_rule == LOD_WIDTH) {
        float far_d = max(u_lod_a.x, width * u_lod_b.w / u_lod_a.y);
        return d <= far_d ? 1.0 : far_d / d;
    }
    if (u_lod_rule == LOD_LEVELS) return (float(lod_level_of(d)) + 1.0) / n;
    if (u_lod_rule == LOD_PRINTED) return (n - float(lod_level_of(d))) / n;
    return 1.0;
}

float lod_area(float u, float s)
{
    if (s <= 0.0) return u;
    float a = u * (1.0 + s);
    float r0 = clamp(a - s, 0.0, 1.0), r1 = clamp(a, 0.0, 1.0);
    return r0 + ((a - r0) * (a - r0) - (a - r1) * (a - r1)) / (2.0 * s);
}

float lod_end_fade(float d)
{
    float fade = u_lod_b.y;
    return fade > 0.0 ? clamp((u_lod_cull - d) / fade, 0.0, 1.0) : (d <= u_lod_cull ? 1.0 : 0.0);
}

float lod_widening(float area)
{
    if (u_lod_b.z == 0.0 || u_lod_rule == LOD_PRINTED) return 1.0;
    return min(1.0 / max(area, 1e-6), u_lod_a.w);
}

/* x: weight (0: culled), y: widening; drawn at width * x * y. */
vec2 lod_blade(uint index, float d, float width)
{
    float u = lod_kept(d, width);
    float e = lod_end_fade(d);
    if (u_lod_rule == LOD_LEVELS || u_lod_rule == LOD_PRINTED) {
        int n = u_lod_levels, level = lod_level_of(d);
        int m = int(index % uint(n));
        bool kept = u_lod_rule == LOD_LEVELS ? m <= level : m >= level;
        return vec2(kept ? e : 0.0, lod_widening(u));
    }
    float s = u_lod_b.x, r = lod_rank(index);
    float w = s > 0.0 ? clamp((u * (1.0 + s) - r) / s, 0.0, 1.0) : (r < u ? 1.0 : 0.0);
    return vec2(w * e, lod_widening(lod_area(u, s)));
}

float lod_coverage(float d, float width)
{
    float u = lod_kept(d, width);
    float area = u_lod_rule == LOD_WIDTH ? lod_area(u, u_lod_b.x) : u;
    return clamp(area * lod_widening(area), 0.0, 1.0) * lod_end_fade(d);
}

float lod_ground(float d, float width)
{
    return 1.0 - lod_coverage(d, width);
}

#endif

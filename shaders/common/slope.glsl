/* slope.glsl: GLSL twin of src/hybrid/hybrid_slope.c, the blade <->
 * billboard deformation hand-over (after Qiu et al.): cell addressing, tilt
 * offsets, fixed-point cell sums, eq. 8's weight and the reconstruction of
 * an element's direction from a cell. See hybrid_slope.h for the formulas.
 * Cells mirror hybrid_slope_cell_t (two vec4) and hybrid_slope_sum_t (two
 * ivec4-sized records). */
#ifndef SLOPE_GLSL
#define SLOPE_GLSL

#include "common/bindings_hybrid.glsl"

#define SLOPE_FIXED 16384.0
#define SLOPE_MAX_TILT 0.999

struct SlopeCell {
    vec4 a; /* T.x, T.z, M, eta */
    vec4 b; /* tau, count, 0, 0 */
};

struct SlopeSum {
    ivec4 a;  /* sums of T.x, T.z, M, eta (fixed point) */
    uvec4 b;  /* count, 0, 0, 0 */
};

uniform vec2 u_slope_origin;
uniform float u_slope_cell;
uniform ivec2 u_slope_dims;

int slope_cell_at(vec2 xz)
{
    ivec2 c = ivec2(floor((xz - u_slope_origin) / u_slope_cell));
    if (c.x < 0 || c.y < 0 || c.x >= u_slope_dims.x || c.y >= u_slope_dims.y) return -1;
    return c.y * u_slope_dims.x + c.x;
}

vec2 slope_offset(vec3 dir, vec3 pose_dir) { return vec2(dir.x - pose_dir.x, dir.z - pose_dir.z); }

int slope_fixed(float v) { return int(round(v * SLOPE_FIXED)); }

float slope_weight(float age, float recover)
{
    float u = 1.0 - clamp(age / recover, 0.0, 1.0);
    return u * u * u;
}

/* hybrid_slope_apply: T, M from c.xyz, fallback unit horizontal (x, z). */
vec3 slope_apply(vec3 pose_dir, vec2 fallback, vec4 c, float w)
{
    float tl = length(c.xy);
    float rest = max(c.z - tl, 0.0);
    vec2 q = pose_dir.xz + w * (c.xy + fallback * rest);
    float ql = length(q);
    if (ql > SLOPE_MAX_TILT) {
        q = q * (SLOPE_MAX_TILT / ql);
        ql = SLOPE_MAX_TILT;
    }
    return vec3(q.x, sqrt(1.0 - ql * ql), q.y);
}

#endif

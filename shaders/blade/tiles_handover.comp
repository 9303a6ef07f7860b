#version 450
/* tiles_handover.comp: blades -> billboards hand-over (after Qiu et al.;
 * src/hybrid/hybrid_slope.h). For the pool slots of tiles that turn to
 * billboards while recovering, every blade adds its tilt offset against
 * the procedural pose P(t) and its eta to the fixed-point sums of the
 * slope cell its root lies in. Invocation i: entry list[i / B] = (slot,
 * tile), blade i % B. tiles_slope_resolve.comp turns the sums into cells. */
#include "blade/tiles_common.glsl"
#include "common/slope.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = BLADE_TILES_BIND_POOL) readonly buffer Pool { Blade pool[]; };
layout(std430, binding = BLADE_TILES_BIND_ETA) readonly buffer Eta { float eta[]; };
layout(std430, binding = BLADE_TILES_BIND_LIST) readonly buffer List { uvec2 list[]; };
layout(std430, binding = HYBRID_BIND_SLOPE_SUMS) buffer Sums { SlopeSum sums[]; };

uniform uint u_count; /* entries * B */

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    uvec2 e = list[i / u_template_blades];
    uint k = i % u_template_blades;
    uint idx = e.x * u_template_blades + k;
    Blade b = pool[idx];
    if (b.v1.w <= 0.0) return;
    int c = slope_cell_at(b.v0.xz);
    if (c < 0) return;
    Blade p = tiles_pose(tiles_rest(e.y, k));
    vec2 o = slope_offset(blade_safe_normalize(b.v2.xyz - b.v0.xyz), blade_safe_normalize(p.v2.xyz - p.v0.xyz));
    atomicAdd(sums[c].a.x, slope_fixed(o.x));
    atomicAdd(sums[c].a.y, slope_fixed(o.y));
    atomicAdd(sums[c].a.z, slope_fixed(length(o)));
    atomicAdd(sums[c].a.w, slope_fixed(eta[idx]));
    atomicAdd(sums[c].b.x, 1u);
}

#version 450
/* bb_slope.comp: the billboards' side of the billboards -> blades
 * hand-over (after Qiu et al.; src/hybrid/hybrid_slope.h). Every billboard
 * holding a deformed mesh adds the tilt offset of its top row's centre
 * against the wind pose (eq. 8's w) to the fixed-point sums of the slope
 * cell of its root, with eta 0; the blades seeded there read the sums
 * (shaders/blade/tiles_init.comp). A billboard whose top row has
 * collapsed onto its root (or with a zero-height wind pose) has no tilt
 * direction and adds nothing. Invocation i: billboard i. */
#define BB_NO_GENERATE
#include "common/bindings_billboard.glsl"
#include "common/bb.glsl"
#include "billboard/bb_points.glsl"
#include "common/slope.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = BB_BIND_MESHES) readonly buffer Meshes { vec4 meshes[]; };
layout(std430, binding = BB_BIND_POINTS) readonly buffer Points { bb_point points[]; };
layout(std430, binding = HYBRID_BIND_SLOPE_SUMS) buffer Sums { SlopeSum sums[]; };

uniform uint u_count;
uniform float u_time;
uniform bb_wind u_wind;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    bb_point p = points[i];
    if (p.pad0 == BB_NO_SLOT) return;
    int c = slope_cell_at(p.position.xz);
    if (c < 0) return;
    vec3 right, up;
    bb_frame(p, right, up);
    vec3 a, b, ta, tb;
    bb_plain_corners(p, right, up, u_wind, u_time, a, b, ta, tb);
    vec3 top = vec3(0.0);
    for (int k = 0; k < BB_N; k++) top = top + meshes[int(p.pad0) * BB_N * BB_M + (BB_M - 1) * BB_N + k].xyz;
    top = top * (1.0 / float(BB_N));
    vec3 dir = top - p.position, pose = 0.5 * (ta + tb) - p.position;
    float dl = length(dir), pl = length(pose);
    if (dl < 1e-6 || pl < 1e-6) return;
    vec2 o = slope_offset(dir * (1.0 / dl), pose * (1.0 / pl));
    atomicAdd(sums[c].a.x, slope_fixed(o.x));
    atomicAdd(sums[c].a.y, slope_fixed(o.y));
    atomicAdd(sums[c].a.z, slope_fixed(length(o)));
    atomicAdd(sums[c].b.x, 1u);
}

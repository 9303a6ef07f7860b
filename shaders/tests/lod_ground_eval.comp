#version 450
/* lod_ground_eval.comp: the thinning (common/lod.glsl) and the grass-shaded
 * ground under it (canopy_under of common/canopy.glsl) for
 * test_lod_ground_gpu (CPU twins: blade_lod_blade, blade_lod_coverage,
 * blade_canopy_under): item i is (distance, width, cover, extent) in
 * in[i]; out[i] = (weight, scale, coverage, ground mix). */
#include "common/canopy.glsl"
#include "common/lod.glsl"

layout(local_size_x = 64) in;
#include "common/bindings_tests.glsl"

layout(std430, binding = TEST_BIND_IN) readonly buffer In { vec4 items[]; };
layout(std430, binding = TEST_BIND_OUT) writeonly buffer Out { vec4 result[]; };

uniform uint u_count;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    vec4 it = items[i];
    vec2 b = lod_blade(i, it.x, it.y);
    float kept = lod_coverage(it.x, it.y);
    result[i] = vec4(b, kept, canopy_under(it.z, it.w, kept));
}

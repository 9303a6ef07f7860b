#version 450
/* world_eval.comp: world_height and world_normal of common/world_height.glsl
 * for test_terrain_world_gpu (CPU twin: terrain_world_height): item i is the
 * point pts[i].xy (world x, z); out[i] = (normal, height). Configured only
 * by world_height.glsl's uniforms (terrain_world_gpu). */
#include "common/world_height.glsl"

layout(local_size_x = 64) in;
#include "common/bindings_tests.glsl"

layout(std430, binding = TEST_BIND_IN) readonly buffer Pts { vec2 pts[]; };
layout(std430, binding = TEST_BIND_OUT) writeonly buffer Out { vec4 result[]; };

uniform uint u_count;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    result[i] = vec4(world_normal(pts[i]), world_height(pts[i]));
}

#version 450
/* canopy_eval.comp: canopy_color of common/canopy.glsl for test_canopy_gpu
 * (CPU twin: blade_canopy_color): item i is a camera at cams[i].xyz and a
 * sun towards suns[i].xyz over the ground point (0, 0, 0) of normal +y;
 * out[i] = (colour, cover). */
#include "common/canopy.glsl"

layout(local_size_x = 64) in;
#include "common/bindings_tests.glsl"

layout(std430, binding = TEST_BIND_IN) readonly buffer Cams { vec4 cams[]; };
layout(std430, binding = TEST_BIND_IN2) readonly buffer Suns { vec4 suns[]; };
layout(std430, binding = TEST_BIND_OUT) writeonly buffer Out { vec4 result[]; };

uniform uint u_count;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    float cover;
    vec3 c = canopy_color(vec3(0.0), vec3(0.0, 1.0, 0.0), cams[i].xyz, suns[i].xyz, cover);
    result[i] = vec4(c, cover);
}

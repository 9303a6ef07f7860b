#version 450
/* bb_lod_eval.comp: the billboard cards' thinning (bb_lod_card of
 * billboard/bb_lod.glsl, which bb_render.geom, bb_quad.vert and
 * bb_raster.comp apply) for test_bb_gpu_lod (CPU twin: bb_lod_card of
 * src/billboard/bb_lod.c): card i of the points buffer in[i] seen from
 * u_eye; out[i] = (weight, widening). */
#define BB_NO_GENERATE
#include "common/bb.glsl"
#include "billboard/bb_points.glsl"
#include "billboard/bb_lod.glsl"

layout(local_size_x = 64) in;
#include "common/bindings_tests.glsl"

layout(std430, binding = TEST_BIND_IN) readonly buffer In { bb_point points[]; };
layout(std430, binding = TEST_BIND_OUT) writeonly buffer Out { vec2 result[]; };

uniform uint u_count;
uniform vec3 u_eye;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i < u_count) result[i] = bb_lod_card(points[i], u_eye);
}

#version 450
/* bb_view.comp: bb_view_weights and bb_view_texel of bb_view.glsl for
 * test_bb_gpu_view (CPU twins: bb_view_weights, bb_view_pick). Query i
 * reads its view direction (xyz) and layer (w) from queries[2 i] and its
 * draw xi from queries[2 i + 1].x, and writes the four views and weights,
 * then the texel and light layer of layer w at the texture's centre from
 * the view xi picks, that view and bb_view_xi of pixel (i, 3 i). */
#include "billboard/bb_view.glsl"

layout(local_size_x = 64) in;
#include "common/bindings_tests.glsl"

layout(std430, binding = TEST_BIND_IN) readonly buffer Queries { vec4 queries[]; };
layout(std430, binding = TEST_BIND_OUT) writeonly buffer Out { vec4 result[]; };

layout(binding = TEST_TEX_IN) uniform sampler2DArray u_clumps;
uniform uint u_count;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    vec4 q = queries[2u * i];
    float xi = queries[2u * i + 1u].x;
    ivec4 view;
    vec4 w;
    bb_view_weights(q.xyz, u_view_wind, u_views, u_view_elevation_max, view, w);
    vec3 light;
    vec4 c = bb_view_texel(u_clumps, vec2(0.5), q.w, vec2(0.0), vec2(0.0), q.xyz, xi, light);
    result[5u * i] = vec4(view);
    result[5u * i + 1u] = w;
    result[5u * i + 2u] = c;
    result[5u * i + 3u] = vec4(light, 0.0);
    result[5u * i + 4u] = vec4(float(bb_view_pick(view, w, xi)), bb_view_xi(uvec2(i, 3u * i)), 0.0, 0.0);
}

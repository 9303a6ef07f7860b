#version 450
/* canopy_eval.comp: canopy_color and canopy_overhang of common/canopy.glsl
 * for test_canopy_gpu (CPU twins: blade_canopy_color,
 * blade_canopy_overhang): item i is a ground point at items[i].pos.xyz of
 * unit normal items[i].normal.xyz seen from a camera at items[i].camera.xyz
 * and lit by a sun towards suns[i].xyz under the wind force
 * items[i].wind.xyz; out[3 i] = (colour, cover) of the
 * column cut at items[i].camera.w (m; 0: the whole column), out[3 i + 1]
 * the whole column's, out[3 i + 2] the overhang of the whole column over
 * that cut with blades kept suns[i].w. */
#include "common/canopy.glsl"

layout(local_size_x = 64) in;
#include "common/bindings_tests.glsl"

struct item_t {
    vec4 pos, normal, camera, wind;
};
layout(std430, binding = TEST_BIND_IN) readonly buffer Items { item_t items[]; };
layout(std430, binding = TEST_BIND_IN2) readonly buffer Suns { vec4 suns[]; };
layout(std430, binding = TEST_BIND_OUT) writeonly buffer Out { vec4 result[]; };

uniform uint u_count;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    float cover, whole;
    item_t it = items[i];
    vec3 c = canopy_color(it.pos.xyz, it.normal.xyz, it.camera.xyz, suns[i].xyz, it.wind.xyz, it.camera.w, cover);
    vec3 w = canopy_color(it.pos.xyz, it.normal.xyz, it.camera.xyz, suns[i].xyz, it.wind.xyz, 0.0, whole);
    result[3 * i] = vec4(c, cover);
    result[3 * i + 1] = vec4(w, whole);
    result[3 * i + 2] = canopy_overhang(vec4(w, whole), vec4(c, cover), suns[i].w);
}

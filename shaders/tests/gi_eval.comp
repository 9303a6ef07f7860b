#version 450
/* gi_eval.comp: the global illumination of common/gi.glsl for test_gi_gpu
 * (CPU twin: gi_volume_ambient). Item i is a point items[2 i].xyz and a
 * unit normal items[2 i + 1].xyz. u_mode 0: out[i] = gi_ambient there;
 * u_mode 1: the colour of a billboard card point there (bb_shade, albedo
 * u_albedo, views off, image row 0.3) lit by its vertex ambient
 * (bb_vertex_ambient), as bb_quad.vert and bb_render.frag light it. */
#include "common/grass_shade.glsl"

layout(local_size_x = 64) in;
#include "common/bindings_tests.glsl"

layout(std430, binding = TEST_BIND_IN) readonly buffer Items { vec4 items[]; };
layout(std430, binding = TEST_BIND_OUT) writeonly buffer Out { vec4 result[]; };

uniform uint u_count;
uniform int u_mode;
uniform vec3 u_camera;
uniform vec3 u_sun;
uniform vec3 u_albedo;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    vec3 p = items[2u * i].xyz, n = items[2u * i + 1u].xyz;
    if (u_mode == 0) {
        result[i] = vec4(gi_ambient(p, n), 0.0);
        return;
    }
    vec3 front, back;
    bb_vertex_ambient(p, n, front, back);
    vec3 c = bb_shade(u_albedo, 1.0, p, n, vec3(0.0), 0.0, 1.0, 0.3, u_camera, u_sun, vec4(0.0), front, back);
    result[i] = vec4(c, 1.0);
}

#version 450
/* uniforms.comp: test_gfx_smoke's program for gfx_uniform's cache. With
 * UNIFORMS_AB it uses u_a (location 2) and u_b (location 3); without, u_b
 * alone at location 7, so a location cached for another program of the
 * same name shows. */
layout(local_size_x = 1) in;

#include "common/bindings_tests.glsl"

layout(std430, binding = TEST_BIND_OUT) buffer Out { float o[]; };

#ifdef UNIFORMS_AB
layout(location = 2) uniform vec4 u_a;
layout(location = 3) uniform float u_b;
#else
layout(location = 7) uniform float u_b;
#endif

void main()
{
#ifdef UNIFORMS_AB
    o[0] = u_a.x + u_b;
#else
    o[0] = u_b;
#endif
}

#version 450
/* blade_surface.comp: blade_build of blade_geom.glsl (Jahrmann & Wimmer 2017
 * eq. 21 and the shape profiles) at a grid of u_us x u_vs points (u, v) of
 * every blade, for test_blade_surface (CPU twin: blade_ref_surface). Point
 * k of blade b is out[2 (b u_us u_vs + k)] (position) and the next vec4
 * (normal); u = (k mod u_us) / (u_us - 1), v = (k / u_us) / (u_vs - 1). */
#include "common/blade.glsl"
#include "blade/blade_geom.glsl"

layout(local_size_x = 64) in;
#include "common/bindings_tests.glsl"

layout(std430, binding = TEST_BIND_IN) readonly buffer Blades { Blade blades[]; };
layout(std430, binding = TEST_BIND_OUT) writeonly buffer Out { vec4 points[]; };

uniform uint u_count; /* blades */
uniform int u_us;
uniform int u_vs;

void main()
{
    uint i = gl_GlobalInvocationID.x, per = uint(u_us * u_vs);
    if (i >= u_count * per) return;
    uint k = i % per;
    float u = float(k % uint(u_us)) / float(u_us - 1), v = float(k / uint(u_us)) / float(u_vs - 1);
    vec3 p, n;
    blade_build(blades[i / per], u, v, p, n);
    points[2u * i] = vec4(p, 0.0);
    points[2u * i + 1u] = vec4(n, 0.0);
}

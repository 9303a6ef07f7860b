#version 450
/* blade.tese: builds the blade surface at (u, v) with De Casteljau and the
 * shape functions (Jahrmann & Wimmer 2017 eq. 21, 23, 24; blade_geom.glsl). */
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "common/switch.glsl"
#include "blade/blade_geom.glsl"

layout(quads, equal_spacing, ccw) in;
layout(std430, binding = BLADE_BIND_BLADES) readonly buffer Blades { Blade blades[]; };

patch in uint tc_blade;
uniform mat4 u_view_proj;

out vec3 f_pos;
out vec3 f_normal;
out float f_v;
out flat float f_root_dist;

void main()
{
    Blade b = blades[tc_blade];
    vec3 p, n;
    blade_build(b, gl_TessCoord.x, gl_TessCoord.y, p, n);
    f_pos = p;
    f_normal = n;
    f_v = gl_TessCoord.y;
    f_root_dist = grass_distance(b.v0.xyz, u_camera);
    gl_Position = u_view_proj * vec4(p, 1.0);
}

#version 450
/* blade.tese: builds the blade surface at (u, v) with De Casteljau and the
 * shape functions (Jahrmann & Wimmer 2017 eq. 21, 23, 24; blade_geom.glsl),
 * the width times the blade's width factor (the thinning's, blade.tesc). */
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "common/switch.glsl"
#include "blade/blade_geom.glsl"

layout(quads, equal_spacing, ccw) in;
layout(std430, binding = BLADE_BIND_BLADES) readonly buffer Blades { Blade blades[]; };

patch in uint tc_blade;
patch in float tc_width;
uniform mat4 u_view_proj;

out vec3 f_pos;
out vec3 f_normal;
out float f_v;
out flat float f_root_dist;

void main()
{
    Blade b = blades[tc_blade];
    b.v2.w *= tc_width;
    vec3 p, n;
    blade_build(b, gl_TessCoord.x, gl_TessCoord.y, p, n);
    f_pos = p;
    f_normal = n;
    f_v = gl_TessCoord.y;
    f_root_dist = grass_distance(b.v0.xyz, u_camera);
    gl_Position = u_view_proj * vec4(p, 1.0);
}

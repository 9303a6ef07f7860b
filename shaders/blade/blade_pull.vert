#version 450
/* blade_pull.vert: vertex-pulling path (no tessellation): one instance per
 * surviving blade, a triangle strip of S = 2 (u_max_level + 1) vertices per
 * column, 2 S + 2 with the eq. 23 displacement (blade_strip_uv; blade.c
 * command_initial). Same geometry as blade.tese
 * (Jahrmann & Wimmer 2017 eq. 21, 23, 24), the width times the survivor's
 * width factor (the thinning's, blade_cull.comp). */
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "common/switch.glsl"
#include "blade/blade_geom.glsl"

layout(std430, binding = BLADE_BIND_BLADES) readonly buffer Blades { Blade blades[]; };
layout(std430, binding = BLADE_BIND_SURVIVORS) readonly buffer Survivors { uvec2 survivors[]; };

uniform mat4 u_view_proj;

out vec3 f_pos;
out vec3 f_normal;
out float f_v;
out flat float f_root_dist;

void main()
{
    uvec2 s = survivors[gl_InstanceID];
    Blade b = blades[s.x];
    b.v2.w *= uintBitsToFloat(s.y);
    int n = blade_lod(b);
    vec2 uv = blade_strip_uv(gl_VertexID, n);
    float v = uv.y;
    vec3 p, nrm;
    blade_build(b, uv.x, v, p, nrm);
    f_pos = p;
    f_normal = nrm;
    f_v = v;
    f_root_dist = grass_distance(b.v0.xyz, u_camera);
    gl_Position = u_view_proj * vec4(p, 1.0);
}

#version 450
/* blade_pull.vert: vertex-pulling path (no tessellation): one instance per
 * surviving blade, a triangle strip of 2 (u_max_level + 1) vertices; vertex
 * k is (u, v) = (k & 1, min(k / 2, n) / n) with n = blade_lod segments, so
 * the strip past level n collapses into degenerate triangles. Same geometry
 * as blade.tese (Jahrmann & Wimmer 2017 eq. 21, 23, 24). */
#include "common/blade.glsl"
#include "blade/blade_geom.glsl"

layout(std430, binding = 0) readonly buffer Blades { Blade blades[]; };
layout(std430, binding = 1) readonly buffer Survivors { uint survivors[]; };

uniform mat4 u_view_proj;

out vec3 f_pos;
out vec3 f_normal;
out float f_v;
out flat float f_root_dist;

void main()
{
    Blade b = blades[survivors[gl_InstanceID]];
    int n = blade_lod(b);
    float v = float(min(gl_VertexID / 2, n)) / float(n);
    vec3 p, nrm;
    blade_build(b, float(gl_VertexID & 1), v, p, nrm);
    f_pos = p;
    f_normal = nrm;
    f_v = v;
    f_root_dist = length(b.v0.xyz - u_camera);
    gl_Position = u_view_proj * vec4(p, 1.0);
}

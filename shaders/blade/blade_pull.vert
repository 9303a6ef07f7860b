#version 450
/* blade_pull.vert: vertex-pulling path (no tessellation): one instance per
 * surviving blade, a triangle strip of S = 2 (u_max_level + 1) vertices per
 * column; vertex k of a column is (u, v) = (k & 1, min(k / 2, n) / n) with
 * n = blade_lod segments, so the strip past level n collapses into
 * degenerate triangles. With the eq. 23 displacement there are 2 columns
 * (u in [0, 0.5], then [0.5, 1]: the midrib gets vertices), joined by 2
 * degenerate vertices (the last of the first, the first of the second):
 * 2 S + 2 vertices (blade.c command_initial). Same geometry as blade.tese
 * (Jahrmann & Wimmer 2017 eq. 21, 23, 24). */
#include "common/blade.glsl"
#include "common/switch.glsl"
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
    int s = 2 * (u_max_level + 1);
    int k = gl_VertexID, column = 0;
    if (k == s) {
        k = s - 1;
    } else if (k > s) {
        column = 1;
        k = max(k - s - 2, 0);
    }
    float cw = 1.0 / float(blade_columns());
    float v = float(min(k / 2, n)) / float(n);
    vec3 p, nrm;
    blade_build(b, (float(column) + float(k & 1)) * cw, v, p, nrm);
    f_pos = p;
    f_normal = nrm;
    f_v = v;
    f_root_dist = grass_distance(b.v0.xyz, u_camera);
    gl_Position = u_view_proj * vec4(p, 1.0);
}

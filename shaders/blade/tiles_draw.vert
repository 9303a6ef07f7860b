#version 450
/* tiles_draw.vert: vertex pulling of the blades appended by
 * tiles_cull.comp: one instance per blade, a triangle strip of
 * 2 (u_max_level + 1) vertices built by blade_geom.glsl (Jahrmann & Wimmer
 * 2017 eq. 21, 23, 24), as blade_pull.vert. Instances past u_capacity
 * (overflow, counted and logged by the host) collapse to a point. */
#include "common/blade.glsl"
#include "blade/blade_geom.glsl"

layout(std430, binding = 8) readonly buffer Drawn { Blade drawn[]; };

uniform mat4 u_view_proj;
uniform uint u_capacity;

out vec3 f_pos;
out vec3 f_normal;
out float f_v;
out flat float f_root_dist;

void main()
{
    if (uint(gl_InstanceID) >= u_capacity) {
        f_pos = vec3(0.0);
        f_normal = vec3(0.0, 1.0, 0.0);
        f_v = 0.0;
        f_root_dist = 0.0;
        gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
        return;
    }
    Blade b = drawn[gl_InstanceID];
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

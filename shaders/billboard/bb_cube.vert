#version 450
/* bb_cube.vert: renders an object's triangles (object = cube space) into
 * face u_face of its depth cube map (Orthmann et al. 2009, sec. 5) with the
 * orthographic camera of collide_get_face_basis: x = u, y = v, depth along
 * `inward`, all over [-half, half]. */
#define BB_NO_GENERATE
#include "common/bb.glsl"

layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;

uniform vec3 u_centre;
uniform float u_half;
uniform int u_face;

out float v_dist;
out vec3 v_normal;

void main()
{
    vec3 rel = a_pos - u_centre;
    float din = dot(rel, bb_face_in[u_face]);
    gl_Position = vec4(dot(rel, bb_face_u[u_face]) / u_half, dot(rel, bb_face_v[u_face]) / u_half, din / u_half, 1.0);
    v_dist = din + u_half;
    v_normal = a_normal;
}

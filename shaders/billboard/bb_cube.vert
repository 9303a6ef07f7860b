#version 450
#extension GL_ARB_shader_viewport_layer_array : require
/* bb_cube.vert: an object's depth cube map (Orthmann et al. 2009, sec. 5),
 * all six faces in one instanced draw: instance = face, drawn into layer
 * u_layer + face with the orthographic camera of collide_get_face_basis:
 * x = u, y = v, depth along `inward`, all over [-half, half]. With
 * u_background the draw is the face's background instead (4 vertices, a
 * strip at the far plane: distance 2 half, normal against `inward`, the
 * texel of a ray that meets nothing), drawn first. */
#define BB_NO_GENERATE
#include "common/bb.glsl"

layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;

uniform vec3 u_centre;
uniform float u_half;
uniform int u_layer;
uniform bool u_background;

out float v_dist;
out vec3 v_normal;

void main()
{
    int face = gl_InstanceID;
    gl_Layer = u_layer + face;
    if (u_background) {
        vec2 corner = vec2(float(gl_VertexID & 1), float(gl_VertexID >> 1)) * 2.0 - 1.0;
        gl_Position = vec4(corner, 1.0, 1.0);
        v_dist = 2.0 * u_half;
        v_normal = -bb_face_in[face];
        return;
    }
    vec3 rel = a_pos - u_centre;
    float din = dot(rel, bb_face_in[face]);
    gl_Position = vec4(dot(rel, bb_face_u[face]) / u_half, dot(rel, bb_face_v[face]) / u_half, din / u_half, 1.0);
    v_dist = din + u_half;
    v_normal = a_normal;
}

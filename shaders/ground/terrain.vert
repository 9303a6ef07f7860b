// terrain.vert: terrain mesh positions to clip space, and the ground
// canopy's colour and cover at the vertex, of the whole column and of the
// column cut below the overhang (ground/terrain_canopy.glsl).
#version 450 core
#include "ground/terrain_canopy.glsl"
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_viewproj;
out vec3 v_pos;
out vec3 v_normal;
out vec4 v_canopy;
out vec4 v_canopy_cut;
void main()
{
    v_pos = a_pos;
    v_normal = a_normal;
    v_canopy = terrain_canopy(a_pos, a_normal, v_canopy_cut);
    gl_Position = u_viewproj * vec4(a_pos, 1.0);
}

// terrain_world.vert: one clipmap level of the world terrain
// (scene/terrain_clipmap.h; CPU twin terrain_clipmap_vertex): grid vertex
// (i, j) at u_origin + (i, j) * u_cell, slid towards the coarser level's
// grid (odd indices onto the even one below) by the morph factor of its
// Chebyshev distance to the camera, then displaced by world_height
// (common/world_height.glsl, configured by terrain_world_defines). Passes
// terrain.frag what terrain.vert does: world position, unit normal and the
// ground canopy at the vertex, whole and cut (ground/terrain_canopy.glsl).
#version 450 core
#include "common/world_height.glsl"
#include "ground/terrain_canopy.glsl"
layout(location = 0) in uvec2 a_grid;
uniform mat4 u_viewproj;
uniform vec2 u_origin;
uniform float u_cell;
uniform vec2 u_morph; /* distance where the morph starts, 1 / (end - start) */
out vec3 v_pos;
out vec3 v_normal;
out vec4 v_canopy;
out vec4 v_canopy_cut;
void main()
{
    vec2 g = vec2(a_grid);
    vec2 p = u_origin + g * u_cell;
    float dist = max(abs(p.x - u_camera.x), abs(p.y - u_camera.z));
    float k = clamp((dist - u_morph.x) * u_morph.y, 0.0, 1.0);
    vec2 xz = u_origin + (g - vec2(a_grid & 1u) * k) * u_cell;
    vec3 e = world_eval(xz);
    v_pos = vec3(xz.x, e.x, xz.y);
    v_normal = normalize(vec3(-e.y, 1.0, -e.z));
    v_canopy = terrain_canopy(v_pos, v_normal, v_canopy_cut);
    gl_Position = u_viewproj * vec4(v_pos, 1.0);
}

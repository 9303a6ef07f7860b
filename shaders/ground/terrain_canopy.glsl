/* terrain_canopy.glsl: the ground canopy's colour (unfogged) and cover at
 * a terrain vertex, for terrain.vert and terrain_world.vert: the table of
 * common/canopy.glsl under the ambient of common/gi.glsl, linear in the
 * normal (the hemisphere, or the volumes' a + B n), taken along the
 * ground's frame (t, g, s) as its value at n = 0 and its changes along
 * them. The colour follows the view's and the sun's angles, which change
 * slowly across a triangle wherever the canopy shows (beyond the
 * thinning's start), so it is computed per vertex and interpolated: per
 * pixel it took 0.23 of meadow_large's 0.95 ms terrain pass (H200, compute
 * path). */
#ifndef TERRAIN_CANOPY_GLSL
#define TERRAIN_CANOPY_GLSL

#include "common/canopy.glsl"
#include "common/gi.glsl"

uniform bool u_canopy_on;
uniform vec3 u_camera;
uniform vec3 u_sun;

vec4 terrain_canopy(vec3 pos, vec3 normal)
{
    if (!u_canopy_on) return vec4(0.0);
    float cover;
    canopy_view_t v = canopy_view(pos, normalize(normal), u_camera, u_sun);
    vec3 up = grass_ambient(pos, v.g), down = grass_ambient(pos, -v.g), amb0 = 0.5 * (up + down);
    mat3 amb_n = mat3(grass_ambient(pos, v.t) - amb0, 0.5 * (up - down), grass_ambient(pos, v.s) - amb0);
    return vec4(canopy_table_color(v, amb0, amb_n, cover), cover);
}

#endif

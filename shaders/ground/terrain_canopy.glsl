/* terrain_canopy.glsl: the ground canopy's colour (unfogged) and cover at
 * a terrain vertex (canopy_color_lit under the ambient of common/gi.glsl),
 * for terrain.vert and terrain_world.vert. The colour follows the view's
 * elevation and the sun's azimuth, which change slowly across a triangle
 * wherever the canopy shows (beyond the thinning's start), so it is
 * computed per vertex and interpolated: per pixel it took 0.23 of
 * meadow_large's 0.95 ms terrain pass (H200, compute path). */
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
    vec3 down = grass_ambient(pos, vec3(0.0, -1.0, 0.0)), up = grass_ambient(pos, vec3(0.0, 1.0, 0.0));
    vec3 c = canopy_color_lit(pos, normalize(normal), u_camera, u_sun, down, up, cover);
    return vec4(c, cover);
}

#endif

/* terrain_canopy.glsl: the ground canopy's colour (unfogged) and cover at
 * a terrain vertex, for terrain.vert and terrain_world.vert: the table of
 * common/canopy.glsl under the ambient of common/gi.glsl, linear in the
 * normal (the hemisphere, or the volumes' a + B n), taken along the
 * ground's frame (t, g, s) as its value at n = 0 and its changes along
 * them; the whole column's, and where the canopy continues the hybrid's
 * blades (u_canopy_switch), the column cut at the height below which the
 * drawn blades' overhang leaves the ray to the canopy (terrain.frag joins
 * the two with canopy_overhang); under the wind at the vertex (the blade
 * physics' fields at u_time: common/blade.glsl). The colour follows the
 * view's and the sun's angles, which change
 * slowly across a triangle wherever the canopy shows (beyond the
 * thinning's start), so it is computed per vertex and interpolated: per
 * pixel it took 0.23 of meadow_large's 0.95 ms terrain pass (H200, compute
 * path). Vertices of no triangle in view skip it. */
#ifndef TERRAIN_CANOPY_GLSL
#define TERRAIN_CANOPY_GLSL

#include "common/bindings_ground.glsl"
#include "common/blade.glsl"
#include "common/canopy.glsl"
#include "common/gi.glsl"
#include "common/switch.glsl"

uniform bool u_canopy_on;
/* The tiles' switch distance and the half width of its fade band (m), where
 * the canopy continues the blades (no billboards between); x 0: nowhere. */
uniform vec2 u_canopy_switch;
uniform vec3 u_camera;
uniform vec3 u_sun;
#define TERRAIN_MAX_WINDS 8 /* BLADE_MAX_WINDS */
uniform int u_wind_count;
uniform vec4 u_winds[2 * TERRAIN_MAX_WINDS]; /* blade_wind_t's a and b of each */
uniform float u_time;
/* The view frustum's planes (unit normals in: grass_view_t.planes)
 * and the longest triangle edge (m): a vertex outside a plane by more
 * than that belongs to no triangle the view shows. */
uniform vec4 u_frustum[6];
uniform float u_canopy_margin;

/* The canopy match's gain (ground.c, canopy_match.comp): a factor per
 * channel on the canopy's colour as the frame stores it; (1, 1, 1) when
 * off. The match measures in linear light what the product does, so its
 * steps take up the difference from a gain in linear light, which would
 * cost two sRGB conversions a vertex. */
layout(std140, binding = GROUND_UBO_MATCH) uniform CanopyMatch { vec4 u_match_gain; };

bool terrain_canopy_seen(vec3 p)
{
    for (int i = 0; i < 6; i++)
        if (dot(u_frustum[i].xyz, p) + u_frustum[i].w < -u_canopy_margin) return false;
    return true;
}

/* The wind force at p: the fields' sum (tiles_wind_sum's); 0 when the
 * table has no wind poses. */
vec3 terrain_wind(vec3 p)
{
    vec3 w = vec3(0.0);
    for (int k = 0; u_canopy_poses > 1 && k < u_wind_count; k++)
        w += blade_wind_field(BladeWind(u_winds[2 * k], u_winds[2 * k + 1]), p, u_time);
    return w;
}

/* The height (m) over a ground point at eye distance d, seen at elevation
 * e, below which the blades rooted past the switch meet the ray: the
 * ground the ray crosses past the switch, d - s, times tan e, with the
 * blades' fade (blade_fade_ramp: alpha 1 - smoothstep over s +- w by the
 * root's distance) integrated along it: 2 w (T^3 - T^4 / 2), T = (d - s +
 * w) / (2 w), in the band; 0 nearer than s - w. */
float terrain_canopy_cut(float d, float e)
{
    float x = d - u_canopy_switch.x, w = u_canopy_switch.y;
    float t = w > 0.0 ? clamp((x + w) / (2.0 * w), 0.0, 1.0) : 0.0;
    float past = x >= w ? x : 2.0 * w * t * t * t * (1.0 - 0.5 * t);
    return past * tan(min(e, 1.5));
}

/* The canopy's (colour, cover) at pos: the whole column's, and in cut the
 * cut column's (the whole column's where the canopy does not continue the
 * blades; cover 0 nearer than the switch's band). */
vec4 terrain_canopy(vec3 pos, vec3 normal, out vec4 cut)
{
    cut = vec4(0.0);
    if (!u_canopy_on || !terrain_canopy_seen(pos)) return vec4(0.0);
    float cover;
    canopy_view_t v = canopy_view(pos, normalize(normal), u_camera, u_sun, terrain_wind(pos));
    vec3 up = grass_ambient(pos, v.g), down = grass_ambient(pos, -v.g), amb0 = 0.5 * (up + down);
    mat3 amb_n = mat3(grass_ambient(pos, v.t) - amb0, 0.5 * (up - down), grass_ambient(pos, v.s) - amb0);
    vec4 full = vec4(u_match_gain.rgb * canopy_table_color(v, amb0, amb_n, cover), cover);
    float h = u_canopy_switch.x > 0.0 ? terrain_canopy_cut(grass_distance(pos, u_camera), v.e) : u_canopy_top;
    cut = h <= 0.0 ? vec4(full.rgb, 0.0) : full;
    if (h > 0.0 && h < u_canopy_top) {
        v.cut = h;
        cut = vec4(u_match_gain.rgb * canopy_table_color(v, amb0, amb_n, cover), cover);
    }
    return full;
}

#endif

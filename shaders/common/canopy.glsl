/* canopy.glsl: the ground canopy, the hybrid's third representation (after
 * Qiu et al.): the terrain shaded as grass beyond the billboards, with the
 * table src/blade/blade_canopy.c measures on the blade model: the mean
 * colour of the blade points a view ray meets (shade() of
 * common/lighting.glsl, integrated) and the cover, by view elevation and by
 * the sun's azimuth from the direction towards the viewer. GLSL twin of
 * blade_canopy_color and blade_canopy_thinned (docs/HYBRID.md "Ground
 * canopy"). Row i is the elevation 90 i / (u_canopy_rows - 1) degrees,
 * azimuth j the angle 180 j / (CANOPY_AZIMUTHS - 1) degrees. */
#ifndef CANOPY_GLSL
#define CANOPY_GLSL

#include "common/lighting.glsl"

#define CANOPY_MAX_ROWS 32
#define CANOPY_AZIMUTHS 9
uniform int u_canopy_rows;
uniform float u_canopy_cover[CANOPY_MAX_ROWS];
uniform vec4 u_canopy_amb[CANOPY_MAX_ROWS]; /* E[ao], E[u ao], E[v ao], E[v u ao] */
uniform vec2 u_canopy_sun[CANOPY_MAX_ROWS * CANOPY_AZIMUTHS]; /* E[D], E[v D] */
uniform vec3 u_canopy_albedo_root;
uniform vec3 u_canopy_albedo_tip;

/* blade_canopy_thinned: cover of the canopy thinned to a fraction e (the
 * gap kept above 0: GLSL's pow(0, 0) is undefined, NaN on NVIDIA). */
float canopy_thinned(float cover, float e)
{
    return 1.0 - pow(max(1.0 - cover, 1e-6), clamp(e, 0.0, 1.0));
}

/* blade_canopy_under: the share of a thinned field's visible ground that
 * the removed blades covered (kept: blade_lod_coverage). */
float canopy_under(float cover, float e, float kept)
{
    float full = canopy_thinned(cover, e), left = canopy_thinned(cover, e * kept);
    return max(full - left, 0.0) / max(1.0 - left, 1e-4);
}

/* blade_canopy_color at elevation e and sun azimuth phi (radians), under
 * an ambient light linear in the normal's height, amb_down facing down and
 * amb_up facing up (the hemisphere of common/lighting.glsl: AMBIENT_DOWN,
 * AMBIENT_UP). */
vec3 canopy_table_color(float e, float phi, vec3 amb_down, vec3 amb_up, out float cover)
{
    float x = clamp(e / 1.5707963, 0.0, 1.0) * float(u_canopy_rows - 1);
    int i = min(int(floor(x)), u_canopy_rows - 2);
    float f = x - float(i);
    float y = clamp(phi / 3.1415927, 0.0, 1.0) * float(CANOPY_AZIMUTHS - 1);
    int j = min(int(floor(y)), CANOPY_AZIMUTHS - 2);
    float g = y - float(j);
    int a = i * CANOPY_AZIMUTHS + j, b = a + CANOPY_AZIMUTHS;
    vec2 s0 = mix(u_canopy_sun[a], u_canopy_sun[b], f), s1 = mix(u_canopy_sun[a + 1], u_canopy_sun[b + 1], f);
    vec2 s = mix(s0, s1, g);
    vec4 amb = mix(u_canopy_amb[i], u_canopy_amb[i + 1], f);
    cover = mix(u_canopy_cover[i], u_canopy_cover[i + 1], f);
    vec3 r = u_canopy_albedo_root, dt = u_canopy_albedo_tip - u_canopy_albedo_root;
    vec3 up = amb_up - amb_down;
    return SUN_COLOR * SUN_DIFFUSE * (r * s.x + dt * s.y) + r * (amb_down * amb.x + up * amb.y) +
           dt * (amb_down * amb.z + up * amb.w);
}

/* The canopy's colour (unfogged) and cover at ground point pos of unit
 * ground normal gn, seen from camera, lit by the sun (unit) and an ambient
 * light linear in the normal's height (amb_down, amb_up). */
vec3 canopy_color_lit(vec3 pos, vec3 gn, vec3 camera, vec3 sun, vec3 amb_down, vec3 amb_up, out float cover)
{
    vec3 to_eye = camera - pos;
    float len = max(length(to_eye), 1e-6);
    float e = asin(clamp(dot(to_eye, gn) / len, 0.0, 1.0));
    vec3 h = to_eye - gn * dot(to_eye, gn), sh = sun - gn * dot(sun, gn);
    float phi = dot(h, h) > 1e-12 && dot(sh, sh) > 1e-12 ? acos(clamp(dot(normalize(h), normalize(sh)), -1.0, 1.0))
                                                         : 0.0;
    return canopy_table_color(e, phi, amb_down, amb_up, cover);
}

/* canopy_color_lit under the hemispheric ambient. */
vec3 canopy_color(vec3 pos, vec3 gn, vec3 camera, vec3 sun, out float cover)
{
    return canopy_color_lit(pos, gn, camera, sun, AMBIENT_DOWN, AMBIENT_UP, cover);
}

#endif

/* canopy.glsl: the ground canopy, the hybrid's third representation (after
 * Qiu et al.): the terrain shaded as grass beyond the billboards, with the
 * table src/blade/blade_canopy.c measures on the blade model: the mean
 * colour of the blade points a view ray meets (shade() of
 * common/lighting.glsl, integrated) and the cover, in the ground's frame
 * (blades grow along its normal): by the view's elevation over the ground,
 * the sun's elevation over it and its azimuth from the direction towards
 * the viewer, and the ambient moments of the blade normals in that frame,
 * which give the mean of any ambient light linear in the normal. GLSL twin of
 * blade_canopy_color and blade_canopy_thinned (docs/HYBRID.md "Ground
 * canopy"). The table is a texture (blade_canopy_pack): row i the view
 * elevation 90 i / (u_canopy_rows - 1) degrees; sun elevation k the angle
 * u_canopy_sun0 + k CANOPY_SUN_STEP, azimuth j 180 j / (CANOPY_AZIMUTHS - 1)
 * degrees. */
#ifndef CANOPY_GLSL
#define CANOPY_GLSL

#include "common/bindings_ground.glsl"
#include "common/lighting.glsl"

#define CANOPY_AZIMUTHS 9
#define CANOPY_SUNS 14
const float CANOPY_SUN_STEP = 0.2617994; /* BLADE_CANOPY_SUN_STEP */
uniform int u_canopy_rows;
uniform float u_canopy_sun0;
/* texel (x, row): x 0 (cover), 1 (E[ao], E[n_t ao], E[n_g ao], E[n_s ao]),
 * 2 (the same times v), 3 + k CANOPY_AZIMUTHS + j (E[D], E[v D]) */
layout(binding = GROUND_TEX_CANOPY) uniform sampler2D u_canopy_table;
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

/* Texel x of table row `row`. */
vec4 canopy_texel(int x, int row)
{
    return texelFetch(u_canopy_table, ivec2(x, row), 0);
}

/* The sun moments (E[D], E[v D]) of table row `row` at sun elevation node k
 * and azimuth node j, g of the way to j + 1. */
vec2 canopy_sun(int row, int k, int j, float g)
{
    int x = 3 + k * CANOPY_AZIMUTHS + j;
    return mix(canopy_texel(x, row).xy, canopy_texel(x + 1, row).xy, g);
}

/* Where a canopy point is seen from and lit from (blade_canopy_view_t):
 * the view's elevation e over the ground, the sun's elevation se over it
 * and azimuth phi from t (radians), and the ground's frame: t the
 * horizontal direction towards the viewer, g the ground normal, s = g x t. */
struct canopy_view_t {
    float e, se, phi;
    vec3 t, g, s;
};

/* The view of ground point pos of unit normal gn from camera, lit by the
 * sun (unit). Seen straight down there is no t: t and s are 0, and the
 * ambient's parts along them, whose moments vanish there by the blades'
 * uniform facings, are left out. */
canopy_view_t canopy_view(vec3 pos, vec3 gn, vec3 camera, vec3 sun)
{
    canopy_view_t v;
    vec3 to_eye = camera - pos;
    float len = max(length(to_eye), 1e-6);
    v.e = asin(clamp(dot(to_eye, gn) / len, 0.0, 1.0));
    v.se = asin(clamp(dot(sun, gn), -1.0, 1.0));
    vec3 h = to_eye - gn * dot(to_eye, gn), sh = sun - gn * dot(sun, gn);
    bool down = dot(h, h) <= 1e-12;
    v.t = down ? vec3(0.0) : normalize(h);
    v.g = gn;
    v.s = cross(gn, v.t);
    v.phi = !down && dot(sh, sh) > 1e-12 ? acos(clamp(dot(v.t, normalize(sh)), -1.0, 1.0)) : 0.0;
    return v;
}

/* blade_canopy_color seen and lit as v under an ambient light linear in the
 * normal n (shade()'s hemisphere, the global illumination's a + B n):
 * amb0 + amb_n (n_t, n_g, n_s), amb0 its value at n = 0 and amb_n's columns
 * its change along t, g and s. */
vec3 canopy_table_color(canopy_view_t v, vec3 amb0, mat3 amb_n, out float cover)
{
    float x = clamp(v.e / 1.5707963, 0.0, 1.0) * float(u_canopy_rows - 1);
    int i = min(int(floor(x)), u_canopy_rows - 2);
    float f = x - float(i);
    float z = clamp((v.se - u_canopy_sun0) / CANOPY_SUN_STEP, 0.0, float(CANOPY_SUNS - 1));
    int k = min(int(floor(z)), CANOPY_SUNS - 2);
    float h = z - float(k);
    float y = clamp(v.phi / 3.1415927, 0.0, 1.0) * float(CANOPY_AZIMUTHS - 1);
    int j = min(int(floor(y)), CANOPY_AZIMUTHS - 2);
    float g = y - float(j);
    vec2 s0 = mix(canopy_sun(i, k, j, g), canopy_sun(i + 1, k, j, g), f);
    vec2 s1 = mix(canopy_sun(i, k + 1, j, g), canopy_sun(i + 1, k + 1, j, g), f);
    vec2 s = mix(s0, s1, h);
    vec4 ao = mix(canopy_texel(1, i), canopy_texel(1, i + 1), f);
    vec4 v_ao = mix(canopy_texel(2, i), canopy_texel(2, i + 1), f);
    cover = mix(canopy_texel(0, i).x, canopy_texel(0, i + 1).x, f);
    vec3 r = u_canopy_albedo_root, dt = u_canopy_albedo_tip - u_canopy_albedo_root;
    return SUN_COLOR * SUN_DIFFUSE * (r * s.x + dt * s.y) + r * (amb0 * ao.x + amb_n * ao.yzw) +
           dt * (amb0 * v_ao.x + amb_n * v_ao.yzw);
}

/* The canopy's colour (unfogged) and cover at ground point pos of unit
 * ground normal gn, seen from camera, lit by the sun (unit) and the
 * hemispheric ambient: mix(AMBIENT_DOWN, AMBIENT_UP, n.y / 2 + 1 / 2), n.y
 * = n . (t.y, g.y, s.y) in the ground's frame. */
vec3 canopy_color(vec3 pos, vec3 gn, vec3 camera, vec3 sun, out float cover)
{
    canopy_view_t v = canopy_view(pos, gn, camera, sun);
    vec3 half_up = 0.5 * (AMBIENT_UP - AMBIENT_DOWN);
    mat3 amb_n = mat3(half_up * v.t.y, half_up * v.g.y, half_up * v.s.y);
    return canopy_table_color(v, 0.5 * (AMBIENT_UP + AMBIENT_DOWN), amb_n, cover);
}

#endif

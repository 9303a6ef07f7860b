/* canopy.glsl: the ground canopy, the hybrid's third representation (after
 * Qiu et al.): the terrain shaded as grass beyond the billboards, with the
 * table src/blade/blade_canopy.c measures on the blade model: the mean
 * colour of the blade points a view ray meets (shade() of
 * common/lighting.glsl, integrated) and the cover, in the ground's frame
 * (blades grow along its normal): by the view's elevation over the ground,
 * the sun's elevation over it and its azimuth from the direction towards
 * the viewer, and the ambient moments of the blade normals in that frame,
 * which give the mean of any ambient light linear in the normal; and the
 * same of the hits below a cut height, which the drawn blades' overhang
 * leaves to the canopy just past the hybrid's switch. GLSL twin of
 * blade_canopy_color, blade_canopy_overhang and blade_canopy_thinned
 * (docs/HYBRID.md "Ground canopy"). The table is a texture
 * (blade_canopy_pack): row i + (l + p CANOPY_LEVELS) u_canopy_rows the
 * view elevation 90 i / (u_canopy_rows - 1) degrees at cut level l (0 at
 * the ground, l in 1..CANOPY_CUTS at u_canopy_top 2^(l - 1 - CANOPY_CUTS)
 * over it, the last the whole column) of pose p (0 at rest; under wind
 * u_canopy_poses of them, mixed by the wind at the point:
 * canopy_table_color); sun
 * elevation k the angle u_canopy_sun0 + k CANOPY_SUN_STEP, azimuth j
 * 180 j / (CANOPY_AZIMUTHS - 1) degrees. */
#ifndef CANOPY_GLSL
#define CANOPY_GLSL

#include "common/bindings_ground.glsl"
#include "common/lighting.glsl"

#define CANOPY_AZIMUTHS 9
#define CANOPY_SUNS 14
#define CANOPY_CUTS 5 /* BLADE_CANOPY_CUTS */
#define CANOPY_LEVELS (CANOPY_CUTS + 2)
#define CANOPY_WIND_AZIMUTHS 4 /* BLADE_CANOPY_WIND_AZIMUTHS */
#define CANOPY_WIND_STEPS 2    /* BLADE_CANOPY_WIND_STEPS */
const float CANOPY_SUN_STEP = 0.2617994; /* BLADE_CANOPY_SUN_STEP */
uniform int u_canopy_rows;
uniform int u_canopy_poses;   /* 1, or 1 + CANOPY_WIND_AZIMUTHS CANOPY_WIND_STEPS */
uniform float u_canopy_wind;  /* the wind poses' largest force (blade_canopy_t.wind) */
uniform float u_canopy_gravity; /* the blades' gravity (blade_canopy_t.gravity) */
uniform float u_canopy_sun0;
uniform float u_canopy_top; /* m, the cuts' scale (blade_canopy_t.top) */
/* texel (x, row + level rows): x 0 (cover), 1 (E[ao], E[n_t ao], E[n_g ao],
 * E[n_s ao]), 2 (the same times v), 3 + k CANOPY_AZIMUTHS + j (E[D], E[v D]) */
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

/* blade_canopy_overhang: the canopy past the switch under the overhang of
 * the blades drawn before it, thinned to `kept` (1: all drawn): full and
 * cut are (colour, cover) of the whole column and of the column cut at the
 * overhang's height. */
vec4 canopy_overhang(vec4 full, vec4 cut, float kept)
{
    float t_cut = 1.0 - cut.w, t_above = min(max(1.0 - full.w, 0.0) / max(t_cut, 1e-6), 1.0);
    float left = clamp(1.0 - kept, 0.0, 1.0), t_left = pow(max(t_above, 1e-6), left);
    float share = t_above < 1.0 - 1e-6 ? (1.0 - t_left) / (1.0 - t_above) : left;
    float cover = 1.0 - t_left * t_cut;
    vec3 above = full.w * full.rgb - t_above * cut.w * cut.rgb; /* premultiplied */
    vec3 p = max(share * above + t_left * cut.w * cut.rgb, 0.0);
    return vec4(cover > 1e-6 ? p / cover : full.rgb, cover);
}

/* canopy_node of blade_canopy.c: the point of x in [0, n - 1] (clamped)
 * between nodes i and i + 1: i, and f the weight of i + 1. */
int canopy_node(float x, int n, out float f)
{
    x = clamp(x, 0.0, float(n - 1));
    int i = min(int(floor(x)), n - 2);
    f = x - float(i);
    return i;
}

/* canopy_cut_level of blade_canopy.c: the cut level of a cut (m; 0: the
 * whole column), linear below the lowest cut, log2 above. */
float canopy_cut_level(float cut)
{
    float h1 = ldexp(max(u_canopy_top, 1e-6), -CANOPY_CUTS);
    if (cut <= 0.0) return float(CANOPY_CUTS + 1);
    return cut < h1 ? cut / h1 : 1.0 + log2(cut / h1);
}

/* Where the table is read: rows i, i + 1 (f of the way) at cut levels l,
 * l + 1 (g of the way) of pose p. */
struct canopy_at_t {
    int i, l, p;
    float f, g;
};

/* Texel x of the table at a, bilinear: between the rows, then the levels
 * (blade_canopy_at_cut's order). On level l + 1 (the whole column, which
 * most of the ground reads) the level below is not fetched: its weight is
 * 0, and mix(lo, hi, 1) is hi. */
vec4 canopy_texel(int x, canopy_at_t a)
{
    int r1 = a.i + (a.l + 1 + a.p * CANOPY_LEVELS) * u_canopy_rows, r0 = r1 - u_canopy_rows;
    vec4 hi = mix(texelFetch(u_canopy_table, ivec2(x, r1), 0), texelFetch(u_canopy_table, ivec2(x, r1 + 1), 0), a.f);
    if (a.g >= 1.0) return hi;
    vec4 lo = mix(texelFetch(u_canopy_table, ivec2(x, r0), 0), texelFetch(u_canopy_table, ivec2(x, r0 + 1), 0), a.f);
    return mix(lo, hi, a.g);
}

/* The sun moments (E[D], E[v D]) at a, sun elevation node k and azimuth
 * node j, g of the way to j + 1. */
vec2 canopy_sun(canopy_at_t a, int k, int j, float g)
{
    int x = 3 + k * CANOPY_AZIMUTHS + j;
    return mix(canopy_texel(x, a).xy, canopy_texel(x + 1, a).xy, g);
}

/* Where a canopy point is seen from and lit from (blade_canopy_view_t):
 * the view's elevation e over the ground, the sun's elevation se over it
 * and azimuth phi from t (radians), the ground's frame: t the horizontal
 * direction towards the viewer, g the ground normal, s = g x t; the cut
 * (m; 0: the whole column); the wind force's magnitude along the ground
 * and its azimuth psi from t towards the sun's side. */
struct canopy_view_t {
    float e, se, phi;
    vec3 t, g, s;
    float cut;
    float wind, psi;
};

/* blade_canopy_slope_lean: the blades' gravity along the ground of unit
 * normal gn, downhill, as a wind force (world). */
vec3 canopy_slope_lean(vec3 gn)
{
    return u_canopy_gravity * (gn.y * gn - vec3(0.0, 1.0, 0.0));
}

/* The view of ground point pos of unit normal gn from camera, lit by the
 * sun (unit), under the wind force `wind` (world) and the slope's lean
 * (canopy_slope_lean). Seen straight down there is no t: t and s are 0,
 * and the ambient's parts along them, whose moments vanish there by the
 * blades' uniform facings, are left out, as is the wind (the rest pose). */
canopy_view_t canopy_view(vec3 pos, vec3 gn, vec3 camera, vec3 sun, vec3 wind)
{
    canopy_view_t v;
    wind += canopy_slope_lean(gn);
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
    v.cut = 0.0;
    vec2 w = vec2(dot(wind, v.t), dot(wind, v.s) * (dot(sh, v.s) < 0.0 ? -1.0 : 1.0));
    v.wind = length(w);
    v.psi = v.wind > 0.0 ? atan(w.y, w.x) : 0.0;
    return v;
}

/* The colour and cover of pose p seen and lit as v under an ambient light
 * linear in the normal n (shade()'s hemisphere, the global illumination's
 * a + B n): amb0 + amb_n (n_t, n_g, n_s), amb0 its value at n = 0 and
 * amb_n's columns its change along t, g and s. */
vec3 canopy_pose_color(canopy_view_t v, int p, vec3 amb0, mat3 amb_n, out float cover)
{
    canopy_at_t a;
    a.p = p;
    a.i = canopy_node(v.e / 1.5707963 * float(u_canopy_rows - 1), u_canopy_rows, a.f);
    a.l = canopy_node(canopy_cut_level(v.cut), CANOPY_CUTS + 2, a.g);
    float h, g;
    int k = canopy_node((v.se - u_canopy_sun0) / CANOPY_SUN_STEP, CANOPY_SUNS, h);
    int j = canopy_node(v.phi / 3.1415927 * float(CANOPY_AZIMUTHS - 1), CANOPY_AZIMUTHS, g);
    vec2 s = mix(canopy_sun(a, k, j, g), canopy_sun(a, k + 1, j, g), h);
    vec4 ao = canopy_texel(1, a), v_ao = canopy_texel(2, a);
    cover = canopy_texel(0, a).x;
    vec3 r = u_canopy_albedo_root, dt = u_canopy_albedo_tip - u_canopy_albedo_root;
    return SUN_COLOR * SUN_DIFFUSE * (r * s.x + dt * s.y) + r * (amb0 * ao.x + amb_n * ao.yzw) +
           dt * (amb0 * v_ao.x + amb_n * v_ao.yzw);
}

/* blade_canopy_color seen and lit as v (canopy_pose_color's light): the
 * poses mixed as blade_canopy_wind_weights mixes them, linear in the
 * wind's magnitude between the rest pose and the steps, and along the
 * azimuths the trigonometric interpolation through the four. Each pose's
 * colour is summed as it comes: mixing their moments in an array of
 * weights instead spilled it to memory (+0.21 ms of meadow_large's
 * terrain pass, H200, compute path). */
vec3 canopy_table_color(canopy_view_t v, vec3 amb0, mat3 amb_n, out float cover)
{
    float q = u_canopy_poses > 1 && v.wind > 0.0 ? min(v.wind / u_canopy_wind, 1.0) * float(CANOPY_WIND_STEPS) : 0.0;
    if (q <= 0.0) return canopy_pose_color(v, 0, amb0, amb_n, cover);
    int m = int(ceil(q));
    float f = q - float(m - 1), one;
    vec3 c = vec3(0.0);
    cover = 0.0;
    if (m == 1) {
        c = (1.0 - f) * canopy_pose_color(v, 0, amb0, amb_n, one);
        cover = (1.0 - f) * one;
    }
    for (int k = 0; k < CANOPY_WIND_AZIMUTHS; k++) {
        float d = v.psi - 1.5707963 * float(k);
        float w = 0.25 * (1.0 + 2.0 * cos(d) + cos(2.0 * d));
        c += f * w * canopy_pose_color(v, 1 + (m - 1) * CANOPY_WIND_AZIMUTHS + k, amb0, amb_n, one);
        cover += f * w * one;
        if (m > 1) {
            c += (1.0 - f) * w * canopy_pose_color(v, 1 + (m - 2) * CANOPY_WIND_AZIMUTHS + k, amb0, amb_n, one);
            cover += (1.0 - f) * w * one;
        }
    }
    cover = clamp(cover, 0.0, 1.0);
    return c;
}

/* The canopy's colour (unfogged) and cover at ground point pos of unit
 * ground normal gn, seen from camera, lit by the sun (unit) and the
 * hemispheric ambient: mix(AMBIENT_DOWN, AMBIENT_UP, n.y / 2 + 1 / 2), n.y
 * = n . (t.y, g.y, s.y) in the ground's frame; of the hits below cut (m;
 * 0: the whole column), under the wind force `wind` (world). */
vec3 canopy_color(vec3 pos, vec3 gn, vec3 camera, vec3 sun, vec3 wind, float cut, out float cover)
{
    canopy_view_t v = canopy_view(pos, gn, camera, sun, wind);
    v.cut = cut;
    vec3 half_up = 0.5 * (AMBIENT_UP - AMBIENT_DOWN);
    mat3 amb_n = mat3(half_up * v.t.y, half_up * v.g.y, half_up * v.s.y);
    return canopy_table_color(v, 0.5 * (AMBIENT_UP + AMBIENT_DOWN), amb_n, cover);
}

#endif

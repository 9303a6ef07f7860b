/* terrain_ground.glsl: the terrain's colour at a ground point (terrain.frag
 * says what it is made of), for terrain.frag and for the canopy match
 * (ground/canopy_match.comp), which shades the ground there as the frame
 * drew it and as the seam measure's canopy reference draws it. */
#ifndef TERRAIN_GROUND_GLSL
#define TERRAIN_GROUND_GLSL

#include "common/bindings_ground.glsl"
#include "common/extent.glsl"
#include "common/gi.glsl"
#include "common/lighting.glsl"
#include "common/lod.glsl"
#include "common/switch.glsl"
#include "ground/terrain_canopy.glsl"

uniform bool u_extent_on;
layout(binding = GROUND_TEX_EXTENT) uniform sampler2D u_extent;
layout(binding = GROUND_TEX_NOISE) uniform sampler2D u_noise;
uniform vec2 u_extent_origin;
uniform float u_extent_spacing;
uniform vec2 u_canopy_fade;
uniform bool u_lod_on;
uniform vec2 u_lod_ground; /* blades' mean width (m), the distance where the thinned blades end (m) */

/* Value noise at p: the lattice's hashes (GROUND_TEX_NOISE, one per
 * integer point, repeating every GROUND_NOISE_SIZE) blended by smoothstep
 * weights, which the bilinear filter does when the sample point is moved
 * to the cell corner plus the weights. One texture fetch: hashing the four
 * corners here took 0.29 of the terrain pass's 0.87 ms (H100, world walk). */
float value_noise(vec2 p)
{
    vec2 i = floor(p), f = fract(p);
    vec2 u = f * f * (3.0 - 2.0 * f);
    return texture(u_noise, (i + u + 0.5) * (1.0 / float(GROUND_NOISE_SIZE))).r;
}

/* The extent map's grass fraction at ground point p. */
float extent_at(vec2 p)
{
    return u_extent_on ? texelFetch(u_extent, extent_texel(u_extent, p, u_extent_origin, u_extent_spacing), 0).r : 1.0;
}

/* The bare ground at pos of unit normal n, lit (unfogged). */
vec3 terrain_ground_color(vec3 pos, vec3 n)
{
    float noise = value_noise(pos.xz * 1.7) * 0.6 + value_noise(pos.xz * 7.3) * 0.4;
    vec3 soil = vec3(0.30, 0.24, 0.16);
    vec3 turf = vec3(0.20, 0.32, 0.10);
    vec3 albedo = mix(soil, turf, smoothstep(0.3, 0.7, noise));
    return shade_lit(albedo, n, u_sun, 1.0, grass_ambient(pos, n));
}

/* The terrain's colour (fogged) at pos of unit normal n, the canopy's
 * colour and cover there of the whole column and of the cut one
 * (terrain_canopy); as_canopy: the ground shaded as canopy from the camera
 * on, as the seam measure's reference draws it (grass_draw_as_t's
 * canopy_all: the band at 0, its ramp 1 everywhere). */
vec3 terrain_shade(vec3 pos, vec3 n, vec4 canopy, vec4 canopy_cut, bool as_canopy)
{
    vec3 c = terrain_ground_color(pos, n);
    vec3 to_frag = pos - u_camera;
    if (as_canopy) {
        c = mix(c, canopy.rgb, canopy_thinned(canopy.w, extent_at(pos.xz)));
    } else if (u_canopy_on && u_canopy_switch.x > 0.0) {
        /* the drawn blades thinned as at their roots, to the switch */
        float d = min(grass_distance(pos, u_camera), u_canopy_switch.x);
        float kept = u_lod_on ? lod_coverage(d, u_lod_ground.x) : 1.0;
        /* every blade drawn and no cut column: canopy_overhang's cover is
         * 0 (below 1e-5 for kept within 1e-6 of 1) */
        if (kept < 1.0 - 1e-6 || canopy_cut.w > 0.0) {
            vec4 k = canopy_overhang(canopy, canopy_cut, kept);
            if (k.w > 0.0) c = mix(c, k.rgb, canopy_thinned(k.w, extent_at(pos.xz)));
        }
    } else if (u_canopy_on) {
        float d = grass_distance(pos, u_camera);
        float ramp = u_canopy_fade.y > 0.0
                         ? clamp((d - u_canopy_fade.x) / max(u_canopy_fade.y - u_canopy_fade.x, 1e-6), 0.0, 1.0)
                         : 0.0;
        float kept = u_lod_on && d < u_lod_ground.y ? lod_coverage(d, u_lod_ground.x) : 1.0;
        if (ramp > 0.0 || kept < 1.0) {
            float cover = canopy.w, e = extent_at(pos.xz);
            c = mix(c, canopy.rgb, max(ramp * canopy_thinned(cover, e), canopy_under(cover, e, kept)));
        }
    }
    return apply_fog(c, length(to_frag), normalize(to_frag));
}

#endif

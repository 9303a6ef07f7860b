// terrain.frag: soil and short-grass ground colour, lit like the grass;
// in the hybrid, beyond the billboards, the ground canopy (common/canopy.glsl,
// its colour per vertex: ground/terrain_canopy.glsl):
// the ground's colour mixed with the canopy's by its cover, thinned by the
// extent map as the blades and billboards are, faded in over
// u_canopy_fade (start, end of the switch distance; end <= 0: no band); and
// nearer, under blades thinned with distance (common/lod.glsl), the ground
// mixed towards the canopy by the share of it the removed blades covered
// (canopy_under), so blades and ground keep the full field's mean colour.
// Where the canopy continues the tiles' blades (u_canopy_switch, no
// billboards between), one rule does both and the fade: the canopy stands
// for the blades not drawn, under the overhang of those drawn before the
// switch (canopy_overhang of the whole column and the cut one).
// Ground and canopy take the global illumination's ambient light per
// fragment when it is on (common/gi.glsl; the canopy per vertex, its table
// taking any ambient linear in the blade normals: ground/terrain_canopy.glsl).
#version 450 core
#include "common/bindings_ground.glsl"
#include "common/lighting.glsl"
#include "ground/terrain_canopy.glsl"
#include "common/switch.glsl"
#include "common/extent.glsl"
#include "common/gi.glsl"
#include "common/lod.glsl"
in vec3 v_pos;
in vec3 v_normal;
in vec4 v_canopy; /* the canopy's colour and cover, per vertex (ground/terrain_canopy.glsl) */
in vec4 v_canopy_cut; /* the same below the overhang's cut (terrain_canopy's cut) */
uniform vec2 u_canopy_fade;
uniform bool u_lod_on;
uniform vec2 u_lod_ground; /* blades' mean width (m), the distance where the thinned blades end (m) */
uniform bool u_extent_on;
layout(binding = GROUND_TEX_EXTENT) uniform sampler2D u_extent;
layout(binding = GROUND_TEX_NOISE) uniform sampler2D u_noise;
uniform vec2 u_extent_origin;
uniform float u_extent_spacing;
out vec4 o_color;

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

void main()
{
    vec3 n = normalize(v_normal);
    float noise = value_noise(v_pos.xz * 1.7) * 0.6 + value_noise(v_pos.xz * 7.3) * 0.4;
    vec3 soil = vec3(0.30, 0.24, 0.16);
    vec3 turf = vec3(0.20, 0.32, 0.10);
    vec3 albedo = mix(soil, turf, smoothstep(0.3, 0.7, noise));
    vec3 c = shade_lit(albedo, n, u_sun, 1.0, grass_ambient(v_pos, n));
    vec3 to_frag = v_pos - u_camera;
    if (u_canopy_on && u_canopy_switch.x > 0.0) {
        /* the drawn blades thinned as at their roots, to the switch */
        float d = min(grass_distance(v_pos, u_camera), u_canopy_switch.x);
        float kept = u_lod_on ? lod_coverage(d, u_lod_ground.x) : 1.0;
        /* every blade drawn and no cut column: canopy_overhang's cover is
         * 0 (below 1e-5 for kept within 1e-6 of 1) */
        if (kept < 1.0 - 1e-6 || v_canopy_cut.w > 0.0) {
            vec4 k = canopy_overhang(v_canopy, v_canopy_cut, kept);
            if (k.w > 0.0) c = mix(c, k.rgb, canopy_thinned(k.w, extent_at(v_pos.xz)));
        }
    } else if (u_canopy_on) {
        float d = grass_distance(v_pos, u_camera);
        float ramp = u_canopy_fade.y > 0.0
                         ? clamp((d - u_canopy_fade.x) / max(u_canopy_fade.y - u_canopy_fade.x, 1e-6), 0.0, 1.0)
                         : 0.0;
        float kept = u_lod_on && d < u_lod_ground.y ? lod_coverage(d, u_lod_ground.x) : 1.0;
        if (ramp > 0.0 || kept < 1.0) {
            float cover = v_canopy.w, e = extent_at(v_pos.xz);
            c = mix(c, v_canopy.rgb, max(ramp * canopy_thinned(cover, e), canopy_under(cover, e, kept)));
        }
    }
    o_color = vec4(apply_fog(c, length(to_frag), normalize(to_frag)), 1.0);
}

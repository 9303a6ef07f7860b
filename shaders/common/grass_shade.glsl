/* grass_shade.glsl: the colour of a grass surface point, shared by the
 * hardware render paths (blade.frag, bb_render.frag) and the compute
 * rasterizer (shaders/raster/), so both paths shade alike: two-sided
 * lighting (normal flipped towards the viewer), the shared sun, sky ambient
 * (or the global illumination volumes', common/gi.glsl) and fog
 * (common/lighting.glsl), and a debug overlay mixed in before fog
 * (weight 0: none); and the hybrid fade's alpha of blades and billboards,
 * which the hardware path turns into coverage with alpha-to-coverage and
 * the compute path with per-sample thresholds. */
#ifndef GRASS_SHADE_GLSL
#define GRASS_SHADE_GLSL

#include "common/gi.glsl"
#include "common/hash.glsl"
#include "common/lighting.glsl"
#include "common/switch.glsl"

/* Hybrid fade of a blade: 1 nearer than fade.x, 0 beyond fade.y (root
 * distance d; fade.y <= fade.x: no fade, 1). */
float blade_fade_ramp(float d, vec2 fade)
{
    return fade.y > fade.x ? 1.0 - smoothstep(fade.x, fade.y, d) : 1.0;
}

/* A blade's fade alpha dithered per pixel px, the alpha that
 * alpha-to-coverage (or the compute path's sample thresholds) turns into
 * coverage. */
float blade_fade_dither(float alpha, uvec2 px)
{
    float dither = hash_float(px.x * 1973u + px.y * 9277u) - 0.5;
    return clamp(alpha + dither * 0.25, 0.0, 1.0);
}

/* The samples a fading blade of dithered alpha a covers, one rule for both
 * rasterizers: sample k of n when a > (k + 0.5) / n (bit k of the mask). */
bool blade_fade_covers(float a, int k, int n)
{
    return a > (float(k) + 0.5) / float(n);
}

uint blade_fade_mask(float a, int n)
{
    uint mask = 0u;
    for (int k = 0; k < n; k++)
        if (blade_fade_covers(a, k, n)) mask |= 1u << uint(k);
    return mask;
}

/* Alpha a scaled by a fade's keep in [0, 1], dithered by interleaved
 * gradient noise of the pixel centre frag (unchanged at keep 1). */
float bb_dither_alpha(float a, float keep, vec2 frag)
{
    float ign = fract(52.9829189 * fract(dot(frag, vec2(0.06711056, 0.00583715))));
    return keep < 1.0 ? clamp(a * keep + (ign - 0.5) * 0.25, 0.0, 1.0) : a;
}

/* A billboard texel's alpha a under the hybrid fade (0 nearer than
 * fade_start, 1 beyond fade_end; fade_end <= 0: none) at distance dist,
 * dithered (bb_dither_alpha). */
float bb_fade_alpha(float a, float dist, float fade_start, float fade_end, vec2 frag)
{
    if (fade_end <= 0.0) return a;
    float fade = clamp((dist - fade_start) / max(fade_end - fade_start, 1e-6), 0.0, 1.0);
    return bb_dither_alpha(a, fade, frag);
}

/* A billboard texel's alpha a under the canopy's fade (1 nearer than
 * far_start, 0 beyond far_end; far_end <= 0: none) at distance dist,
 * dithered as the near fade. */
float bb_far_alpha(float a, float dist, float far_start, float far_end, vec2 frag)
{
    if (far_end <= 0.0) return a;
    float keep = 1.0 - clamp((dist - far_start) / max(far_end - far_start, 1e-6), 0.0, 1.0);
    return bb_dither_alpha(a, keep, frag);
}

/* Alpha to coverage, one rule for both rasterizers and every driver: a
 * fragment of alpha a covers ceil(a n) of its pixel's n samples (Mesa's
 * rule), the run of them starting at sample hash(pixel) mod n (bit k:
 * sample k). Drivers differ in how they turn alpha into a mask (NVIDIA's
 * covers about round(a n): billboards seen from the side covered 0.807 of
 * the ground there against 0.848 on Mesa), so the hardware path writes
 * this mask itself (gl_SampleMask) instead of GL_SAMPLE_ALPHA_TO_COVERAGE. */
uint grass_coverage_mask(float a, int n, uvec2 pixel)
{
    int covered = min(int(ceil(a * float(n))), n);
    uint first = hash_u32(pixel.x * 1973u + pixel.y * 9277u) % uint(n);
    uint run = covered >= 32 ? 0xffffffffu : (1u << uint(covered)) - 1u;
    return ((run << first) | (run >> (uint(n) - first))) & ((1u << uint(n)) - 1u);
}

/* A blade point at height v (0 root, 1 tip), albedo mixed root to tip. */
vec3 blade_shade(vec3 pos, vec3 normal, float v, vec3 camera, vec3 sun, vec3 albedo_root, vec3 albedo_tip,
                 vec4 overlay)
{
    vec3 view = camera - pos;
    vec3 n = normalize(normal);
    if (dot(n, view) < 0.0) n = -n;
    vec3 albedo = mix(albedo_root, albedo_tip, v);
    vec3 c = shade_lit(albedo, n, sun, mix(0.45, 1.0, v), grass_ambient(pos, n));
    c = mix(c, overlay.rgb, overlay.a);
    return apply_fog(c, length(view), normalize(-view));
}

/* The ambient light of a billboard vertex at pos of normal n, for its two
 * faces (bb_shade's amb_front, amb_back); zero with GI off. */
void bb_vertex_ambient(vec3 pos, vec3 n, out vec3 front, out vec3 back)
{
    vec3 u = normalize(n);
    front = u_gi_on != 0 ? gi_ambient(pos, u) : vec3(0.0);
    back = u_gi_on != 0 ? gi_ambient(pos, -u) : vec3(0.0);
}

/* A billboard point. Views off (lit 0, Orthmann's cards): clump texel
 * albedo (bb_layout: the blades' root-to-tip mix, unlit) times the
 * billboard's tint (bb_tint, mean 1), lit with the card's normal turned
 * towards the viewer and ambient occlusion from the image row (v_img 0 at
 * the top of the clump image): the layers draw blades at their height in
 * metres, so the row stands for the height on the blades a viewer sees.
 * Measured against the blade field (docs/BILLBOARDS.md), this AO matches
 * it better than the exact per-texel mix(0.45, 1, v) of the blades drawn
 * in the texel. Views on (lit 1): the lit colour of the card's
 * view-dependent bakes (bb_view.glsl; light: its blades' mean colour as
 * blade_shade lights them before fog, under the scene's sun) times the
 * tint; a deformed mesh (card 0) scales it by how much more (or less)
 * light its own normal takes than the same normal stood upright (its
 * horizontal part; at most twice), so a billboard pressed flat turns to
 * the sky and one barely touched keeps the plain card's colour.
 * Global illumination (u_gi_on, common/gi.glsl): the ambient light of the
 * card's two faces, amb_front for the normal as given and amb_back for
 * its flip, computed per vertex (bb_vertex_ambient) and interpolated, as
 * Orthmann et al. sec. 6.1 do; the views' lit colour is scaled by how much
 * it changes the plain shading. */
vec3 bb_shade(vec3 texel, float tint, vec3 world, vec3 normal, vec3 light, float lit, float card, float v_img,
              vec3 camera, vec3 sun, vec4 overlay, vec3 amb_front, vec3 amb_back)
{
    vec3 to_eye = camera - world;
    float dist = length(to_eye);
    vec3 n = normalize(normal);
    bool back = dot(n, to_eye) < 0.0;
    if (back) n = -n;
    float ao = mix(0.45, 1.0, 1.0 - v_img);
    vec3 c = shade(texel * tint, n, sun, ao);
    vec3 gi = vec3(1.0);
    if (u_gi_on != 0) {
        vec3 c_gi = shade_lit(texel * tint, n, sun, ao, back ? amb_back : amb_front);
        gi = c_gi / max(c, vec3(1e-4));
        c = c_gi;
    }
    if (lit > 0.5) {
        vec3 flat_n = vec3(n.x, 0.0, n.z), eye_h = vec3(to_eye.x, 0.0, to_eye.z);
        vec3 stood = dot(flat_n, flat_n) > 1e-6 ? normalize(flat_n) : eye_h / max(length(eye_h), 1e-6);
        vec3 scale = card > 0.5 ? vec3(1.0) : min(c / max(shade(texel * tint, stood, sun, ao), vec3(1e-4)), vec3(2.0));
        c = light * tint * scale * (card > 0.5 ? gi : vec3(1.0));
    }
    c = mix(c, overlay.rgb, overlay.a);
    return apply_fog(c, dist, -to_eye / max(dist, 1e-6));
}

#endif

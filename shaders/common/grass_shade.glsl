/* grass_shade.glsl: the colour of a grass surface point, shared by the
 * hardware render paths (blade.frag, bb_render.frag) and the compute
 * rasterizer (shaders/raster/), so both paths shade alike: two-sided
 * lighting (normal flipped towards the viewer), the shared sun, sky ambient
 * and fog (common/lighting.glsl), and a debug overlay mixed in before fog
 * (weight 0: none). The hybrid fade's coverage is the callers' business. */
#ifndef GRASS_SHADE_GLSL
#define GRASS_SHADE_GLSL

#include "common/lighting.glsl"

/* A blade point at height v (0 root, 1 tip), albedo mixed root to tip. */
vec3 blade_shade(vec3 pos, vec3 normal, float v, vec3 camera, vec3 sun, vec3 albedo_root, vec3 albedo_tip,
                 vec4 overlay)
{
    vec3 view = camera - pos;
    vec3 n = normalize(normal);
    if (dot(n, view) < 0.0) n = -n;
    vec3 albedo = mix(albedo_root, albedo_tip, v);
    vec3 c = shade(albedo, n, sun, mix(0.45, 1.0, v));
    c = mix(c, overlay.rgb, overlay.a);
    return apply_fog(c, length(view), normalize(-view));
}

/* A billboard point: clump texel colour times the clump tint, ambient
 * occlusion from the image row (v_img 0 at the top of the clump image). */
vec3 bb_shade(vec3 texel, float tint, vec3 world, vec3 normal, float v_img, vec3 camera, vec3 sun, vec4 overlay)
{
    vec3 to_eye = camera - world;
    float dist = length(to_eye);
    vec3 n = normalize(normal);
    if (dot(n, to_eye) < 0.0) n = -n;
    vec3 c = shade(texel * tint, n, sun, mix(0.45, 1.0, 1.0 - v_img));
    c = mix(c, overlay.rgb, overlay.a);
    return apply_fog(c, dist, -to_eye / max(dist, 1e-6));
}

#endif

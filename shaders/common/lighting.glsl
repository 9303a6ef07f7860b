// lighting.glsl: the sun, sky ambient and distance fog shared by terrain,
// grass and characters, so every representation is lit the same way
// (grass and terrain take the ambient from common/gi.glsl when the global
// illumination volumes are on).
#ifndef LIGHTING_GLSL
#define LIGHTING_GLSL
const vec3 SKY_ZENITH = vec3(0.36, 0.55, 0.85);
const vec3 SKY_HORIZON = vec3(0.78, 0.85, 0.92);
const vec3 SUN_COLOR = vec3(1.0, 0.95, 0.85);

vec3 sky_color(vec3 dir)
{
    float t = clamp(dir.y * 1.5, 0.0, 1.0);
    return mix(SKY_HORIZON, SKY_ZENITH, t);
}

// The terms of shade() (twins: BLADE_CANOPY_* in src/blade/blade_canopy.h,
// whose table integrates them over the blades).
const float SUN_DIFFUSE = 0.85;
const vec3 AMBIENT_DOWN = vec3(0.18, 0.17, 0.14);
const vec3 AMBIENT_UP = vec3(0.35, 0.42, 0.55);

// The hemispheric sky ambient: the irradiance / pi of a sky of radiance
// AMBIENT_UP above the horizon and AMBIENT_DOWN below, exactly.
vec3 hemisphere_ambient(vec3 n)
{
    return mix(AMBIENT_DOWN, AMBIENT_UP, n.y * 0.5 + 0.5);
}

// Lambert sun + an ambient light (hemisphere_ambient, or the global
// illumination volumes' of common/gi.glsl) times the surface's own
// occlusion ao.
vec3 shade_lit(vec3 albedo, vec3 n, vec3 sun_dir, float ao, vec3 ambient)
{
    float ndl = max(dot(n, sun_dir), 0.0);
    return albedo * (SUN_COLOR * ndl * SUN_DIFFUSE + ambient * ao);
}

// Lambert sun + hemispheric sky ambient. two_sided flips the normal toward
// the viewer (grass is lit from both faces). Twin: clump_shade in
// src/blade/blade_clump.c (the clump bakes' lit colour).
vec3 shade(vec3 albedo, vec3 n, vec3 sun_dir, float ao)
{
    return shade_lit(albedo, n, sun_dir, ao, hemisphere_ambient(n));
}

vec3 apply_fog(vec3 c, float dist, vec3 view_dir)
{
    float f = 1.0 - exp(-dist * 0.006);
    return mix(c, sky_color(view_dir), clamp(f, 0.0, 0.6));
}

#endif

#version 450
/* blade.frag: two-sided blade shading with the shared sun, sky ambient and
 * fog (common/lighting.glsl). With BLADE_FADE, the hybrid cross-fade: alpha
 * 1 nearer than u_fade.x, 0 beyond u_fade.y, in between dithered per pixel
 * (hash of the pixel) and turned into the pixel's sample mask by
 * blade_fade_mask, the compute rasterizer's rule (GL's alpha to coverage
 * covers a different number of samples on each driver). Without it the
 * blade is opaque and the depth test runs before this shader: with the
 * fade's discard and sample mask the driver shades every hidden blade
 * fragment first (docs/PERFORMANCE.md). */
#include "common/grass_shade.glsl"

#ifndef BLADE_FADE
layout(early_fragment_tests) in;
#endif

in vec3 f_pos;
in vec3 f_normal;
in float f_v;
in flat float f_root_dist;
#ifdef BLADE_OVERLAY
in flat vec4 f_overlay; /* debug overlay colour and weight (tiled field) */
#endif

uniform vec3 u_camera;
uniform vec3 u_sun;
#ifdef BLADE_FADE
uniform vec2 u_fade; /* start, end; end <= start: no fade */
#endif
uniform vec3 u_albedo_root;
uniform vec3 u_albedo_tip;

out vec4 o_color;

void main()
{
#ifdef BLADE_FADE
    float ramp = blade_fade_ramp(f_root_dist, u_fade);
    uint mask = 0xffffffffu; /* alpha 1 stays 1, not dithered below it (as blade_raster.comp) */
    if (ramp < 1.0) mask = blade_fade_mask(blade_fade_dither(ramp, uvec2(gl_FragCoord.xy)), gl_NumSamples);
    if (mask == 0u) discard;
    gl_SampleMask[0] = int(mask);
#endif
#ifdef BLADE_OVERLAY
    vec4 overlay = f_overlay;
#else
    vec4 overlay = vec4(0.0);
#endif
    vec3 c = blade_shade(f_pos, f_normal, f_v, u_camera, u_sun, u_albedo_root, u_albedo_tip, overlay);
    o_color = vec4(c, 1.0);
}

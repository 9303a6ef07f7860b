#version 450
/* bb_render.frag: billboard shading of Orthmann et al. 2009: clump texture
 * array, two-sided lighting (normal flipped towards the viewer), fog, and
 * alpha-to-coverage without sorting (the mask written here,
 * grass_coverage_mask, the compute rasterizer's rule). The hybrid distance
 * fade multiplies alpha by a ramp from fade_start to fade_end plus an
 * interleaved-gradient dither, so the MSAA coverage cross-fades instead of
 * blending; the canopy's fade (u_far_start to u_far_end) ramps it back down
 * the same way, where the ground canopy fades in (terrain.frag). The texel
 * is the view-dependent blend of the clump bakes (bb_view.glsl), and so is
 * the lit colour cards show (bb_shade), lit by the global illumination's
 * per-vertex ambient light with BB_GI (common/gi.glsl). */
#include "common/bindings_billboard.glsl"
#include "common/grass_shade.glsl"
#include "billboard/bb_view.glsl"

layout(binding = BB_TEX_CLUMPS) uniform sampler2DArray u_clumps;
uniform vec3 u_camera;
uniform vec3 u_sun;
uniform float u_fade_start;
uniform float u_fade_end;
uniform float u_far_start;
uniform float u_far_end;

in vec3 g_world;
in vec3 g_normal;
in vec3 g_uvl;
flat in float g_tint;
flat in float g_card; /* 1: plain card; 0: deformed mesh (bb_shade) */
flat in uint g_overlay; /* packUnorm4x8 */
#ifdef BB_GI
in vec3 g_amb_front; /* per-vertex global illumination, interpolated (bb_shade) */
in vec3 g_amb_back;
#else
const vec3 g_amb_front = vec3(0.0), g_amb_back = vec3(0.0);
#endif

out vec4 frag;

void main()
{
    /* Views off (no BB_VIEW_CARDS): the one bake. */
#ifdef BB_VIEW_CARDS
    vec3 light;
    vec4 tex = bb_view_texel(u_clumps, g_uvl.xy, g_uvl.z, dFdx(g_uvl.xy), dFdy(g_uvl.xy), u_camera - g_world,
                             bb_view_xi(uvec2(gl_FragCoord.xy)), light);
    const float lit = 1.0;
#else
    const vec3 light = vec3(0.0);
    vec4 tex = texture(u_clumps, g_uvl);
    const float lit = 0.0;
#endif
    vec3 c = bb_shade(tex.rgb, g_tint, g_world, g_normal, light, lit, g_card, g_uvl.y, u_camera, u_sun,
                      unpackUnorm4x8(g_overlay), g_amb_front, g_amb_back);
    float dist = grass_distance(g_world, u_camera);
    float a = bb_fade_alpha(tex.a, dist, u_fade_start, u_fade_end, gl_FragCoord.xy);
    a = bb_far_alpha(a, dist, u_far_start, u_far_end, gl_FragCoord.xy);
    uint mask = grass_coverage_mask(a, gl_NumSamples, uvec2(gl_FragCoord.xy));
    if (a < 1.0 / 255.0 || mask == 0u) discard;
    gl_SampleMask[0] = int(mask);
    frag = vec4(c, 1.0);
}

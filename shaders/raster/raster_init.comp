#version 450
/* raster_init.comp: starts a frame of the compute rasterizer: every sample
 * of the visibility buffer gets the opaque depth of the hardware pass
 * (terrain, sky, characters, balls) and colour word 0, which marks "no
 * grass" (grass colours carry alpha 255). Reads the target's depth texture
 * itself, on every SM, instead of a resolve blit on the graphics engine:
 * with RASTER_DEPTH_MS (a multisample target) raster sample k takes target
 * sample k u_target_samples / u_raster_samples (the same sample when both
 * are 4: the raster's offsets are the standard 4x pattern), else the
 * pixel's depth. Also writes the farthest opaque depth of each pixel to
 * u_opaque (r32f), what occlusion culling reads (conservative: a blade is
 * hidden only behind all of the pixel's samples). Works on the buffer as
 * two uints per sample, the layout of both variants in raster.glsl
 * (colour word first, depth word second). */
layout(local_size_x = 16, local_size_y = 16) in;

#include "raster/raster_frame.glsl"

/* The same memory seen as (colour, depth) pairs and as pairs of them:
 * a pixel's samples are written with the widest stores its count allows
 * (H100, meadow_large at 1080p: 0.138 ms with one 32-bit store per word,
 * 0.098 with 64-bit, 0.066 with 128-bit). */
layout(std430, binding = RASTER_BIND_VIS) writeonly buffer RasterVis { uvec2 words2[]; };
layout(std430, binding = RASTER_BIND_VIS) writeonly buffer RasterVis4 { uvec4 words4[]; };

#ifdef RASTER_DEPTH_MS
layout(binding = RASTER_TEX_DEPTH) uniform sampler2DMS u_depth;
uniform int u_target_samples;
#else
layout(binding = RASTER_TEX_DEPTH) uniform sampler2D u_depth;
#endif
layout(binding = RASTER_IMG_OPAQUE, r32f) uniform writeonly image2D u_opaque;

float target_depth(ivec2 px, int k)
{
#ifdef RASTER_DEPTH_MS
    return texelFetch(u_depth, px, k * u_target_samples / u_raster_samples).r;
#else
    return texelFetch(u_depth, px, 0).r;
#endif
}

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_raster_pixels.x || px.y >= u_raster_pixels.y) return;
    int n = u_raster_samples;
    int base = (px.y * u_raster_pixels.x + px.x) * n;
    if (n == 4) {
        vec4 d = max(vec4(target_depth(px, 0), target_depth(px, 1), target_depth(px, 2), target_depth(px, 3)), 0.0);
        uvec4 bits = floatBitsToUint(d);
        words4[base / 2] = uvec4(0u, bits.x, 0u, bits.y);
        words4[base / 2 + 1] = uvec4(0u, bits.z, 0u, bits.w);
    } else {
        for (int k = 0; k < n; k++) words2[base + k] = uvec2(0u, floatBitsToUint(max(target_depth(px, k), 0.0)));
    }
    float far = 0.0;
#ifdef RASTER_DEPTH_MS
    for (int k = 0; k < u_target_samples; k++) far = max(far, texelFetch(u_depth, px, k).r);
#else
    far = texelFetch(u_depth, px, 0).r;
#endif
    imageStore(u_opaque, px, vec4(far));
}

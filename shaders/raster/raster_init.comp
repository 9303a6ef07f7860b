#version 450
/* raster_init.comp: starts a frame of the compute rasterizer: every sample
 * of the visibility buffer gets the opaque depth of its pixel (the resolved
 * depth of the hardware pass: terrain, sky, characters, balls) and colour
 * word 0, which marks "no grass" (grass colours carry alpha 255). Works on
 * the buffer as two uints per sample, the layout of both variants in
 * raster.glsl (colour word first, depth word second). */
layout(local_size_x = 16, local_size_y = 16) in;

#include "raster/raster_frame.glsl"

layout(std430, binding = RASTER_VIS_BINDING) writeonly buffer RasterVis { uint words[]; };

layout(binding = 0) uniform sampler2D u_depth;


void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (px.x >= u_raster_pixels.x || px.y >= u_raster_pixels.y) return;
    uint depth = floatBitsToUint(max(texelFetch(u_depth, px, 0).r, 0.0));
    int n = u_raster_samples;
    int base = (px.y * u_raster_pixels.x + px.x) * n;
    for (int k = 0; k < n; k++) {
        words[2 * (base + k)] = 0u;
        words[2 * (base + k) + 1] = depth;
    }
}

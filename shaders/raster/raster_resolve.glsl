/* raster_resolve.glsl: one pixel of the compute rasterizer's visibility
 * buffer resolved (raster_composite.frag and raster_composite.comp): the
 * colour of its grass samples, premultiplied by coverage, coverage (grass
 * samples / samples) as alpha, and the nearest grass sample's depth. */
#ifndef RASTER_RESOLVE_GLSL
#define RASTER_RESOLVE_GLSL

#include "raster/raster_frame.glsl"

/* (colour, depth) words, read with the widest loads the sample count
 * allows (H100, meadow_large at 1080p: 0.545 ms with 32-bit loads, 0.391
 * with 128-bit). */
layout(std430, binding = RASTER_BIND_VIS) readonly buffer RasterVis { uvec2 words2[]; };
layout(std430, binding = RASTER_BIND_VIS) readonly buffer RasterVis4 { uvec4 words4[]; };

/* False where no sample of px holds grass. */
bool raster_resolve(ivec2 px, out vec4 premul, out float depth)
{
    int n = u_raster_samples;
    int base = (px.y * u_raster_pixels.x + px.x) * n;
    vec3 sum = vec3(0.0);
    int covered = 0;
    depth = 1.0;
    uvec4 w[2] = uvec4[2](uvec4(0u), uvec4(0u));
    if (n == 4) {
        w[0] = words4[base / 2];
        w[1] = words4[base / 2 + 1];
    } else {
        w[0].xy = words2[base];
    }
    for (int k = 0; k < n; k++) {
        uvec2 cd = (k & 1) == 0 ? w[k >> 1].xy : w[k >> 1].zw;
        if ((cd.x >> 24) == 0u) continue;
        sum += unpackUnorm4x8(cd.x).rgb;
        covered++;
        depth = min(depth, uintBitsToFloat(cd.y));
    }
    premul = vec4(sum / float(n), float(covered) / float(n));
    return covered > 0;
}

#endif

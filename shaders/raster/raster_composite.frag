#version 450
/* raster_composite.frag: resolves the compute rasterizer's samples of one
 * pixel and composites them over the hardware-drawn opaque scene: colour
 * the mean of the grass samples, premultiplied, with coverage (grass
 * samples / samples) as alpha (blend ONE, ONE_MINUS_SRC_ALPHA), and depth
 * the nearest grass sample, so later passes and screenshots see the grass.
 * Pixels without grass are discarded. */
#include "raster/raster_frame.glsl"

layout(std430, binding = RASTER_VIS_BINDING) readonly buffer RasterVis { uint words[]; };


out vec4 o_color;

void main()
{
    ivec2 px = ivec2(gl_FragCoord.xy);
    int n = u_raster_samples;
    int base = (px.y * u_raster_pixels.x + px.x) * n;
    vec3 sum = vec3(0.0);
    int covered = 0;
    float depth = 1.0;
    for (int k = 0; k < n; k++) {
        uint rgba = words[2 * (base + k)];
        if ((rgba >> 24) == 0u) continue;
        sum += unpackUnorm4x8(rgba).rgb;
        covered++;
        depth = min(depth, uintBitsToFloat(words[2 * (base + k) + 1]));
    }
    if (covered == 0) discard;
    o_color = vec4(sum / float(n), float(covered) / float(n));
    gl_FragDepth = depth;
}

#version 450
/* raster_composite.frag: composites the compute rasterizer's grass over
 * the hardware-drawn opaque scene with its depth (raster_end: frames whose
 * depth is read back, as the seam measure's): colour premultiplied, with
 * coverage as alpha (blend ONE, ONE_MINUS_SRC_ALPHA), and depth the nearest
 * grass sample, so later passes see the grass. Pixels without grass are
 * discarded. */
#include "raster/raster_resolve.glsl"

out vec4 o_color;

void main()
{
    vec4 premul;
    float depth;
    if (!raster_resolve(ivec2(gl_FragCoord.xy), premul, depth)) discard;
    o_color = premul;
    gl_FragDepth = depth;
}

#version 450
/* raster_composite.comp: composites the compute rasterizer's grass over
 * the hardware-drawn opaque scene, colour only (raster_end_color): every
 * sample of the target's colour becomes premul + (1 - alpha) * itself,
 * the blend raster_composite.frag asks of the hardware, without its
 * fragment pass (on the H100 a full-screen fragment pass over the 4x MSAA
 * target costs 0.30 ms even writing a constant). The target's depth keeps
 * the opaque scene. RASTER_TARGET_MS: the colour is a multisample texture
 * of u_target_samples samples. */
#include "raster/raster_resolve.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
#ifdef RASTER_TARGET_MS
layout(rgba8, binding = RASTER_IMG_TARGET) uniform image2DMS u_target;
uniform int u_target_samples;
#else
layout(rgba8, binding = RASTER_IMG_TARGET) uniform image2D u_target;
#endif

void main()
{
    ivec2 px = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(px, u_raster_pixels))) return;
    vec4 premul;
    float depth;
    if (!raster_resolve(px, premul, depth)) return;
    float keep = 1.0 - premul.a;
#ifdef RASTER_TARGET_MS
    for (int s = 0; s < u_target_samples; s++)
        imageStore(u_target, px, s, premul + keep * imageLoad(u_target, px, s));
#else
    imageStore(u_target, px, premul + keep * imageLoad(u_target, px));
#endif
}

#version 450
/* depth_nearest.comp: the nearest of each pixel's depth samples of a
 * multisampled depth texture, into a float per pixel (row 0 at the bottom,
 * as glReadPixels): gfx_target_read_depth_nearest. */
layout(local_size_x = 8, local_size_y = 8) in;

#include "common/bindings_gfx.glsl"

layout(binding = GFX_TEX_DEPTH) uniform sampler2DMS u_depth;
uniform int u_samples;

layout(std430, binding = GFX_BIND_NEAREST) writeonly buffer Nearest { float nearest[]; };

void main()
{
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    ivec2 size = textureSize(u_depth);
    if (p.x >= size.x || p.y >= size.y) return;
    float d = 1.0;
    for (int s = 0; s < u_samples; s++) d = min(d, texelFetch(u_depth, p, s).r);
    nearest[p.y * size.x + p.x] = d;
}

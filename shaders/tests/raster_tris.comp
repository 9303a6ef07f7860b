#version 450
/* raster_tris.comp: flat-coloured clip-space triangles through the compute
 * rasterizer, for test_raster (CPU twin: raster_ref_triangle). Triangle i
 * is tris[4i .. 4i+2] (clip positions) and floatBitsToUint(tris[4i+3].x)
 * (its colour word). */
#include "raster/raster.glsl"
#include "common/bindings_tests.glsl"

#ifdef RASTER_BIG
layout(local_size_x = RASTER_BIG_THREADS) in;
#else
layout(local_size_x = 64) in;
#endif

layout(std430, binding = TEST_BIND_IN) readonly buffer Tris { vec4 tris[]; };

uniform uint u_count;

uint g_rgba;

void raster_fragment(int s, vec3 w, float depth)
{
    raster_put(s, floatBitsToUint(depth), g_rgba);
}

void main()
{
#ifdef RASTER_BIG
    uvec2 item;
    bool group;
    if (!raster_queued_item(item, group)) return;
    uint i = item.x;
    g_rgba = floatBitsToUint(tris[4 * i + 3].x);
    raster_triangle(tris[4 * i], tris[4 * i + 1], tris[4 * i + 2], group);
#else
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    g_rgba = floatBitsToUint(tris[4 * i + 3].x);
    raster_triangle_or_queue(tris[4 * i], tris[4 * i + 1], tris[4 * i + 2], i, 0u);
#endif
}

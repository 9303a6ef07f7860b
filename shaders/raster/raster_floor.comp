#version 450
/* raster_floor.comp: the compute floor (app_floor.c): the hardware floor's
 * triangles (three clip-space vec4 each, Tris) through the compute
 * rasterizer with trivial shading: one constant colour for every sample
 * that passes the depth test. With RASTER_BIG the queued triangles. */
#include "raster/raster.glsl"

#ifdef RASTER_BIG
layout(local_size_x = RASTER_BIG_THREADS) in;
#else
layout(local_size_x = 64) in;
#endif

layout(std430, binding = RASTER_BIND_FLOOR_TRIS) readonly buffer Tris { vec4 tri_v[]; };

uniform uint u_count;

void raster_fragment(int s, vec3 w, float depth)
{
    uint d = floatBitsToUint(depth);
    if (raster_occluded(s, d)) return;
    raster_put(s, d, 0xff808080u);
}

void main()
{
#ifdef RASTER_BIG
    uvec2 item;
    bool group;
    if (!raster_queued_item(item, group)) return;
    uint t = 3u * item.x;
    raster_triangle(tri_v[t], tri_v[t + 1u], tri_v[t + 2u], group);
#else
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    uint t = 3u * i;
    raster_triangle_or_queue(tri_v[t], tri_v[t + 1u], tri_v[t + 2u], i, 0u);
#endif
}

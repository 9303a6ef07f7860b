/* bb_ground.glsl: the terrain under the billboards, from the field's height
 * texture (bb.c upload_heights: a heightfield's own vertices, or a mesh
 * terrain resampled at the candidate spacing), or with BB_GROUND_WORLD the
 * world's height function (the billboard ring, bb_ring.c, which sets its
 * uniforms). Included before common/bb.glsl, it defines
 * BB_GROUND, and bb_push_mesh then keeps every vertex on or above the
 * terrain (twin: bb_collide_desc_t.ground). */
#ifndef BB_GROUND_GLSL
#define BB_GROUND_GLSL
#define BB_GROUND

#include "common/bindings_billboard.glsl"

#ifdef BB_GROUND_WORLD
#include "common/world_height.glsl"
float terrain_height(float x, float z) { return world_height(vec2(x, z)); }
#else

/* R32F grid vertex heights */
layout(binding = BB_TEX_HEIGHTS) uniform sampler2D u_heights;
uniform vec2 u_hmin;   /* height grid: first vertex (x, z) */
uniform vec2 u_hmax;   /* height grid: clamp bound (x, z) */
uniform float u_hcell; /* height grid cell size */

/* Twin of grid_height in src/scene/terrain.c (same two triangles per cell). */
float terrain_height(float x, float z)
{
    ivec2 res = textureSize(u_heights, 0) - 1;
    float fx = (clamp(x, u_hmin.x, u_hmax.x) - u_hmin.x) / u_hcell;
    float fz = (clamp(z, u_hmin.y, u_hmax.y) - u_hmin.y) / u_hcell;
    int i = clamp(int(floor(fx)), 0, res.x - 1);
    int j = clamp(int(floor(fz)), 0, res.y - 1);
    float u = fx - float(i), v = fz - float(j);
    float p00 = texelFetch(u_heights, ivec2(i, j), 0).r;
    float p10 = texelFetch(u_heights, ivec2(i + 1, j), 0).r;
    float p01 = texelFetch(u_heights, ivec2(i, j + 1), 0).r;
    float p11 = texelFetch(u_heights, ivec2(i + 1, j + 1), 0).r;
    if (min(min(p00, p10), min(p01, p11)) < -1e29) return -3.0e38; /* no ground (mesh hole) */
    if (v >= u) return p00 + u * (p11 - p01) + v * (p01 - p00);
    return p00 + u * (p10 - p00) + v * (p11 - p10);
}
#endif

#endif

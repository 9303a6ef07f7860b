#version 450
/* bb_raster.comp: billboards of Orthmann et al. 2009 drawn by the compute
 * rasterizer, the twin of bb_render.geom + bb_render.frag. One thread per
 * billboard: its thinning with distance (bb_lod.glsl: culled, or drawn
 * wider), frustum test of its bounding sphere, the hybrid near drop,
 * then a plain quad (top edge in the wind pose, slope hand-over shift) or
 * its deformed N x M mesh (normals from central differences), 2 or
 * 2 (N-1)(M-1) triangles. Texels come from the clump array at the level of
 * detail of the billboard's projected size (no derivatives in compute).
 * Fragments are shaded at pixel rate (one texel fetch and one shading per
 * pixel, as the hardware path's fragment shader); alpha and the hybrid fade
 * then cover round(alpha n) of the pixel's n samples, starting at a sample
 * chosen by a hash of the pixel (grass_coverage_mask, the hardware path's
 * rule too).
 * The texel and the lit colour cards show are the view-dependent blend of
 * the clump bakes (bb_view.glsl, bb_shade); with BB_GI each triangle vertex
 * takes the global illumination's ambient light, interpolated per pixel.
 * Fragments behind what the samples already hold are skipped before the
 * texel fetch. With RASTER_BIG the queued large triangles, each scanned by
 * its whole work group sharing out the covered pixels (RASTER_GROUP_SCAN,
 * raster.glsl). */
#define BB_NO_GENERATE
#include "common/bindings_billboard.glsl"
#include "common/bb.glsl"
#include "billboard/bb_points.glsl"
#include "billboard/bb_pool.glsl"
#include "billboard/bb_slope.glsl"
#include "common/grass_shade.glsl"
#include "common/hash.glsl"
#include "billboard/bb_view.glsl"
#include "billboard/bb_lod.glsl"
#define RASTER_PIXEL_RATE 1
#define RASTER_NO_MEDIUM 1
#define RASTER_GROUP_SCAN 1
#define RASTER_BIG_THREADS 32
#define RASTER_BANDS 1 /* the billboards at the camera fill the screen */
#include "raster/raster.glsl"

#ifdef RASTER_BIG
layout(local_size_x = RASTER_BIG_THREADS) in;
#else
layout(local_size_x = 64) in;
#endif

layout(std430, binding = BB_BIND_POINTS) readonly buffer Points { bb_point points[]; };

layout(binding = BB_TEX_CLUMPS) uniform sampler2DArray u_clumps;
uniform mat4 u_viewproj;
uniform vec4 u_planes[6];
uniform vec3 u_camera;
uniform vec3 u_sun;
uniform float u_time;
uniform float u_fade_start;
uniform float u_fade_end;
uniform float u_far_start;
uniform float u_far_end;
uniform bb_wind u_wind;
uniform uint u_count;

/* A queued triangle is (billboard, triangle | level of detail << 8): at
 * most 2 (8-1)^2 = 98 triangles, the level in 1/256 steps (below level
 * 256, so the word stays under raster.glsl's band bits, 1 << 24). */
#define BB_LOD_SHIFT 8u
#define BB_LOD_SCALE 256.0

bb_point g_p;
float g_layer, g_tint, g_lod;
vec3 g_right, g_up;
vec3 g_corner[4];
vec3 g_plain_n;
vec3 g_pos[3];
vec3 g_nrm[3];
vec2 g_uv[3]; /* u, height h (0 root) */
vec3 g_amb[3][2]; /* per vertex: global illumination of the two faces (bb_vertex_ambient) */

/* Loads billboard `prim`; false when it is culled or dropped. Sets the
 * plain corners (a, b, c, d) or the mesh in bb_pos. The RASTER_BIG pass
 * takes only billboards the first pass kept, and their texel level of
 * detail from the queue: it skips the tests and the projections. */
bool bb_setup(uint prim)
{
    g_p = points[prim];
    float k;
    bool kept = bb_lod_thin(g_p, u_camera, k);
    bb_point p = g_p;
#ifndef RASTER_BIG
    if (!kept || p.size.y <= 0.0) return false;
    float r = 0.5 * length(vec2(p.size.x, p.size.y)) + u_wind.strength;
    vec3 centre = p.position + 0.5 * p.size.y * p.growth;
    for (int i = 0; i < 6; i++)
        if (dot(u_planes[i].xyz, centre) + u_planes[i].w < -r) return false;
    if (bb_fade_dropped(p, u_camera, u_fade_start, u_fade_end) || bb_far_dropped(p, u_camera, u_far_end)) return false;
#endif
    bb_frame(p, g_right, g_up);
    g_layer = float(p.layer);
    g_tint = bb_tint(p);
#ifndef RASTER_BIG
    raster_vert r0, r1, r2;
    bool ok = raster_project(u_viewproj * vec4(p.position, 1.0), r0);
    ok = raster_project(u_viewproj * vec4(p.position + p.size.y * g_up, 1.0), r1) && ok;
    ok = raster_project(u_viewproj * vec4(p.position + p.size.x * g_right, 1.0), r2) && ok;
    vec2 texels = vec2(textureSize(u_clumps, 0).xy);
    vec2 extent = max(vec2(distance(r0.p.xy, r2.p.xy), distance(r0.p.xy, r1.p.xy)), vec2(1.0));
    g_lod = ok ? max(log2(max(texels.x / extent.x, texels.y / extent.y)), 0.0) : 0.0;
#endif
    vec3 a, b, ta, tb;
    bb_plain_corners(p, g_right, g_up, u_wind, u_time, a, b, ta, tb);
    if (p.pad0 == BB_NO_SLOT) {
        vec3 shift = bb_slope_shift(p, ta, tb);
        g_corner[0] = a;
        g_corner[1] = b;
        g_corner[2] = ta + shift;
        g_corner[3] = tb + shift;
        g_plain_n = bb_plain_normal(a, b, g_corner[2], g_corner[3]);
    } else {
        bb_load_mesh(p.pad0);
        bb_lod_mesh(p.position, g_right, k);
        if (u_slope_on != 0) bb_slope_mesh(p, ta, tb);
    }
    return true;
}

int bb_triangles()
{
    return g_p.pad0 == BB_NO_SLOT ? 2 : 2 * (BB_N - 1) * (BB_M - 1);
}

/* Grid vertex (i, j) (plain quad: corner) into triangle slot `slot`;
 * returns its clip position. */
vec4 bb_vertex(int i, int j, int slot)
{
    vec3 pos, n;
    vec2 uv;
    if (g_p.pad0 == BB_NO_SLOT) {
        pos = g_corner[j * 2 + i];
        n = g_plain_n;
        uv = vec2(float(i), float(j));
    } else {
        pos = bb_pos[j * BB_N + i];
        n = bb_mesh_normal(i, j, cross(g_right, g_up));
        uv = vec2(float(i) / float(BB_N - 1), float(j) / float(BB_M - 1));
    }
    g_pos[slot] = pos;
    g_nrm[slot] = n;
    g_uv[slot] = uv;
#ifdef BB_GI
    bb_vertex_ambient(pos, n, g_amb[slot][0], g_amb[slot][1]);
#endif
    return u_viewproj * vec4(pos, 1.0);
}

void bb_triangle(int t, out vec4 a, out vec4 b, out vec4 c)
{
    int cols = g_p.pad0 == BB_NO_SLOT ? 1 : BB_N - 1;
    int cell = t / 2, i = cell % cols, j = cell / cols;
    if ((t & 1) == 0) {
        a = bb_vertex(i, j, 0);
        b = bb_vertex(i + 1, j, 1);
        c = bb_vertex(i, j + 1, 2);
    } else {
        a = bb_vertex(i + 1, j, 0);
        b = bb_vertex(i, j + 1, 1);
        c = bb_vertex(i + 1, j + 1, 2);
    }
}

void raster_fragment(int s0, vec3 w, float depth)
{
    uint depth_bits = floatBitsToUint(depth);
    int n = u_raster_samples;
    bool hidden = true;
    for (int k = 0; k < n; k++) hidden = hidden && raster_occluded(s0 + k, depth_bits);
    if (hidden) return;
    vec2 uv = w.x * g_uv[0] + w.y * g_uv[1] + w.z * g_uv[2];
    vec3 world = w.x * g_pos[0] + w.y * g_pos[1] + w.z * g_pos[2];
    int pixel = s0 / n;
    uvec2 px = uvec2(pixel % u_raster_pixels.x, pixel / u_raster_pixels.x);
    /* Views off (no BB_VIEW_CARDS): one bake at the card's level. */
#ifdef BB_VIEW_CARDS
    vec3 light;
    vec2 grad = exp2(g_lod) / vec2(textureSize(u_clumps, 0).xy);
    vec4 tex = bb_view_texel(u_clumps, vec2(uv.x, 1.0 - uv.y), g_layer, vec2(grad.x, 0.0), vec2(0.0, grad.y),
                             u_camera - world, bb_view_xi(px), light);
    const float lit = 1.0;
#else
    const vec3 light = vec3(0.0);
    vec4 tex = textureLod(u_clumps, vec3(uv.x, 1.0 - uv.y, g_layer), g_lod);
    const float lit = 0.0;
#endif
    float dist = grass_distance(world, u_camera);
    float a = bb_fade_alpha(tex.a, dist, u_fade_start, u_fade_end, vec2(px) + 0.5);
    a = bb_far_alpha(a, dist, u_far_start, u_far_end, vec2(px) + 0.5);
    if (a < 1.0 / 255.0) return;
    uint mask = grass_coverage_mask(a, n, px);
    if (mask == 0u) return;
    uint rgba = 0u;
    if (raster_color_pass()) {
        vec3 nrm = w.x * g_nrm[0] + w.y * g_nrm[1] + w.z * g_nrm[2];
        float card = g_p.pad0 == BB_NO_SLOT ? 1.0 : 0.0;
#ifdef BB_GI
        vec3 amb_front = w.x * g_amb[0][0] + w.y * g_amb[1][0] + w.z * g_amb[2][0];
        vec3 amb_back = w.x * g_amb[0][1] + w.y * g_amb[1][1] + w.z * g_amb[2][1];
#else
        const vec3 amb_front = vec3(0.0), amb_back = vec3(0.0);
#endif
        vec3 c = bb_shade(tex.rgb, g_tint, world, nrm, light, lit, card, 1.0 - uv.y, u_camera, u_sun,
                          vec4(0.0), amb_front, amb_back);
        rgba = packUnorm4x8(vec4(c, 1.0));
    }
    for (int k = 0; k < n; k++)
        if ((mask & (1u << uint(k))) != 0u) raster_put(s0 + k, depth_bits, rgba);
}

void main()
{
#ifdef RASTER_BIG
    uvec2 item;
    bool group;
    if (!raster_queued_item(item, group)) return;
    g_lod = float(item.y >> BB_LOD_SHIFT) / BB_LOD_SCALE;
    bb_setup(item.x);
    vec4 a, b, c;
    bb_triangle(int(item.y & ((1u << BB_LOD_SHIFT) - 1u)), a, b, c);
    raster_triangle(a, b, c, group);
#else
    uint prim = gl_GlobalInvocationID.x;
    if (prim >= u_count || !bb_setup(prim)) return;
    int n = bb_triangles();
    /* A deformed mesh's triangles share the quad's budget: scanned here
     * one after the other they would hold the warp for (N-1)(M-1) quads. */
    float small = float(u_raster_small_samples) * 2.0 / float(n);
    for (int t = 0; t < n; t++) {
        vec4 a, b, c;
        bb_triangle(t, a, b, c);
        raster_triangle_or_queue_within(a, b, c, prim, uint(t) | uint(g_lod * BB_LOD_SCALE + 0.5) << BB_LOD_SHIFT,
                                        small);
    }
#endif
}

#version 450
/* blade_raster.comp: Bezier blades (Jahrmann & Wimmer 2017) drawn by the
 * compute rasterizer. One thread per listed blade (u_use_ids: blade
 * ids[i].x drawn ids[i].y (float bits) times as wide, blade mode's
 * survivors with their width factors; else blades[i]; the count is the
 * uint at u_count_index of Count, written by the culling pass): the blade
 * surface of blade_geom.glsl
 * (eq. 21, 24) as a strip of n segments, n from the blade's projected
 * length (u_segment_pixels pixels per segment, 1 to u_max_level). A blade
 * narrower than the sample spacing is widened to it and covers each sample
 * with the probability of its true width, so a far blade is a thin line of
 * the right average coverage. Hybrid fade: alpha as blade.frag, turned into
 * coverage by fixed per-sample thresholds (blade_fade_covers, the rule
 * blade.frag's sample mask follows). Shaded per vertex (blade_shade at
 * the triangle's three vertices, the colour interpolated): the shading is
 * Lambert, ambient and fog, smooth across a blade's triangle, and per
 * sample it was a third of the pass (1.0 of 3.2 ms on the H100 world walk).
 * With RASTER_BIG the queued medium and large triangles (raster.glsl). */
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "blade/blade_geom.glsl"
#include "common/grass_shade.glsl"
#include "common/hash.glsl"
#include "raster/raster.glsl"

#ifdef RASTER_BIG
layout(local_size_x = RASTER_BIG_THREADS) in;
#else
layout(local_size_x = 64) in;
#endif

layout(std430, binding = BLADE_BIND_BLADES) readonly buffer Blades { Blade blades[]; };
layout(std430, binding = BLADE_BIND_RASTER_IDS) readonly buffer Ids { uvec2 ids[]; };
layout(std430, binding = BLADE_BIND_RASTER_COUNT) readonly buffer Count { uint count_words[]; };

uniform mat4 u_view_proj;
uniform int u_use_ids;
uniform uint u_count_index;
uniform uint u_count_max;
uniform vec3 u_sun;
uniform vec2 u_fade; /* start, end; end <= start: no fade */
uniform vec3 u_albedo_root;
uniform vec3 u_albedo_tip;
uniform float u_segment_pixels;

/* The blade being drawn and its current triangle's vertex colours. */
Blade g_blade;
float g_keep;      /* probability that a covered sample is drawn (thin blades) */
float g_alpha;     /* hybrid fade alpha before the dither */
uint g_seed;
vec3 g_col[3];

uint blade_count()
{
    return min(count_words[u_count_index], u_count_max);
}

/* Loads blade `prim` of the list and sets its width widening and fade. */
int blade_setup(uint prim)
{
    uvec2 id = u_use_ids != 0 ? ids[prim] : uvec2(prim, floatBitsToUint(1.0));
    uint index = id.x;
    g_blade = blades[index];
    g_blade.v2.w *= uintBitsToFloat(id.y);
    g_seed = hash_u32(index * 0x9e3779b9u);
    float root_dist = grass_distance(g_blade.v0.xyz, u_camera);
    g_alpha = blade_fade_ramp(root_dist, u_fade);
    raster_vert r0, r1, r2;
    vec3 t1, front;
    blade_frame(g_blade, t1, front);
    bool ok = raster_project(u_view_proj * vec4(g_blade.v0.xyz, 1.0), r0);
    ok = raster_project(u_view_proj * vec4(g_blade.v0.xyz + t1 * g_blade.v2.w, 1.0), r1) && ok;
    ok = raster_project(u_view_proj * vec4(g_blade.v2.xyz, 1.0), r2) && ok;
    /* the sample spacing: 1 pixel, 0.5 with 4 samples */
    float spacing = inversesqrt(float(u_raster_samples));
    float width = distance(r0.p.xy, r1.p.xy);
    g_keep = 1.0;
    if (ok && width < spacing) {
        g_keep = max(width / spacing, 1.0 / 64.0);
        g_blade.v2.w /= g_keep;
    }
    float len = ok ? distance(r0.p.xy, r2.p.xy) : 1e9;
    return clamp(int(ceil(len / u_segment_pixels)), 1, max(u_max_level, 1));
}

vec4 blade_vertex(float u, float v, int slot)
{
    vec3 p, n;
    blade_build(g_blade, u, v, p, n);
    if (raster_color_pass())
        g_col[slot] = blade_shade(p, n, v, u_camera, u_sun, u_albedo_root, u_albedo_tip, vec4(0.0));
    return u_view_proj * vec4(p, 1.0);
}

void raster_fragment(int s, vec3 w, float depth)
{
    if (raster_occluded(s, floatBitsToUint(depth))) return;
    if (g_keep < 1.0 && hash_float(g_seed ^ uint(s) * 0x85ebca6bu) >= g_keep) return;
    if (g_alpha < 1.0) {
        int pixel = s / u_raster_samples;
        uvec2 px = uvec2(pixel % u_raster_pixels.x, pixel / u_raster_pixels.x);
        if (!blade_fade_covers(blade_fade_dither(g_alpha, px), s % u_raster_samples, u_raster_samples)) return;
    }
    uint rgba = 0u;
    if (raster_color_pass()) rgba = packUnorm4x8(vec4(w.x * g_col[0] + w.y * g_col[1] + w.z * g_col[2], 1.0));
    raster_put(s, floatBitsToUint(depth), rgba);
}

/* Triangle t of the strip: segment t / 2, lower (t even) or upper half. */
void blade_triangle(int t, int n, out vec4 a, out vec4 b, out vec4 c)
{
    float v0 = float(t / 2) / float(n), v1 = float(t / 2 + 1) / float(n);
    if ((t & 1) == 0) {
        a = blade_vertex(0.0, v0, 0);
        b = blade_vertex(1.0, v0, 1);
        c = blade_vertex(0.0, v1, 2);
    } else {
        a = blade_vertex(1.0, v0, 0);
        b = blade_vertex(0.0, v1, 1);
        c = blade_vertex(1.0, v1, 2);
    }
}

void main()
{
#ifdef RASTER_BIG
    uvec2 item;
    bool group;
    if (!raster_queued_item(item, group)) return;
    int n = blade_setup(item.x);
    vec4 a, b, c;
    blade_triangle(int(item.y), n, a, b, c);
    raster_triangle(a, b, c, group);
#else
    uint prim = gl_GlobalInvocationID.x;
    if (prim >= blade_count()) return;
    int n = blade_setup(prim);
    if (g_blade.v1.w <= 0.0) return;
    for (int t = 0; t < 2 * n; t++) {
        vec4 a, b, c;
        blade_triangle(t, n, a, b, c);
        raster_triangle_or_queue(a, b, c, prim, uint(t));
    }
#endif
}

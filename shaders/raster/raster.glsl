/* raster.glsl: the compute rasterizer's side of the visibility buffer
 * (src/raster/raster.h). Grass shaders that draw in compute include this
 * file, set up a primitive (a blade, a billboard), hand its triangles in
 * clip space to raster_triangle_or_queue; each covered sample calls the
 * including shader's raster_fragment, which decides coverage, shades (only
 * when raster_color_pass()) and calls raster_put.
 *
 * Samples: u_raster_samples per pixel (1: the pixel centre; 4: the
 * standard 4x MSAA pattern, offsets (-2,-6) (6,-2) (-6,2) (2,6) / 16 pixel
 * from the centre, the rotated grid the hardware path's 4x MSAA uses, so
 * near-vertical blade edges get four coverage steps, not two). Sample k of
 * pixel p is word p n + k. Each sample index k is a regular lattice (the
 * pixel grid shifted by its offset), so a triangle is scanned once per
 * lattice, row by row.
 *
 * Visibility buffer: one 64-bit word per sample, depth (float bits of the
 * window depth, which order like uints for depth >= 0) in the high half and
 * packed RGBA8 colour in the low half. With RASTER_ATOMIC64
 * (GL_NV_shader_atomic_int64) one atomicMin keeps the nearest sample.
 * Without it (Mesa llvmpipe) the same memory is two uints per sample and
 * every draw runs twice: pass 0 takes atomicMin of the depth, pass 1 stores
 * the colour where its depth won.
 *
 * Pixel rate (RASTER_PIXEL_RATE defined before including): one lattice, the
 * pixel centres, and raster_fragment gets the pixel's first sample; the
 * shader then covers some of the pixel's samples (alpha as coverage, as
 * alpha-to-coverage does). For shaders whose cost is per fragment (texture,
 * shading) and whose edges are soft anyway.
 *
 * Work split by size (samples = pixel bounding box times the lattices it
 * is scanned on): up to u_raster_small_samples the primitive's thread scans
 * the triangle at once; up to u_raster_medium_samples it is queued
 * (primitive, triangle) on the medium list, larger ones and those crossing
 * the near plane on the large list. The RASTER_BIG variant of the same
 * shader then runs both lists (raster_queued_item): medium triangles one
 * per thread (similar sizes side by side, so the threads of a warp finish
 * together), large ones one per work group of RASTER_BIG_THREADS, one row
 * per thread in turn (near-plane crossings clipped there). A shader that
 * defines RASTER_NO_MEDIUM queues everything it does not scan at once on
 * the large list (compiled out, not just a threshold). */
#ifndef RASTER_GLSL
#define RASTER_GLSL

#include "raster/raster_frame.glsl"

#define RASTER_BIG_THREADS 64

layout(std430, binding = RASTER_VIS_BINDING) buffer RasterVis {
#ifdef RASTER_ATOMIC64
    uint64_t raster_vis[];
#else
    uint raster_vis[];
#endif
};

/* Large count and overflow, medium count and overflow, then the large
 * list (u_raster_queue_capacity (primitive, triangle) pairs) and the
 * medium list (as many); see raster.c. */
layout(std430, binding = RASTER_QUEUE_BINDING) buffer RasterQueue {
    uint raster_large_count;
    uint raster_large_overflow;
    uint raster_medium_count;
    uint raster_medium_overflow;
    uvec2 raster_queue[];
};

uniform int u_raster_pass;          /* without RASTER_ATOMIC64: 0 depth, 1 colour */
uniform uint u_raster_small_samples;  /* scanned by the primitive's thread up to this */
uniform uint u_raster_medium_samples; /* queued one per thread up to this, else one per work group */
uniform uint u_raster_queue_capacity; /* per list */

bool raster_color_pass()
{
#ifdef RASTER_ATOMIC64
    return true;
#else
    return u_raster_pass == 1;
#endif
}

/* Sample k's offset from the pixel centre, in pixels. */
vec2 raster_offset(int k)
{
    const vec2 o4[4] = vec2[4](vec2(-2.0, -6.0), vec2(6.0, -2.0), vec2(-6.0, 2.0), vec2(2.0, 6.0));
    return u_raster_samples == 4 ? o4[k] * (1.0 / 16.0) : vec2(0.0);
}

/* Lattices a triangle is scanned on: one per sample, or one at pixel rate. */
int raster_lattices()
{
#ifdef RASTER_PIXEL_RATE
    return 1;
#else
    return u_raster_samples;
#endif
}

/* True when sample s already holds something nearer than depth_bits: the
 * fragment can be skipped before it is shaded (a plain read: the stored
 * depth only decreases, so a stale value is only less useful). Equal depth
 * is not skipped where the colour decides the tie (the 64-bit atomicMin;
 * the colour pass of the two-pass variant, which has to match it), so the
 * image does not depend on the order in which threads run. */
bool raster_occluded(int s, uint depth_bits)
{
#ifdef RASTER_ATOMIC64
    return depth_bits > unpackUint2x32(raster_vis[s]).y;
#else
    uint stored = raster_vis[2 * s + 1];
    return u_raster_pass == 0 ? depth_bits >= stored : depth_bits > stored;
#endif
}

void raster_put(int s, uint depth_bits, uint rgba)
{
#ifdef RASTER_ATOMIC64
    atomicMin(raster_vis[s], packUint2x32(uvec2(rgba, depth_bits)));
#else
    if (u_raster_pass == 0) {
        atomicMin(raster_vis[2 * s + 1], depth_bits);
    } else if (raster_vis[2 * s + 1] == depth_bits) {
        raster_vis[2 * s] = rgba;
    }
#endif
}

/* A projected vertex: sample-space x, y, window depth z, and 1 / w. */
struct raster_vert {
    vec3 p;
    float inv_w;
};

/* False behind the camera (w <= 0): v is then meaningless. */
bool raster_project(vec4 clip, out raster_vert v)
{
    v.p = vec3(0.0);
    v.inv_w = 0.0;
    if (clip.w <= 0.0) return false;
    float iw = 1.0 / clip.w;
    vec3 ndc = clip.xyz * iw;
    v.p = vec3((ndc.xy * 0.5 + 0.5) * vec2(u_raster_pixels), ndc.z * 0.5 + 0.5);
    v.inv_w = iw;
    return true;
}

/* Pixel area of a box clamped to the target, times the lattices scanned. */
float raster_box_samples(vec2 lo, vec2 hi)
{
    vec2 size = vec2(u_raster_pixels);
    vec2 a = clamp(lo, vec2(0.0), size), b = clamp(hi, vec2(0.0), size);
    return max(b.x - a.x + 1.0, 0.0) * max(b.y - a.y + 1.0, 0.0) * float(raster_lattices());
}

/* The including shader's fragment: sample s (pixel rate: the pixel's
 * first sample) at perspective-correct weights w of the triangle's three
 * vertices, window depth `depth`. */
void raster_fragment(int s, vec3 w, float depth);

/* Scans rows first_row, first_row + row_step, ... of the projected
 * triangle a b c on every lattice (each lattice's rows from first_row);
 * fragment weights are to_tri * (weights of a, b, c). A sample on a shared
 * edge may be drawn by both triangles (same depth: no artefact). */
void raster_scan(raster_vert a, raster_vert b, raster_vert c, mat3 to_tri, int first_row, int row_step)
{
    vec2 p0 = a.p.xy, p1 = b.p.xy, p2 = c.p.xy;
    float det = (p1.y - p2.y) * (p0.x - p2.x) + (p2.x - p1.x) * (p0.y - p2.y);
    if (abs(det) < 1e-10) return;
    float id = 1.0 / det;
    vec3 A = vec3(p1.y - p2.y, p2.y - p0.y, 0.0) * id;
    vec3 B = vec3(p2.x - p1.x, p0.x - p2.x, 0.0) * id;
    A.z = -A.x - A.y;
    B.z = -B.x - B.y;
    vec3 C = vec3(-(A.x * p2.x + B.x * p2.y), -(A.y * p2.x + B.y * p2.y), 0.0);
    C.z = 1.0 - C.x - C.y;
    ivec2 size = u_raster_pixels;
    float ylo = min(p0.y, min(p1.y, p2.y)), yhi = max(p0.y, max(p1.y, p2.y));
    float xlo = min(p0.x, min(p1.x, p2.x)), xhi = max(p0.x, max(p1.x, p2.x));
    vec3 z = vec3(a.p.z, b.p.z, c.p.z), iw = vec3(a.inv_w, b.inv_w, c.inv_w);
    for (int k = 0; k < raster_lattices(); k++) {
#ifdef RASTER_PIXEL_RATE
        const vec2 o = vec2(0.5);
#else
        vec2 o = raster_offset(k) + 0.5;
#endif
        int y0 = max(int(ceil(ylo - o.y)), 0), y1 = min(int(floor(yhi - o.y)), size.y - 1);
        for (int y = y0 + first_row; y <= y1; y += row_step) {
            float yc = float(y) + o.y;
            vec3 K = B * yc + C;
            float lo = xlo, hi = xhi;
            for (int i = 0; i < 3; i++) {
                if (A[i] > 0.0) lo = max(lo, -K[i] / A[i]);
                else if (A[i] < 0.0) hi = min(hi, -K[i] / A[i]);
                else if (K[i] < 0.0) hi = lo - 1.0;
            }
            int x0 = max(int(ceil(lo - o.x)), 0), x1 = min(int(floor(hi - o.x)), size.x - 1);
            int base = y * size.x * u_raster_samples + k;
            for (int x = x0; x <= x1; x++) {
                vec3 l = max(A * (float(x) + o.x) + K, vec3(0.0));
                float depth = dot(l, z) / max(l.x + l.y + l.z, 1e-20);
                if (!(depth >= 0.0 && depth <= 1.0)) continue;
                vec3 q = l * iw;
                raster_fragment(base + x * u_raster_samples, to_tri * (q / max(q.x + q.y + q.z, 1e-30)), depth);
            }
        }
    }
}

/* Distance of a clip-space point in front of the near plane (z = -w). */
float raster_near(vec4 c) { return c.z + c.w; }

/* Scans the triangle with clip-space vertices c0 c1 c2 (rows as
 * raster_scan), clipped against the near plane first when it crosses it:
 * the clipped polygon (up to 4 vertices) is scanned as a fan whose weights
 * map back to c0 c1 c2. */
void raster_triangle(vec4 c0, vec4 c1, vec4 c2, int first_row, int row_step)
{
    vec4 c[3] = vec4[3](c0, c1, c2);
    vec3 d = vec3(raster_near(c0), raster_near(c1), raster_near(c2));
    raster_vert a, b, e;
    if (all(greaterThanEqual(d, vec3(0.0))) && c0.w > 0.0 && c1.w > 0.0 && c2.w > 0.0) {
        raster_project(c0, a);
        raster_project(c1, b);
        raster_project(c2, e);
        raster_scan(a, b, e, mat3(1.0), first_row, row_step);
        return;
    }
    vec4 poly[4];
    vec3 bary[4];
    int n = 0;
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3;
        vec3 bi = vec3(0.0), bj = vec3(0.0);
        bi[i] = 1.0;
        bj[j] = 1.0;
        if (d[i] >= 0.0) {
            poly[n] = c[i];
            bary[n] = bi;
            n++;
        }
        if ((d[i] >= 0.0) != (d[j] >= 0.0)) {
            float t = d[i] / (d[i] - d[j]);
            poly[n] = mix(c[i], c[j], t);
            bary[n] = mix(bi, bj, t);
            n++;
        }
    }
    if (n < 3) return;
    raster_vert pv[4];
    for (int i = 0; i < n; i++)
        if (!raster_project(poly[i], pv[i])) return;
    for (int i = 1; i + 1 < n; i++)
        raster_scan(pv[0], pv[i], pv[i + 1], mat3(bary[0], bary[i], bary[i + 1]), first_row, row_step);
}

/* In the per-primitive pass: scans a small triangle now, or queues it
 * (prim, tri) on the medium or the large list (large also when it crosses
 * the near plane). Triangles wholly behind the near plane vanish. */
void raster_triangle_or_queue(vec4 c0, vec4 c1, vec4 c2, uint prim, uint tri)
{
    vec3 d = vec3(raster_near(c0), raster_near(c1), raster_near(c2));
    if (all(lessThan(d, vec3(0.0)))) return;
    bool medium = false;
    if (all(greaterThanEqual(d, vec3(0.0))) && c0.w > 0.0 && c1.w > 0.0 && c2.w > 0.0) {
        raster_vert a, b, c;
        raster_project(c0, a);
        raster_project(c1, b);
        raster_project(c2, c);
        vec2 lo = min(a.p.xy, min(b.p.xy, c.p.xy)), hi = max(a.p.xy, max(b.p.xy, c.p.xy));
        float area = raster_box_samples(lo, hi);
        if (area <= float(u_raster_small_samples)) {
            raster_scan(a, b, c, mat3(1.0), 0, 1);
            return;
        }
#ifndef RASTER_NO_MEDIUM
        medium = area <= float(u_raster_medium_samples);
#endif
    }
    if (medium) {
        uint slot = atomicAdd(raster_medium_count, 1u);
        if (slot < u_raster_queue_capacity) raster_queue[u_raster_queue_capacity + slot] = uvec2(prim, tri);
        else atomicAdd(raster_medium_overflow, 1u);
    } else {
        uint slot = atomicAdd(raster_large_count, 1u);
        if (slot < u_raster_queue_capacity) raster_queue[slot] = uvec2(prim, tri);
        else atomicAdd(raster_large_overflow, 1u);
    }
}

/* In the RASTER_BIG pass: this invocation's queued triangle and the rows it
 * scans (raster_triangle's first_row, row_step). The first
 * ceil(medium / RASTER_BIG_THREADS) work groups take the medium list, one
 * triangle per thread; each later group takes one large triangle. False:
 * nothing for this invocation. */
bool raster_queued_item(out uvec2 item, out int first_row, out int row_step)
{
    item = uvec2(0u);
    uint g = gl_WorkGroupID.x;
#ifdef RASTER_NO_MEDIUM
    uint q = g;
#else
    uint medium = min(raster_medium_count, u_raster_queue_capacity);
    uint medium_groups = (medium + uint(RASTER_BIG_THREADS) - 1u) / uint(RASTER_BIG_THREADS);
    if (g < medium_groups) {
        uint i = g * uint(RASTER_BIG_THREADS) + gl_LocalInvocationID.x;
        first_row = 0;
        row_step = 1;
        if (i >= medium) return false;
        item = raster_queue[u_raster_queue_capacity + i];
        return true;
    }
    uint q = g - medium_groups;
#endif
    first_row = int(gl_LocalInvocationID.x);
    row_step = RASTER_BIG_THREADS;
    if (q >= min(raster_large_count, u_raster_queue_capacity)) return false;
    item = raster_queue[q];
    return true;
}

#endif

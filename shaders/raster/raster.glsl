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
 * together), large ones one per work group of RASTER_BIG_THREADS
 * (near-plane crossings clipped there): one row per invocation in turn, or,
 * where the shader defines RASTER_GROUP_SCAN, the invocations share out the
 * covered pixels (raster_scan_group). Measured on the H100 (meadow_large):
 * the shared scan takes billboards' short, wide triangles from 4.75 to
 * 2.94 ms but blades' tall, thin ones from 1.31 to 1.57 ms
 * (docs/RASTER.md), so each shader chooses. A shader that defines
 * RASTER_NO_MEDIUM queues everything it does not scan at once on the large
 * list (compiled out, not just a threshold).
 *
 * Bands (RASTER_BANDS): a large triangle in front of the near plane whose
 * box covers more than RASTER_BAND_SPLIT_SAMPLES is queued once per band
 * of RASTER_BAND_ROWS pixel rows that its box touches, so that a billboard
 * filling the screen is spread over as many work groups as it has bands
 * instead of holding one while the rest of the GPU waits. H100, 2 km world
 * in billboard mode: frame p99 8.86 -> 5.49 ms, bb.raster's median +1 %
 * (docs/RASTER.md). Blades, whose large triangles are few, do without:
 * the loop alone cost blade.raster 14 %. Splitting near-plane crossings
 * by the box of their part in front cost billboards 10 % at the median,
 * so they stay whole. */
#ifndef RASTER_GLSL
#define RASTER_GLSL

#include "raster/raster_frame.glsl"

/* Invocations per work group of the RASTER_BIG pass (a shader without the
 * medium list may choose its own: raster.c sizes only the medium groups). */
#ifndef RASTER_BIG_THREADS
#define RASTER_BIG_THREADS 64
#endif
/* Pixel rows per band of a large triangle (RASTER_BANDS); at least
 * ceil(height / 255) so that the band fits the item's top 8 bits, whose
 * last value (RASTER_BAND_ALL) stands for every row. */
#ifndef RASTER_BAND_ROWS
#define RASTER_BAND_ROWS RASTER_BIG_THREADS
#endif
/* A large triangle whose box (the part in front of the near plane) covers
 * more samples than this is queued in bands, a smaller one once: about
 * 256 samples per invocation of its work group. */
#ifndef RASTER_BAND_SPLIT_SAMPLES
#define RASTER_BAND_SPLIT_SAMPLES (RASTER_BIG_THREADS * 256)
#endif
#define RASTER_BAND_ALL 255

layout(std430, binding = RASTER_BIND_VIS) buffer RasterVis {
#ifdef RASTER_ATOMIC64
    uint64_t raster_vis[];
#else
    uint raster_vis[];
#endif
};

/* Large count and overflow, medium count and overflow, then the large
 * list (u_raster_queue_capacity (primitive, triangle | band << 24) pairs:
 * a shader's triangle word stays below 1 << 24) and the medium list (as
 * many (primitive, triangle)); see raster.c. */
layout(std430, binding = RASTER_BIND_QUEUE) buffer RasterQueue {
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

/* A projected triangle set up for scanning: the edge functions, at a
 * sample point (x, y), l = A x + (B y + C) are the unnormalised weights of
 * its vertices a, b, c; its box in pixels; depth and 1 / w per vertex. */
struct raster_tri {
    vec3 A, B, C;
    vec2 lo, hi;
    vec3 z, iw;
};

/* False for a degenerate (zero-area) triangle. */
bool raster_tri_setup(raster_vert a, raster_vert b, raster_vert c, out raster_tri t)
{
    vec2 p0 = a.p.xy, p1 = b.p.xy, p2 = c.p.xy;
    float det = (p1.y - p2.y) * (p0.x - p2.x) + (p2.x - p1.x) * (p0.y - p2.y);
    t.A = t.B = t.C = t.z = t.iw = vec3(0.0);
    t.lo = t.hi = vec2(0.0);
    if (abs(det) < 1e-10) return false;
    float id = 1.0 / det;
    t.A = vec3(p1.y - p2.y, p2.y - p0.y, 0.0) * id;
    t.B = vec3(p2.x - p1.x, p0.x - p2.x, 0.0) * id;
    t.A.z = -t.A.x - t.A.y;
    t.B.z = -t.B.x - t.B.y;
    t.C = vec3(-(t.A.x * p2.x + t.B.x * p2.y), -(t.A.y * p2.x + t.B.y * p2.y), 0.0);
    t.C.z = 1.0 - t.C.x - t.C.y;
    t.lo = min(p0, min(p1, p2));
    t.hi = max(p0, max(p1, p2));
    t.z = vec3(a.p.z, b.p.z, c.p.z);
    t.iw = vec3(a.inv_w, b.inv_w, c.inv_w);
    return true;
}

/* Lattice k's sample position within a pixel (pixel rate: the centre). */
vec2 raster_lattice_offset(int k)
{
#ifdef RASTER_PIXEL_RATE
    return vec2(0.5);
#else
    return raster_offset(k) + 0.5;
#endif
}

/* The pixel rows this invocation may scan: a large triangle's band in
 * the RASTER_BIG pass (raster_queued_item), else all. */
ivec2 raster_band = ivec2(0, 1 << 30);

/* Pixel rows per band of a large triangle on this target. */
int raster_band_rows() { return max(RASTER_BAND_ROWS, (u_raster_pixels.y + 254) / 255); }

/* Rows [y0, y1] of the triangle on the lattice at offset o, within the
 * band. */
void raster_tri_rows(raster_tri t, vec2 o, out int y0, out int y1)
{
    y0 = max(int(ceil(t.lo.y - o.y)), max(raster_band.x, 0));
    y1 = min(int(floor(t.hi.y - o.y)), min(raster_band.y, u_raster_pixels.y - 1));
}

/* Row y's edge functions on the lattice at offset o, without the x term:
 * l = A x + K. */
vec3 raster_tri_row(raster_tri t, int y, vec2 o) { return t.B * (float(y) + o.y) + t.C; }

/* Columns [x0, x1] of the row with edge functions K on the lattice at
 * offset o (x1 < x0: none). */
void raster_tri_span(raster_tri t, vec3 K, vec2 o, out int x0, out int x1)
{
    float lo = t.lo.x, hi = t.hi.x;
    for (int i = 0; i < 3; i++) {
        if (t.A[i] > 0.0) lo = max(lo, -K[i] / t.A[i]);
        else if (t.A[i] < 0.0) hi = min(hi, -K[i] / t.A[i]);
        else if (K[i] < 0.0) hi = lo - 1.0;
    }
    x0 = max(int(ceil(lo - o.x)), 0);
    x1 = min(int(floor(hi - o.x)), u_raster_pixels.x - 1);
}

/* The fragment of sample `s` at column x of the row with edge functions K
 * (lattice offset o), when its depth is in range; weights are to_tri *
 * (perspective-correct weights of a, b, c). */
void raster_tri_pixel(raster_tri t, mat3 to_tri, vec3 K, int x, int s, vec2 o)
{
    vec3 l = max(t.A * (float(x) + o.x) + K, vec3(0.0));
    float depth = dot(l, t.z) / max(l.x + l.y + l.z, 1e-20);
    if (!(depth >= 0.0 && depth <= 1.0)) return;
    vec3 q = l * t.iw;
    raster_fragment(s, to_tri * (q / max(q.x + q.y + q.z, 1e-30)), depth);
}

/* Scans rows first_row, first_row + row_step, ... of the projected
 * triangle a b c on every lattice (each lattice's rows from its first). A
 * sample on a shared edge may be drawn by both triangles (same depth: no
 * artefact). */
void raster_scan(raster_vert a, raster_vert b, raster_vert c, mat3 to_tri, int first_row, int row_step)
{
    raster_tri t;
    if (!raster_tri_setup(a, b, c, t)) return;
    for (int k = 0; k < raster_lattices(); k++) {
        vec2 o = raster_lattice_offset(k);
        int y0, y1;
        raster_tri_rows(t, o, y0, y1);
        for (int y = y0 + first_row; y <= y1; y += row_step) {
            vec3 K = raster_tri_row(t, y, o);
            int x0, x1;
            raster_tri_span(t, K, o, x0, x1);
            int base = y * u_raster_pixels.x * u_raster_samples + k;
            for (int x = x0; x <= x1; x++) raster_tri_pixel(t, to_tri, K, x, base + x * u_raster_samples, o);
        }
    }
}

/* Distance of a clip-space point in front of the near plane (z = -w). */
float raster_near(vec4 c) { return c.z + c.w; }

#if defined(RASTER_BIG) && defined(RASTER_GROUP_SCAN)
shared int raster_span_x0[RASTER_BIG_THREADS];
shared int raster_span_start[RASTER_BIG_THREADS + 1];

/* The same scan by the whole work group (every invocation calls it with
 * the same triangle): per block of RASTER_BIG_THREADS rows, each invocation
 * finds one row's span, a prefix sum lays the spans end to end, and the
 * invocations take the covered pixels in turn, so every lane works on a
 * covered pixel whatever the triangle's shape (one row per lane left most
 * lanes idle on the billboards' short, wide triangles). */
void raster_scan_group(raster_vert a, raster_vert b, raster_vert c, mat3 to_tri)
{
    raster_tri t;
    if (!raster_tri_setup(a, b, c, t)) return;
    int lane = int(gl_LocalInvocationID.x);
    for (int k = 0; k < raster_lattices(); k++) {
        vec2 o = raster_lattice_offset(k);
        int y0, y1;
        raster_tri_rows(t, o, y0, y1);
        for (int base = y0; base <= y1; base += RASTER_BIG_THREADS) {
            int x0 = 0, x1 = -1;
            if (base + lane <= y1) raster_tri_span(t, raster_tri_row(t, base + lane, o), o, x0, x1);
            raster_span_x0[lane] = x0;
            raster_span_start[lane + 1] = max(x1 - x0 + 1, 0);
            barrier();
            if (lane == 0) {
                raster_span_start[0] = 0;
                for (int i = 1; i <= RASTER_BIG_THREADS; i++) raster_span_start[i] += raster_span_start[i - 1];
            }
            barrier();
            int total = raster_span_start[RASTER_BIG_THREADS];
            for (int i = lane; i < total; i += RASTER_BIG_THREADS) {
                /* The last row starting at or before pixel i (rows without
                 * pixels start where the next one does). */
                int lo = 0, hi = RASTER_BIG_THREADS - 1;
                while (lo < hi) {
                    int mid = (lo + hi + 1) / 2;
                    if (raster_span_start[mid] <= i) lo = mid;
                    else hi = mid - 1;
                }
                int x = raster_span_x0[lo] + i - raster_span_start[lo], y = base + lo;
                int s = (y * u_raster_pixels.x + x) * u_raster_samples + k;
                raster_tri_pixel(t, to_tri, raster_tri_row(t, y, o), x, s, o);
            }
            barrier();
        }
    }
}

#endif

#ifdef RASTER_BIG
/* In the RASTER_BIG pass: scans the triangle with clip-space vertices c0
 * c1 c2 in this invocation, or with the whole work group (`group`, the same
 * for every invocation of the group): its invocations share out the
 * covered pixels with RASTER_GROUP_SCAN (raster_scan_group), else take one
 * row each in turn. Clipped against the near plane first: the polygon in
 * front of it (the triangle itself, or up to 4 vertices where it crosses)
 * is scanned as a fan whose weights map back to c0 c1 c2; one call site of
 * the scan, which the compiler inlines. */
void raster_triangle(vec4 c0, vec4 c1, vec4 c2, bool group)
{
    vec4 c[3] = vec4[3](c0, c1, c2);
    vec3 d = vec3(raster_near(c0), raster_near(c1), raster_near(c2));
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
    int first_row = 0, row_step = 1;
#ifndef RASTER_GROUP_SCAN
    if (group) {
        first_row = int(gl_LocalInvocationID.x);
        row_step = RASTER_BIG_THREADS;
    }
#endif
    for (int i = 1; i + 1 < n; i++) {
        mat3 to_tri = mat3(bary[0], bary[i], bary[i + 1]);
#ifdef RASTER_GROUP_SCAN
        if (group) {
            raster_scan_group(pv[0], pv[i], pv[i + 1], to_tri);
            continue;
        }
#endif
        raster_scan(pv[0], pv[i], pv[i + 1], to_tri, first_row, row_step);
    }
}

#endif

/* In the per-primitive pass: scans a triangle whose box covers at most
 * `small` samples now, or queues it (prim, tri) on the medium or the large
 * list (large also when it crosses the near plane). Triangles wholly
 * behind the near plane vanish. A primitive of many triangles passes its
 * share of u_raster_small_samples, so that its thread does not scan them
 * all one after the other while its warp waits. */
void raster_triangle_or_queue_within(vec4 c0, vec4 c1, vec4 c2, uint prim, uint tri, float small)
{
    vec3 d = vec3(raster_near(c0), raster_near(c1), raster_near(c2));
    if (all(lessThan(d, vec3(0.0)))) return;
    bool medium = false;
    vec2 lo = vec2(1e30), hi = vec2(-1e30);
    if (all(greaterThanEqual(d, vec3(0.0))) && c0.w > 0.0 && c1.w > 0.0 && c2.w > 0.0) {
        raster_vert a, b, c;
        raster_project(c0, a);
        raster_project(c1, b);
        raster_project(c2, c);
        lo = min(a.p.xy, min(b.p.xy, c.p.xy));
        hi = max(a.p.xy, max(b.p.xy, c.p.xy));
        float area = raster_box_samples(lo, hi);
        if (area <= small) {
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
        return;
    }
#ifdef RASTER_BANDS
    /* Bands of rows, every lattice's (offsets within the pixel), where the
     * box is large enough; else (near-plane crossings too: their box stays
     * empty) one item for all rows. */
    int band0 = RASTER_BAND_ALL, band1 = RASTER_BAND_ALL;
    if (raster_box_samples(lo, hi) > float(RASTER_BAND_SPLIT_SAMPLES)) {
        int rows = raster_band_rows(), last = u_raster_pixels.y - 1;
        band0 = int(clamp(floor(lo.y) - 1.0, 0.0, float(last))) / rows;
        band1 = int(clamp(floor(hi.y), 0.0, float(last))) / rows;
    }
    uint bands = uint(band1 - band0 + 1);
    uint slot = atomicAdd(raster_large_count, bands);
    for (uint b = 0u; b < bands; b++)
        if (slot + b < u_raster_queue_capacity) raster_queue[slot + b] = uvec2(prim, tri | uint(band0 + int(b)) << 24);
    if (slot + bands > u_raster_queue_capacity)
        atomicAdd(raster_large_overflow, slot + bands - max(slot, u_raster_queue_capacity));
#else
    uint slot = atomicAdd(raster_large_count, 1u);
    if (slot < u_raster_queue_capacity) raster_queue[slot] = uvec2(prim, tri | uint(RASTER_BAND_ALL) << 24);
    else atomicAdd(raster_large_overflow, 1u);
#endif
}

/* raster_triangle_or_queue_within with the whole u_raster_small_samples. */
void raster_triangle_or_queue(vec4 c0, vec4 c1, vec4 c2, uint prim, uint tri)
{
    raster_triangle_or_queue_within(c0, c1, c2, prim, tri, float(u_raster_small_samples));
}

/* In the RASTER_BIG pass: this invocation's queued triangle (a large
 * one's band set in raster_band), and whether
 * the work group scans it together (raster_triangle's `group`). The first
 * ceil(medium / RASTER_BIG_THREADS) work groups take the medium list, one
 * triangle per invocation; each later group takes one large triangle. False:
 * nothing for this invocation (for a large item: for the whole group). */
bool raster_queued_item(out uvec2 item, out bool group)
{
    item = uvec2(0u);
    group = false;
    uint g = gl_WorkGroupID.x;
#ifdef RASTER_NO_MEDIUM
    uint q = g;
#else
    uint medium = min(raster_medium_count, u_raster_queue_capacity);
    uint medium_groups = (medium + uint(RASTER_BIG_THREADS) - 1u) / uint(RASTER_BIG_THREADS);
    if (g < medium_groups) {
        uint i = g * uint(RASTER_BIG_THREADS) + gl_LocalInvocationID.x;
        if (i >= medium) return false;
        item = raster_queue[u_raster_queue_capacity + i];
        return true;
    }
    uint q = g - medium_groups;
#endif
    group = true;
    if (q >= min(raster_large_count, u_raster_queue_capacity)) return false;
    item = raster_queue[q];
    int rows = raster_band_rows(), band = int(item.y >> 24);
    if (band != RASTER_BAND_ALL) raster_band = ivec2(band * rows, band * rows + rows - 1);
    item.y &= 0xffffffu;
    return true;
}

#endif

/* raster_ref: CPU twin of shaders/raster/raster.glsl (raster_triangle,
 * raster_scan, raster_put); see raster_ref.h. */
#include "raster/raster_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct vert_t {
    float x, y, z, inv_w;
} vert_t;

bool raster_ref_init(raster_ref_t *r, int w, int h, int samples, float depth)
{
    size_t n = (size_t)w * (size_t)h * (size_t)samples;
    *r = (raster_ref_t){.w = w, .h = h, .samples = samples, .colour = calloc(n, 4), .depth = malloc(n * 4)};
    if (!r->colour || !r->depth) {
        raster_ref_free(r);
        return false;
    }
    uint32_t bits;
    memcpy(&bits, &depth, 4);
    for (size_t i = 0; i < n; i++) r->depth[i] = bits;
    return true;
}

void raster_ref_free(raster_ref_t *r)
{
    free(r->colour);
    free(r->depth);
    memset(r, 0, sizeof *r);
}

void raster_ref_sample_offset(int samples, int k, float out[2])
{
    static const float o4[4][2] = {{-2, -6}, {6, -2}, {-6, 2}, {2, 6}};
    out[0] = samples == 4 ? o4[k][0] / 16.0f : 0.0f;
    out[1] = samples == 4 ? o4[k][1] / 16.0f : 0.0f;
}

static void put(raster_ref_t *r, int s, float depth, uint32_t rgba)
{
    uint32_t bits;
    memcpy(&bits, &depth, 4);
    if (bits < r->depth[s] || (bits == r->depth[s] && rgba < r->colour[s])) {
        r->depth[s] = bits;
        r->colour[s] = rgba;
    }
}

static vert_t project(const raster_ref_t *r, const float c[4])
{
    float iw = 1.0f / c[3];
    return (vert_t){(c[0] * iw * 0.5f + 0.5f) * (float)r->w, (c[1] * iw * 0.5f + 0.5f) * (float)r->h,
                    c[2] * iw * 0.5f + 0.5f, iw};
}

static void scan(raster_ref_t *r, vert_t a, vert_t b, vert_t c, uint32_t rgba)
{
    float det = (b.y - c.y) * (a.x - c.x) + (c.x - b.x) * (a.y - c.y);
    if (fabsf(det) < 1e-10f) return;
    float id = 1.0f / det;
    float A[3] = {(b.y - c.y) * id, (c.y - a.y) * id, 0}, B[3] = {(c.x - b.x) * id, (a.x - c.x) * id, 0};
    A[2] = -A[0] - A[1];
    B[2] = -B[0] - B[1];
    float C[3] = {-(A[0] * c.x + B[0] * c.y), -(A[1] * c.x + B[1] * c.y), 0};
    C[2] = 1.0f - C[0] - C[1];
    float ylo = fminf(a.y, fminf(b.y, c.y)), yhi = fmaxf(a.y, fmaxf(b.y, c.y));
    float xlo = fminf(a.x, fminf(b.x, c.x)), xhi = fmaxf(a.x, fmaxf(b.x, c.x));
    float z[3] = {a.z, b.z, c.z};
    for (int k = 0; k < r->samples; k++) {
        float o[2];
        raster_ref_sample_offset(r->samples, k, o);
        o[0] += 0.5f;
        o[1] += 0.5f;
        int y0 = (int)fmaxf(ceilf(ylo - o[1]), 0.0f), y1 = (int)fminf(floorf(yhi - o[1]), (float)(r->h - 1));
        for (int y = y0; y <= y1; y++) {
            float yc = (float)y + o[1], K[3], lo = xlo, hi = xhi;
            for (int i = 0; i < 3; i++) {
                K[i] = B[i] * yc + C[i];
                if (A[i] > 0.0f) lo = fmaxf(lo, -K[i] / A[i]);
                else if (A[i] < 0.0f) hi = fminf(hi, -K[i] / A[i]);
                else if (K[i] < 0.0f) hi = lo - 1.0f;
            }
            int x0 = (int)fmaxf(ceilf(lo - o[0]), 0.0f), x1 = (int)fminf(floorf(hi - o[0]), (float)(r->w - 1));
            for (int x = x0; x <= x1; x++) {
                float l[3], sum = 0.0f, d = 0.0f;
                for (int i = 0; i < 3; i++) {
                    l[i] = fmaxf(A[i] * ((float)x + o[0]) + K[i], 0.0f);
                    sum += l[i];
                    d += l[i] * z[i];
                }
                d /= fmaxf(sum, 1e-20f);
                if (!(d >= 0.0f && d <= 1.0f)) continue;
                put(r, (y * r->w + x) * r->samples + k, d, rgba);
            }
        }
    }
}

void raster_ref_triangle(raster_ref_t *r, const float c0[4], const float c1[4], const float c2[4], uint32_t rgba)
{
    const float *c[3] = {c0, c1, c2};
    float d[3];
    bool all_in = true;
    for (int i = 0; i < 3; i++) {
        d[i] = c[i][2] + c[i][3];
        all_in = all_in && d[i] >= 0.0f && c[i][3] > 0.0f;
    }
    if (all_in) {
        scan(r, project(r, c0), project(r, c1), project(r, c2), rgba);
        return;
    }
    float poly[4][4];
    int n = 0;
    for (int i = 0; i < 3; i++) {
        int j = (i + 1) % 3;
        if (d[i] >= 0.0f) memcpy(poly[n++], c[i], sizeof poly[0]);
        if ((d[i] >= 0.0f) != (d[j] >= 0.0f)) {
            float t = d[i] / (d[i] - d[j]);
            for (int k = 0; k < 4; k++) poly[n][k] = c[i][k] + (c[j][k] - c[i][k]) * t;
            n++;
        }
    }
    if (n < 3) return;
    vert_t pv[4];
    for (int i = 0; i < n; i++) {
        if (!(poly[i][3] > 0.0f)) return;
        pv[i] = project(r, poly[i]);
    }
    for (int i = 1; i + 1 < n; i++) scan(r, pv[0], pv[i], pv[i + 1], rgba);
}

/* raster_ref: CPU twin of shaders/raster/raster.glsl (raster_triangle,
 * raster_scan, raster_put); see raster_ref.h. */
#include "raster/raster_ref.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct vert_t {
    float x, y, z, inv_w;
} vert_t;

bool raster_ref_init(raster_ref_t *r, int w, int h, int ss, float depth)
{
    size_t n = (size_t)w * (size_t)h * (size_t)(ss * ss);
    *r = (raster_ref_t){.w = w, .h = h, .ss = ss, .colour = calloc(n, 4), .depth = malloc(n * 4)};
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

int raster_ref_sample_index(const raster_ref_t *r, int x, int y)
{
    int ss = r->ss, px = x / ss, py = y / ss;
    return ((py * r->w + px) * ss + (y - py * ss)) * ss + (x - px * ss);
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
    return (vert_t){(c[0] * iw * 0.5f + 0.5f) * (float)(r->w * r->ss), (c[1] * iw * 0.5f + 0.5f) * (float)(r->h * r->ss),
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
    int sw = r->w * r->ss, sh = r->h * r->ss;
    float ylo = fminf(a.y, fminf(b.y, c.y)), yhi = fmaxf(a.y, fmaxf(b.y, c.y));
    float xlo = fminf(a.x, fminf(b.x, c.x)), xhi = fmaxf(a.x, fmaxf(b.x, c.x));
    int y0 = (int)fmaxf(ceilf(ylo - 0.5f), 0.0f), y1 = (int)fminf(floorf(yhi - 0.5f), (float)(sh - 1));
    float z[3] = {a.z, b.z, c.z};
    for (int y = y0; y <= y1; y++) {
        float yc = (float)y + 0.5f, K[3], lo = xlo, hi = xhi;
        for (int i = 0; i < 3; i++) {
            K[i] = B[i] * yc + C[i];
            if (A[i] > 0.0f) lo = fmaxf(lo, -K[i] / A[i]);
            else if (A[i] < 0.0f) hi = fminf(hi, -K[i] / A[i]);
            else if (K[i] < 0.0f) hi = lo - 1.0f;
        }
        int x0 = (int)fmaxf(ceilf(lo - 0.5f), 0.0f), x1 = (int)fminf(floorf(hi - 0.5f), (float)(sw - 1));
        for (int x = x0; x <= x1; x++) {
            float l[3], sum = 0.0f, d = 0.0f;
            for (int i = 0; i < 3; i++) {
                l[i] = fmaxf(A[i] * ((float)x + 0.5f) + K[i], 0.0f);
                sum += l[i];
                d += l[i] * z[i];
            }
            d /= fmaxf(sum, 1e-20f);
            if (!(d >= 0.0f && d <= 1.0f)) continue;
            put(r, raster_ref_sample_index(r, x, y), d, rgba);
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

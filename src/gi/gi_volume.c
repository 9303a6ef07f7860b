/* gi_volume.c: the ambient-occlusion and irradiance volumes of gi_volume.h.
 * The scene's heights are sampled once on a grid of half a cell (read
 * bilinearly). Per column of cells (x, z): the ground height, the grass
 * cover and the terrain's height profile along every ray azimuth (steps
 * samples out to reach, quadratically spaced so that the near ground is
 * sampled finely), and the height above which every ray clears it.
 * Per cell: the horizon angle of that profile per azimuth, then per ray
 * (azimuth, elevation; elevations at equal steps of sin e, so every ray
 * stands for the same solid angle 2 pi / rays) the transmittance
 * T = terrain x grass x objects:
 *   terrain: a smooth step of width soft around the horizon angle;
 *   grass: exp(-extinction cover (path - grass_near)) for the path through
 *     a layer of the grass's height over locally flat ground;
 *   objects: 0 when the ray meets a box within reach.
 * The sums are the Monte Carlo estimates of gi_volume.h's integrals with
 * a uniform solid-angle density, exact on open ground (A = 1, and a constant
 * sky L gives irradiance pi L facing up). */
#include "gi/gi_volume.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "core/core.h"

#define GI_PI 3.14159265358979f
#define GI_MAX_RAYS 1024

/* The rays of one desc: directions, weights and sky radiance per ray. */
typedef struct gi_rays_t {
    int n, na, ne;
    float dir[GI_MAX_RAYS][3];
    float elev[GI_MAX_RAYS]; /* per elevation: angle */
    float sin_e[GI_MAX_RAYS];
    float sky[GI_MAX_RAYS][3]; /* per elevation: radiance */
} gi_rays_t;

/* max and clamp without libm's NaN rules (fmaxf is a call unless finite
 * math is assumed; these are the volume's inner loops). */
static inline float max2(float a, float b)
{
    return a > b ? a : b;
}

static inline float clamp01(float a)
{
    return a < 0.0f ? 0.0f : (a > 1.0f ? 1.0f : a);
}

static float luminance(const float c[3])
{
    return 0.2126f * c[0] + 0.7152f * c[1] + 0.0722f * c[2];
}

/* sky_color of common/lighting.glsl between the desc's two colours. */
static void sky_radiance(const float zenith[3], const float horizon[3], float dir_y, float out[3])
{
    float t = fminf(fmaxf(dir_y * 1.5f, 0.0f), 1.0f);
    for (int c = 0; c < 3; c++) out[c] = horizon[c] + (zenith[c] - horizon[c]) * t;
}

static void rays_make(gi_rays_t *r, int na, int ne, const float zenith[3], const float horizon[3])
{
    r->na = na;
    r->ne = ne;
    r->n = na * ne;
    for (int j = 0; j < ne; j++) {
        r->sin_e[j] = ((float)j + 0.5f) / (float)ne;
        r->elev[j] = asinf(r->sin_e[j]);
        sky_radiance(zenith, horizon, r->sin_e[j], r->sky[j]);
        float ce = cosf(r->elev[j]);
        for (int a = 0; a < na; a++) {
            float az = 2.0f * GI_PI * ((float)a + 0.5f * (float)(j & 1)) / (float)na;
            float *d = r->dir[j * na + a];
            d[0] = ce * cosf(az);
            d[1] = r->sin_e[j];
            d[2] = ce * sinf(az);
        }
    }
}

/* Up-facing irradiance / pi of the unoccluded sky of r (no scaling), as
 * its first-order projection gives it (cell_eval's a + B.y). */
static void open_sky_up(const gi_rays_t *r, float out[3])
{
    memset(out, 0, 3 * sizeof(float));
    for (int j = 0; j < r->ne; j++)
        for (int c = 0; c < 3; c++) out[c] += r->sky[j][c] * (0.5f + r->sin_e[j]) / (float)r->ne;
}

gi_volume_desc_t gi_volume_desc_defaults(const gi_volume_desc_t *d)
{
    gi_volume_desc_t o = *d;
    static const int res[3] = {64, 16, 64};
    for (int i = 0; i < 3; i++)
        if (o.res[i] <= 0) o.res[i] = res[i];
    if (o.azimuths <= 0) o.azimuths = 8;
    if (o.elevations <= 0) o.elevations = 4;
    if (o.reach <= 0.0f) o.reach = 24.0f;
    if (o.steps <= 0) o.steps = 12;
    if (o.soft <= 0.0f) o.soft = 0.1f;
    static const float down[3] = GI_AMBIENT_DOWN;
    if (luminance(o.bounce) <= 0.0f) memcpy(o.bounce, down, sizeof o.bounce);
    if (luminance(o.sky_zenith) <= 0.0f && luminance(o.sky_horizon) <= 0.0f) {
        static const float zenith[3] = GI_SKY_ZENITH, horizon[3] = GI_SKY_HORIZON, up[3] = GI_AMBIENT_UP;
        gi_rays_t *r = malloc(sizeof *r);
        float scale = 1.0f;
        if (r && o.azimuths * o.elevations <= GI_MAX_RAYS) {
            float e[3];
            rays_make(r, 1, o.elevations, zenith, horizon);
            open_sky_up(r, e);
            scale = luminance(up) / luminance(e);
        }
        free(r);
        for (int c = 0; c < 3; c++) {
            o.sky_zenith[c] = zenith[c] * scale;
            o.sky_horizon[c] = horizon[c] * scale;
        }
    }
    return o;
}

/* Distance along the ray from p in direction d to box o within (0, reach],
 * or a negative number when it misses. */
static float box_hit(const gi_object_t *o, const float p[3], const float d[3], float reach)
{
    float t0 = 0.0f, t1 = reach;
    for (int k = 0; k < 3; k++) {
        if (fabsf(d[k]) < 1e-8f) {
            if (p[k] < o->lo[k] || p[k] > o->hi[k]) return -1.0f;
            continue;
        }
        float a = (o->lo[k] - p[k]) / d[k], b = (o->hi[k] - p[k]) / d[k];
        t0 = fmaxf(t0, fminf(a, b));
        t1 = fminf(t1, fmaxf(a, b));
    }
    return t0 <= t1 ? t0 : -1.0f;
}

/* The ground heights the rays see: the scene's height function sampled
 * once on a grid of half a cell over the volume and reach around it, read
 * bilinearly (no ground: GI_NO_GROUND). */
#define GI_NO_GROUND -1e30f
typedef struct gi_heights_t {
    float x0, z0, inv; /* the grid's first sample, 1 / spacing */
    int nx, nz;
    float *h;
} gi_heights_t;

static bool heights_make(gi_heights_t *g, const gi_volume_desc_t *d, const gi_scene_t *s)
{
    float cell = fminf((d->hi[0] - d->lo[0]) / (float)d->res[0], (d->hi[2] - d->lo[2]) / (float)d->res[2]);
    float spacing = 0.5f * cell;
    g->x0 = d->lo[0] - d->reach - spacing;
    g->z0 = d->lo[2] - d->reach - spacing;
    g->inv = 1.0f / spacing;
    g->nx = (int)ceilf((d->hi[0] - d->lo[0] + 2.0f * d->reach) / spacing) + 3;
    g->nz = (int)ceilf((d->hi[2] - d->lo[2] + 2.0f * d->reach) / spacing) + 3;
    g->h = malloc(sizeof(float) * (size_t)g->nx * (size_t)g->nz);
    if (!g->h) return false;
    for (int j = 0; j < g->nz; j++)
        for (int i = 0; i < g->nx; i++) {
            float x = g->x0 + (float)i * spacing, z = g->z0 + (float)j * spacing;
            float h = s->height ? s->height(s->user, x, z) : d->lo[1];
            g->h[(size_t)j * (size_t)g->nx + (size_t)i] = isfinite(h) && h > GI_NO_GROUND ? h : GI_NO_GROUND;
        }
    return true;
}

static float heights_at(const gi_heights_t *g, float x, float z)
{
    float u = (x - g->x0) * g->inv, w = (z - g->z0) * g->inv;
    int i = (int)u, j = (int)w;
    i = i < 0 ? 0 : (i > g->nx - 2 ? g->nx - 2 : i);
    j = j < 0 ? 0 : (j > g->nz - 2 ? g->nz - 2 : j);
    float fu = clamp01(u - (float)i), fw = clamp01(w - (float)j);
    const float *r0 = g->h + (size_t)j * (size_t)g->nx + (size_t)i, *r1 = r0 + g->nx;
    return (r0[0] + (r0[1] - r0[0]) * fu) * (1.0f - fw) + (r1[0] + (r1[1] - r1[0]) * fu) * fw;
}

/* One column's inputs: ground, cover, the terrain profile per azimuth and
 * the objects within reach. */
typedef struct gi_column_t {
    float x, z, ground, cover;
    float *profile;        /* na * steps heights */
    const float *inv_dist; /* steps inverse distances */
    const gi_heights_t *heights;
    float open_y;          /* above this every ray clears the terrain (horizon() returns low) */
    int near_objects[64];
    int near_count;
} gi_column_t;

/* tan_low: the tangent of cell_eval's low horizon. */
static void column_make(gi_column_t *col, const gi_volume_desc_t *d, const gi_scene_t *s, const gi_rays_t *r,
                        float tan_low)
{
    col->ground = heights_at(col->heights, col->x, col->z);
    col->cover = s->cover ? fminf(fmaxf(s->cover(s->user, col->x, col->z), 0.0f), 1.0f) : 1.0f;
    col->open_y = col->ground;
    for (int a = 0; a < r->na; a++) {
        float az = 2.0f * GI_PI * (float)a / (float)r->na, cx = cosf(az), sz = sinf(az);
        for (int k = 0; k < d->steps; k++) {
            float dist = 1.0f / col->inv_dist[k];
            float h = heights_at(col->heights, col->x + cx * dist, col->z + sz * dist);
            col->profile[a * d->steps + k] = h;
            col->open_y = max2(col->open_y, h - tan_low * dist);
        }
    }
    col->near_count = 0;
    for (int i = 0; i < s->object_count && col->near_count < 64; i++) {
        const gi_object_t *o = &s->objects[i];
        float dx = fmaxf(fmaxf(o->lo[0] - col->x, col->x - o->hi[0]), 0.0f);
        float dz = fmaxf(fmaxf(o->lo[2] - col->z, col->z - o->hi[2]), 0.0f);
        if (dx * dx + dz * dz <= d->reach * d->reach) col->near_objects[col->near_count++] = i;
    }
}

/* The horizon angle of azimuth a seen from height y; horizons below
 * `low` (where every ray is wholly visible) are returned as `low`. */
static float horizon(const gi_column_t *col, const gi_volume_desc_t *d, int a, float y, float low)
{
    float s = -FLT_MAX;
    const float *h = col->profile + a * d->steps;
    for (int k = 0; k < d->steps; k++) s = max2(s, (h[k] - y) * col->inv_dist[k]);
    return s <= low ? low : atanf(s);
}

/* Accumulates one cell at height y: ao and irradiance into out. */
static void cell_eval(const gi_column_t *col, const gi_volume_desc_t *d, const gi_scene_t *s, const gi_rays_t *r,
                      float y, float *ao, float irr[GI_IRR_FLOATS])
{
    float p[3] = {col->x, fmaxf(y, col->ground + 0.02f), col->z};
    /* Profile azimuths run at whole steps; odd elevation rows sit half a
     * step off, between two. A horizon below low = e_0 - soft / 2 hides
     * nothing (tan low < low: the test needs no arc tangent). */
    float above = p[1] - col->ground, hz[GI_MAX_RAYS], low = r->elev[0] - 0.5f * d->soft;
    for (int a = 0; a < r->na; a++) hz[a] = p[1] >= col->open_y ? low : horizon(col, d, a, p[1], low);
    float sum_ao = 0.0f, m0[3] = {0}, m1[3][3] = {{0}};
    for (int j = 0; j < r->ne; j++) {
        float tg = 1.0f;
        if (above < s->grass_height) {
            float path = (s->grass_height - above) / r->sin_e[j];
            tg = expf(-s->grass_extinction * col->cover * fmaxf(path - s->grass_near, 0.0f));
        }
        float st = 0.0f, sd[3] = {0}, inv_soft = 1.0f / d->soft;
        for (int a = 0; a < r->na; a++) {
            const float *dir = r->dir[j * r->na + a];
            float h = (j & 1) ? 0.5f * (hz[a] + hz[a + 1 == r->na ? 0 : a + 1]) : hz[a];
            float t = clamp01((r->elev[j] - h) * inv_soft + 0.5f) * tg;
            for (int i = 0; i < col->near_count && t > 0.0f; i++)
                if (box_hit(&s->objects[col->near_objects[i]], p, dir, d->reach) >= 0.0f) t = 0.0f;
            st += t;
            for (int k = 0; k < 3; k++) sd[k] += t * dir[k];
        }
        sum_ao += st * r->sin_e[j];
        for (int c = 0; c < 3; c++) {
            m0[c] += st * r->sky[j][c];
            for (int k = 0; k < 3; k++) m1[k][c] += sd[k] * r->sky[j][c];
        }
    }
    float w = 2.0f * GI_PI / (float)r->n;
    *ao = 2.0f * sum_ao / (float)r->n;
    for (int c = 0; c < 3; c++) {
        irr[c] = m0[c] * w / (4.0f * GI_PI);
        for (int k = 0; k < 3; k++) irr[3 + 3 * k + c] = m1[k][c] * w / (2.0f * GI_PI);
    }
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static bool desc_valid(const gi_volume_desc_t *d)
{
    for (int i = 0; i < 3; i++)
        if (!(d->hi[i] > d->lo[i]) || d->res[i] > 1024) return false;
    return d->azimuths * d->elevations <= GI_MAX_RAYS && d->steps <= 256;
}

bool gi_volume_make(gi_volume_t *v, const gi_volume_desc_t *desc, const gi_scene_t *scene)
{
    double t0 = now_ms();
    memset(v, 0, sizeof *v);
    gi_volume_desc_t d = gi_volume_desc_defaults(desc);
    if (!desc_valid(&d)) {
        core_log_error("gi: bad volume (box, resolution at most 1024, at most %d rays)", GI_MAX_RAYS);
        return false;
    }
    gi_scene_t s = *scene;
    if (s.grass_near <= 0.0f) s.grass_near = (d.hi[0] - d.lo[0]) / (float)d.res[0];
    size_t cells = (size_t)d.res[0] * (size_t)d.res[1] * (size_t)d.res[2];
    gi_rays_t *r = malloc(sizeof *r);
    float *profile = malloc(sizeof(float) * (size_t)(d.azimuths * d.steps)), inv_dist[256];
    gi_heights_t heights;
    bool have_heights = heights_make(&heights, &d, &s);
    v->ao = malloc(sizeof(float) * cells);
    v->irr = malloc(sizeof(float) * GI_IRR_FLOATS * cells);
    if (!r || !profile || !have_heights || !v->ao || !v->irr) {
        free(r);
        free(profile);
        free(heights.h);
        gi_volume_free(v);
        core_log_error("gi: out of memory for a %dx%dx%d volume", d.res[0], d.res[1], d.res[2]);
        return false;
    }
    rays_make(r, d.azimuths, d.elevations, d.sky_zenith, d.sky_horizon);
    for (int k = 0; k < d.steps; k++) inv_dist[k] = 1.0f / (d.reach * powf((float)(k + 1) / (float)d.steps, 2.0f));
    memcpy(v->res, d.res, sizeof v->res);
    memcpy(v->lo, d.lo, sizeof v->lo);
    memcpy(v->hi, d.hi, sizeof v->hi);
    memcpy(v->bounce, d.bounce, sizeof v->bounce);
    float cell[3];
    for (int i = 0; i < 3; i++) cell[i] = (d.hi[i] - d.lo[i]) / (float)d.res[i];
    /* A cell whose rays all clear the terrain, above the grass and with no
     * object within reach sees the open sky: evaluated once. */
    gi_column_t col = {.profile = profile, .inv_dist = inv_dist, .heights = &heights, .ground = GI_NO_GROUND,
                       .open_y = GI_NO_GROUND};
    float open_ao, open_irr[GI_IRR_FLOATS], tan_low = tanf(r->elev[0] - 0.5f * d.soft);
    cell_eval(&col, &d, &s, r, 0.0f, &open_ao, open_irr);
    for (int iz = 0; iz < d.res[2]; iz++)
        for (int ix = 0; ix < d.res[0]; ix++) {
            col.x = d.lo[0] + ((float)ix + 0.5f) * cell[0];
            col.z = d.lo[2] + ((float)iz + 0.5f) * cell[2];
            column_make(&col, &d, &s, r, tan_low);
            for (int iy = 0; iy < d.res[1]; iy++) {
                size_t c = ((size_t)iz * (size_t)d.res[1] + (size_t)iy) * (size_t)d.res[0] + (size_t)ix;
                float y = d.lo[1] + ((float)iy + 0.5f) * cell[1];
                if (y >= col.open_y && y >= col.ground + s.grass_height && col.near_count == 0) {
                    v->ao[c] = open_ao;
                    memcpy(&v->irr[c * GI_IRR_FLOATS], open_irr, sizeof open_irr);
                } else {
                    cell_eval(&col, &d, &s, r, y, &v->ao[c], &v->irr[c * GI_IRR_FLOATS]);
                }
            }
        }
    free(r);
    free(profile);
    free(heights.h);
    v->build_ms = now_ms() - t0;
    return true;
}

void gi_volume_free(gi_volume_t *v)
{
    free(v->ao);
    free(v->irr);
    memset(v, 0, sizeof *v);
}

void gi_volume_sample(const gi_volume_t *v, const float pos[3], float *ao, float irr[GI_IRR_FLOATS])
{
    int i0[3], i1[3];
    float f[3];
    for (int k = 0; k < 3; k++) {
        float u = (pos[k] - v->lo[k]) / (v->hi[k] - v->lo[k]) * (float)v->res[k] - 0.5f;
        float fl = floorf(u);
        f[k] = u - fl;
        int i = (int)fl;
        i0[k] = i < 0 ? 0 : (i > v->res[k] - 1 ? v->res[k] - 1 : i);
        i1[k] = i + 1 < 0 ? 0 : (i + 1 > v->res[k] - 1 ? v->res[k] - 1 : i + 1);
    }
    *ao = 0.0f;
    memset(irr, 0, sizeof(float) * GI_IRR_FLOATS);
    for (int corner = 0; corner < 8; corner++) {
        int ix = corner & 1 ? i1[0] : i0[0], iy = corner & 2 ? i1[1] : i0[1], iz = corner & 4 ? i1[2] : i0[2];
        float w = (corner & 1 ? f[0] : 1.0f - f[0]) * (corner & 2 ? f[1] : 1.0f - f[1]) *
                  (corner & 4 ? f[2] : 1.0f - f[2]);
        size_t c = ((size_t)iz * (size_t)v->res[1] + (size_t)iy) * (size_t)v->res[0] + (size_t)ix;
        *ao += w * v->ao[c];
        for (int k = 0; k < GI_IRR_FLOATS; k++) irr[k] += w * v->irr[c * GI_IRR_FLOATS + k];
    }
}

void gi_volume_ambient(const gi_volume_t *v, const float pos[3], const float n[3], float out[3])
{
    float ao, irr[GI_IRR_FLOATS];
    gi_volume_sample(v, pos, &ao, irr);
    float hidden = 1.0f - ao * (1.0f + n[1]) * 0.5f;
    for (int c = 0; c < 3; c++) {
        float e = irr[c] + n[0] * irr[3 + c] + n[1] * irr[6 + c] + n[2] * irr[9 + c];
        out[c] = fmaxf(e + v->bounce[c] * hidden, 0.0f);
    }
}

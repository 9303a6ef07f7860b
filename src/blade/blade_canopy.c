/* blade_canopy: the ground canopy's table measured on the blade model by
 * ray casting a settled, periodic patch of blades (see blade_canopy.h).
 *
 * Rays look along +x, so a ray keeps its z: the patch's triangles are
 * binned into strips of z (a triangle that crosses the patch's z border is
 * binned once more, shifted by the patch side), and a ray tests the
 * triangles of its strip in the periodic copies along x that its x span
 * crosses, copy by copy, nearest first, until a hit lies before the next
 * copy can begin. Intersection: Moller-Trumbore. The rays' frame is the
 * ground's (blade_canopy_row_t): t = -x, g = +y, s = +z. */
#include "blade/blade_canopy.h"

#include "blade/blade_ref.h"
#include "core/core.h"

#include <assert.h>
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define CANOPY_STRIPS 64
#define CANOPY_SETTLE_STEPS 90 /* 1.5 s at 60 Hz, as the clump layers settle */

typedef struct canopy_tri_t {
    float p[3][3], n[3][3], v[3];
    float xlo, xhi;
} canopy_tri_t;

typedef struct canopy_entry_t {
    uint32_t tri;
    float zshift;
} canopy_entry_t;

typedef struct canopy_strip_t {
    canopy_entry_t *e;
    int count, cap;
    float xlo, xhi; /* over its entries */
} canopy_strip_t;

blade_canopy_desc_t blade_canopy_desc_defaults(const blade_canopy_desc_t *desc)
{
    blade_canopy_desc_t d = *desc;
    d.population = blade_population_defaults(&d.population);
    if (d.rows <= 0) d.rows = 16;
    if (d.rays <= 0) d.rays = 4096;
    if (d.segments <= 0) d.segments = BLADE_CANOPY_SEGMENTS;
    if (d.patches <= 0) d.patches = BLADE_CANOPY_PATCHES;
    /* A denser field gets a smaller patch of at most BLADE_CANOPY_PATCH_BLADES
     * blades: every ray meets the blades of its strip, so the bake grew with
     * the density (10,000 blades/m^2 took 47 s on 2 cores for 2 m). */
    if (d.patch <= 0.0f) d.patch = fminf(2.0f, sqrtf(BLADE_CANOPY_PATCH_BLADES / d.population.density));
    return d;
}

static bool strip_add(canopy_strip_t *s, uint32_t tri, float zshift, const canopy_tri_t *t)
{
    if (s->count == s->cap) {
        int cap = s->cap ? 2 * s->cap : 64;
        canopy_entry_t *e = realloc(s->e, sizeof *e * (size_t)cap);
        if (!e) return false;
        s->e = e;
        s->cap = cap;
    }
    s->e[s->count++] = (canopy_entry_t){tri, zshift};
    s->xlo = s->count == 1 ? t->xlo : fminf(s->xlo, t->xlo);
    s->xhi = s->count == 1 ? t->xhi : fmaxf(s->xhi, t->xhi);
    return true;
}

/* Bins triangle i into the strips its z range covers, in the patch and in
 * the copies one side beyond either z border. */
static bool bin_triangle(canopy_strip_t *strips, const canopy_tri_t *t, uint32_t i, float patch)
{
    float zlo = fminf(t->p[0][2], fminf(t->p[1][2], t->p[2][2]));
    float zhi = fmaxf(t->p[0][2], fmaxf(t->p[1][2], t->p[2][2]));
    for (int k = -1; k <= 1; k++) {
        float shift = (float)k * patch, lo = zlo + shift, hi = zhi + shift;
        if (hi < 0.0f || lo >= patch) continue;
        int s0 = (int)floorf(fmaxf(lo, 0.0f) / patch * CANOPY_STRIPS);
        int s1 = (int)floorf(fminf(hi, patch * 0.99999f) / patch * CANOPY_STRIPS);
        for (int s = s0; s <= s1 && s < CANOPY_STRIPS; s++)
            if (!strip_add(&strips[s], i, shift, t)) return false;
    }
    return true;
}

/* Moller-Trumbore: ray o + t d against triangle t shifted by (sx, 0, sz);
 * t of the hit (INFINITY: none) and its barycentrics (b1, b2). */
static float intersect(const canopy_tri_t *tr, float sx, float sz, const float o[3], const float d[3], float *b1,
                       float *b2)
{
    float p0[3] = {tr->p[0][0] + sx, tr->p[0][1], tr->p[0][2] + sz};
    float e1[3], e2[3], s[3], q[3], h[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = tr->p[1][k] - tr->p[0][k];
        e2[k] = tr->p[2][k] - tr->p[0][k];
        s[k] = o[k] - p0[k];
    }
    h[0] = d[1] * e2[2] - d[2] * e2[1];
    h[1] = d[2] * e2[0] - d[0] * e2[2];
    h[2] = d[0] * e2[1] - d[1] * e2[0];
    float a = e1[0] * h[0] + e1[1] * h[1] + e1[2] * h[2];
    if (fabsf(a) < 1e-12f) return INFINITY;
    float f = 1.0f / a, u = f * (s[0] * h[0] + s[1] * h[1] + s[2] * h[2]);
    if (u < 0.0f || u > 1.0f) return INFINITY;
    q[0] = s[1] * e1[2] - s[2] * e1[1];
    q[1] = s[2] * e1[0] - s[0] * e1[2];
    q[2] = s[0] * e1[1] - s[1] * e1[0];
    float v = f * (d[0] * q[0] + d[1] * q[1] + d[2] * q[2]);
    if (v < 0.0f || u + v > 1.0f) return INFINITY;
    float t = f * (e2[0] * q[0] + e2[1] * q[1] + e2[2] * q[2]);
    if (t <= 0.0f) return INFINITY;
    *b1 = u;
    *b2 = v;
    return t;
}

/* Seeds and settles the patch's blades and cuts them into triangles. */
static canopy_tri_t *make_triangles(const blade_canopy_desc_t *d, uint64_t stream, int *blades_out, int *tri_count,
                                    float *top)
{
    int blades = (int)lroundf(d->population.density * d->patch * d->patch);
    blades = blades < 1 ? 1 : blades;
    int segs = d->segments, per = 2 * segs;
    canopy_tri_t *tris = malloc(sizeof *tris * (size_t)blades * (size_t)per);
    if (!tris) return NULL;
    core_rng_t rng;
    core_rng_seed(&rng, d->seed, 0xca90u + stream);
    blade_env_t env = blade_env_defaults(&(blade_env_t){.dt = BLADE_SETTLE_DT, .gravity = d->population.gravity});
    *top = 0.0f;
    for (int n = 0; n < blades; n++) {
        float h = core_rng_range(&rng, d->population.height[0], d->population.height[1]);
        float w = core_rng_range(&rng, d->population.width[0], d->population.width[1]);
        float s = core_rng_range(&rng, d->population.stiffness[0], d->population.stiffness[1]);
        float angle = core_rng_range(&rng, 0.0f, 6.2831853f);
        float x = core_rng_float(&rng) * d->patch, z = core_rng_float(&rng) * d->patch;
        blade_t b = {.v0 = {x, 0.0f, z, angle}, .v1 = {x, h, z, h}, .v2 = {x, h, z, w}, .up = {0.0f, 1.0f, 0.0f, s}};
        float eta = 0.0f;
        for (int i = 0; i < CANOPY_SETTLE_STEPS; i++) blade_ref_step_one(&b, &eta, &env, NULL);
        float p[BLADE_CANOPY_MAX_SEGMENTS + 1][2][3], nrm[BLADE_CANOPY_MAX_SEGMENTS + 1][2][3];
        for (int i = 0; i <= segs; i++)
            for (int u = 0; u < 2; u++) {
                blade_ref_surface(&b, d->population.shape, (float)u, (float)i / (float)segs, p[i][u], nrm[i][u]);
                *top = fmaxf(*top, p[i][u][1]);
            }
        for (int i = 0; i < segs; i++) {
            /* (i,0) (i,1) (i+1,0) and (i,1) (i+1,1) (i+1,0), as the clumps */
            static const int corner[2][3][2] = {{{0, 0}, {0, 1}, {1, 0}}, {{0, 1}, {1, 1}, {1, 0}}};
            for (int k = 0; k < 2; k++) {
                canopy_tri_t *t = &tris[(size_t)n * (size_t)per + (size_t)(2 * i + k)];
                t->xlo = INFINITY;
                t->xhi = -INFINITY;
                for (int c = 0; c < 3; c++) {
                    int row = i + corner[k][c][0], side = corner[k][c][1];
                    memcpy(t->p[c], p[row][side], sizeof t->p[c]);
                    memcpy(t->n[c], nrm[row][side], sizeof t->n[c]);
                    t->v[c] = (float)row / (float)segs;
                    t->xlo = fminf(t->xlo, t->p[c][0]);
                    t->xhi = fmaxf(t->xhi, t->p[c][0]);
                }
            }
        }
    }
    *blades_out = blades;
    *tri_count = blades * per;
    return tris;
}

/* The suns of the table in the rays' frame: elevation k, azimuth j. */
typedef float canopy_suns_t[BLADE_CANOPY_SUNS][BLADE_CANOPY_AZIMUTHS][3];

/* Sums over the points a row's rays meet (blade_canopy.h). */
typedef struct canopy_acc_t {
    double ao[4], v_ao[4];
    double sun[BLADE_CANOPY_SUNS][BLADE_CANOPY_AZIMUTHS][2];
} canopy_acc_t;

/* Adds a met point of blade parameter v and normal n (unit, flipped to the
 * viewer, in the rays' frame). */
static void accumulate(canopy_acc_t *a, float v, const float n[3], const canopy_suns_t *suns)
{
    double ao = 0.45 + 0.55 * v, m[4] = {ao, -n[0] * ao, n[1] * ao, n[2] * ao};
    for (int c = 0; c < 4; c++) {
        a->ao[c] += m[c];
        a->v_ao[c] += v * m[c];
    }
    for (int k = 0; k < BLADE_CANOPY_SUNS; k++)
        for (int j = 0; j < BLADE_CANOPY_AZIMUTHS; j++) {
            const float *l = (*suns)[k][j];
            double d = fmax(n[0] * l[0] + n[1] * l[1] + n[2] * l[2], 0.0);
            a->sun[k][j][0] += d;
            a->sun[k][j][1] += v * d;
        }
}

/* The first surface ray (o, dir) meets in strip s between the copies its x
 * span [x0, x1] crosses, shaded into acc; true on a hit. */
static bool cast(const canopy_strip_t *s, const canopy_tri_t *tris, float patch, const float o[3],
                 const float dir[3], float x0, float x1, const canopy_suns_t *suns, canopy_acc_t *acc)
{
    if (s->count == 0) return false;
    int k0 = (int)ceilf((x0 - s->xhi) / patch), k1 = (int)floorf((x1 - s->xlo) / patch);
    float best = INFINITY, bb1 = 0.0f, bb2 = 0.0f;
    const canopy_tri_t *hit = NULL;
    for (int k = k0; k <= k1; k++) {
        float sx = (float)k * patch;
        for (int i = 0; i < s->count; i++) {
            const canopy_tri_t *t = &tris[s->e[i].tri];
            if (t->xhi + sx < x0 || t->xlo + sx > x1) continue;
            float b1 = 0.0f, b2 = 0.0f, th = intersect(t, sx, s->e[i].zshift, o, dir, &b1, &b2);
            if (th < best) best = th, bb1 = b1, bb2 = b2, hit = t;
        }
        /* Copies further along x begin at s->xlo + (k + 1) patch. */
        if (hit && o[0] + best * dir[0] < s->xlo + (float)(k + 1) * patch) break;
    }
    if (!hit) return false;
    float b0 = 1.0f - bb1 - bb2, n[3], len = 0.0f;
    for (int c = 0; c < 3; c++) {
        n[c] = b0 * hit->n[0][c] + bb1 * hit->n[1][c] + bb2 * hit->n[2][c];
        len += n[c] * n[c];
    }
    len = sqrtf(len) > 1e-12f ? sqrtf(len) : 1.0f;
    /* flipped to face the viewer, as blade_shade flips it */
    float facing = (n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2]) > 0.0f ? -1.0f : 1.0f;
    for (int c = 0; c < 3; c++) n[c] *= facing / len;
    accumulate(acc, b0 * hit->v[0] + bb1 * hit->v[1] + bb2 * hit->v[2], n, suns);
    return true;
}

/* Rows [begin, end) of the table (core_parallel_for): each row casts its
 * rays from a random stream of its own (seed, row), so the table does not
 * depend on how the rows are shared out. */
typedef struct canopy_rows_t {
    const blade_canopy_desc_t *d;
    blade_canopy_t *out;
    const canopy_strip_t *strips;
    const canopy_tri_t *tris;
    float top;
    const canopy_suns_t *suns;
    int side, rays; /* the patch's rays, side x side stratified */
    uint64_t stream;
} canopy_rows_t;

static void canopy_rows(void *user, int begin, int end)
{
    const canopy_rows_t *job = user;
    const blade_canopy_desc_t *d = job->d;
    int side = job->side;
    for (int r = begin; r < end; r++) {
        core_rng_t rng;
        core_rng_seed(&rng, d->seed, 0xca91u + job->stream + (uint64_t)r);
        float e = fmaxf((float)r / (float)(d->rows - 1) * 1.5707963f, 0.0174533f);
        float dir[3] = {cosf(e), -sinf(e), 0.0f}, h = job->top + 0.01f, along = h / sinf(e);
        canopy_acc_t acc = {0};
        int hits = 0, rays = 0;
        for (int j = 0; j < side; j++)
            for (int i = 0; i < side && rays < job->rays; i++, rays++) {
                /* stratified ground points of the patch */
                float gx = ((float)i + core_rng_float(&rng)) / (float)side * d->patch;
                float gz = ((float)j + core_rng_float(&rng)) / (float)side * d->patch;
                float o[3] = {gx - dir[0] * along, h, gz};
                int s = (int)(gz / d->patch * CANOPY_STRIPS);
                s = s < CANOPY_STRIPS ? s : CANOPY_STRIPS - 1;
                hits += cast(&job->strips[s], job->tris, d->patch, o, dir, o[0], gx, job->suns, &acc);
            }
        double inv = hits ? 1.0 / hits : 0.0;
        blade_canopy_row_t *row = &job->out->row[r];
        job->out->elevation[r] = e;
        row->cover = (float)hits / (float)rays;
        for (int c = 0; c < 4; c++) {
            row->ao[c] = (float)(acc.ao[c] * inv);
            row->v_ao[c] = (float)(acc.v_ao[c] * inv);
        }
        for (int k = 0; k < BLADE_CANOPY_SUNS; k++)
            for (int j = 0; j < BLADE_CANOPY_AZIMUTHS; j++) {
                row->sun[k][j][0] = (float)(acc.sun[k][j][0] * inv);
                row->sun[k][j][1] = (float)(acc.sun[k][j][1] * inv);
            }
    }
}

/* One patch of blades (random streams offset by `stream`) cast into
 * out's rows, its share of the rays; *blades: its blades. False: out of
 * memory. */
static bool canopy_patch(const blade_canopy_desc_t *d, const canopy_suns_t *suns, uint64_t stream,
                         blade_canopy_t *out, int *blades)
{
    int ntri = 0;
    float top = 0.0f;
    canopy_tri_t *tris = make_triangles(d, stream, blades, &ntri, &top);
    canopy_strip_t strips[CANOPY_STRIPS] = {{0}};
    bool ok = tris != NULL;
    for (int i = 0; ok && i < ntri; i++) ok = bin_triangle(strips, &tris[i], (uint32_t)i, d->patch);
    if (ok) {
        int rays = (d->rays + d->patches - 1) / d->patches;
        canopy_rows_t job = {.d = d, .out = out, .strips = strips, .tris = tris, .top = top,
                             .suns = suns, .side = (int)ceilf(sqrtf((float)rays)), .rays = rays,
                             .stream = stream};
        core_parallel_for(d->rows, canopy_rows, &job);
    }
    for (int s = 0; s < CANOPY_STRIPS; s++) free(strips[s].e);
    free(tris);
    return ok;
}

bool blade_canopy_make(blade_canopy_t *out, const blade_canopy_desc_t *desc)
{
    blade_canopy_desc_t d = blade_canopy_desc_defaults(desc);
    memset(out, 0, sizeof *out);
    if (d.sun[0] == 0.0f && d.sun[1] == 0.0f && d.sun[2] == 0.0f) {
        core_log_error("blade_canopy_make: no sun direction");
        return false;
    }
    const blade_population_t *b = &d.population;
    if (d.rows < 2 || d.rows > BLADE_CANOPY_MAX_ROWS || d.segments > BLADE_CANOPY_MAX_SEGMENTS ||
        b->height[0] > b->height[1] || b->width[0] > b->width[1] || b->density < 0.0f ||
        b->density * d.patch * d.patch > 1e6f) {
        core_log_error("blade_canopy_make: rows %d (2..%d), segments %d (at most %d), height [%g, %g], width "
                       "[%g, %g], %g blades per patch",
                       d.rows, BLADE_CANOPY_MAX_ROWS, d.segments, BLADE_CANOPY_MAX_SEGMENTS, b->height[0],
                       b->height[1], b->width[0], b->width[1], b->density * d.patch * d.patch);
        return false;
    }
    /* The sun at elevation k over the ground, from sun0 (at or below -pi / 2)
     * up in steps through the desc's sun's elevation (so that flat ground
     * lit by it needs no interpolation between elevations) to pi / 2 or
     * beyond, and at azimuth j from the direction towards the viewer, -x. */
    double sl = sqrt((double)d.sun[0] * d.sun[0] + (double)d.sun[1] * d.sun[1] + (double)d.sun[2] * d.sun[2]);
    double sun_e = asin(fmin(fmax(d.sun[1] / sl, -1.0), 1.0));
    double sun0 = sun_e - BLADE_CANOPY_SUN_STEP * ceil((sun_e + 1.5707963267948966) / BLADE_CANOPY_SUN_STEP);
    canopy_suns_t suns;
    for (int k = 0; k < BLADE_CANOPY_SUNS; k++)
        for (int j = 0; j < BLADE_CANOPY_AZIMUTHS; j++) {
            double el = sun0 + k * (double)BLADE_CANOPY_SUN_STEP;
            double phi = 3.141592653589793 * j / (BLADE_CANOPY_AZIMUTHS - 1);
            suns[k][j][0] = (float)(-cos(el) * cos(phi));
            suns[k][j][1] = (float)sin(el);
            suns[k][j][2] = (float)(cos(el) * sin(phi));
        }
    /* Per row, the hits of every patch pooled: the cover is the patches'
     * mean, each mean over the met points their hit-weighted mean. */
    enum { N = sizeof(blade_canopy_row_t) / sizeof(float) };
    static_assert(offsetof(blade_canopy_row_t, cover) == 0, "the cover leads the row");
    double sum[BLADE_CANOPY_MAX_ROWS][N] = {{0}};
    int blades = 0;
    for (int p = 0; p < d.patches; p++) {
        blade_canopy_t one;
        if (!canopy_patch(&d, (const canopy_suns_t *)&suns, (uint64_t)p << 16, &one, &blades)) {
            core_log_error("blade_canopy_make: out of memory");
            return false;
        }
        for (int r = 0; r < d.rows; r++) {
            float f[N];
            memcpy(f, &one.row[r], sizeof f);
            sum[r][0] += f[0];
            for (int k = 1; k < N; k++) sum[r][k] += (double)f[0] * f[k];
            out->elevation[r] = one.elevation[r];
        }
    }
    for (int r = 0; r < d.rows; r++) {
        float f[N];
        f[0] = (float)(sum[r][0] / d.patches);
        for (int k = 1; k < N; k++) f[k] = sum[r][0] > 0.0 ? (float)(sum[r][k] / sum[r][0]) : 0.0f;
        memcpy(&out->row[r], f, sizeof f);
    }
    out->rows = d.rows;
    out->sun0 = (float)sun0;
    out->blades = blades;
    return true;
}

/* The point of x in [0, n - 1] (clamped) between nodes i and i + 1: i and
 * the weight of i + 1. */
static int canopy_node(float x, int n, float *f)
{
    x = fminf(fmaxf(x, 0.0f), (float)(n - 1));
    int i = (int)floorf(x);
    i = i < n - 1 ? i : n - 2;
    *f = x - (float)i;
    return i;
}

blade_canopy_row_t blade_canopy_at(const blade_canopy_t *c, float elevation)
{
    float f;
    int i = canopy_node(elevation / 1.5707963f * (float)(c->rows - 1), c->rows, &f);
    /* the row is floats only: blend them one by one */
    enum { N = sizeof(blade_canopy_row_t) / sizeof(float) };
    float a[N], b[N], m[N];
    memcpy(a, &c->row[i], sizeof a);
    memcpy(b, &c->row[i + 1], sizeof b);
    for (int k = 0; k < N; k++) m[k] = a[k] + f * (b[k] - a[k]);
    blade_canopy_row_t out;
    memcpy(&out, m, sizeof out);
    return out;
}

void blade_canopy_pack(const blade_canopy_t *c, blade_canopy_texture_t *out)
{
    memset(out, 0, sizeof *out);
    out->rows = c->rows;
    out->sun0 = c->sun0;
    for (int r = 0; r < c->rows; r++) {
        const blade_canopy_row_t *w = &c->row[r];
        float(*t)[4] = out->texel[r];
        t[0][0] = w->cover;
        memcpy(t[1], w->ao, sizeof w->ao);
        memcpy(t[2], w->v_ao, sizeof w->v_ao);
        for (int k = 0; k < BLADE_CANOPY_SUNS; k++)
            for (int j = 0; j < BLADE_CANOPY_AZIMUTHS; j++)
                memcpy(t[3 + k * BLADE_CANOPY_AZIMUTHS + j], w->sun[k][j], sizeof w->sun[k][j]);
    }
}

void blade_canopy_color(const blade_canopy_t *c, const blade_canopy_view_t *v, const float root[3],
                        const float tip[3], float rgb[3], float *cover)
{
    static const float sun_color[3] = BLADE_CANOPY_SUN_COLOR, down[3] = BLADE_CANOPY_AMBIENT_DOWN,
                       up[3] = BLADE_CANOPY_AMBIENT_UP;
    blade_canopy_row_t r = blade_canopy_at(c, v->elevation);
    float h, g;
    int k = canopy_node((v->sun_elevation - c->sun0) / BLADE_CANOPY_SUN_STEP, BLADE_CANOPY_SUNS, &h);
    int j = canopy_node(v->azimuth / 3.1415927f * (float)(BLADE_CANOPY_AZIMUTHS - 1), BLADE_CANOPY_AZIMUTHS, &g);
    float s[2];
    for (int m = 0; m < 2; m++) {
        float lo = r.sun[k][j][m] + g * (r.sun[k][j + 1][m] - r.sun[k][j][m]);
        float hi = r.sun[k + 1][j][m] + g * (r.sun[k + 1][j + 1][m] - r.sun[k + 1][j][m]);
        s[m] = lo + h * (hi - lo);
    }
    /* shade()'s ambient mix(DOWN, UP, u), u = n.y / 2 + 1 / 2 with n.y the
     * normal's world height: n . up in the ground's frame */
    const float q[4] = {0.5f, 0.5f * v->up[0], 0.5f * v->up[1], 0.5f * v->up[2]};
    float u_ao = 0.0f, vu_ao = 0.0f;
    for (int m = 0; m < 4; m++) {
        u_ao += q[m] * r.ao[m];
        vu_ao += q[m] * r.v_ao[m];
    }
    for (int m = 0; m < 3; m++) {
        float dt = tip[m] - root[m];
        rgb[m] = sun_color[m] * BLADE_CANOPY_SUN_DIFFUSE * (root[m] * s[0] + dt * s[1]) +
                 root[m] * (down[m] * r.ao[0] + (up[m] - down[m]) * u_ao) +
                 dt * (down[m] * r.v_ao[0] + (up[m] - down[m]) * vu_ao);
    }
    *cover = r.cover;
}

float blade_canopy_thinned(float cover, float e)
{
    return 1.0f - powf(fmaxf(1.0f - cover, 1e-6f), fminf(fmaxf(e, 0.0f), 1.0f));
}

float blade_canopy_under(float cover, float e, float kept)
{
    float full = blade_canopy_thinned(cover, e), left = blade_canopy_thinned(cover, e * kept);
    return fmaxf(full - left, 0.0f) / fmaxf(1.0f - left, 1e-4f);
}

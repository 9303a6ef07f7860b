/* blade_canopy: the ground canopy's table measured on the blade model by
 * ray casting a settled, periodic patch of blades (see blade_canopy.h).
 *
 * Rays look along +x, so a ray keeps its z: the patch's triangles are
 * binned into strips of z (a triangle that crosses the patch's z border is
 * binned once more, shifted by the patch side), and a ray tests the
 * triangles of its strip in the periodic copies along x that its x span
 * crosses, copy by copy, nearest first, until a hit lies before the next
 * copy can begin. Intersection: Moller-Trumbore. The rays' frame is the
 * ground's (blade_canopy_row_t): t = -x, g = +y, s = +z. A ray keeps the
 * nearest hit of every cut level (the hits past the point where it sinks
 * below the cut); the copies before the highest cut still open are
 * skipped. */
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
    float xlo, xhi, ylo, yhi;
} canopy_tri_t;

/* A triangle in a strip, with its bounds along x and y (scanned without
 * touching the triangle). */
typedef struct canopy_entry_t {
    uint32_t tri;
    float zshift, xlo, xhi, ylo, yhi;
} canopy_entry_t;

/* Its entries sorted by xlo once binned (patch_make). */
typedef struct canopy_strip_t {
    canopy_entry_t *e;
    int count, cap;
    float xlo, xhi, span; /* over its entries; span: the widest xhi - xlo */
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
    if (d.wind_rays <= 0) {
        /* a quarter of the rays, fewer in proportion past 1,024 blades a
         * patch: a denser patch is dearer per ray */
        float blades = d.population.density * d.patch * d.patch, r = (float)(d.rays / 4);
        if (blades > 1024.0f) r *= 1024.0f / blades;
        d.wind_rays = r > 64.0f ? (int)r : 64;
    }
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
    s->e[s->count++] = (canopy_entry_t){tri, zshift, t->xlo, t->xhi, t->ylo, t->yhi};
    s->xlo = s->count == 1 ? t->xlo : fminf(s->xlo, t->xlo);
    s->xhi = s->count == 1 ? t->xhi : fmaxf(s->xhi, t->xhi);
    s->span = fmaxf(s->span, t->xhi - t->xlo);
    return true;
}

static int entry_order(const void *a, const void *b)
{
    const canopy_entry_t *x = a, *y = b;
    if (x->xlo != y->xlo) return x->xlo < y->xlo ? -1 : 1;
    if (x->tri != y->tri) return x->tri < y->tri ? -1 : 1;
    return (x->zshift > y->zshift) - (x->zshift < y->zshift);
}

/* The first entry of s whose xlo is at least x (s sorted). */
static int strip_first(const canopy_strip_t *s, float x)
{
    int lo = 0, hi = s->count;
    while (lo < hi) {
        int mid = (lo + hi) / 2;
        if (s->e[mid].xlo < x) lo = mid + 1;
        else hi = mid;
    }
    return lo;
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

/* Blades [begin, end) of a patch settled and cut (core_parallel_for):
 * each writes its own triangles and top. */
typedef struct canopy_settle_t {
    const blade_canopy_desc_t *d;
    const blade_env_t *env;
    blade_t *blades;
    canopy_tri_t *tris;
    float *tops;
} canopy_settle_t;

static void settle_blades(void *user, int begin, int end)
{
    const canopy_settle_t *job = user;
    int segs = job->d->segments, per = 2 * segs;
    for (int n = begin; n < end; n++) {
        blade_t b = job->blades[n];
        float eta = 0.0f, top = 0.0f;
        for (int i = 0; i < CANOPY_SETTLE_STEPS; i++) blade_ref_step_one(&b, &eta, job->env, NULL);
        float p[BLADE_CANOPY_MAX_SEGMENTS + 1][2][3], nrm[BLADE_CANOPY_MAX_SEGMENTS + 1][2][3];
        for (int i = 0; i <= segs; i++)
            for (int u = 0; u < 2; u++) {
                blade_ref_surface(&b, job->d->population.shape, (float)u, (float)i / (float)segs, p[i][u],
                                  nrm[i][u]);
                top = fmaxf(top, p[i][u][1]);
            }
        job->tops[n] = top;
        for (int i = 0; i < segs; i++) {
            /* (i,0) (i,1) (i+1,0) and (i,1) (i+1,1) (i+1,0), as the clumps */
            static const int corner[2][3][2] = {{{0, 0}, {0, 1}, {1, 0}}, {{0, 1}, {1, 1}, {1, 0}}};
            for (int k = 0; k < 2; k++) {
                canopy_tri_t *t = &job->tris[(size_t)n * (size_t)per + (size_t)(2 * i + k)];
                t->xlo = t->ylo = INFINITY;
                t->xhi = t->yhi = -INFINITY;
                for (int c = 0; c < 3; c++) {
                    int row = i + corner[k][c][0], side = corner[k][c][1];
                    memcpy(t->p[c], p[row][side], sizeof t->p[c]);
                    memcpy(t->n[c], nrm[row][side], sizeof t->n[c]);
                    t->v[c] = (float)row / (float)segs;
                    t->xlo = fminf(t->xlo, t->p[c][0]);
                    t->xhi = fmaxf(t->xhi, t->p[c][0]);
                    t->ylo = fminf(t->ylo, t->p[c][1]);
                    t->yhi = fmaxf(t->yhi, t->p[c][1]);
                }
            }
        }
    }
}

/* Seeds the patch's blades (one random stream, in order), settles them
 * under the uniform wind force (x, z) in the rays' frame and cuts them
 * into triangles, the blades shared out over threads. */
static canopy_tri_t *make_triangles(const blade_canopy_desc_t *d, uint64_t stream, const float wind[2],
                                    int *blades_out, int *tri_count, float *top)
{
    int blades = (int)lroundf(d->population.density * d->patch * d->patch);
    blades = blades < 1 ? 1 : blades;
    int per = 2 * d->segments;
    canopy_tri_t *tris = malloc(sizeof *tris * (size_t)blades * (size_t)per);
    blade_t *seeded = malloc(sizeof *seeded * (size_t)blades);
    float *tops = malloc(sizeof *tops * (size_t)blades);
    if (!tris || !seeded || !tops) {
        free(tris);
        free(seeded);
        free(tops);
        return NULL;
    }
    core_rng_t rng;
    core_rng_seed(&rng, d->seed, 0xca90u + stream);
    blade_env_t env = blade_env_defaults(&(blade_env_t){.dt = BLADE_SETTLE_DT, .gravity = d->population.gravity});
    float m = sqrtf(wind[0] * wind[0] + wind[1] * wind[1]);
    if (m > 0.0f) {
        /* uniform: a wave at its mean, half its strength, whose phase moves
         * 1e-5 radians across the patch */
        env.winds[0] = blade_wind_wave(wind[0] / m, wind[1] / m, 2.0f * m, 1e6f, 0.0f);
        env.wind_count = 1;
    }
    for (int n = 0; n < blades; n++) {
        float h = core_rng_range(&rng, d->population.height[0], d->population.height[1]);
        float w = core_rng_range(&rng, d->population.width[0], d->population.width[1]);
        float s = core_rng_range(&rng, d->population.stiffness[0], d->population.stiffness[1]);
        float angle = core_rng_range(&rng, 0.0f, 6.2831853f);
        float x = core_rng_float(&rng) * d->patch, z = core_rng_float(&rng) * d->patch;
        seeded[n] = (blade_t){.v0 = {x, 0.0f, z, angle}, .v1 = {x, h, z, h}, .v2 = {x, h, z, w},
                              .up = {0.0f, 1.0f, 0.0f, s}};
    }
    core_parallel_for(blades, settle_blades,
                      &(canopy_settle_t){.d = d, .env = &env, .blades = seeded, .tris = tris, .tops = tops});
    *top = 0.0f;
    for (int n = 0; n < blades; n++) *top = fmaxf(*top, tops[n]);
    free(seeded);
    free(tops);
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

/* The cut levels a ray keeps a hit of: the cuts, then the whole column. */
enum { CANOPY_LEVELS = BLADE_CANOPY_CUTS + 1 };

/* Adds a met point of blade parameter v and normal n (unit, flipped to the
 * viewer, in the rays' frame) to acc[0 .. count). */
static void accumulate(canopy_acc_t *acc, int count, float v, const float n[3], const canopy_suns_t *suns)
{
    canopy_acc_t one;
    double ao = 0.45 + 0.55 * v, m[4] = {ao, -n[0] * ao, n[1] * ao, n[2] * ao};
    for (int c = 0; c < 4; c++) {
        one.ao[c] = m[c];
        one.v_ao[c] = v * m[c];
    }
    for (int k = 0; k < BLADE_CANOPY_SUNS; k++)
        for (int j = 0; j < BLADE_CANOPY_AZIMUTHS; j++) {
            const float *l = (*suns)[k][j];
            double d = n[0] * l[0] + n[1] * l[1] + n[2] * l[2];
            d = d > 0.0 ? d : 0.0;
            one.sun[k][j][0] = d;
            one.sun[k][j][1] = v * d;
        }
    enum { N = sizeof(canopy_acc_t) / sizeof(double) };
    const double *src = (const double *)&one;
    for (int a = 0; a < count; a++) {
        double *dst = (double *)&acc[a];
        for (int k = 0; k < N; k++) dst[k] += src[k];
    }
}

/* The nearest hit of one cut level: t along the ray, its triangle and
 * barycentrics. */
typedef struct canopy_hit_t {
    float t, b1, b2;
    const canopy_tri_t *tri;
} canopy_hit_t;

/* The first surface ray (o, dir) meets in strip s between the copies its x
 * span [x0, x1] crosses, past t_cut[l] for every level l (ascending: the
 * cuts from the top down), shaded into acc[l]; hits[l] counts them. */
static void cast(const canopy_strip_t *s, const canopy_tri_t *tris, float patch, const float o[3],
                 const float dir[3], float x0, float x1, const float t_cut[CANOPY_LEVELS], const canopy_suns_t *suns,
                 canopy_acc_t acc[CANOPY_LEVELS], int hits[CANOPY_LEVELS])
{
    if (s->count == 0) return;
    canopy_hit_t best[CANOPY_LEVELS];
    for (int l = 0; l < CANOPY_LEVELS; l++) best[l] = (canopy_hit_t){INFINITY, 0.0f, 0.0f, NULL};
    /* Levels settle from the top down (a hit below a lower cut is one below
     * a higher cut): open is the first level not settled. */
    int open = 0, k = (int)ceilf((x0 - s->xhi) / patch), k1 = (int)floorf((x1 - s->xlo) / patch);
    float from = x0, slope = dir[1] / dir[0]; /* the ray's height o[1] + (x - o[0]) slope */
    while (k <= k1) {
        float sx = (float)k * patch;
        for (int i = strip_first(s, from - sx - s->span); i < s->count; i++) {
            const canopy_entry_t *en = &s->e[i];
            float lo = en->xlo + sx, hi = en->xhi + sx;
            if (lo > x1) break;
            /* before the span, or the ray above or below the triangle all along its x */
            if (hi < from || o[1] + (hi - o[0]) * slope > en->yhi + 1e-5f ||
                o[1] + (lo - o[0]) * slope < en->ylo - 1e-5f)
                continue;
            const canopy_tri_t *t = &tris[en->tri];
            float b1 = 0.0f, b2 = 0.0f, th = intersect(t, sx, en->zshift, o, dir, &b1, &b2);
            for (int l = open; l < CANOPY_LEVELS && th >= t_cut[l]; l++)
                if (th < best[l].t) best[l] = (canopy_hit_t){th, b1, b2, t};
        }
        /* Copies further along x begin at s->xlo + (k + 1) patch. */
        float next = s->xlo + (float)(k + 1) * patch;
        while (open < CANOPY_LEVELS && best[open].tri && o[0] + best[open].t * dir[0] < next) open++;
        if (open == CANOPY_LEVELS) break;
        from = fmaxf(x0, o[0] + t_cut[open] * dir[0]);
        k = k + 1 > (int)ceilf((from - s->xhi) / patch) ? k + 1 : (int)ceilf((from - s->xhi) / patch);
    }
    for (int l = 0; l < CANOPY_LEVELS;) {
        const canopy_hit_t *h = &best[l];
        if (!h->tri) break; /* no hit here, none below */
        int same = l + 1;
        while (same < CANOPY_LEVELS && best[same].tri == h->tri && best[same].t == h->t) same++;
        float b0 = 1.0f - h->b1 - h->b2, n[3], len = 0.0f;
        for (int c = 0; c < 3; c++) {
            n[c] = b0 * h->tri->n[0][c] + h->b1 * h->tri->n[1][c] + h->b2 * h->tri->n[2][c];
            len += n[c] * n[c];
        }
        len = sqrtf(len) > 1e-12f ? sqrtf(len) : 1.0f;
        /* flipped to face the viewer, as blade_shade flips it */
        float facing = (n[0] * dir[0] + n[1] * dir[1] + n[2] * dir[2]) > 0.0f ? -1.0f : 1.0f;
        for (int c = 0; c < 3; c++) n[c] *= facing / len;
        float v = b0 * h->tri->v[0] + h->b1 * h->tri->v[1] + h->b2 * h->tri->v[2];
        accumulate(&acc[l], same - l, v, n, suns);
        for (int a = l; a < same; a++) hits[a]++;
        l = same;
    }
}

/* Row r of c's pose p at cut level l (blade_canopy_at_cut's levels less
 * level 0): the cuts from the lowest, then the whole column. */
static blade_canopy_row_t *level_row(const blade_canopy_t *c, int p, int r, int l)
{
    if (p > 0) {
        blade_canopy_pose_t *w = &c->windy[p - 1];
        return l < BLADE_CANOPY_CUTS ? &w->below[r][l] : &w->row[r];
    }
    return (blade_canopy_row_t *)(l < BLADE_CANOPY_CUTS ? &c->below[r][l] : &c->row[r]);
}

/* The uniform wind force of pose p (1..) in the rays' frame: t is -x, s
 * is +z. */
static void pose_wind(const blade_canopy_t *c, int p, float out[2])
{
    int k = (p - 1) % BLADE_CANOPY_WIND_AZIMUTHS, m = (p - 1) / BLADE_CANOPY_WIND_AZIMUTHS;
    float psi = 1.5707963f * (float)k, f = c->wind * (float)(m + 1) / (float)BLADE_CANOPY_WIND_STEPS;
    out[0] = -f * cosf(psi);
    out[1] = f * sinf(psi);
}

/* A patch of blades cut into triangles and binned into strips. */
typedef struct canopy_patch_t {
    canopy_tri_t *tris;
    canopy_strip_t strips[CANOPY_STRIPS];
    float top;
} canopy_patch_t;

/* Rows of jobs [begin, end) of the table (core_parallel_for): each row
 * casts its rays from a random stream of its own (seed, row), so the table
 * does not depend on how the rows are shared out. */
typedef struct canopy_rows_t {
    const blade_canopy_desc_t *d;
    blade_canopy_t *out;
    const canopy_patch_t *patch;
    float top; /* the table's: the cuts' heights are fractions of it */
    const canopy_suns_t *suns;
    int side, rays; /* the patch's rays, side x side stratified */
    uint64_t stream;
} canopy_rows_t;

static void canopy_rows(void *user, int begin, int end)
{
    const canopy_rows_t *job = user;
    const blade_canopy_desc_t *d = job->d;
    int side = job->side;
    /* job n is row n / 2 from the bottom when even, from the top when odd:
     * a band of jobs mixes the dear grazing rows with the cheap steep ones
     * (in row order the first band took most of the time) */
    for (int n = begin; n < end; n++) {
        int r = n % 2 ? d->rows - 1 - n / 2 : n / 2;
        core_rng_t rng;
        core_rng_seed(&rng, d->seed, 0xca91u + job->stream + (uint64_t)r);
        float e = fmaxf((float)r / (float)(d->rows - 1) * 1.5707963f, 0.0174533f);
        float dir[3] = {cosf(e), -sinf(e), 0.0f}, h = job->top + 0.01f, along = h / sinf(e);
        /* cast()'s levels: the whole column, then the cuts from the top down */
        float t_cut[CANOPY_LEVELS] = {0.0f};
        for (int l = 1; l < CANOPY_LEVELS; l++)
            t_cut[l] = (h - ldexpf(job->top, -l)) / sinf(e);
        canopy_acc_t acc[CANOPY_LEVELS];
        memset(acc, 0, sizeof acc);
        int hits[CANOPY_LEVELS] = {0}, rays = 0;
        for (int j = 0; j < side; j++)
            for (int i = 0; i < side && rays < job->rays; i++, rays++) {
                /* stratified ground points of the patch */
                float gx = ((float)i + core_rng_float(&rng)) / (float)side * d->patch;
                float gz = ((float)j + core_rng_float(&rng)) / (float)side * d->patch;
                float o[3] = {gx - dir[0] * along, h, gz};
                int s = (int)(gz / d->patch * CANOPY_STRIPS);
                s = s < CANOPY_STRIPS ? s : CANOPY_STRIPS - 1;
                cast(&job->patch->strips[s], job->patch->tris, d->patch, o, dir, o[0], gx, t_cut, job->suns, acc,
                     hits);
            }
        job->out->elevation[r] = e;
        for (int l = 0; l < CANOPY_LEVELS; l++) {
            double inv = hits[l] ? 1.0 / hits[l] : 0.0;
            blade_canopy_row_t *row = level_row(job->out, 0, r, l ? BLADE_CANOPY_CUTS - l : BLADE_CANOPY_CUTS);
            row->cover = (float)hits[l] / (float)rays;
            for (int c = 0; c < 4; c++) {
                row->ao[c] = (float)(acc[l].ao[c] * inv);
                row->v_ao[c] = (float)(acc[l].v_ao[c] * inv);
            }
            for (int k = 0; k < BLADE_CANOPY_SUNS; k++)
                for (int j = 0; j < BLADE_CANOPY_AZIMUTHS; j++) {
                    row->sun[k][j][0] = (float)(acc[l].sun[k][j][0] * inv);
                    row->sun[k][j][1] = (float)(acc[l].sun[k][j][1] * inv);
                }
        }
    }
}

/* One patch of blades (random streams offset by `stream`) settled under
 * wind (blade_canopy_make's), cut and binned; *blades: its blades. False:
 * out of memory. */
static bool patch_make(const blade_canopy_desc_t *d, uint64_t stream, const float wind[2], canopy_patch_t *p,
                       int *blades)
{
    int ntri = 0;
    memset(p, 0, sizeof *p);
    p->tris = make_triangles(d, stream, wind, blades, &ntri, &p->top);
    bool ok = p->tris != NULL;
    for (int i = 0; ok && i < ntri; i++) ok = bin_triangle(p->strips, &p->tris[i], (uint32_t)i, d->patch);
    for (int k = 0; ok && k < CANOPY_STRIPS; k++)
        if (p->strips[k].count > 1) /* an empty strip has no array */
            qsort(p->strips[k].e, (size_t)p->strips[k].count, sizeof *p->strips[k].e, entry_order);
    return ok;
}

static void patch_free(canopy_patch_t *p)
{
    for (int s = 0; s < CANOPY_STRIPS; s++) free(p->strips[s].e);
    free(p->tris);
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
    /* Per pose, every patch first: the cuts are fractions of the tallest
     * blade of all at rest, the same heights in every pose. */
    enum { N = sizeof(blade_canopy_row_t) / sizeof(float) };
    static_assert(offsetof(blade_canopy_row_t, cover) == 0, "the cover leads the row");
    out->wind = d.wind > 0.0f ? d.wind : 0.0f;
    out->gravity = d.population.gravity;
    out->poses = out->wind > 0.0f ? BLADE_CANOPY_POSES : 1;
    canopy_patch_t *patches = calloc((size_t)d.patches, sizeof *patches);
    blade_canopy_t *one = calloc(1, sizeof *one);
    double(*sum)[CANOPY_LEVELS][N] = calloc(BLADE_CANOPY_MAX_ROWS, sizeof *sum);
    out->windy = out->poses > 1 ? calloc((size_t)out->poses - 1, sizeof *out->windy) : NULL;
    bool ok = patches && one && sum && (out->poses == 1 || out->windy);
    int blades = 0;
    float top = 0.0f;
    for (int pose = 0; ok && pose < out->poses; pose++) {
        float wind[2] = {0.0f, 0.0f};
        if (pose > 0) pose_wind(out, pose, wind);
        for (int p = 0; ok && p < d.patches; p++) {
            ok = patch_make(&d, (uint64_t)p << 16, wind, &patches[p], &blades);
            if (pose == 0) top = fmaxf(top, patches[p].top);
        }
        /* Per row and level, the hits of every patch pooled: the cover is
         * the patches' mean, each mean over the met points their
         * hit-weighted mean. */
        int rays = ((pose ? d.wind_rays : d.rays) + d.patches - 1) / d.patches; /* the patches share them */
        memset(sum, 0, BLADE_CANOPY_MAX_ROWS * sizeof *sum);
        for (int p = 0; ok && p < d.patches; p++) {
            canopy_rows_t job = {.d = &d, .out = one, .patch = &patches[p], .top = top,
                                 .suns = (const canopy_suns_t *)&suns, .side = (int)ceilf(sqrtf((float)rays)),
                                 .rays = rays, .stream = (uint64_t)p << 16};
            core_parallel_for(d.rows, canopy_rows, &job);
            for (int r = 0; r < d.rows; r++)
                for (int l = 0; l < CANOPY_LEVELS; l++) {
                    float f[N];
                    memcpy(f, level_row(one, 0, r, l), sizeof f);
                    sum[r][l][0] += f[0];
                    for (int k = 1; k < N; k++) sum[r][l][k] += (double)f[0] * f[k];
                }
        }
        if (ok && pose == 0) memcpy(out->elevation, one->elevation, sizeof out->elevation); /* every patch's */
        for (int r = 0; ok && r < d.rows; r++)
            for (int l = 0; l < CANOPY_LEVELS; l++) {
                float f[N];
                f[0] = (float)(sum[r][l][0] / d.patches);
                for (int k = 1; k < N; k++) f[k] = sum[r][l][0] > 0.0 ? (float)(sum[r][l][k] / sum[r][l][0]) : 0.0f;
                memcpy(level_row(out, pose, r, l), f, sizeof f);
            }
        for (int p = 0; patches && p < d.patches; p++) patch_free(&patches[p]);
    }
    free(patches);
    free(one);
    free(sum);
    if (!ok) {
        core_log_error("blade_canopy_make: out of memory");
        blade_canopy_free(out);
        memset(out, 0, sizeof *out);
        return false;
    }
    out->rows = d.rows;
    out->sun0 = (float)sun0;
    out->top = top;
    out->blades = blades;
    return true;
}

void blade_canopy_free(blade_canopy_t *c)
{
    free(c->windy);
    c->windy = NULL;
    c->poses = c->poses > 1 ? 1 : c->poses;
    c->wind = 0.0f;
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

/* a + f (b - a), float by float (the row is floats only). */
static blade_canopy_row_t row_mix(const blade_canopy_row_t *a, const blade_canopy_row_t *b, float f)
{
    enum { N = sizeof(blade_canopy_row_t) / sizeof(float) };
    float x[N], y[N];
    memcpy(x, a, sizeof x);
    memcpy(y, b, sizeof y);
    for (int k = 0; k < N; k++) x[k] += f * (y[k] - x[k]);
    blade_canopy_row_t out;
    memcpy(&out, x, sizeof out);
    return out;
}

/* Row r of pose p at blade_canopy_at_cut's level l (0: the cut at 0). */
static blade_canopy_row_t level_at(const blade_canopy_t *c, int p, int r, int l)
{
    blade_canopy_row_t w = *level_row(c, p, r, l > 0 ? l - 1 : 0);
    if (l == 0) w.cover = 0.0f;
    return w;
}

/* blade_canopy_at_cut's level q of a cut (0: the whole column). */
static float canopy_cut_level(float cut, float top)
{
    float h1 = ldexpf(fmaxf(top, 1e-6f), -BLADE_CANOPY_CUTS);
    if (cut <= 0.0f) return (float)(BLADE_CANOPY_LEVELS - 1);
    return cut < h1 ? cut / h1 : 1.0f + log2f(cut / h1);
}

blade_canopy_row_t blade_canopy_at_cut(const blade_canopy_t *c, int pose, float elevation, float cut)
{
    float f, g;
    int p = pose > 0 && pose < c->poses ? pose : 0;
    int i = canopy_node(elevation / 1.5707963f * (float)(c->rows - 1), c->rows, &f);
    int l = canopy_node(canopy_cut_level(cut, c->top), BLADE_CANOPY_LEVELS, &g);
    blade_canopy_row_t a = level_at(c, p, i, l), b = level_at(c, p, i + 1, l);
    blade_canopy_row_t lo = row_mix(&a, &b, f);
    a = level_at(c, p, i, l + 1);
    b = level_at(c, p, i + 1, l + 1);
    blade_canopy_row_t hi = row_mix(&a, &b, f);
    return row_mix(&lo, &hi, g);
}

blade_canopy_row_t blade_canopy_at(const blade_canopy_t *c, float elevation)
{
    return blade_canopy_at_cut(c, 0, elevation, 0.0f);
}

void blade_canopy_wind_weights(const blade_canopy_t *c, float wind, float psi, float out[BLADE_CANOPY_POSES])
{
    memset(out, 0, sizeof(float) * BLADE_CANOPY_POSES);
    float q = c->poses > 1 && wind > 0.0f ? fminf(wind / c->wind, 1.0f) * BLADE_CANOPY_WIND_STEPS : 0.0f;
    if (q <= 0.0f) {
        out[0] = 1.0f;
        return;
    }
    /* magnitude: between step m - 1 (0: the rest pose) and step m */
    int m = (int)ceilf(q);
    float f = q - (float)(m - 1);
    if (m == 1) out[0] = 1.0f - f;
    for (int k = 0; k < BLADE_CANOPY_WIND_AZIMUTHS; k++) {
        float d = psi - 1.5707963f * (float)k;
        float w = 0.25f * (1.0f + 2.0f * cosf(d) + cosf(2.0f * d));
        out[1 + (m - 1) * BLADE_CANOPY_WIND_AZIMUTHS + k] += f * w;
        if (m > 1) out[1 + (m - 2) * BLADE_CANOPY_WIND_AZIMUTHS + k] += (1.0f - f) * w;
    }
}

void blade_canopy_slope_lean(const blade_canopy_t *c, const float n[3], float out[3])
{
    for (int k = 0; k < 3; k++) out[k] = c->gravity * (n[1] * n[k] - (k == 1 ? 1.0f : 0.0f));
}

void blade_canopy_pack(const blade_canopy_t *c, blade_canopy_texture_t *out)
{
    memset(out, 0, sizeof *out);
    out->rows = c->rows;
    out->poses = c->poses;
    out->sun0 = c->sun0;
    out->top = c->top;
    out->wind = c->wind;
    out->gravity = c->gravity;
    for (int p = 0; p < c->poses; p++)
        for (int l = 0; l < BLADE_CANOPY_LEVELS; l++)
            for (int r = 0; r < c->rows; r++) {
                blade_canopy_row_t w = level_at(c, p, r, l);
                float(*t)[4] = out->texel[r + (l + p * BLADE_CANOPY_LEVELS) * c->rows];
                t[0][0] = w.cover;
                memcpy(t[1], w.ao, sizeof w.ao);
                memcpy(t[2], w.v_ao, sizeof w.v_ao);
                for (int k = 0; k < BLADE_CANOPY_SUNS; k++)
                    for (int j = 0; j < BLADE_CANOPY_AZIMUTHS; j++)
                        memcpy(t[3 + k * BLADE_CANOPY_AZIMUTHS + j], w.sun[k][j], sizeof w.sun[k][j]);
            }
}

void blade_canopy_color(const blade_canopy_t *c, const blade_canopy_view_t *v, const float root[3],
                        const float tip[3], float rgb[3], float *cover)
{
    static const float sun_color[3] = BLADE_CANOPY_SUN_COLOR, down[3] = BLADE_CANOPY_AMBIENT_DOWN,
                       up[3] = BLADE_CANOPY_AMBIENT_UP;
    float wt[BLADE_CANOPY_POSES];
    blade_canopy_wind_weights(c, v->wind, v->wind_azimuth, wt);
    enum { N = sizeof(blade_canopy_row_t) / sizeof(float) };
    float acc[N] = {0};
    for (int p = 0; p < c->poses; p++) {
        if (wt[p] == 0.0f) continue;
        blade_canopy_row_t one = blade_canopy_at_cut(c, p, v->elevation, v->cut);
        float f[N];
        memcpy(f, &one, sizeof f);
        for (int k = 0; k < N; k++) acc[k] += wt[p] * f[k];
    }
    blade_canopy_row_t r;
    memcpy(&r, acc, sizeof r);
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
    *cover = fminf(fmaxf(r.cover, 0.0f), 1.0f);
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

void blade_canopy_overhang(const float full[4], const float cut[4], float kept, float out[4])
{
    /* transmittance of the cut column, above the cut, and of the blades
     * above it that are not drawn */
    float t_cut = 1.0f - cut[3], t_above = fminf(fmaxf(1.0f - full[3], 0.0f) / fmaxf(t_cut, 1e-6f), 1.0f);
    float left = fminf(fmaxf(1.0f - kept, 0.0f), 1.0f), t_left = powf(fmaxf(t_above, 1e-6f), left);
    /* the not drawn's share of the hits above the cut */
    float share = t_above < 1.0f - 1e-6f ? (1.0f - t_left) / (1.0f - t_above) : left;
    out[3] = 1.0f - t_left * t_cut;
    for (int m = 0; m < 3; m++) {
        float above = full[3] * full[m] - t_above * cut[3] * cut[m]; /* premultiplied */
        float p = fmaxf(share * above + t_left * cut[3] * cut[m], 0.0f);
        out[m] = out[3] > 1e-6f ? p / out[3] : full[m];
    }
}

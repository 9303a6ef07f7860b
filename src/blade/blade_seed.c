/* blade_seed: blade placement on triangle meshes (uniform by area or
 * Poisson-disk tufts) and Morton-ordered patches with conservative AABBs,
 * for the Bézier blades of Jahrmann & Wimmer 2017 (sec. 4). */
#include "blade/blade_seed.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"

#define MORTON_CELLS 2097152.0f /* 2^21 */
#define TUFT_REDRAWS 8

blade_seed_desc_t blade_seed_desc_defaults(const blade_seed_desc_t *desc)
{
    blade_seed_desc_t d = *desc;
    d.population = blade_population_defaults(&d.population);
    if (d.angle_min == 0.0f && d.angle_max == 0.0f) d.angle_max = 6.28318531f;
    if (d.tuft_min_distance == 0.0f) d.tuft_min_distance = 0.25f;
    if (d.tuft_blades == 0) d.tuft_blades = 8;
    if (d.tuft_radius == 0.0f) d.tuft_radius = 0.06f;
    if (d.tuft_attempts_per_centre == 0) d.tuft_attempts_per_centre = 30;
    if (d.max_blades == 0) d.max_blades = (size_t)1 << 22;
    if (d.patch_size == 0) d.patch_size = 256;
    return d;
}

/* ---- small vector helpers ---------------------------------------------- */

static void sub3(const float *a, const float *b, float *o) { o[0] = a[0] - b[0]; o[1] = a[1] - b[1]; o[2] = a[2] - b[2]; }
static float dot3(const float *a, const float *b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void cross3(const float *a, const float *b, float *o)
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}
static bool normalize3(float *a)
{
    float l = sqrtf(dot3(a, a));
    if (l < 1e-12f) return false;
    a[0] /= l; a[1] /= l; a[2] /= l;
    return true;
}

/* ---- mesh access --------------------------------------------------------- */

typedef struct sampler_t {
    const blade_mesh_t *mesh;
    size_t tri_count;
    double *cdf; /* cumulative areas, tri_count entries */
    double area;
} sampler_t;

static const float *vpos(const blade_mesh_t *m, size_t tri, int k)
{
    return m->positions + 3 * (size_t)m->indices[3 * tri + (size_t)k];
}

static float tri_area(const blade_mesh_t *m, size_t tri, float n[3])
{
    float e1[3], e2[3], c[3];
    sub3(vpos(m, tri, 1), vpos(m, tri, 0), e1);
    sub3(vpos(m, tri, 2), vpos(m, tri, 0), e2);
    cross3(e1, e2, c);
    float l = sqrtf(dot3(c, c));
    if (n) {
        n[0] = c[0]; n[1] = c[1]; n[2] = c[2];
        if (!normalize3(n)) { n[0] = 0.0f; n[1] = 1.0f; n[2] = 0.0f; }
    }
    return 0.5f * l;
}

static size_t pick_triangle(const sampler_t *s, core_rng_t *rng)
{
    double u = (double)core_rng_float(rng) * s->area;
    /* first triangle with cdf > u: never one of zero area */
    size_t lo = 0, hi = s->tri_count - 1;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (s->cdf[mid] > u) hi = mid;
        else lo = mid + 1;
    }
    return lo;
}

void blade_seed_point(const blade_mesh_t *m, size_t tri, const float bary[3], float p[3])
{
    for (int k = 0; k < 3; k++)
        p[k] = bary[0] * vpos(m, tri, 0)[k] + bary[1] * vpos(m, tri, 1)[k] + bary[2] * vpos(m, tri, 2)[k];
}

void blade_seed_normal(const blade_mesh_t *m, size_t tri, const float bary[3], float n[3])
{
    float fn[3];
    tri_area(m, tri, fn);
    if (m->normals) {
        for (int k = 0; k < 3; k++) {
            n[k] = 0.0f;
            for (int c = 0; c < 3; c++) n[k] += bary[c] * m->normals[3 * (size_t)m->indices[3 * tri + (size_t)c] + (size_t)k];
        }
        if (normalize3(n)) return;
    }
    memcpy(n, fn, sizeof fn);
}

static void random_bary(core_rng_t *rng, float bary[3])
{
    float s = sqrtf(core_rng_float(rng));
    float r2 = core_rng_float(rng);
    bary[0] = 1.0f - s;
    bary[1] = s * (1.0f - r2);
    bary[2] = s * r2;
}

/* Barycentric coordinates of p (assumed in the plane) w.r.t. triangle tri. */
static void bary_of(const blade_mesh_t *m, size_t tri, const float p[3], float bary[3])
{
    float v0[3], v1[3], v2[3];
    sub3(vpos(m, tri, 1), vpos(m, tri, 0), v0);
    sub3(vpos(m, tri, 2), vpos(m, tri, 0), v1);
    sub3(p, vpos(m, tri, 0), v2);
    float d00 = dot3(v0, v0), d01 = dot3(v0, v1), d11 = dot3(v1, v1);
    float d20 = dot3(v2, v0), d21 = dot3(v2, v1);
    float den = d00 * d11 - d01 * d01;
    float v = (d11 * d20 - d01 * d21) / den;
    float w = (d00 * d21 - d01 * d20) / den;
    bary[0] = 1.0f - v - w;
    bary[1] = v;
    bary[2] = w;
}

/* Closest point of triangle tri to p (Ericson, Real-Time Collision
 * Detection 5.1.5), as barycentric coordinates. */
static void closest_bary(const blade_mesh_t *m, size_t tri, const float p[3], float bary[3])
{
    const float *a = vpos(m, tri, 0), *b = vpos(m, tri, 1), *c = vpos(m, tri, 2);
    float ab[3], ac[3], ap[3], bp[3], cp[3];
    sub3(b, a, ab); sub3(c, a, ac); sub3(p, a, ap);
    float d1 = dot3(ab, ap), d2 = dot3(ac, ap);
    if (d1 <= 0.0f && d2 <= 0.0f) { bary[0] = 1; bary[1] = 0; bary[2] = 0; return; }
    sub3(p, b, bp);
    float d3 = dot3(ab, bp), d4 = dot3(ac, bp);
    if (d3 >= 0.0f && d4 <= d3) { bary[0] = 0; bary[1] = 1; bary[2] = 0; return; }
    float vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
        float v = d1 / (d1 - d3);
        bary[0] = 1 - v; bary[1] = v; bary[2] = 0;
        return;
    }
    sub3(p, c, cp);
    float d5 = dot3(ab, cp), d6 = dot3(ac, cp);
    if (d6 >= 0.0f && d5 <= d6) { bary[0] = 0; bary[1] = 0; bary[2] = 1; return; }
    float vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
        float w = d2 / (d2 - d6);
        bary[0] = 1 - w; bary[1] = 0; bary[2] = w;
        return;
    }
    float va = d3 * d6 - d5 * d4;
    if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
        float w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        bary[0] = 0; bary[1] = 1 - w; bary[2] = w;
        return;
    }
    float den = 1.0f / (va + vb + vc);
    bary[1] = vb * den;
    bary[2] = vc * den;
    bary[0] = 1.0f - bary[1] - bary[2];
}

void blade_seed_rest(blade_t *b, const float v0[3], const float up[3], float height, float width, float stiffness,
                     float angle)
{
    for (int k = 0; k < 3; k++) {
        b->v0[k] = v0[k];
        b->v1[k] = v0[k] + up[k] * height;
        b->v2[k] = v0[k] + up[k] * height;
        b->up[k] = up[k];
    }
    b->v0[3] = angle;
    b->v1[3] = height;
    b->v2[3] = width;
    b->up[3] = stiffness;
}

static void make_blade(blade_t *b, const float v0[3], const float up[3], core_rng_t *rng,
                       const blade_seed_desc_t *d)
{
    float h = core_rng_range(rng, d->population.height[0], d->population.height[1]);
    float w = core_rng_range(rng, d->population.width[0], d->population.width[1]);
    float s = core_rng_range(rng, d->population.stiffness[0], d->population.stiffness[1]);
    float a = core_rng_range(rng, d->angle_min, d->angle_max);
    blade_seed_rest(b, v0, up, h, w, s, a);
}

/* ---- Poisson-disk tuft centres ------------------------------------------ */

typedef struct centre_t {
    float p[3];
    size_t tri;
} centre_t;

typedef struct grid_t {
    int32_t *head; /* bucket -> first centre, -1 when empty */
    int32_t *next; /* centre -> next centre in the bucket */
    size_t mask;
    float cell;
} grid_t;

static size_t grid_bucket(const grid_t *g, int64_t x, int64_t y, int64_t z)
{
    uint32_t h = core_hash_u32((uint32_t)x ^ core_hash_u32((uint32_t)y ^ core_hash_u32((uint32_t)z)));
    return (size_t)h & g->mask;
}

static bool grid_far_enough(const grid_t *g, const centre_t *c, const float p[3], float min_d)
{
    int64_t cx = (int64_t)floorf(p[0] / g->cell), cy = (int64_t)floorf(p[1] / g->cell),
            cz = (int64_t)floorf(p[2] / g->cell);
    for (int64_t dz = -1; dz <= 1; dz++)
        for (int64_t dy = -1; dy <= 1; dy++)
            for (int64_t dx = -1; dx <= 1; dx++)
                for (int32_t i = g->head[grid_bucket(g, cx + dx, cy + dy, cz + dz)]; i >= 0; i = g->next[i]) {
                    float e[3];
                    sub3(c[i].p, p, e);
                    if (dot3(e, e) < min_d * min_d) return false;
                }
    return true;
}

static void grid_insert(grid_t *g, int32_t i, const float p[3])
{
    size_t b = grid_bucket(g, (int64_t)floorf(p[0] / g->cell), (int64_t)floorf(p[1] / g->cell),
                           (int64_t)floorf(p[2] / g->cell));
    g->next[i] = g->head[b];
    g->head[b] = i;
}

/* ---- Morton order ----------------------------------------------------------- */

static uint64_t spread21(uint64_t x)
{
    x &= 0x1fffffULL;
    x = (x | x << 32) & 0x1f00000000ffffULL;
    x = (x | x << 16) & 0x1f0000ff0000ffULL;
    x = (x | x << 8) & 0x100f00f00f00f00fULL;
    x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
    x = (x | x << 2) & 0x1249249249249249ULL;
    return x;
}

uint64_t blade_seed_morton(const blade_field_t *f, const float p[3])
{
    uint64_t q[3];
    for (int k = 0; k < 3; k++) {
        float c = floorf((p[k] - f->morton_origin[k]) * f->morton_scale);
        c = fminf(fmaxf(c, 0.0f), MORTON_CELLS - 1.0f);
        q[k] = (uint64_t)c;
    }
    return spread21(q[0]) | spread21(q[1]) << 1 | spread21(q[2]) << 2;
}

static int cmp_order(const void *a, const void *b)
{
    const blade_order_key_t *x = a, *y = b;
    if (x->dist2 != y->dist2) return x->dist2 < y->dist2 ? -1 : 1;
    return (x->id > y->id) - (x->id < y->id);
}

void blade_order_sort(blade_order_key_t *keys, size_t n)
{
    if (n > 1) qsort(keys, n, sizeof *keys, cmp_order);
}

/* Sorts keys by code, ties by index: an LSD radix sort of 11-bit digits
 * (stable, so keys made in index order keep it among equal codes: the
 * order qsort by (code, index) gave, 6.5x faster on 12M blades). tmp holds
 * n keys. Passes whose digit is the same in every key are skipped. */
enum { RADIX_BITS = 11, RADIX = 1 << RADIX_BITS, RADIX_PASSES = (64 + RADIX_BITS - 1) / RADIX_BITS };

void blade_seed_sort(blade_seed_key_t *keys, blade_seed_key_t *tmp, size_t n)
{
    size_t(*count)[RADIX] = calloc(RADIX_PASSES, sizeof *count);
    assert(count);
    for (size_t i = 0; i < n; i++)
        for (int p = 0; p < RADIX_PASSES; p++) count[p][(keys[i].code >> (p * RADIX_BITS)) & (RADIX - 1)]++;
    blade_seed_key_t *from = keys, *to = tmp;
    for (int p = 0; p < RADIX_PASSES; p++) {
        size_t *c = count[p], sum = 0;
        bool one_digit = false;
        for (int d = 0; d < RADIX; d++) {
            one_digit = one_digit || c[d] == n;
            size_t k = c[d];
            c[d] = sum;
            sum += k;
        }
        if (one_digit) continue;
        for (size_t i = 0; i < n; i++) to[c[(from[i].code >> (p * RADIX_BITS)) & (RADIX - 1)]++] = from[i];
        blade_seed_key_t *t = from;
        from = to;
        to = t;
    }
    if (from != keys) memcpy(keys, from, n * sizeof *keys);
    free(count);
}

/* ---- seeding ------------------------------------------------------------------ */

static bool fail(blade_field_t *out, const char *msg, size_t a, size_t b)
{
    core_log_error("blade_seed_mesh: %s (%zu, %zu)", msg, a, b);
    blade_field_free(out);
    return false;
}

static void seed_uniform(const sampler_t *s, const blade_seed_desc_t *d, core_rng_t *rng,
                         blade_t *blades, size_t count)
{
    for (size_t i = 0; i < count; i++) {
        size_t tri = pick_triangle(s, rng);
        float bary[3], p[3], n[3];
        random_bary(rng, bary);
        blade_seed_point(s->mesh, tri, bary, p);
        blade_seed_normal(s->mesh, tri, bary, n);
        make_blade(&blades[i], p, n, rng, d);
    }
}

/* Dart throwing; returns the number of centres accepted (<= target). */
static size_t tuft_centres(const sampler_t *s, const blade_seed_desc_t *d, core_rng_t *rng,
                           centre_t *c, size_t target)
{
    grid_t g;
    size_t buckets = 16;
    while (buckets < 2 * target) buckets *= 2;
    g.head = malloc(buckets * sizeof *g.head);
    g.next = malloc(target * sizeof *g.next);
    g.mask = buckets - 1;
    g.cell = d->tuft_min_distance;
    assert(g.head && g.next);
    memset(g.head, 0xff, buckets * sizeof *g.head);
    size_t accepted = 0;
    size_t attempts = target * (size_t)d->tuft_attempts_per_centre;
    for (size_t a = 0; a < attempts && accepted < target; a++) {
        size_t tri = pick_triangle(s, rng);
        float bary[3], p[3];
        random_bary(rng, bary);
        blade_seed_point(s->mesh, tri, bary, p);
        if (!grid_far_enough(&g, c, p, d->tuft_min_distance)) continue;
        memcpy(c[accepted].p, p, sizeof p);
        c[accepted].tri = tri;
        grid_insert(&g, (int32_t)accepted, p);
        accepted++;
    }
    free(g.head);
    free(g.next);
    return accepted;
}

static void seed_tuft(const sampler_t *s, const blade_seed_desc_t *d, core_rng_t *rng,
                      const centre_t *c, blade_t *blades)
{
    float n[3], t1[3], t2[3];
    tri_area(s->mesh, c->tri, n);
    float helper[3] = {fabsf(n[0]) < 0.9f ? 1.0f : 0.0f, fabsf(n[0]) < 0.9f ? 0.0f : 1.0f, 0.0f};
    cross3(n, helper, t1);
    normalize3(t1);
    cross3(n, t1, t2);
    for (int i = 0; i < d->tuft_blades; i++) {
        float p[3], bary[3];
        bool inside = false;
        for (int tries = 0; tries < TUFT_REDRAWS && !inside; tries++) {
            float rad = d->tuft_radius * sqrtf(core_rng_float(rng));
            float phi = 6.28318531f * core_rng_float(rng);
            for (int k = 0; k < 3; k++) p[k] = c->p[k] + rad * (cosf(phi) * t1[k] + sinf(phi) * t2[k]);
            bary_of(s->mesh, c->tri, p, bary);
            inside = bary[0] >= 0.0f && bary[1] >= 0.0f && bary[2] >= 0.0f;
        }
        if (!inside) closest_bary(s->mesh, c->tri, p, bary);
        float root[3], up[3];
        blade_seed_point(s->mesh, c->tri, bary, root);
        blade_seed_normal(s->mesh, c->tri, bary, up);
        make_blade(&blades[i], root, up, rng, d);
    }
}

void blade_seed_frame(const blade_mesh_t *mesh, blade_field_t *f)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < mesh->index_count; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], mesh->positions[3 * (size_t)mesh->indices[i] + (size_t)k]);
            hi[k] = fmaxf(hi[k], mesh->positions[3 * (size_t)mesh->indices[i] + (size_t)k]);
        }
    float extent = fmaxf(fmaxf(hi[0] - lo[0], hi[1] - lo[1]), fmaxf(hi[2] - lo[2], 1e-6f));
    memcpy(f->morton_origin, lo, sizeof f->morton_origin);
    f->morton_scale = MORTON_CELLS / extent;
}

static void build_patches(blade_field_t *f, const blade_t *unsorted)
{
    size_t n = f->blade_count;
    blade_seed_key_t *keys = malloc((n ? n : 1) * sizeof *keys), *tmp = malloc((n ? n : 1) * sizeof *tmp);
    assert(keys && tmp);
    for (size_t i = 0; i < n; i++) {
        keys[i].code = blade_seed_morton(f, unsorted[i].v0);
        keys[i].index = (uint32_t)i;
    }
    blade_seed_sort(keys, tmp, n);
    for (size_t i = 0; i < n; i++) f->blades[i] = unsorted[keys[i].index];
    free(tmp);
    free(keys);
    for (size_t i = n; i < f->padded_count; i++) {
        blade_t *b = &f->blades[i];
        *b = f->blades[n - 1];
        memcpy(b->v1, b->v0, 3 * sizeof(float));
        memcpy(b->v2, b->v0, 3 * sizeof(float));
        b->v1[3] = 0.0f;
        b->v2[3] = 0.0f;
    }
    blade_seed_patch_boxes(f);
}

void blade_seed_patch_boxes(blade_field_t *f)
{
    size_t ps = (size_t)f->patch_size;
    for (size_t p = 0; p < f->patch_count; p++) {
        blade_aabb_t *box = &f->patch_aabbs[p];
        float grow = 0.0f;
        for (int k = 0; k < 3; k++) { box->min[k] = INFINITY; box->max[k] = -INFINITY; }
        for (size_t i = p * ps; i < (p + 1) * ps; i++) {
            const blade_t *b = &f->blades[i];
            for (int k = 0; k < 3; k++) {
                box->min[k] = fminf(box->min[k], b->v0[k]);
                box->max[k] = fmaxf(box->max[k], b->v0[k]);
            }
            grow = fmaxf(grow, b->v1[3] + 0.5f * b->v2[3]);
        }
        for (int k = 0; k < 3; k++) { box->min[k] -= grow; box->max[k] += grow; }
    }
}

bool blade_seed_mesh(const blade_mesh_t *mesh, const blade_seed_desc_t *desc, blade_field_t *out)
{
    memset(out, 0, sizeof *out);
    blade_seed_desc_t d = blade_seed_desc_defaults(desc);
    out->patch_size = d.patch_size;
    if (!mesh->positions || !mesh->indices || mesh->index_count % 3 != 0)
        return fail(out, "mesh needs positions and a multiple of 3 indices", mesh->index_count, 0);
    if (d.patch_size <= 0 || d.tuft_blades <= 0 || d.population.density < 0.0f)
        return fail(out, "bad patch_size or tuft_blades or density", (size_t)d.patch_size, (size_t)d.tuft_blades);
    for (size_t i = 0; i < mesh->index_count; i++)
        if (mesh->indices[i] >= mesh->vertex_count)
            return fail(out, "index out of range (index, vertex_count)", mesh->indices[i], mesh->vertex_count);

    sampler_t s = {mesh, mesh->index_count / 3, NULL, 0.0};
    if (s.tri_count == 0) return true;
    s.cdf = malloc(s.tri_count * sizeof *s.cdf);
    assert(s.cdf);
    for (size_t t = 0; t < s.tri_count; t++) {
        s.area += tri_area(mesh, t, NULL);
        s.cdf[t] = s.area;
    }

    core_rng_t rng;
    core_rng_seed(&rng, d.seed, 0x626c616465ULL);
    double expected = (double)d.population.density * s.area;
    size_t count, tufts = 0, k = (size_t)d.tuft_blades;
    centre_t *centres = NULL;
    if (d.mode == BLADE_SEED_TUFTS) {
        size_t target = (size_t)floor(expected / (double)k + 0.5);
        if (target * k > d.max_blades) {
            free(s.cdf);
            return fail(out, "tuft blade count exceeds max_blades", target * k, d.max_blades);
        }
        centres = malloc((target ? target : 1) * sizeof *centres);
        assert(centres);
        tufts = target ? tuft_centres(&s, &d, &rng, centres, target) : 0;
        if (tufts < target)
            core_log_warn("blade_seed_mesh: dart throwing placed %zu of %zu tufts (min distance %.3g m)",
                          tufts, target, (double)d.tuft_min_distance);
        count = tufts * k;
    } else {
        count = (size_t)floor(expected + 0.5);
        if (count > d.max_blades) {
            free(s.cdf);
            return fail(out, "blade count exceeds max_blades", count, d.max_blades);
        }
    }
    if (count == 0) {
        free(centres);
        free(s.cdf);
        return true;
    }

    blade_t *unsorted = malloc(count * sizeof *unsorted);
    assert(unsorted);
    if (d.mode == BLADE_SEED_TUFTS)
        for (size_t t = 0; t < tufts; t++) seed_tuft(&s, &d, &rng, &centres[t], &unsorted[t * k]);
    else
        seed_uniform(&s, &d, &rng, unsorted, count);
    free(centres);
    free(s.cdf);

    size_t ps = (size_t)d.patch_size;
    out->blade_count = count;
    out->patch_count = (count + ps - 1) / ps;
    out->padded_count = out->patch_count * ps;
    out->blades = malloc(out->padded_count * sizeof *out->blades);
    out->eta = calloc(out->padded_count, sizeof *out->eta);
    out->patch_aabbs = malloc(out->patch_count * sizeof *out->patch_aabbs);
    assert(out->blades && out->eta && out->patch_aabbs);
    blade_seed_frame(mesh, out);
    build_patches(out, unsorted);
    free(unsorted);
    return true;
}

void blade_field_free(blade_field_t *f)
{
    free(f->blades);
    free(f->eta);
    free(f->patch_aabbs);
    memset(f, 0, sizeof *f);
}

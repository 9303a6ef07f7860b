/* test_blade_seed: blade seeding on triangle meshes (Jahrmann & Wimmer 2017
 * sec. 4) and patch grouping. Checks counts against density x area (area
 * recomputed here), area-proportional distribution, determinism by state
 * hash, roots on the mesh by brute-force point-triangle distance, Morton
 * order by an independent bit-by-bit interleave, padding, and patch AABBs
 * under arbitrary displacements and under simulation. */
#include "blade/blade_ref.h"
#include "blade/blade_seed.h"
#include "core/core.h"
#include "test.h"

#include <stdint.h>
#include <string.h>

/* Bumpy terrain, NX x NZ quads over [0,10]^2, with analytic normals. The
 * left half (x < 5) is subdivided twice as finely to vary triangle sizes. */
typedef struct mesh_t {
    float *pos, *nrm;
    uint32_t *idx;
    size_t nv, ni;
} mesh_t;

static float bump(float x, float z) { return 0.5f * sinf(x) * cosf(0.7f * z); }

static mesh_t make_terrain(void)
{
    enum { NX = 30, NZ = 20 };
    mesh_t m = {0};
    m.nv = (NX + 1) * (NZ + 1);
    m.pos = malloc(m.nv * 3 * sizeof(float));
    m.nrm = malloc(m.nv * 3 * sizeof(float));
    m.idx = malloc(NX * NZ * 6 * sizeof(uint32_t));
    for (int j = 0; j <= NZ; j++)
        for (int i = 0; i <= NX; i++) {
            /* columns 0..19 cover x in [0,5], columns 20..29 cover [5,10] */
            float x = i <= 20 ? 0.25f * (float)i : 5.0f + 0.5f * (float)(i - 20);
            float z = 0.5f * (float)j;
            float *p = &m.pos[3 * (size_t)(j * (NX + 1) + i)], *n = &m.nrm[3 * (size_t)(j * (NX + 1) + i)];
            p[0] = x;
            p[1] = bump(x, z);
            p[2] = z;
            float dx = 0.5f * cosf(x) * cosf(0.7f * z), dz = -0.35f * sinf(x) * sinf(0.7f * z);
            float l = sqrtf(dx * dx + 1 + dz * dz);
            n[0] = -dx / l;
            n[1] = 1 / l;
            n[2] = -dz / l;
        }
    for (int j = 0; j < NZ; j++)
        for (int i = 0; i < NX; i++) {
            uint32_t a = (uint32_t)(j * (NX + 1) + i), b = a + 1, c = a + NX + 1, d = c + 1;
            uint32_t q[6] = {a, c, b, b, c, d};
            memcpy(&m.idx[m.ni], q, sizeof q);
            m.ni += 6;
        }
    return m;
}

/* A closed, rotated cube of side 2 (12 triangles, no normals): blades on
 * every face, including walls and the underside. */
static mesh_t make_cube(void)
{
    mesh_t m = {0};
    m.nv = 8;
    m.pos = malloc(8 * 3 * sizeof(float));
    for (int i = 0; i < 8; i++) {
        float x = (i & 1) ? 1.0f : -1.0f, y = (i & 2) ? 1.0f : -1.0f, z = (i & 4) ? 1.0f : -1.0f;
        float c = cosf(0.5f), s = sinf(0.5f);
        m.pos[3 * i + 0] = c * x - s * y + 3.0f;
        m.pos[3 * i + 1] = s * x + c * y;
        m.pos[3 * i + 2] = z - 2.0f;
    }
    static const uint32_t q[36] = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                   2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    m.idx = malloc(sizeof q);
    memcpy(m.idx, q, sizeof q);
    m.ni = 36;
    return m;
}

static void mesh_free(mesh_t *m)
{
    free(m->pos);
    free(m->nrm);
    free(m->idx);
}

static blade_mesh_t view(const mesh_t *m)
{
    return (blade_mesh_t){m->pos, m->nrm, m->nv, m->idx, m->ni};
}

static const double *dv(const mesh_t *m, uint32_t i, double out[3])
{
    for (int k = 0; k < 3; k++) out[k] = m->pos[3 * i + (uint32_t)k];
    return out;
}

static double area_of(const mesh_t *m, double xmax)
{
    double a = 0;
    for (size_t t = 0; t < m->ni; t += 3) {
        double p[3][3];
        for (int k = 0; k < 3; k++) dv(m, m->idx[t + (size_t)k], p[k]);
        if ((p[0][0] + p[1][0] + p[2][0]) / 3 > xmax) continue;
        double e1[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
        double e2[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
        double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        a += 0.5 * sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    return a;
}

static double seg_dist2(const double p[3], const double a[3], const double b[3])
{
    double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    double t = (ab[0] * ap[0] + ab[1] * ap[1] + ab[2] * ap[2]) / (ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2]);
    t = t < 0 ? 0 : (t > 1 ? 1 : t);
    double d[3] = {ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]};
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
}

/* Distance from p to the nearest triangle: plane distance when the
 * projection is inside (same-side tests), else the nearest edge. */
static double mesh_dist(const mesh_t *m, const float pf[3])
{
    double p[3] = {pf[0], pf[1], pf[2]}, best = INFINITY;
    for (size_t t = 0; t < m->ni; t += 3) {
        double v[3][3];
        for (int k = 0; k < 3; k++) dv(m, m->idx[t + (size_t)k], v[k]);
        double e1[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
        double e2[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        for (int k = 0; k < 3; k++) n[k] /= nl;
        double sd = (p[0] - v[0][0]) * n[0] + (p[1] - v[0][1]) * n[1] + (p[2] - v[0][2]) * n[2];
        double q[3] = {p[0] - sd * n[0], p[1] - sd * n[1], p[2] - sd * n[2]};
        bool inside = true;
        for (int k = 0; k < 3; k++) {
            const double *a = v[k], *b = v[(k + 1) % 3];
            double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, aq[3] = {q[0] - a[0], q[1] - a[1], q[2] - a[2]};
            double c[3] = {ab[1] * aq[2] - ab[2] * aq[1], ab[2] * aq[0] - ab[0] * aq[2], ab[0] * aq[1] - ab[1] * aq[0]};
            if (c[0] * n[0] + c[1] * n[1] + c[2] * n[2] < 0) inside = false;
        }
        double d2 = inside ? sd * sd
                           : fmin(seg_dist2(p, v[0], v[1]), fmin(seg_dist2(p, v[1], v[2]), seg_dist2(p, v[2], v[0])));
        if (d2 < best) best = d2;
    }
    return sqrt(best);
}

/* Morton code by a plain bit loop, independent of the library's magic masks. */
static uint64_t morton_loop(const blade_field_t *f, const float p[3])
{
    uint64_t q[3], code = 0;
    for (int k = 0; k < 3; k++) {
        double c = floor((double)((p[k] - f->morton_origin[k]) * f->morton_scale));
        q[k] = c < 0 ? 0 : (c > 2097151.0 ? 2097151u : (uint64_t)c);
    }
    for (int bit = 0; bit < 21; bit++)
        for (int k = 0; k < 3; k++) code |= ((q[k] >> bit) & 1u) << (3 * bit + k);
    return code;
}

static uint64_t field_hash(const blade_field_t *f)
{
    uint64_t h = core_hash_bytes(f->blades, f->padded_count * sizeof *f->blades, 0);
    h = core_hash_bytes(f->eta, f->padded_count * sizeof *f->eta, h);
    return core_hash_bytes(f->patch_aabbs, f->patch_count * sizeof *f->patch_aabbs, h);
}

static bool in_box(const blade_aabb_t *b, const float p[3])
{
    for (int k = 0; k < 3; k++)
        if (p[k] < b->min[k] || p[k] > b->max[k]) return false;
    return true;
}

/* Structure shared by every seeded field: roots on the mesh, unit up,
 * rest pose, Morton order, padding and AABBs. */
static void check_field(const mesh_t *m, const blade_field_t *f, core_rng_t *rng)
{
    CHECK(f->padded_count % (size_t)f->patch_size == 0);
    CHECK(f->padded_count == f->patch_count * (size_t)f->patch_size);
    CHECK(f->padded_count >= f->blade_count && f->padded_count - f->blade_count < (size_t)f->patch_size);
    double worst_dist = 0;
    int bad_up = 0, bad_order = 0, bad_code = 0, bad_box = 0;
    uint64_t prev = 0;
    for (size_t i = 0; i < f->padded_count; i++) {
        const blade_t *b = &f->blades[i];
        const blade_aabb_t *box = &f->patch_aabbs[i / (size_t)f->patch_size];
        if (i >= f->blade_count) {
            CHECK(b->v1[3] == 0.0f && b->v2[3] == 0.0f);
            CHECK(in_box(box, b->v0));
            continue;
        }
        double d = mesh_dist(m, b->v0);
        if (d > worst_dist) worst_dist = d;
        float ul = sqrtf(b->up[0] * b->up[0] + b->up[1] * b->up[1] + b->up[2] * b->up[2]);
        bad_up += fabsf(ul - 1.0f) > 1e-5f;
        float h = b->v1[3];
        for (int k = 0; k < 3; k++) bad_up += fabsf(b->v2[k] - (b->v0[k] + b->up[k] * h)) > 1e-5f;
        uint64_t code = morton_loop(f, b->v0);
        bad_code += code != blade_seed_morton(f, b->v0);
        bad_order += i > 0 && code < prev; /* monotone inside and across patches */
        prev = code;
        /* any point within the blade's height of its root is in the box */
        for (int trial = 0; trial < 16; trial++) {
            float dir[3], l2 = 0;
            for (int k = 0; k < 3; k++) {
                dir[k] = core_rng_range(rng, -1, 1);
                l2 += dir[k] * dir[k];
            }
            float s = trial < 8 ? h / sqrtf(l2) : h * core_rng_float(rng) / sqrtf(l2);
            float p[3] = {b->v0[0] + dir[0] * s, b->v0[1] + dir[1] * s, b->v0[2] + dir[2] * s};
            bad_box += !in_box(box, p);
        }
        for (int c = 0; c < 6; c++) { /* the six extreme points */
            float p[3] = {b->v0[0], b->v0[1], b->v0[2]};
            p[c / 2] += (c & 1) ? h : -h;
            bad_box += !in_box(box, p);
        }
    }
    printf("field: %zu blades, %zu patches; worst root-mesh distance %.2e\n", f->blade_count,
           f->patch_count, worst_dist);
    CHECK(worst_dist < 1e-4);
    CHECK(bad_up == 0);
    CHECK(bad_code == 0);
    CHECK(bad_order == 0);
    CHECK(bad_box == 0);
}

int main(void)
{
    core_log_set_quiet(true);
    core_rng_t rng;
    core_rng_seed(&rng, 5, 5);
    mesh_t terrain = make_terrain();
    blade_mesh_t tv = view(&terrain);
    double area = area_of(&terrain, INFINITY), left = area_of(&terrain, 5.0);

    /* uniform by area */
    blade_field_t f;
    blade_seed_desc_t desc = {.seed = 1, .population = {.density = 60.0f}};
    CHECK(blade_seed_mesh(&tv, &desc, &f));
    long want = lround(60.0 * area);
    printf("uniform: area %.3f m^2, %zu blades (want %ld)\n", area, f.blade_count, want);
    CHECK(labs((long)f.blade_count - want) <= 1);
    size_t n_left = 0;
    for (size_t i = 0; i < f.blade_count; i++) n_left += f.blades[i].v0[0] < 5.0f;
    double frac = (double)n_left / (double)f.blade_count, want_frac = left / area;
    double sigma = sqrt(want_frac * (1 - want_frac) / (double)f.blade_count);
    printf("uniform: left half %.4f of blades, %.4f of area (sigma %.4f)\n", frac, want_frac, sigma);
    CHECK(fabs(frac - want_frac) < 4 * sigma);
    for (size_t i = 0; i < f.blade_count; i++) {
        const blade_t *b = &f.blades[i];
        CHECK(b->v1[3] >= BLADE_DEFAULT_HEIGHT_MIN && b->v1[3] < BLADE_DEFAULT_HEIGHT_MAX);
        CHECK(b->v2[3] >= BLADE_DEFAULT_WIDTH_MIN && b->v2[3] < BLADE_DEFAULT_WIDTH_MAX);
        CHECK(b->up[3] >= BLADE_DEFAULT_STIFFNESS_MIN && b->up[3] < BLADE_DEFAULT_STIFFNESS_MAX);
        CHECK(b->v0[3] >= 0.0f && b->v0[3] < 6.2831854f);
        if (test_failures) break;
    }
    check_field(&terrain, &f, &rng);

    /* determinism */
    uint64_t h1 = field_hash(&f);
    blade_field_t g;
    CHECK(blade_seed_mesh(&tv, &desc, &g));
    CHECK(field_hash(&g) == h1);
    blade_field_free(&g);
    desc.seed = 2;
    CHECK(blade_seed_mesh(&tv, &desc, &g));
    CHECK(field_hash(&g) != h1);
    blade_field_free(&g);

    /* draw order: the nearest-first sort (ties by id) */
    {
        blade_order_key_t keys[6] = {{4, 7}, {1, 3}, {4, 2}, {0, 9}, {9, 0}, {1, 1}};
        blade_order_sort(keys, 6);
        const uint32_t order[6] = {9, 1, 3, 2, 7, 0};
        for (int k = 0; k < 6; k++) CHECK(keys[k].id == order[k]);
    }

    /* patch AABBs hold the whole simulated blade (curve samples) */
    {
        blade_env_t env = {.dt = 1.0f / 30.0f, .gravity = 20.0f, .wind_count = 1};
        static collide_set_t set = {.sphere_count = 1};
        env.winds[0] = blade_wind_wave(1, 0.5f, 12.0f, 4.0f, 3.0f);
        int outside = 0;
        for (int s = 0; s < 60; s++) {
            env.time = (float)s * env.dt;
            set.spheres[0] = (blade_sphere_t){.centre_radius = {(float)s / 6.0f, 0.3f, 5.0f, 1.0f}};
            blade_ref_step(f.blades, f.eta, f.padded_count, &env, &set);
        }
        for (size_t i = 0; i < f.padded_count; i++) {
            const blade_t *b = &f.blades[i];
            for (int j = 0; j <= 8; j++) {
                float t = (float)j / 8, u = 1 - t, p[3];
                for (int k = 0; k < 3; k++) p[k] = u * u * b->v0[k] + 2 * u * t * b->v1[k] + t * t * b->v2[k];
                outside += !in_box(&f.patch_aabbs[i / (size_t)f.patch_size], p);
            }
        }
        CHECK(outside == 0);
    }
    blade_field_free(&f);

    /* tufts */
    desc = (blade_seed_desc_t){.seed = 9,
                               .mode = BLADE_SEED_TUFTS,
                               .population = {.density = 80.0f},
                               .tuft_blades = 10,
                               .tuft_min_distance = 0.2f,
                               .tuft_radius = 0.08f,
                               .patch_size = 128};
    CHECK(blade_seed_mesh(&tv, &desc, &f));
    long want_tufts = lround(80.0 * area / 10.0);
    printf("tufts: %zu blades (want %ld)\n", f.blade_count, want_tufts * 10);
    CHECK((long)f.blade_count == want_tufts * 10);
    CHECK(f.patch_size == 128);
    check_field(&terrain, &f, &rng);
    h1 = field_hash(&f);
    CHECK(blade_seed_mesh(&tv, &desc, &g));
    CHECK(field_hash(&g) == h1);
    blade_field_free(&g);
    blade_field_free(&f);
    /* unreachable Poisson target: fewer tufts and a warning, not a failure */
    int warns = core_log_warn_count();
    desc.tuft_min_distance = 1.5f;
    CHECK(blade_seed_mesh(&tv, &desc, &f));
    CHECK(core_log_warn_count() == warns + 1);
    CHECK((long)f.blade_count < want_tufts * 10 && f.blade_count % 10 == 0);
    blade_field_free(&f);

    /* a closed rotated cube without normals: up = face normal, outward */
    mesh_t cube = make_cube();
    blade_mesh_t cv = view(&cube);
    desc = (blade_seed_desc_t){.seed = 3, .population = {.density = 200.0f}, .patch_size = 100};
    CHECK(blade_seed_mesh(&cv, &desc, &f));
    CHECK(labs((long)f.blade_count - 4800) <= 1);
    check_field(&cube, &f, &rng);
    int inward = 0;
    for (size_t i = 0; i < f.blade_count; i++) {
        const blade_t *b = &f.blades[i];
        float c[3] = {b->v0[0] - 3.0f, b->v0[1], b->v0[2] + 2.0f};
        inward += c[0] * b->up[0] + c[1] * b->up[1] + c[2] * b->up[2] < 0.9f;
    }
    CHECK(inward == 0);
    blade_field_free(&f);

    /* no silent caps: over max_blades is an error */
    int errs = core_log_error_count();
    desc.max_blades = 1000;
    CHECK(!blade_seed_mesh(&cv, &desc, &f));
    CHECK(core_log_error_count() == errs + 1);
    CHECK(f.blades == NULL && f.blade_count == 0);
    /* bad index */
    uint32_t bad[3] = {0, 1, 99};
    blade_mesh_t bv = {cube.pos, NULL, 8, bad, 3};
    CHECK(!blade_seed_mesh(&bv, &desc, &f));
    CHECK(core_log_error_count() == errs + 2);

    blade_seed_desc_t dd = blade_seed_desc_defaults(&(blade_seed_desc_t){0});
    CHECK(dd.population.density == BLADE_DEFAULT_DENSITY && dd.patch_size == 256 && dd.tuft_blades == 8);
    CHECK(dd.max_blades == (size_t)1 << 22);
    mesh_free(&terrain);
    mesh_free(&cube);
    TEST_END();
}

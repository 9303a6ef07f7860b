/* test_blade_ref: the CPU reference of the Jahrmann & Wimmer 2017 blade
 * simulation and culling. Hand-computed single steps for recovery (eq. 3),
 * gravity (eq. 4-6), wind (eq. 7-8), collision (eq. 14-16) and validation
 * (eq. 9-13); invariants over 1000 steps with wind, moving spheres and
 * random dt; culling counts against an independent brute-force recount. */
#include "blade/blade_ref.h"
#include "core/core.h"
#include "test.h"

#include <cglm/cglm.h>
#include <stdint.h>
#include <string.h>

#define EPS 1e-5
#define PEN_BOUND 1e-6 /* v2 and m end outside (exit margin 1e-4 r) */

static blade_t upright(float x, float z, float h, float angle, float s)
{
    blade_t b = {{x, 0, z, angle}, {x, h, z, h}, {x, h, z, 0.02f}, {0, 1, 0, s}};
    return b;
}

static void check_v3(const float *a, double x, double y, double z, double eps, int line)
{
    if (fabs(a[0] - x) > eps || fabs(a[1] - y) > eps || fabs(a[2] - z) > eps) {
        fprintf(stderr, "line %d: got (%.7g %.7g %.7g) want (%.7g %.7g %.7g)\n", line, a[0], a[1],
                a[2], x, y, z);
        test_failures++;
    }
}
#define CHECK_V3(a, x, y, z, eps) check_v3((a), (x), (y), (z), (eps), __LINE__)

static void test_frame_and_forces(void)
{
    float w[3], f[3], o[3];
    blade_t b = upright(0, 0, 1, 0.0f, 2.0f);
    blade_ref_frame(&b, w, f);
    CHECK_V3(w, 1, 0, 0, EPS);
    CHECK_V3(f, 0, 0, -1, EPS);
    b.v0[3] = GLM_PI_2f;
    blade_ref_frame(&b, w, f);
    CHECK_V3(w, 0, 0, 1, EPS);
    CHECK_V3(f, 1, 0, 0, EPS);
    /* up parallel to (cos a, 0, sin a): falls back to (-sin a, 0, cos a) */
    blade_t side = {{0, 0, 0, 0}, {0, 0, 0, 1}, {1, 0, 0, 0.02f}, {1, 0, 0, 1}};
    blade_ref_frame(&side, w, f);
    CHECK_V3(w, 0, 0, 1, EPS);

    /* recovery, eq. 3 */
    b = upright(0, 0, 1, 0.0f, 2.0f);
    b.v2[0] = 0.5f;
    b.v2[1] = 0.5f;
    blade_ref_recovery(&b, 0.0f, o);
    CHECK_V3(o, -1, 1, 0, EPS);
    blade_ref_recovery(&b, 0.5f, o);
    CHECK_V3(o, -0.5, 0.5, 0, EPS);
    blade_ref_recovery(&b, 0.95f, o); /* max(1 - eta, 0.1) */
    CHECK_V3(o, -0.1, 0.1, 0, EPS);

    /* gravity, eq. 4-6: direction only */
    b = upright(0, 0, 1, 0.0f, 2.0f);
    blade_env_t env = blade_env_defaults(&(blade_env_t){.gravity = 10.0f});
    blade_ref_gravity(&b, &env, o);
    CHECK_V3(o, 0, -10, -2.5, EPS);
    /* mixed with centre gravity, t = 0.5, centre direction (0.6, 0, 0.8) */
    env = blade_env_defaults(&(blade_env_t){
        .gravity = 10.0f, .gravity_centre = {3, 0, 4}, .gravity_centre_mix = 0.5f});
    blade_ref_gravity(&b, &env, o);
    CHECK_V3(o, 3, -5, 4 - 0.25 * sqrt(50.0), EPS);
    env = blade_env_defaults(&(blade_env_t){.gravity_off = true});
    blade_ref_gravity(&b, &env, o);
    CHECK_V3(o, 0, 0, 0, 0);
    env = blade_env_defaults(&(blade_env_t){0});
    CHECK_NEAR(env.gravity, 9.81, 1e-6);
    CHECK_NEAR(env.gravity_dir[1], -1.0, 0);
    CHECK_NEAR(env.collision_decay, 1.0, 0);

    /* wind fields */
    blade_wind_t wave = blade_wind_wave(2.0f, 0.0f, 2.0f, 4.0f, 1.0f);
    float p[3] = {1, 0, 0};
    blade_ref_wind_field(&wave, p, 0.0f, o); /* phase pi/2 */
    CHECK_V3(o, 2, 0, 0, EPS);
    blade_ref_wind_field(&wave, p, 1.0f, o); /* phase 0 */
    CHECK_V3(o, 1, 0, 0, EPS);
    blade_ref_wind_field(&wave, p, 2.0f, o); /* phase -pi/2 */
    CHECK_V3(o, 0, 0, 0, EPS);
    blade_wind_t point = blade_wind_point((float[3]){0, 0, 0}, 3.0f, 2.0f);
    blade_ref_wind_field(&point, p, 0.0f, o);
    CHECK_V3(o, 1.5, 0, 0, EPS);
    blade_ref_wind_field(&point, (float[3]){0, 0, -3}, 0.0f, o);
    CHECK_V3(o, 0, 0, 0, 0);

    /* wind on a blade, eq. 7-8 */
    env = blade_env_defaults(&(blade_env_t){.wind_count = 1});
    env.winds[0] = blade_wind_point((float[3]){-1, 0, 0}, 4.0f, 2.0f); /* w_i(0) = (2, 0, 0) */
    b = upright(0, 0, 1, 0.0f, 2.0f);
    blade_ref_wind(&b, &env, o); /* f_d = 1, f_r = 1 */
    CHECK_V3(o, 2, 0, 0, EPS);
    b.v2[0] = 0.6f;
    b.v2[1] = 0.8f; /* f_d = 1 - 0.6, f_r = 0.8 */
    blade_ref_wind(&b, &env, o);
    CHECK_V3(o, 2 * 0.4 * 0.8, 0, 0, EPS);
    b.v2[0] = 1.0f;
    b.v2[1] = 0.0f; /* lying along the wind: f_d = 0, f_r = 0 */
    blade_ref_wind(&b, &env, o);
    CHECK_V3(o, 0, 0, 0, EPS);
}

static void test_validation(void)
{
    /* tip pushed below the ground: eq. 9 lifts it, eq. 10-13 by hand */
    blade_t b = upright(0, 0, 1, 0.0f, 1.0f);
    b.v2[0] = 0.5f;
    b.v2[1] = -0.3f;
    blade_ref_validate(&b, BLADE_LENGTH_PAPER);
    double l1 = 0.5 + sqrt(0.5), len = (2 * 0.5 + l1) / 3, r = 1 / len;
    CHECK_V3(b.v1, 0, 0.5 * r, 0, EPS);
    CHECK_V3(b.v2, 0.5 * r, 0, 0, EPS);
    CHECK(b.v2[1] >= 0.0f);
    /* eq. 12's estimate leaves this bend 4.7% long; the quadrature does not */
    CHECK_NEAR(blade_ref_curve_length(&b, 256), 1.0468, 0.001);
    b = upright(0, 0, 1, 0.0f, 1.0f);
    b.v2[0] = 0.5f;
    b.v2[1] = -0.3f;
    blade_ref_validate(&b, BLADE_LENGTH_QUADRATURE);
    CHECK(b.v2[1] >= 0.0f);
    CHECK_NEAR(blade_ref_curve_length(&b, 4096), 1.0, 0.002);
    CHECK_NEAR(b.v1[0], 0.0, 0);
    CHECK_NEAR(b.v2[0] / b.v1[1], 1.0, EPS); /* ratio v2.x : v1.y = 0.5 : 0.5 kept */
    /* folded back onto the root: the worst case of eq. 12 */
    b = upright(0, 0, 1, 0.0f, 1.0f);
    b.v2[0] = 0.001f;
    b.v2[1] = 0.0f;
    blade_ref_validate(&b, BLADE_LENGTH_QUADRATURE);
    CHECK_NEAR(blade_ref_curve_length(&b, 4096), 1.0, 0.002);
    CHECK_NEAR(blade_ref_length_estimate(&b, BLADE_LENGTH_QUADRATURE), 1.0, 1e-5);

    /* flattened completely: v1 at 5% of h per eq. 11 before the rescale */
    b = upright(0, 0, 1, 0.0f, 1.0f);
    b.v2[0] = 1.0f;
    b.v2[1] = 0.0f;
    blade_ref_validate(&b, BLADE_LENGTH_PAPER);
    l1 = 0.05 + sqrt(1 + 0.05 * 0.05);
    r = 1 / ((2 + l1) / 3);
    CHECK_V3(b.v1, 0, 0.05 * r, 0, EPS);
    CHECK_V3(b.v2, r, 0, 0, EPS);

    /* straight but twice too long: halved */
    b = upright(0, 0, 1, 0.0f, 1.0f);
    b.v2[1] = 2.0f;
    blade_ref_validate(&b, BLADE_LENGTH_PAPER);
    CHECK_V3(b.v1, 0, 0.5, 0, EPS);
    CHECK_V3(b.v2, 0, 1, 0, EPS);

    /* a tilted ground: up = (0.6, 0.8, 0), tip pushed through the plane */
    blade_t t = {{1, 2, 3, 0}, {0, 0, 0, 0.5f}, {0, 0, 0, 0.02f}, {0.6f, 0.8f, 0, 1}};
    t.v2[0] = 1 - 0.3f;
    t.v2[1] = 2 - 0.1f;
    t.v2[2] = 3;
    blade_ref_validate(&t, BLADE_LENGTH_PAPER);
    float e[3] = {t.v2[0] - 1, t.v2[1] - 2, t.v2[2] - 3};
    CHECK(0.6f * e[0] + 0.8f * e[1] >= -1e-6f);
    CHECK_NEAR(blade_ref_length_estimate(&t, BLADE_LENGTH_PAPER), 0.5, 1e-5);
    blade_ref_validate(&t, BLADE_LENGTH_QUADRATURE);
    CHECK_NEAR(blade_ref_curve_length(&t, 4096), 0.5, 0.001);

    /* padding blade: untouched */
    blade_t pad = {{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 1, 0, 1}};
    blade_t pad0 = pad;
    blade_ref_validate(&pad, BLADE_LENGTH_QUADRATURE);
    CHECK(memcmp(&pad, &pad0, sizeof pad) == 0);
}

static void test_collision_and_step(void)
{
    /* upright blade h = 1, sphere (0.3, 1, 0) r 0.5 */
    blade_t b = upright(0, 0, 1, 0.0f, 1.0f);
    blade_sphere_t s = {.centre_radius = {0.3f, 1.0f, 0.0f, 0.5f}};
    float d[3];
    blade_ref_collide(&b, &s, 1, BLADE_LENGTH_QUADRATURE, 1.0f, d);
    /* v2 pushed to (-0.2, 1, 0); m = (-0.05, 0.75, 0); m's push-out, 4x
     * (the paper), puts m exactly on the sphere before validation */
    double mx = 0.35, my = 0.25, ml = sqrt(mx * mx + my * my), pen = ml - 0.5;
    double dmx = 4 * pen * mx / ml, dmy = 4 * pen * my / ml;
    blade_t paper = upright(0, 0, 1, 0.0f, 1.0f);
    paper.v2[0] = (float)(-0.2 + dmx);
    paper.v2[1] = (float)(1 + dmy);
    float m[3];
    blade_ref_midpoint(&paper, m);
    double dm = sqrt((m[0] - 0.3) * (m[0] - 0.3) + (m[1] - 1.0) * (m[1] - 1.0));
    CHECK_NEAR(dm, 0.5, 1e-5);
    /* validated, that m ends q outside: the push is scaled by p / (p + q) */
    blade_ref_validate(&paper, BLADE_LENGTH_QUADRATURE);
    blade_ref_midpoint(&paper, m);
    double q = sqrt((m[0] - 0.3) * (m[0] - 0.3) + (m[1] - 1.0) * (m[1] - 1.0)) - 0.5;
    double p = -pen, sc = q > 0 ? p / (p + q) : 1.0;
    CHECK(q > 0.01);
    CHECK_V3(d, -0.2 + sc * dmx, sc * dmy, 0, EPS);
    CHECK_V3(b.v2, -0.2 + sc * dmx, 1 + sc * dmy, 0, EPS);
    /* no contact: no displacement */
    b = upright(0, 0, 1, 0.0f, 1.0f);
    blade_sphere_t far = {.centre_radius = {3, 1, 0, 0.5f}};
    blade_ref_collide(&b, &far, 1, BLADE_LENGTH_QUADRATURE, 1.0f, d);
    CHECK_V3(d, 0, 0, 0, 0);

    /* a whole step, gravity only, hand-computed in double */
    blade_env_t env = {.dt = 0.01f, .gravity = 10.0f, .length_mode = BLADE_LENGTH_PAPER};
    b = upright(0, 0, 1, 0.0f, 2.0f);
    float eta = 0.0f;
    blade_ref_step(&b, &eta, 1, &env, NULL);
    {
        /* g = (0, -10, -2.5), gain k = (1 - exp(-s dt)) / s, s = 2, dt 0.01 */
        double k = (1 - exp(-0.02)) / 2;
        CHECK_NEAR(blade_ref_step_gain(2.0f, 0.0f, 0.01f), k, 1e-8);
        double v2y = 1 - 10 * k, v2z = -2.5 * k;
        double lproj = -v2z, v1y = 1 - lproj;
        double l0 = sqrt(v2y * v2y + v2z * v2z);
        double l1 = v1y + sqrt((v2y - v1y) * (v2y - v1y) + v2z * v2z);
        double r = 1 / ((2 * l0 + l1) / 3);
        CHECK_V3(b.v1, 0, v1y * r, 0, EPS);
        CHECK_V3(b.v2, 0, v1y * r + r * (v2y - v1y), r * v2z, EPS);
        CHECK_NEAR(eta, 0.0, 0);
    }
    /* step with a collision: eta = d.d (1/60 / dt) - a dt; v0 untouched */
    env = (blade_env_t){.dt = 0.01f, .gravity_off = true, .collision_decay = 2.0f};
    static collide_set_t set;
    set.sphere_count = 1;
    set.spheres[0] = s;
    b = upright(0, 0, 1, 0.0f, 2.0f);
    blade_t ref = b;
    float rescale = blade_ref_validate(&ref, BLADE_LENGTH_QUADRATURE);
    CHECK_NEAR(rescale, 1.0, 1e-6);
    blade_ref_collide(&ref, &s, 1, BLADE_LENGTH_QUADRATURE, rescale, d);
    blade_ref_revalidate(&ref, BLADE_LENGTH_QUADRATURE, rescale);
    blade_ref_friction(&ref, &b, d, &set, BLADE_LENGTH_QUADRATURE);
    blade_ref_exit(&ref, &s, 1);
    eta = 0.0f;
    blade_ref_step(&b, &eta, 1, &env, &set);
    CHECK_NEAR(eta, (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) * (1.0 / 60.0 / 0.01) - 2.0 * 0.01, 1e-5);
    CHECK(memcmp(b.v0, ref.v0, sizeof b.v0) == 0);
    CHECK_V3(b.v2, ref.v2[0], ref.v2[1], ref.v2[2], 1e-6);
    /* eta decays to exactly zero, never below */
    set.sphere_count = 0;
    for (int i = 0; i < 1000; i++) blade_ref_step(&b, &eta, 1, &env, &set);
    CHECK(eta == 0.0f);
    /* recovery brings it back upright */
    CHECK_V3(b.v2, 0, 1, 0, 1e-3);
}

static bool has_nan(const blade_t *b)
{
    const float *f = &b->v0[0];
    for (int i = 0; i < 16; i++)
        if (!isfinite(f[i])) return true;
    return false;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}

static float sphere_pen(const blade_sphere_t *s, const float p[3])
{
    float dx = p[0] - s->centre_radius[0], dy = p[1] - s->centre_radius[1], dz = p[2] - s->centre_radius[2];
    return s->centre_radius[3] - sqrtf(dx * dx + dy * dy + dz * dz);
}

/* 1000 steps of N blades (flat ground and a 30 degree slope, side by side)
 * under wind, gravity and two moving spheres, dt random in [1/240, 1/10].
 * Residual penetration after a contact is measured for blades whose root is
 * outside every sphere (a root inside a sphere cannot get out). The paper's
 * single radial push left up to 0.56 h inside (the length correction pulls
 * a pushed tip back in); the exit step (blade_ref_exit: rigid rotations about
 * the root, then a straight-blade fallback) must leave v2 and m outside
 * after every update with a contact, keeping length and ground. */
static void run_invariants(int length_mode, int steps, double len_bound)
{
    enum { N = 1600 };
    core_rng_t rng;
    core_rng_seed(&rng, 7, 1);
    blade_t *b = malloc(N * sizeof *b), *b0 = malloc(N * sizeof *b0);
    float *eta = calloc(N, sizeof *eta);
    for (int i = 0; i < N; i++) {
        float up[3] = {0, 1, 0};
        float x = core_rng_range(&rng, -2, 2), z = core_rng_range(&rng, -2, 2), y = 0.0f;
        if (i % 2) { /* slope y = x tan 30 on z in [3, 7] */
            up[0] = -0.5f;
            up[1] = 0.8660254f;
            z += 5.0f;
            y = 0.57735027f * x;
        }
        float h = core_rng_range(&rng, 0.2f, 0.8f);
        b[i] = (blade_t){{x, y, z, core_rng_range(&rng, 0, 6.2831853f)},
                         {x + up[0] * h, y + up[1] * h, z, h},
                         {x + up[0] * h, y + up[1] * h, z, 0.02f},
                         {up[0], up[1], up[2], core_rng_range(&rng, 1.0f, 9.0f)}};
    }
    memcpy(b0, b, N * sizeof *b);
    blade_env_t env = {.gravity = 9.81f, .wind_count = 2, .length_mode = length_mode};
    static collide_set_t set;
    set.sphere_count = 2;
    env.winds[0] = blade_wind_wave(1.0f, 0.3f, 6.0f, 3.0f, 2.0f);
    env.winds[1] = blade_wind_point((float[3]){0, 0.5f, 2.5f}, 8.0f, 2.5f);
    double t = 0.0, worst_len = 0.0, worst_pen_v2 = 0.0, worst_pen_m = 0.0, worst_below = 0.0;
    double worst_root_inside = 0.0;
    long contacts = 0, root_inside = 0;
    size_t nres = 0, cap = 1 << 16;
    double sum_pre = 0.0, sum_post = 0.0;
    float *resid = malloc(cap * sizeof *resid);
    bool nan = false, moved_root = false, composed = true;
    for (int step = 0; step < steps; step++) {
        env.dt = core_rng_range(&rng, 1.0f / 240.0f, 1.0f / 10.0f);
        env.time = (float)t;
        float a = (float)t * 0.7f;
        /* sphere 0 circles over the flat patch, sphere 1 sweeps the slope */
        set.spheres[0] = (blade_sphere_t){.centre_radius = {1.2f * cosf(a), 0.45f, 1.2f * sinf(a), 0.4f}};
        float sx = -2.0f + fmodf(0.5f * (float)t, 4.0f);
        set.spheres[1] = (blade_sphere_t){.centre_radius = {sx, 0.57735f * sx + 0.3f, 5.0f + sinf(a), 0.5f}};
        blade_env_t res = blade_env_defaults(&env);
        for (int i = 0; i < N; i++) {
            /* the step composed by hand from the public pieces, to get d */
            blade_t c = b[i];
            float r[3], g[3], w[3], d[3];
            blade_ref_recovery(&c, eta[i], r);
            blade_ref_gravity(&c, &res, g);
            blade_ref_wind(&c, &res, w);
            float kg = blade_ref_step_gain(c.up[3], eta[i], res.dt);
            for (int k = 0; k < 3; k++) c.v2[k] += (r[k] + g[k] + w[k]) * kg;
            float rescale = blade_ref_validate(&c, length_mode);
            float pre = 0.0f, cm[3];
            blade_ref_midpoint(&c, cm);
            for (int k = 0; k < set.sphere_count; k++)
                pre = fmaxf(pre, fmaxf(sphere_pen(&set.spheres[k], c.v2), sphere_pen(&set.spheres[k], cm)));
            blade_ref_collide(&c, set.spheres, set.sphere_count, res.length_mode, rescale, d);
            bool hit = d[0] != 0.0f || d[1] != 0.0f || d[2] != 0.0f;
            if (hit) {
                blade_ref_revalidate(&c, length_mode, rescale);
                blade_ref_friction(&c, &b[i], d, &set, length_mode);
                blade_ref_exit(&c, set.spheres, set.sphere_count);
            }

            blade_ref_step_one(&b[i], &eta[i], &res, &set);
            composed &= memcmp(&c, &b[i], sizeof c) == 0;
            nan |= has_nan(&b[i]) || !isfinite(eta[i]);
            moved_root |= memcmp(b[i].v0, b0[i].v0, sizeof b[i].v0) != 0;
            float h = b[i].v1[3];
            double len = blade_ref_curve_length(&b[i], 64);
            if (fabs(len - h) / h > worst_len) worst_len = fabs(len - h) / h;
            float e[3] = {b[i].v2[0] - b[i].v0[0], b[i].v2[1] - b[i].v0[1], b[i].v2[2] - b[i].v0[2]};
            float above = e[0] * b[i].up[0] + e[1] * b[i].up[1] + e[2] * b[i].up[2];
            if (-above > worst_below) worst_below = -above;
            if (!hit) continue;
            contacts++;
            float m[3];
            blade_ref_midpoint(&b[i], m);
            bool inside = false;
            for (int k = 0; k < set.sphere_count; k++) inside |= sphere_pen(&set.spheres[k], b[i].v0) >= 0.0f;
            float worst_here = 0.0f;
            for (int k = 0; k < set.sphere_count; k++) {
                worst_here = fmaxf(worst_here, fmaxf(sphere_pen(&set.spheres[k], b[i].v2),
                                                     sphere_pen(&set.spheres[k], m)) / h);
                double pv2 = sphere_pen(&set.spheres[k], b[i].v2) / h, pm = sphere_pen(&set.spheres[k], m) / h;
                if (inside) {
                    worst_root_inside = fmax(worst_root_inside, fmax(pv2, pm));
                    continue;
                }
                worst_pen_v2 = fmax(worst_pen_v2, pv2);
                worst_pen_m = fmax(worst_pen_m, pm);
            }
            root_inside += inside;
            if (!inside) {
                if (nres == cap) resid = realloc(resid, (cap *= 2) * sizeof *resid);
                resid[nres++] = worst_here;
                sum_pre += pre / h;
                sum_post += worst_here;
            }
        }
        t += env.dt;
    }
    qsort(resid, nres, sizeof *resid, cmp_float);
    double p90 = nres ? resid[nres * 90 / 100] : 0, p99 = nres ? resid[nres * 99 / 100] : 0;
    long over = 0;
    for (size_t i = 0; i < nres; i++) over += resid[i] > 0.01f;
    printf("  contacts with the root outside: %zu; mean penetration / h before the push %.4f, "
           "after the step %.4f; p90 %.4f p99 %.4f; above 0.01 h: %ld\n",
           nres, sum_pre / (double)nres, sum_post / (double)nres, p90, p99, over);
    CHECK(sum_post < 0.7 * sum_pre);
    free(resid);
    printf("invariants (%s length): %d blades x %d steps, %ld contacts (%ld with the root inside); "
           "worst |len-h|/h %.4f, below ground %.2e; residual penetration / h: v2 %.4f, m %.4f "
           "(root inside: %.3f)\n",
           length_mode == BLADE_LENGTH_PAPER ? "eq. 12" : "quadrature", N, steps, contacts,
           root_inside, worst_len, worst_below, worst_pen_v2, worst_pen_m, worst_root_inside);
    CHECK(!nan);
    CHECK(!moved_root);
    CHECK(composed);
    CHECK(contacts > 1000);
    CHECK(worst_len < len_bound);
    CHECK(worst_below <= 1e-6);
    CHECK(worst_pen_v2 < PEN_BOUND);
    CHECK(worst_pen_m < PEN_BOUND);
    free(b);
    free(b0);
    free(eta);
}

static void test_determinism(void)
{
    enum { N = 500 };
    core_rng_t rng;
    core_rng_seed(&rng, 3, 3);
    blade_t *b = malloc(N * sizeof *b), *c = malloc(N * sizeof *c);
    float *eb = calloc(N, sizeof *eb), *ec = calloc(N, sizeof *ec);
    for (int i = 0; i < N; i++)
        b[i] = upright(core_rng_range(&rng, -2, 2), core_rng_range(&rng, -2, 2), 0.5f,
                       core_rng_range(&rng, 0, 6.3f), 5.0f);
    memcpy(c, b, N * sizeof *b);
    blade_env_t env = {.dt = 1.0f / 60.0f, .wind_count = 1};
    env.winds[0] = blade_wind_wave(1, 1, 3, 2, 1);
    static collide_set_t set = {.sphere_count = 1, .spheres[0] = {{0, 0.3f, 0, 0.6f}}};
    for (int s = 0; s < 20; s++) {
        env.time = (float)s / 60.0f;
        blade_ref_step(b, eb, N, &env, &set);
        blade_ref_step(c, ec, N, &env, &set);
    }
    CHECK(core_hash_bytes(b, N * sizeof *b, 0) == core_hash_bytes(c, N * sizeof *c, 0));
    CHECK(core_hash_bytes(eb, N * sizeof *eb, 0) == core_hash_bytes(ec, N * sizeof *ec, 0));
    free(b);
    free(c);
    free(eb);
    free(ec);
}

/* ---- culling: independent brute force ------------------------------------ */

static void brute_clip(const float *vp, const float p[3], float out[4])
{
    for (int r = 0; r < 4; r++)
        out[r] = vp[0 * 4 + r] * p[0] + vp[1 * 4 + r] * p[1] + vp[2 * 4 + r] * p[2] + vp[3 * 4 + r];
}

static int brute_cull(const blade_t *b, uint32_t i, const float cam[3], const float *vp,
                      const float *depth, int w, int h)
{
    if (b->v1[3] <= 0.0f) return -1;
    float up[3] = {b->up[0], b->up[1], b->up[2]};
    float v[3] = {b->v0[0] - cam[0], b->v0[1] - cam[1], b->v0[2] - cam[2]};
    float vu = v[0] * up[0] + v[1] * up[1] + v[2] * up[2];
    float g[3] = {v[0] - up[0] * vu, v[1] - up[1] * vu, v[2] - up[2] * vu};
    float gl = sqrtf(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    /* every blade in this scene stands on flat ground: width = (cos a, 0, sin a) */
    float wd[3] = {cosf(b->v0[3]), 0.0f, sinf(b->v0[3])};
    if (gl > 1e-6f && fabsf((g[0] * wd[0] + g[2] * wd[2]) / gl) > 0.9f) return 0;
    float pts[3][3], clip[3][4];
    for (int k = 0; k < 3; k++) {
        pts[0][k] = b->v0[k];
        pts[1][k] = 0.25f * b->v0[k] + 0.5f * b->v1[k] + 0.25f * b->v2[k];
        pts[2][k] = b->v2[k];
    }
    int inside = 0;
    for (int j = 0; j < 3; j++) {
        brute_clip(vp, pts[j], clip[j]);
        float lim = clip[j][3] + 0.1f;
        inside += fabsf(clip[j][0]) <= lim && fabsf(clip[j][1]) <= lim && fabsf(clip[j][2]) <= lim;
    }
    if (!inside) return 1;
    if (gl > 60.0f) return 2;
    if ((int)(i % 8) > (int)floorf(8.0f * (1.0f - gl / 60.0f))) return 2;
    int occ = 0;
    for (int j = 0; j < 3; j++) {
        float cw = clip[j][3];
        if (cw <= 0) continue;
        float x = clip[j][0] / cw, y = clip[j][1] / cw, z = clip[j][2] / cw;
        if (x < -1 || x > 1 || y < -1 || y > 1) continue;
        int px = (int)floorf((x + 1) * 0.5f * w), py = (int)floorf((y + 1) * 0.5f * h);
        if (px >= w) px = w - 1;
        if (py >= h) py = h - 1;
        occ += z > depth[py * w + px] + 1e-3f;
    }
    return occ == 3 ? 3 : 4;
}

/* direction angle whose width is perpendicular to the view from the origin */
#define FACE_ON(x, z) (atan2f((z), (x)) + GLM_PI_2f)

static void test_cull(void)
{
    enum { GX = 120, GZ = 120, N = GX * GZ + 1, W = 64, H = 48 };
    blade_t *b = malloc(N * sizeof *b);
    core_rng_t rng;
    core_rng_seed(&rng, 11, 3);
    for (int z = 0; z < GZ; z++)
        for (int x = 0; x < GX; x++) {
            float px = (float)(x - GX / 2) * 0.8f, pz = (float)(z - GZ / 2) * 0.8f;
            b[z * GX + x] = upright(px, pz, core_rng_range(&rng, 0.3f, 0.7f),
                                    core_rng_range(&rng, 0, 6.2831853f), 4.0f);
            b[z * GX + x].v2[0] += core_rng_range(&rng, -0.2f, 0.2f); /* some bend */
            blade_ref_validate(&b[z * GX + x], BLADE_LENGTH_QUADRATURE);
        }
    b[N - 1] = (blade_t){{0, 0, 0, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}, {0, 1, 0, 1}}; /* padding */
    vec3 eye = {0, 1.7f, 0}, centre = {10, 1.0f, 12}, upv = {0, 1, 0};
    mat4 view, proj, vp;
    glm_lookat(eye, centre, upv, view);
    glm_perspective(glm_rad(60.0f), (float)W / H, 0.1f, 200.0f, proj);
    glm_mat4_mul(proj, view, vp);
    /* depth: a wall at NDC depth 0.9 over the left third, far plane elsewhere */
    float *depth = malloc(W * H * sizeof *depth);
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) depth[y * W + x] = x < W / 3 ? 0.9f : 1.0f;
    /* eq. 19-20 as the text states them (the LEVELS rule) without widening
     * or end fade: what the brute force recounts */
    blade_cull_desc_t desc = {.view.camera = {0, 1.7f, 0}, .depth = depth, .depth_w = W, .depth_h = H,
                              .lod = {.rule = BLADE_LOD_LEVELS, .no_compensation = true, .no_fade = true}};
    memcpy(desc.view.viewproj, vp, sizeof desc.view.viewproj);
    uint32_t *surv = malloc(N * sizeof *surv);
    blade_cull_stats_t st;
    size_t count = blade_ref_cull(b, N, &desc, surv, NULL, &st);

    uint32_t want[5] = {0, 0, 0, 0, 0};
    size_t k = 0;
    bool order_ok = true;
    for (uint32_t i = 0; i < N; i++) {
        int r = brute_cull(&b[i], i, desc.view.camera, desc.view.viewproj, depth, W, H);
        if (r < 0) continue;
        want[r]++;
        if (r == 4) order_ok &= k < count && surv[k++] == i;
    }
    printf("cull: orientation %u frustum %u distance %u occlusion %u visible %u (brute %u %u %u %u %u)\n",
           st.culled[0], st.culled[1], st.culled[2], st.culled[3], st.visible, want[0], want[1],
           want[2], want[3], want[4]);
    for (int t = 0; t < 4; t++) CHECK(st.culled[t] == want[t]);
    CHECK(st.visible == want[4]);
    CHECK(count == st.visible);
    CHECK(order_ok && k == count);
    for (int t = 0; t < 4; t++) CHECK(st.culled[t] > 0); /* the scene exercises every test */
    CHECK(st.visible > 0);
    CHECK(st.culled[0] + st.culled[1] + st.culled[2] + st.culled[3] + st.visible == N - 1);

    /* hand cases: edge-on blade, blade behind the camera, far blade */
    blade_t one = upright(0, 0, 5, 0.0f, 1.0f); /* width along x, camera looks along x */
    blade_cull_desc_t d1 = {.view.camera = {-5, 1, 0}, .disable = BLADE_CULL_FRUSTUM};
    d1 = blade_cull_desc_defaults(&d1);
    CHECK(blade_ref_cull_one(&one, 0, &d1, NULL) == BLADE_CULL_ORIENTATION);
    one.v0[3] = GLM_PI_2f; /* width along z: seen face-on */
    CHECK(blade_ref_cull_one(&one, 0, &d1, NULL) == BLADE_CULL_VISIBLE);
    desc = blade_cull_desc_defaults(&desc);
    one = upright(-5, -5, 1, FACE_ON(-5, -5), 1.0f); /* behind the camera */
    CHECK(blade_ref_cull_one(&one, 0, &desc, NULL) == BLADE_CULL_FRUSTUM);
    desc.disable = BLADE_CULL_FRUSTUM;
    one = upright(50, 60, 1, FACE_ON(50, 60), 1.0f); /* 78 m away */
    CHECK(blade_ref_cull_one(&one, 0, &desc, NULL) == BLADE_CULL_DISTANCE);
    one = upright(3, 3, 1, FACE_ON(3, 3), 1.0f); /* near: every index survives the distance test */
    desc.disable = BLADE_CULL_FRUSTUM | BLADE_CULL_OCCLUSION;
    for (uint32_t i = 0; i < 8; i++) CHECK(blade_ref_cull_one(&one, i, &desc, NULL) == BLADE_CULL_VISIBLE);

    /* The levels over 60 m cut at 100 m (lod.level_distance): a blade
     * within the cut keeps one index in 8 past 60 m, a blade beyond it is
     * culled whatever its index; near blades thin as with the 60 m cut. */
    blade_cull_desc_t cut = desc;
    cut.max_distance = 100.0f;
    cut.lod.level_distance = BLADE_CULL_MAX_DISTANCE_DEFAULT;
    one = upright(50, 60, 1, FACE_ON(50, 60), 1.0f); /* 78 m */
    int kept = 0;
    for (uint32_t i = 0; i < 8; i++) kept += blade_ref_cull_one(&one, i, &cut, NULL) == BLADE_CULL_VISIBLE;
    CHECK(kept == 1 && blade_ref_cull_one(&one, 0, &cut, NULL) == BLADE_CULL_VISIBLE);
    one = upright(70, 80, 1, FACE_ON(70, 80), 1.0f); /* 106 m: beyond the cut */
    for (uint32_t i = 0; i < 8; i++) CHECK(blade_ref_cull_one(&one, i, &cut, NULL) == BLADE_CULL_DISTANCE);
    cut.max_distance = 12.0f; /* a cap nearer than the levels' end */
    one = upright(10, 10, 1, FACE_ON(10, 10), 1.0f); /* 14 m */
    CHECK(blade_ref_cull_one(&one, 0, &cut, NULL) == BLADE_CULL_DISTANCE);
    one = upright(20, 20, 1, FACE_ON(20, 20), 1.0f); /* 28 m: level floor(8 (1 - 28.3 / 60)) = 4 */
    cut.max_distance = 100.0f;
    blade_cull_desc_t paper = desc;
    paper.max_distance = BLADE_CULL_MAX_DISTANCE_DEFAULT;
    for (uint32_t i = 0; i < 8; i++) {
        int want_level = i <= 4 ? BLADE_CULL_VISIBLE : BLADE_CULL_DISTANCE;
        CHECK(blade_ref_cull_one(&one, i, &cut, NULL) == want_level);
        CHECK(blade_ref_cull_one(&one, i, &paper, NULL) == want_level);
    }
    free(b);
    free(depth);
    free(surv);
}

/* The default thinning (BLADE_LOD_WIDTH) in the cull: a survivor's width
 * factor is blade_lod_blade's weight * scale, weight 0 is a distance cull,
 * and a widened blade passes the orientation test at the widened
 * threshold (blade_ref_lod_orientation) that culls it unwidened. */
static void test_cull_lod(void)
{
    blade_cull_desc_t d = blade_cull_desc_defaults(&(blade_cull_desc_t){.view.camera = {0, 1, 0},
                                                                          .disable = BLADE_CULL_FRUSTUM});
    blade_t one = upright(24, 32, 1, FACE_ON(24, 32), 1.0f); /* 40 m: u = 10 / 40 */
    int visible = 0, distance = 0, wrong = 0;
    for (uint32_t i = 0; i < 256; i++) {
        float factor = -1.0f;
        int why = blade_ref_cull_one(&one, i, &d, &factor);
        blade_lod_draw_t l = blade_lod_blade(&d.lod, i, 40.0f, one.v2[3], d.focal_px, d.max_distance);
        visible += why == BLADE_CULL_VISIBLE;
        distance += why == BLADE_CULL_DISTANCE;
        wrong += why == BLADE_CULL_VISIBLE ? fabsf(factor - l.weight * l.scale) > 1e-6f : l.weight > 0.0f;
    }
    printf("cull lod: 40 m, 256 indices: %d visible, %d thinned, %d differ from blade_lod_blade\n", visible, distance,
           wrong);
    CHECK(wrong == 0 && visible + distance == 256);
    CHECK(visible > 256 / 4 && visible < 256 / 4 + 256 / 8); /* u = 0.25, window 0.1 */
    /* edge-on at c = 0.95: culled unwidened (near), kept when widened 4x */
    float a = atan2f(32.0f, 24.0f) + acosf(0.95f);
    one = upright(24, 32, 1, a, 1.0f);
    uint32_t kept_index = 0;
    float factor = 0.0f;
    while (blade_ref_cull_one(&one, kept_index, &d, &factor) != BLADE_CULL_VISIBLE && kept_index < 256) kept_index++;
    printf("cull lod: edge-on at c = 0.95, 40 m: index %u kept with factor %.2f (threshold %.3f)\n", kept_index,
           factor, blade_ref_lod_orientation(0.9f, factor));
    CHECK(kept_index < 256 && factor > 3.0f);
    one = upright(3, 4, 1, atan2f(4.0f, 3.0f) + acosf(0.95f), 1.0f); /* 5 m: factor 1 */
    CHECK(blade_ref_cull_one(&one, kept_index, &d, NULL) == BLADE_CULL_ORIENTATION);
}

/* Swept collision: a ball r 0.3 m at (1, 0.3, 0) that came from (-1, 0.3, 0)
 * this step (sweep (-2, 0, 0)) is the capsule between them, less the half
 * of the start sphere behind x = -1 (the ball left it as the step began:
 * points there take the current sphere); an upright blade at x = 0 lies in
 * neither end sphere and is bent by the step, as it would be by a ball
 * moving 2 m over 20 steps. */
static void test_swept(void)
{
    blade_sphere_t s = {.centre_radius = {1.0f, 0.3f, 0.0f, 0.3f}, .sweep = {-2.0f, 0.0f, 0.0f, 0.0f}}, at;
    blade_ref_sphere_at(&s, (float[3]){0.2f, 0.5f, 0.1f}, &at);
    CHECK_V3(at.centre_radius, 0.2, 0.3, 0.0, EPS);
    CHECK(at.centre_radius[3] == 0.3f);
    blade_ref_sphere_at(&s, (float[3]){-0.9f, 0.5f, 0.1f}, &at);
    CHECK_V3(at.centre_radius, -0.9, 0.3, 0.0, EPS);
    blade_ref_sphere_at(&s, (float[3]){-1.1f, 0.5f, 0.1f}, &at);
    CHECK_V3(at.centre_radius, 1.0, 0.3, 0.0, EPS);
    blade_ref_sphere_at(&s, (float[3]){-3.0f, 0.5f, 0.1f}, &at);
    CHECK_V3(at.centre_radius, 1.0, 0.3, 0.0, EPS);
    blade_ref_sphere_at(&s, (float[3]){3.0f, 0.5f, 0.1f}, &at);
    CHECK_V3(at.centre_radius, 1.0, 0.3, 0.0, EPS);
    blade_sphere_t rest = {.centre_radius = {1.0f, 0.3f, 0.0f, 0.3f}};
    blade_ref_sphere_at(&rest, (float[3]){0.0f, 0.5f, 0.0f}, &at);
    CHECK(memcmp(&at, &rest, sizeof at) == 0);

    blade_env_t env = {.dt = 1.0f / 60.0f, .gravity_off = true};
    static collide_set_t set;
    set.sphere_count = 1;
    set.spheres[0] = s;
    blade_t b = upright(0.0f, 0.1f, 0.4f, 0.0f, 10.0f);
    float eta = 0.0f;
    blade_ref_step(&b, &eta, 1, &env, &set);
    float m[3];
    blade_ref_midpoint(&b, m);
    double tip = sqrt((b.v2[0] - 0.0) * (b.v2[0] - 0.0) + (b.v2[1] - 0.4) * (b.v2[1] - 0.4) +
                      (b.v2[2] - 0.1) * (b.v2[2] - 0.1));
    printf("swept: tip of a blade between the ends moved %.3f m (h 0.4 m)\n", tip);
    CHECK(tip > 0.2 * 0.4);
    /* v2 and m end outside the capsule */
    for (int k = 0; k < 2; k++) {
        const float *p = k ? m : b.v2;
        blade_ref_sphere_at(&s, p, &at);
        double dx = p[0] - at.centre_radius[0], dy = p[1] - at.centre_radius[1], dz = p[2] - at.centre_radius[2];
        CHECK(sqrt(dx * dx + dy * dy + dz * dz) >= 0.3 - PEN_BOUND);
    }
    CHECK(eta > 0.0f);
}

int main(void)
{
    core_log_set_quiet(true);
    CHECK(sizeof(blade_t) == 64);
    CHECK(sizeof(blade_wind_t) == 32);
    CHECK(sizeof(blade_sphere_t) == 32);
    test_frame_and_forces();
    test_validation();
    test_collision_and_step();
    test_swept();
    run_invariants(BLADE_LENGTH_QUADRATURE, 1000, 0.02);
    run_invariants(BLADE_LENGTH_PAPER, 300, 0.55);
    test_determinism();
    test_cull();
    test_cull_lod();
    TEST_END();
}

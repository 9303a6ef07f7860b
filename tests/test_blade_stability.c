/* test_blade_stability: the blade step (blade_ref_step_one) is stable and
 * rate-independent (docs/BLADES.md, integration):
 *   sweep     a 0.5 m blade laid flat, no wind or gravity, for every
 *             stiffness in (0, 100] and dt in (0, 1] s the scene parser
 *             accepts (grid): the tip's distance to the rest pose never
 *             grows and the tip never swings past it;
 *   rate      a r 0.3 m ball crosses a strip of blades at 5 m/s and
 *             leaves; the time until every tip is back within 1 cm of an
 *             undisturbed twin (interpolated between frames) agrees with
 *             144 Hz within 5 % at 240, 60, 30 and 15 Hz, and the blades
 *             also recover at 8 and 4 Hz.
 * Scene values as `meadow bench --stability` (app_world.c's env: gravity
 * 1 m/s^2, eta gain 1 / (0.1 h)^2, recover time 1 s, one wind wave). */
#include "blade/blade_ref.h"
#include "test.h"

#include <stdint.h>
#include <string.h>

static float frand(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)(*s >> 8) / 16777216.0f;
}

static void test_sweep(void)
{
    static const float stiffness[] = {0.01f, 0.5f, 2.0f, 8.0f, 20.0f, 50.0f, 100.0f};
    static const float dts[] = {1.0f / 240.0f, 1.0f / 60.0f, 1.0f / 15.0f, 0.25f, 1.0f};
    double worst_grow = 0.0, worst_past = 0.0;
    for (size_t i = 0; i < sizeof stiffness / sizeof *stiffness; i++) {
        for (size_t j = 0; j < sizeof dts / sizeof *dts; j++) {
            float s = stiffness[i], dt = dts[j];
            blade_t b = {{0, 0, 0, 0.0f}, {0, 0.05f, 0, 0.5f}, {0.5f, 0.0f, 0, 0.02f}, {0, 1, 0, s}};
            blade_ref_validate(&b, BLADE_LENGTH_QUADRATURE);
            float eta = 0.0f;
            blade_env_t env = blade_env_defaults(&(blade_env_t){.dt = dt, .gravity_off = true});
            double prev = hypot(b.v2[0], b.v2[1] - 0.5);
            int steps = (int)fmin(1e5, ceil(fmax(20.0 / s, 10.0) / dt));
            for (int k = 0; k < steps; k++) {
                blade_ref_step_one(&b, &eta, &env, NULL);
                double dist = hypot(b.v2[0], b.v2[1] - 0.5);
                worst_grow = fmax(worst_grow, dist - prev);
                worst_past = fmax(worst_past, -b.v2[0]);
                CHECK_MSG(dist <= prev + 1e-5 && b.v2[0] >= -1e-5, "stiffness %g dt %g step %d: tip %.4f %.4f", s,
                          dt, k, b.v2[0], b.v2[1]);
                if (!(dist <= prev + 1e-5 && b.v2[0] >= -1e-5)) break;
                prev = dist;
            }
            if (s >= 0.5f) CHECK_MSG(prev < 1e-3, "stiffness %g dt %g: %.4f m from rest at the end", s, dt, prev);
        }
    }
    printf("sweep: stiffness 0.01-100 x dt 1/240-1 s: worst distance growth %.2e m, worst swing past rest %.2e m\n",
           worst_grow, worst_past);
}

typedef struct strip_t {
    blade_t *b;
    float *eta;
    int n;
} strip_t;

static strip_t strip_make(uint32_t seed)
{
    int n = 360;
    strip_t f = {calloc((size_t)n, sizeof(blade_t)), calloc((size_t)n, sizeof(float)), n};
    for (int i = 0; i < n; i++) {
        float x = -2.5f + 5.0f * frand(&seed), z = -0.6f + 1.2f * frand(&seed);
        float h = 0.35f + 0.15f * frand(&seed), a = 6.2831853f * frand(&seed), s = 8.0f + 4.0f * frand(&seed);
        f.b[i] = (blade_t){{x, 0, z, a}, {x, h, z, h}, {x, h, z, 0.03f}, {0, 1, 0, s}};
    }
    return f;
}

static double strip_offset(const strip_t *a, const strip_t *b)
{
    double worst = 0.0;
    for (int i = 0; i < a->n; i++) {
        double d = hypot(hypot(a->b[i].v2[0] - b->b[i].v2[0], a->b[i].v2[1] - b->b[i].v2[1]),
                         a->b[i].v2[2] - b->b[i].v2[2]);
        if (!(d <= worst)) worst = d;
    }
    return worst;
}

/* Seconds after the ball leaves (t = 1 s) until the offset stays <= 1 cm,
 * interpolated log-linearly between the last frame above and the next;
 * INFINITY when still above at the end (5 s). */
static double pass_recovery(float hz)
{
    strip_t f = strip_make(7), tw = strip_make(7);
    float h = 0.425f, dt = 1.0f / hz;
    blade_env_t env = {.gravity = 1.0f, .collision_gain = 1.0f / (0.01f * h * h), .collision_decay = 1.0f,
                       .dt = dt, .wind_count = 1};
    env.winds[0] = blade_wind_wave(1, 0, 0.5f, 4, 1);
    static collide_set_t set;
    double t_acc = 0.0, last = 0.0, last_off = 0.0, next = 0.0, next_off = 0.0;
    int frames = (int)ceilf(5.0f / dt);
    for (int k = 0; k < frames; k++) {
        t_acc += dt;
        float t = (float)t_acc;
        env.time = t;
        set.sphere_count = t <= 1.0f ? 1 : 0;
        set.spheres[0] = (blade_sphere_t){.centre_radius = {-2.5f + 5.0f * t, 0.3f, 0, 0.3f}};
        blade_ref_step(f.b, f.eta, (size_t)f.n, &env, &set);
        blade_ref_step(tw.b, tw.eta, (size_t)tw.n, &env, NULL);
        if (t <= 1.0f) continue;
        double off = strip_offset(&f, &tw);
        if (!(off <= 0.01)) {
            last = t, last_off = off, next = 0.0;
        } else if (next == 0.0) {
            next = t, next_off = off;
        }
    }
    free(f.b), free(f.eta), free(tw.b), free(tw.eta);
    if (next == 0.0) return INFINITY;
    if (last == 0.0) return 0.0;
    double u = log(last_off / 0.01) / log(last_off / fmax(next_off, 1e-9));
    return last + u * (next - last) - 1.0;
}

static void test_rate(void)
{
    static const float hz[] = {240, 60, 30, 15, 8, 4};
    double ref = pass_recovery(144);
    printf("rate: recovery at 144 Hz %.3f s\n", ref);
    CHECK(ref > 0.2 && isfinite(ref));
    for (size_t i = 0; i < sizeof hz / sizeof *hz; i++) {
        double r = pass_recovery(hz[i]);
        printf("rate: %g Hz %.3f s (%+.1f %%)\n", hz[i], r, 100.0 * (r / ref - 1.0));
        CHECK_MSG(isfinite(r), "%g Hz: the blades never recover", hz[i]);
        if (hz[i] >= 15) CHECK_MSG(fabs(r / ref - 1.0) <= 0.05, "%g Hz: %.3f s against %.3f s", hz[i], r, ref);
    }
}

int main(void)
{
    test_sweep();
    test_rate();
    TEST_END();
}

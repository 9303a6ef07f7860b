/* test_blade_gpu_physics: blade_physics.comp (Jahrmann & Wimmer 2017
 * eq. 3-13 and the collision exit) against the CPU reference blade_ref_step,
 * blade for blade, over several steps of random winds, spheres and gravity
 * variants; then the invariants after as many GPU frames as fit in ~15 s
 * with moving spheres, wind and random dt in [1/240, 1/10]: v0 unchanged,
 * curve length within 2% of the height, v2 above the ground plane, no NaN,
 * and no v2 / m inside a sphere (root outside it) after an update with a
 * contact. */
#include "blade/blade.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>
#include <time.h>

/* A flat 4x4 m square at y = 0 beside a 30 degree slope (normal (-0.5,
 * 0.866, 0)) on z in [3, 7]. */
static bool seed_field(blade_field_t *f, float density, uint64_t seed)
{
    static const float pos[] = {-2, 0, -2, 2, 0, -2, 2, 0, 2, -2, 0, 2,
                                -2, -1.1547005f, 3, 2, 1.1547005f, 3, 2, 1.1547005f, 7, -2, -1.1547005f, 7};
    static const float nrm[] = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0,
                                -0.5f, 0.8660254f, 0, -0.5f, 0.8660254f, 0, -0.5f, 0.8660254f, 0,
                                -0.5f, 0.8660254f, 0};
    static const uint32_t idx[] = {0, 2, 1, 0, 3, 2, 4, 6, 5, 4, 7, 6};
    blade_mesh_t mesh = {pos, nrm, 8, idx, 12};
    return blade_seed_mesh(
        &mesh,
        &(blade_seed_desc_t){.seed = seed,
                             .population = {.density = density, .height = {0.2f, 0.8f}, .stiffness = {1.0f, 9.0f}}},
        f);
}

static bool bad_float(const blade_t *b)
{
    const float *p = &b->v0[0];
    for (int i = 0; i < 16; i++)
        if (!isfinite(p[i])) return true;
    return false;
}

static float pen(const blade_sphere_t *s, const float p[3])
{
    float dx = p[0] - s->centre_radius[0], dy = p[1] - s->centre_radius[1], dz = p[2] - s->centre_radius[2];
    return s->centre_radius[3] - sqrtf(dx * dx + dy * dy + dz * dz);
}

static void random_env(core_rng_t *rng, blade_env_t *env, collide_set_t *set, int variant)
{
    memset(env, 0, sizeof *env);
    memset(set, 0, sizeof *set);
    env->dt = core_rng_range(rng, 1.0f / 240.0f, 1.0f / 10.0f);
    env->time = core_rng_range(rng, 0, 100);
    env->wind_count = 1 + (int)(core_rng_u32(rng) % 3);
    for (int i = 0; i < env->wind_count; i++) {
        if (core_rng_u32(rng) & 1)
            env->winds[i] = blade_wind_wave(core_rng_range(rng, -1, 1), core_rng_range(rng, -1, 1),
                                            core_rng_range(rng, 1, 10), core_rng_range(rng, 1, 8),
                                            core_rng_range(rng, 0, 4));
        else
            env->winds[i] = blade_wind_point((float[3]){core_rng_range(rng, -2, 2), 0.5f, core_rng_range(rng, -2, 7)},
                                             core_rng_range(rng, 1, 10), core_rng_range(rng, 1, 4));
    }
    set->sphere_count = 3;
    for (int i = 0; i < 3; i++)
        set->spheres[i] = (blade_sphere_t){.centre_radius = {core_rng_range(rng, -2, 2), core_rng_range(rng, 0.1f, 0.8f),
                                                             core_rng_range(rng, -2, 7), core_rng_range(rng, 0.2f, 0.6f)}};
    /* spheres 1 and 2 moved up to 1.5 m along x and z this step (swept) */
    for (int i = 1; i < 3; i++) {
        set->spheres[i].sweep[0] = core_rng_range(rng, -1.5f, 1.5f);
        set->spheres[i].sweep[2] = core_rng_range(rng, -1.5f, 1.5f);
    }
    if (variant == 1) env->gravity_off = true;
    if (variant == 2) {
        env->gravity_dir[0] = 0.3f, env->gravity_dir[1] = -1.0f;
        env->gravity = 4.0f;
        env->gravity_centre[1] = -5.0f;
        env->gravity_centre_mix = 0.5f;
    }
    if (variant == 3) env->length_mode = BLADE_LENGTH_PAPER;
    if (variant == 4) env->paper = true; /* the paper's step as printed */
}

static void test_against_reference(void)
{
    blade_field_t f;
    CHECK(seed_field(&f, 120.0f, 11));
    printf("reference comparison: %zu blades (%zu padded)\n", f.blade_count, f.padded_count);
    blade_gpu_t *g = blade_gpu_make(&(blade_gpu_desc_t){.field = &f, .label = "physics_test"});
    CHECK(g);
    size_t n = f.padded_count;
    blade_t *cpu = malloc(n * sizeof *cpu), *gpu = malloc(n * sizeof *gpu);
    float *ecpu = calloc(n, sizeof *ecpu), *egpu = calloc(n, sizeof *egpu);
    core_rng_t rng;
    core_rng_seed(&rng, 5, 2);
    for (int variant = 0; variant < 5; variant++) {
        memcpy(cpu, f.blades, n * sizeof *cpu);
        memset(ecpu, 0, n * sizeof *ecpu);
        blade_gpu_write_blades(g, cpu, NULL);
        double worst = 0.0, worst_eta = 0.0;
        size_t over = 0;
        for (int step = 0; step < 6; step++) {
            blade_env_t env;
            static collide_set_t set;
            random_env(&rng, &env, &set, variant);
            blade_gpu_update(g, &env, &set);
            blade_ref_step(cpu, ecpu, n, &env, &set);
            blade_gpu_read_blades(g, gpu, egpu);
            for (size_t i = 0; i < n; i++) {
                double d = 0.0;
                for (int k = 0; k < 3; k++) {
                    d = fmax(d, fabs(cpu[i].v1[k] - gpu[i].v1[k]));
                    d = fmax(d, fabs(cpu[i].v2[k] - gpu[i].v2[k]));
                }
                worst = fmax(worst, d);
                over += d > 1e-4;
                worst_eta = fmax(worst_eta, fabs(ecpu[i] - egpu[i]));
                CHECK(memcmp(cpu[i].v0, gpu[i].v0, sizeof cpu[i].v0) == 0);
            }
        }
        printf("  variant %d (%s): 6 steps, worst |gpu-cpu| %.2e m, eta %.2e, blades over 1e-4 m: %zu\n",
               variant, (const char *[]){"gravity", "no gravity", "centre gravity", "eq. 12 length", "paper's step"}[variant],
               worst, worst_eta, over);
        /* Nearly every blade agrees to 0.1 mm. A collision exit is a branch
         * (rotate or straighten): a blade sitting on a branch boundary may
         * take the other side when the GPU contracts a*b+c into an fma, as
         * NVIDIA's compiler does (measured on an H100: 2 of 4137 blades,
         * worst 3 mm). Allow those few, bounded. */
        CHECK(over <= n / 1000);
        CHECK(worst < 1e-2);
        CHECK(worst_eta < 1e-3);
    }
    free(cpu);
    free(gpu);
    free(ecpu);
    free(egpu);
    blade_gpu_destroy(g);
    blade_field_free(&f);
}

static void test_invariants(double budget_s)
{
    blade_field_t f;
    CHECK(seed_field(&f, 100.0f, 3));
    blade_gpu_t *g = blade_gpu_make(&(blade_gpu_desc_t){.field = &f, .label = "physics_inv"});
    CHECK(g);
    size_t n = f.padded_count;
    blade_t *b = malloc(n * sizeof *b);
    core_rng_t rng;
    core_rng_seed(&rng, 9, 4);
    blade_env_t env = {.wind_count = 2};
    static collide_set_t set = {.sphere_count = 2};
    env.winds[0] = blade_wind_wave(1.0f, 0.3f, 6.0f, 3.0f, 2.0f);
    env.winds[1] = blade_wind_point((float[3]){0, 0.5f, 2.5f}, 8.0f, 2.5f);
    double t = 0.0, worst_len = 0.0, worst_below = 0.0, worst_pen = -1.0;
    long frames = 0, contacts = 0, checked = 0;
    bool nan = false, moved = false;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (;;) {
        env.dt = core_rng_range(&rng, 1.0f / 240.0f, 1.0f / 10.0f);
        env.time = (float)t;
        float a = (float)t * 0.7f;
        set.spheres[0] = (blade_sphere_t){.centre_radius = {1.2f * cosf(a), 0.45f, 1.2f * sinf(a), 0.4f}};
        float sx = -2.0f + fmodf(0.5f * (float)t, 4.0f);
        set.spheres[1] = (blade_sphere_t){.centre_radius = {sx, 0.57735f * sx + 0.3f, 5.0f + sinf(a), 0.5f}};
        blade_gpu_update(g, &env, &set);
        blade_gpu_read_blades(g, b, NULL);
        frames++;
        for (size_t i = 0; i < f.blade_count; i++) {
            blade_t *x = &b[i];
            nan |= bad_float(x);
            moved |= memcmp(x->v0, f.blades[i].v0, sizeof x->v0) != 0;
            float h = x->v1[3];
            double len = blade_ref_curve_length(x, 32);
            worst_len = fmax(worst_len, fabs(len - h) / h);
            float e[3] = {x->v2[0] - x->v0[0], x->v2[1] - x->v0[1], x->v2[2] - x->v0[2]};
            worst_below = fmax(worst_below, -(e[0] * x->up[0] + e[1] * x->up[1] + e[2] * x->up[2]));
            float m[3];
            blade_ref_midpoint(x, m);
            for (int k = 0; k < set.sphere_count; k++) {
                const blade_sphere_t *s = &set.spheres[k];
                if (pen(s, x->v0) >= 0.0f) continue; /* root inside: cannot leave */
                /* any point that was inside at this update was a contact; both must now be outside */
                float p = fmaxf(pen(s, x->v2), pen(s, m));
                checked++;
                if (p > -0.05f * h) contacts++;
                worst_pen = fmax(worst_pen, p / h);
            }
        }
        t += env.dt;
        clock_gettime(CLOCK_MONOTONIC, &t1);
        if ((double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec) > budget_s) break;
    }
    printf("invariants: %zu blades x %ld GPU frames (%.1f s simulated); blades within 5%% h of a sphere "
           "%ld; worst |len-h|/h %.4f, below ground %.2e, worst (sphere penetration)/h of v2 or m %.2e\n",
           f.blade_count, frames, t, contacts, worst_len, worst_below, worst_pen);
    CHECK(frames >= 50);
    CHECK(contacts > 1000);
    CHECK(!nan);
    CHECK(!moved);
    CHECK(worst_len < 0.02);
    CHECK(worst_below <= 1e-5);
    CHECK(worst_pen <= 1e-5);
    (void)checked;
    free(b);
    blade_gpu_destroy(g);
    blade_field_free(&f);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    test_against_reference();
    test_invariants(8.0);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

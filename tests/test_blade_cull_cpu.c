/* test_blade_cull_cpu: the CPU cost of blade mode's cull submit
 * (blade_gpu_cull, Jahrmann & Wimmer 2017 sec. 6 with the patch test on
 * the GPU). A field of about 10^5 blades in patches of 256 and one of
 * the same blades in patches of 16 (6400 patches: the per-patch work a
 * CPU loop would do shows), a camera at the field's edge: the median over
 * 24 calls of the calling thread's CPU time and of the wall time around
 * blade_gpu_cull (glFinish before and after, outside the clock), with the
 * patch test and without it (no_patch_cull). Bound: with the patch test
 * the thread's CPU time stays within twice the run without culling plus
 * 0.25 ms, on either field: nothing on the CPU grows with the patches. */
#include "blade/blade.h"
#include "platform/plat.h"
#include "test.h"
#include "test_gl.h"

#include <cglm/cglm.h>
#include <stdlib.h>
#include <string.h>

enum { RUNS = 24 };

static bool seed_plane(blade_field_t *f, int patch_size)
{
    static const float pos[] = {-20, 0, -20, 20, 0, -20, 20, 0, 20, -20, 0, 20};
    static const uint32_t idx[] = {0, 2, 1, 0, 3, 2};
    blade_mesh_t mesh = {pos, NULL, 4, idx, 6};
    return blade_seed_mesh(&mesh, &(blade_seed_desc_t){.seed = 5, .population = {.density = 64.0f},
                                                         .patch_size = patch_size},
                           f);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median CPU (thread) and wall milliseconds of one blade_gpu_cull. */
static void measure(const blade_field_t *f, bool patch_cull, double *cpu_ms, double *wall_ms)
{
    blade_gpu_t *g = blade_gpu_make(&(blade_gpu_desc_t){.field = f, .path = BLADE_PATH_PULLING,
                                                         .no_patch_cull = !patch_cull, .label = "cull_cpu"});
    CHECK(g);
    blade_cull_desc_t cd = {.max_distance = 80.0f};
    mat4 view, proj, vp;
    vec3 eye = {-19.0f, 1.7f, -19.0f}, at = {0.0f, 0.0f, -5.0f}, up = {0, 1, 0};
    glm_lookat(eye, at, up, view);
    glm_perspective(glm_rad(60.0f), 16.0f / 9.0f, 0.1f, 200.0f, proj);
    glm_mat4_mul(proj, view, vp);
    memcpy(cd.view.viewproj, vp, sizeof vp);
    memcpy(cd.view.camera, eye, sizeof eye);
    double cpu[RUNS], wall[RUNS];
    for (int i = -3; i < RUNS; i++) { /* 3 warm-up calls: programs and buffers settle */
        glFinish();
        double c0 = plat_thread_time(), w0 = plat_time();
        blade_gpu_cull(g, &cd, 0);
        double c1 = plat_thread_time(), w1 = plat_time();
        glFinish();
        if (i >= 0) cpu[i] = 1e3 * (c1 - c0), wall[i] = 1e3 * (w1 - w0);
    }
    qsort(cpu, RUNS, sizeof *cpu, cmp_double);
    qsort(wall, RUNS, sizeof *wall, cmp_double);
    *cpu_ms = cpu[RUNS / 2];
    *wall_ms = wall[RUNS / 2];
    blade_gpu_stats_t st = blade_gpu_stats(g, true);
    printf("  %-15s survivors %u, patches drawn %u, patch-culled %u: CPU %.3f ms, wall %.3f ms\n",
           patch_cull ? "patch test" : "no patch test", st.survivors, st.patches_drawn, st.patch_culled, *cpu_ms,
           *wall_ms);
    blade_gpu_destroy(g);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    static const int sizes[] = {256, 16};
    for (int s = 0; s < 2; s++) {
        blade_field_t f;
        CHECK(seed_plane(&f, sizes[s]));
        printf("field: %zu blades, %zu patches of %d\n", f.blade_count, f.patch_count, sizes[s]);
        double cpu_patch, wall_patch, cpu_all, wall_all;
        measure(&f, true, &cpu_patch, &wall_patch);
        measure(&f, false, &cpu_all, &wall_all);
        CHECK_MSG(cpu_patch <= 2.0 * cpu_all + 0.25, "patch test %.3f ms against %.3f ms without", cpu_patch,
                  cpu_all);
        blade_field_free(&f);
    }
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

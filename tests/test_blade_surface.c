/* test_blade_surface: the blade surface of blade_geom.glsl (blade_build:
 * De Casteljau eq. 21, the five shape profiles, the normal) against its C
 * twin blade_ref_surface, which draws the billboard clump layers
 * (bb_layout.c): 64 blades settled under gravity with random heights,
 * widths, angles and tilted up vectors, each shape, 9 x 17 points per
 * blade, with eq. 23 and eq. 24 off, each alone and both, and eq. 24 as
 * printed (alone and with the other two), positions and normals within
 * 1e-5 (relative to the blade height); eq. 23, eq. 24 and eq. 24 as
 * printed in numbers on the C twin (test_terms).
 * The profile's documented values (blade_geom.glsl banner) are checked on
 * the CPU. */
#include "common/bindings_tests.glsl"
#include "blade/blade_ref.h"
#include "gfx/gfx.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>

enum { BLADES = 64, US = 9, VS = 17 };

static void sub3(const float a[3], const float b[3], float d[3])
{
    for (int i = 0; i < 3; i++) d[i] = a[i] - b[i];
}

/* Eq. 23 and eq. 24 in numbers on one upright blade (width 0.08 m along
 * x, normal along z): each fails when its term is dropped.
 *   eq. 23 as printed, d = w' n (0.5 - |u - 0.5| (1 - v)) with w' = w / 2
 *   the paper's half width: at displacement 1 the midrib moves w / 4 =
 *   0.02 m along n at the root and at the tip, the edges 0 at the root and
 *   w / 4 at the tip; displacement 2 doubles it.
 *   eq. 24 step: seen exactly edge-on (camera along the width direction,
 *   n . view = 0) with width_correction 0.5 the root is 1 / 0.5 = 2 times
 *   as wide; 0.2 hits the 4x cap; seen face-on it is unchanged. */
static void test_terms(void)
{
    blade_t b = {{0, 0, 0, 0.0f}, {0, 0.5f, 0, 0.5f}, {0, 0.5f, 0, 0.08f}, {0, 1, 0, 3}};
    float flat[3], p[3], n[3], d[3];
    static const float uv[4][3] = {{0.5f, 0.0f, 0.02f}, {0.5f, 1.0f, 0.02f}, {0.0f, 0.0f, 0.0f}, {1.0f, 1.0f, 0.02f}};
    for (int k = 1; k <= 2; k++)
        for (int i = 0; i < 4; i++) {
            blade_ref_surface(&b, BLADE_SHAPE_QUAD, uv[i][0], uv[i][1], flat, n);
            blade_ref_surface_at(&b, &(blade_ref_surface_desc_t){.shape = BLADE_SHAPE_QUAD, .displacement = (float)k},
                                 uv[i][0], uv[i][1], p, n);
            sub3(p, flat, d);
            CHECK_NEAR(d[2] * n[2], k * uv[i][2], 1e-6);
            CHECK_NEAR(fabs(d[0]) + fabs(d[1]), 0.0, 1e-6);
        }
    printf("eq. 23 (displacement 1, w 0.08 m): midrib %.4f m at the root, %.4f m at the tip\n",
           (double)(0.25f * b.v2[3]), (double)(0.25f * b.v2[3]));
    static const float wc[3][2] = {{0.5f, 2.0f}, {0.2f, 4.0f}, {0.9f, 1.0f / 0.9f}};
    for (int i = 0; i < 3; i++) {
        float e0[3], e1[3];
        blade_ref_surface_desc_t sd = {.shape = BLADE_SHAPE_QUAD, .width_correction = wc[i][0],
                                       .camera = {3.0f, 0.0f, 0.0f}};
        blade_ref_surface_at(&b, &sd, 0.0f, 0.0f, e0, n);
        blade_ref_surface_at(&b, &sd, 1.0f, 0.0f, e1, n);
        sub3(e1, e0, d);
        CHECK_NEAR(sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), wc[i][1] * b.v2[3], 1e-6);
        printf("eq. 24 step (width_correction %.1f, edge-on): root width %.3f m of %.3f m\n", (double)wc[i][0],
               (double)sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), (double)b.v2[3]);
    }
    float e0[3], e1[3];
    blade_ref_surface_desc_t face = {.shape = BLADE_SHAPE_QUAD, .width_correction = 0.5f, .camera = {0, 0, 3.0f}};
    blade_ref_surface_at(&b, &face, 0.0f, 0.0f, e0, n);
    blade_ref_surface_at(&b, &face, 1.0f, 0.0f, e1, n);
    sub3(e1, e0, d);
    CHECK_NEAR(sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]), b.v2[3], 1e-6);
    /* eq. 24 as printed, w_min 1 px, w_span 2 px, focal 1000 px, the
     * quadratic blade (0.75 w wide at v = 0.5) seen face-on along z from
     * 100 m (w_p 0.8 px: Phi 1, a quad, w wide), 40 m (2 px: Phi 0.5, t
     * from 0.0625 to 0.6875, 0.625 w wide, off the midrib by 0.125 w) and
     * 10 m (8 px: Phi 0, unchanged) */
    static const float printed[3][3] = {{100.0f, 1.0f, 0.0f}, {40.0f, 0.625f, -0.125f}, {10.0f, 0.75f, 0.0f}};
    for (int i = 0; i < 3; i++) {
        blade_ref_surface_desc_t sd = {.shape = BLADE_SHAPE_QUADRATIC, .width_printed = {1.0f, 2.0f},
                                       .focal_px = 1000.0f, .camera = {0.0f, 0.25f, printed[i][0]}};
        blade_ref_surface_at(&b, &sd, 0.0f, 0.5f, e0, n);
        blade_ref_surface_at(&b, &sd, 1.0f, 0.5f, e1, n);
        sub3(e1, e0, d);
        CHECK_NEAR(d[0], printed[i][1] * b.v2[3], 1e-6);
        CHECK_NEAR(0.5f * (e0[0] + e1[0]), printed[i][2] * b.v2[3], 1e-6);
        printf("eq. 24 as printed (w_min 1 px, w_span 2 px), %g m away: width at v = 0.5 %.3f w, centre %+.3f w\n",
               (double)printed[i][0], (double)(d[0] / b.v2[3]), (double)(0.5f * (e0[0] + e1[0]) / b.v2[3]));
    }
}

int main(void)
{
    /* Profiles: quadratic 1 - v^2, quad 1, triangle 1 - v, triangle_tip 1
     * to v = 0.5 then down to 0, dandelion (1 - v) times the teeth. */
    CHECK_NEAR(blade_ref_profile(BLADE_SHAPE_QUADRATIC, 0.5f), 0.75, 1e-7);
    CHECK_NEAR(blade_ref_profile(BLADE_SHAPE_QUAD, 0.9f), 1.0, 0.0);
    CHECK_NEAR(blade_ref_profile(BLADE_SHAPE_TRIANGLE, 0.25f), 0.75, 1e-7);
    CHECK_NEAR(blade_ref_profile(BLADE_SHAPE_TRIANGLE_TIP, 0.4f), 1.0, 0.0);
    CHECK_NEAR(blade_ref_profile(BLADE_SHAPE_TRIANGLE_TIP, 0.75f), 0.5, 1e-7);
    CHECK_NEAR(blade_ref_profile(BLADE_SHAPE_DANDELION, 0.125f), 0.875 * 0.35, 1e-6);
    CHECK_NEAR(blade_ref_profile(BLADE_SHAPE_DANDELION, 0.0f), 1.0, 1e-7);

    test_terms();

    test_gl_init();
    core_rng_t rng;
    core_rng_seed(&rng, 5, 1);
    blade_t b[BLADES];
    blade_env_t env = blade_env_defaults(&(blade_env_t){.dt = 1.0f / 60.0f, .gravity = 1.0f});
    for (int i = 0; i < BLADES; i++) {
        float up[3] = {core_rng_range(&rng, -0.3f, 0.3f), 1.0f, core_rng_range(&rng, -0.3f, 0.3f)};
        float l = sqrtf(up[0] * up[0] + up[1] * up[1] + up[2] * up[2]), h = core_rng_range(&rng, 0.2f, 0.9f);
        float p[3] = {core_rng_range(&rng, -2.0f, 2.0f), core_rng_range(&rng, -0.5f, 0.5f),
                      core_rng_range(&rng, -2.0f, 2.0f)};
        b[i] = (blade_t){.v0 = {p[0], p[1], p[2], core_rng_range(&rng, 0.0f, 6.2831853f)},
                         .v2 = {0, 0, 0, core_rng_range(&rng, 0.01f, 0.08f)},
                         .up = {up[0] / l, up[1] / l, up[2] / l, core_rng_range(&rng, 2.0f, 12.0f)}};
        b[i].v1[3] = h;
        for (int k = 0; k < 3; k++) b[i].v1[k] = b[i].v2[k] = p[k] + b[i].up[k] * h;
        float eta = 0.0f;
        for (int s = 0; s < 40; s++) blade_ref_step_one(&b[i], &eta, &env, NULL);
    }
    gfx_program_t prog = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/blade_surface.comp"});
    CHECK(prog.id != 0);
    size_t n = (size_t)BLADES * US * VS;
    gfx_buffer_t in = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof b, .data = b, .label = "surface.blades"});
    gfx_buffer_t out = gfx_buffer_make(&(gfx_buffer_desc_t){.size = n * 32, .label = "surface.points"});
    float *gpu = malloc(n * 32);
    double worst_p = 0.0, worst_n = 0.0;
    /* eq. 23 and eq. 24 off, each alone, both, eq. 24 as printed alone and
     * with both (w_min 1 px, w_span 2 px at a focal length of 50 px: the
     * blades' 0.1-4 px span it; the camera near the blades) */
    static const float terms[6][3] = {{0.0f, 0.0f, 0.0f}, {1.0f, 0.0f, 0.0f}, {0.0f, 0.3f, 0.0f},
                                      {1.5f, 0.3f, 0.0f}, {0.0f, 0.0f, 2.0f}, {1.5f, 0.3f, 2.0f}};
    for (int run = 0; run < 6 * 5 && prog.id; run++) {
        blade_ref_surface_desc_t sd = {.shape = BLADE_SHAPE_QUADRATIC + run % 5,
                                       .displacement = terms[run / 5][0],
                                       .width_correction = terms[run / 5][1],
                                       .width_printed = {1.0f, terms[run / 5][2]},
                                       .focal_px = 50.0f,
                                       .camera = {0.7f, 0.4f, 2.5f}};
        glUseProgram(prog.id);
        glUniform1i(gfx_uniform(prog, "u_shape"), sd.shape);
        glUniform1f(gfx_uniform(prog, "u_displacement"), sd.displacement);
        glUniform1f(gfx_uniform(prog, "u_width_correction"), sd.width_correction);
        glUniform3f(gfx_uniform(prog, "u_width_printed"), sd.width_printed[0], sd.width_printed[1], sd.focal_px);
        glUniform3fv(gfx_uniform(prog, "u_camera"), 1, sd.camera);
        glUniform1ui(gfx_uniform(prog, "u_count"), BLADES);
        glUniform1i(gfx_uniform(prog, "u_us"), US);
        glUniform1i(gfx_uniform(prog, "u_vs"), VS);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN, in.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_OUT, out.id);
        glDispatchCompute((GLuint)((n + 63) / 64), 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        CHECK(gfx_buffer_read(out, 0, n * 32, gpu));
        for (size_t i = 0; i < n; i++) {
            size_t k = i % (US * VS);
            const blade_t *bl = &b[i / (US * VS)];
            float p[3], nr[3];
            blade_ref_surface_at(bl, &sd, (float)(k % US) / (US - 1), (float)(k / US) / (VS - 1), p, nr);
            worst_p = fmax(worst_p, test_dist3(p, gpu + i * 8) / bl->v1[3]);
            worst_n = fmax(worst_n, test_dist3(nr, gpu + i * 8 + 4));
        }
    }
    printf("blade surface, GLSL vs C twin (5 shapes x eq. 23/24 off, each, both, eq. 24 printed alone and with "
           "both; %d blades, %d points each): "
           "position %.2g (of the height), normal %.2g\n",
           BLADES, US * VS, worst_p, worst_n);
    CHECK(worst_p < 1e-5 && worst_n < 1e-5);
    free(gpu);
    gfx_buffer_destroy(&in);
    gfx_buffer_destroy(&out);
    gfx_program_destroy(&prog);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

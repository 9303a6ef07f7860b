/* test_blade_surface: the blade surface of blade_geom.glsl (blade_build:
 * De Casteljau eq. 21, the five shape profiles, the normal) against its C
 * twin blade_ref_surface, which draws the billboard clump layers
 * (bb_layout.c): 64 blades settled under gravity with random heights,
 * widths, angles and tilted up vectors, each shape, 9 x 17 points per
 * blade, positions and normals within 1e-5 (relative to the blade height).
 * The profile's documented values (blade_geom.glsl banner) are checked on
 * the CPU. */
#include "blade/blade_ref.h"
#include "gfx/gfx.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>

enum { BLADES = 64, US = 9, VS = 17 };

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
    for (int shape = BLADE_SHAPE_QUADRATIC; shape <= BLADE_SHAPE_DANDELION && prog.id; shape++) {
        glUseProgram(prog.id);
        glUniform1i(gfx_uniform(prog, "u_shape"), shape);
        glUniform1f(gfx_uniform(prog, "u_displacement"), 0.0f);
        glUniform1f(gfx_uniform(prog, "u_width_correction"), 0.0f);
        glUniform1ui(gfx_uniform(prog, "u_count"), BLADES);
        glUniform1i(gfx_uniform(prog, "u_us"), US);
        glUniform1i(gfx_uniform(prog, "u_vs"), VS);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.id);
        glDispatchCompute((GLuint)((n + 63) / 64), 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        CHECK(gfx_buffer_read(out, 0, n * 32, gpu));
        for (size_t i = 0; i < n; i++) {
            size_t k = i % (US * VS);
            const blade_t *bl = &b[i / (US * VS)];
            float p[3], nr[3];
            blade_ref_surface(bl, shape, (float)(k % US) / (US - 1), (float)(k / US) / (VS - 1), p, nr);
            worst_p = fmax(worst_p, test_dist3(p, gpu + i * 8) / bl->v1[3]);
            worst_n = fmax(worst_n, test_dist3(nr, gpu + i * 8 + 4));
        }
    }
    printf("blade surface, GLSL vs C twin (5 shapes, %d blades, %d points each): position %.2g (of the height), "
           "normal %.2g\n",
           BLADES, US * VS, worst_p, worst_n);
    CHECK(worst_p < 1e-5 && worst_n < 1e-5);
    free(gpu);
    gfx_buffer_destroy(&in);
    gfx_buffer_destroy(&out);
    gfx_program_destroy(&prog);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

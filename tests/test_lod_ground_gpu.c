/* test_lod_ground_gpu: the thinning in GLSL (lod_blade and lod_coverage of
 * common/lod.glsl, which the blade culls and the terrain read) and the
 * grass-shaded ground under it (canopy_under of common/canopy.glsl, mixed
 * into terrain.frag) against their C twins blade_lod_blade,
 * blade_lod_coverage and blade_canopy_under: 4096 blades at random
 * distances, widths, covers and extents, the uniforms set as the ground
 * sets them (blade_lod_uniforms), for each rule with and without
 * compensation and the shrink window; all four values within 1e-4. */
#include "common/bindings_tests.glsl"
#include "blade/blade.h"
#include "blade/blade_canopy.h"
#include "gfx/gfx.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>

enum { N = 4096 };

int main(void)
{
    test_gl_init();
    static float in[N][4], got[N][4];
    core_rng_t rng;
    core_rng_seed(&rng, 5, 1);
    for (int i = 0; i < N; i++) {
        in[i][0] = core_rng_range(&rng, 0.0f, 130.0f);
        in[i][1] = core_rng_range(&rng, 0.01f, 0.06f);
        in[i][2] = core_rng_range(&rng, 0.0f, 0.99f);
        in[i][3] = core_rng_range(&rng, 0.0f, 1.0f);
    }
    gfx_program_t prog = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/lod_ground_eval.comp", .label = "lod"});
    CHECK(prog.id != 0);
    gfx_buffer_t bi = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof in, .data = in, .label = "lod.in"});
    gfx_buffer_t bo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof got, .label = "lod.out"});
    static const blade_lod_t cases[] = {
        {.rule = BLADE_LOD_WIDTH},
        {.rule = BLADE_LOD_WIDTH, .no_compensation = true, .start = 5.0f, .width_px = 3.0f},
        {.rule = BLADE_LOD_WIDTH, .no_shrink = true, .no_fade = true, .max_scale = 3.0f},
        {.rule = BLADE_LOD_LEVELS, .levels = 8},
        {.rule = BLADE_LOD_PRINTED, .levels = 4, .level_distance = 50.0f},
    };
    const float focal = 935.3f, cull = 100.0f;
    double worst = 0.0, ground_spread = 0.0;
    int culled = 0;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        blade_lod_t l = blade_lod_defaults(&cases[c]);
        glUseProgram(prog.id);
        glUniform1ui(gfx_uniform(prog, "u_count"), N);
        blade_lod_uniforms(prog, &l, focal, cull);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN, bi.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_OUT, bo.id);
        glDispatchCompute((N + 63) / 64, 1, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        memset(got, 0, sizeof got);
        CHECK(gfx_buffer_read(bo, 0, sizeof got, got));
        for (int i = 0; i < N; i++) {
            blade_lod_draw_t b = blade_lod_blade(&l, (uint32_t)i, in[i][0], in[i][1], focal, cull);
            float kept = blade_lod_coverage(&l, in[i][0], in[i][1], focal, cull);
            float want[4] = {b.weight, b.scale, kept, blade_canopy_under(in[i][2], in[i][3], kept)};
            for (int k = 0; k < 4; k++) {
                double e = fabs(got[i][k] - want[k]);
                if (e > worst) worst = e;
            }
            culled += b.weight == 0.0f;
            ground_spread = fmax(ground_spread, want[3]);
        }
    }
    printf("thinning and grass-shaded ground, GLSL vs C twin (%d blades x 5 rules): worst %.2g\n", N, worst);
    CHECK(worst < 1e-4);
    CHECK(culled > N / 4);         /* the rules cull: the comparison covers both sides */
    CHECK(ground_spread > 0.3);    /* and the ground mixes in */
    gfx_buffer_destroy(&bi);
    gfx_buffer_destroy(&bo);
    gfx_program_destroy(&prog);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

/* test_canopy_gpu: the ground canopy's colour in GLSL (canopy_color of
 * common/canopy.glsl, which terrain.frag shades the far ground with)
 * against its C twin blade_canopy_color: 256 cameras and suns at random
 * elevations and azimuths over a flat ground point, the table of the
 * default blades uploaded as the terrain uploads it (blade_canopy_pack);
 * colour and cover within 1e-3 (a quarter of an 8-bit step; the angles
 * come from float dot products, ill-conditioned near 0 and pi). The twin's inputs (elevation, azimuth of
 * the sun from the direction to the viewer) are computed here from the
 * same vectors. */
#include "common/bindings_tests.glsl"
#include "blade/blade_canopy.h"
#include "gfx/gfx.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>

enum { N = 256 };

int main(void)
{
    test_gl_init();
    blade_canopy_t c;
    CHECK(blade_canopy_make(&c, &(blade_canopy_desc_t){.seed = 9, .rays = 1024, .sun = {0.45f, 0.8f, 0.35f}}));
    blade_canopy_uniforms_t u;
    blade_canopy_pack(&c, &u);
    static const float root[3] = {0.10f, 0.25f, 0.05f}, tip[3] = {0.45f, 0.65f, 0.20f};
    float cams[N][4], suns[N][4], want[N][4], got[N][4];
    core_rng_t rng;
    core_rng_seed(&rng, 11, 2);
    for (int i = 0; i < N; i++) {
        float e = core_rng_range(&rng, 0.01f, 1.56f), a = core_rng_range(&rng, -3.14f, 3.14f);
        float se = core_rng_range(&rng, 0.1f, 1.4f), phi = core_rng_range(&rng, 0.0f, 3.14f);
        float dist = core_rng_range(&rng, 5.0f, 200.0f);
        cams[i][0] = dist * cosf(e) * cosf(a);
        cams[i][1] = dist * sinf(e);
        cams[i][2] = dist * cosf(e) * sinf(a);
        suns[i][0] = cosf(se) * cosf(a + phi);
        suns[i][1] = sinf(se);
        suns[i][2] = cosf(se) * sinf(a + phi);
        cams[i][3] = suns[i][3] = 0.0f;
        blade_canopy_color(&c, e, phi, root, tip, want[i], &want[i][3]);
    }
    gfx_program_t prog = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/canopy_eval.comp", .label = "canopy"});
    CHECK(prog.id != 0);
    gfx_buffer_t bc = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof cams, .data = cams, .label = "canopy.cams"});
    gfx_buffer_t bs = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof suns, .data = suns, .label = "canopy.suns"});
    gfx_buffer_t bo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof got, .label = "canopy.out"});
    glUseProgram(prog.id);
    glUniform1ui(gfx_uniform(prog, "u_count"), N);
    glUniform1i(gfx_uniform(prog, "u_canopy_rows"), u.rows);
    glUniform1fv(gfx_uniform(prog, "u_canopy_cover"), u.rows, u.cover);
    glUniform4fv(gfx_uniform(prog, "u_canopy_amb"), u.rows, &u.amb[0][0]);
    glUniform2fv(gfx_uniform(prog, "u_canopy_sun"), u.rows * BLADE_CANOPY_AZIMUTHS, &u.sun[0][0]);
    glUniform3fv(gfx_uniform(prog, "u_canopy_albedo_root"), 1, root);
    glUniform3fv(gfx_uniform(prog, "u_canopy_albedo_tip"), 1, tip);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN, bc.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN2, bs.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_OUT, bo.id);
    glDispatchCompute((N + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    memset(got, 0, sizeof got);
    CHECK(gfx_buffer_read(bo, 0, sizeof got, got));
    double worst = 0.0, spread = 0.0;
    for (int i = 0; i < N; i++)
        for (int k = 0; k < 4; k++) {
            worst = fmax(worst, fabs(got[i][k] - want[i][k]));
            spread = fmax(spread, fabs(want[i][k] - want[0][k]));
        }
    printf("canopy colour and cover, GLSL vs C twin (%d views): worst %.2g (values spread %.3f)\n", N, worst, spread);
    CHECK(worst < 1e-3); /* a quarter of an 8-bit step: acos / asin of float dots near +-1 */
    CHECK(spread > 0.1); /* the views differ: the comparison compares something */
    gfx_buffer_destroy(&bc);
    gfx_buffer_destroy(&bs);
    gfx_buffer_destroy(&bo);
    gfx_program_destroy(&prog);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

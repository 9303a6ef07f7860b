/* test_gi_gpu: the global illumination volumes on the GPU. (1) gi_ambient
 * of common/gi.glsl, read back at 256 random points and normals, against
 * its C twin gi_volume_ambient on the same volume (terrain with a valley
 * and a peak, a wall, a grass layer), through the textures gi_gpu_make
 * uploads (half floats) and the binding gi_set_uniforms makes. (2) The
 * billboard shading (bb_vertex_ambient + bb_shade, as bb_quad.vert and
 * bb_render.frag light a card): a card in the valley is darker than the
 * same card on the peak with GI on, and equal with GI off (the camera, sun
 * and fog are symmetric between the two), so the test fails when GI is
 * dropped from the billboards. */
#include "common/bindings_tests.glsl"
#include "gfx/gfx.h"
#include "gi/gi.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>

enum { N = 256 };

/* A V valley at x = -20 and a peak at x = +20, slopes 0.8, capped 20 m
 * away (the cliff at x = 0 is beyond the rays' 12 m reach from both). */
static float terrain(const void *user, float x, float z)
{
    (void)user;
    (void)z;
    return x < 0.0f ? 0.8f * fminf(fabsf(x + 20.0f), 15.0f) : -0.8f * fminf(fabsf(x - 20.0f), 15.0f);
}

static float cover(const void *user, float x, float z)
{
    (void)user;
    (void)x;
    return z < 0.0f ? 1.0f : 0.3f;
}

/* Runs gi_eval.comp over items (2 vec4 per item) with GI bound by b. */
static void eval(gfx_program_t prog, const gi_bind_t *b, int mode, const float (*items)[4], int count, float (*out)[4])
{
    gfx_buffer_t bi = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof(float) * 8 * (size_t)count, .data = items,
                                                           .label = "gi_eval.items"});
    gfx_buffer_t bo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof(float) * 4 * (size_t)count,
                                                           .label = "gi_eval.out"});
    /* The camera level with both cards (y 0.3) and the sun without an x
     * part: the valley's card and the peak's see the same light and fog. */
    const float camera[3] = {0.0f, 0.3f, 30.0f}, sun[3] = {0.0f, 0.8f, 0.6f}, albedo[3] = {0.3f, 0.5f, 0.2f};
    glUseProgram(prog.id);
    gi_set_uniforms(prog.id, b);
    glUniform1ui(gfx_uniform(prog, "u_count"), (GLuint)count);
    glUniform1i(gfx_uniform(prog, "u_mode"), mode);
    glUniform3fv(gfx_uniform(prog, "u_camera"), 1, camera);
    glUniform3fv(gfx_uniform(prog, "u_sun"), 1, sun);
    glUniform3fv(gfx_uniform(prog, "u_albedo"), 1, albedo);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN, bi.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_OUT, bo.id);
    glDispatchCompute((GLuint)(count + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    memset(out, 0, sizeof(float) * 4 * (size_t)count);
    CHECK(gfx_buffer_read(bo, 0, sizeof(float) * 4 * (size_t)count, out));
    gfx_buffer_destroy(&bi);
    gfx_buffer_destroy(&bo);
}

int main(void)
{
    test_gl_init();
    gi_object_t wall = {.lo = {-4.0f, -12.0f, 6.0f}, .hi = {4.0f, 3.0f, 7.0f}};
    gi_scene_t scene = {.height = terrain, .cover = cover, .grass_height = 0.5f, .grass_extinction = 3.0f,
                        .objects = &wall, .object_count = 1};
    gi_volume_t v;
    CHECK(gi_volume_make(&v, &(gi_volume_desc_t){.res = {32, 16, 16}, .lo = {-40.0f, -12.5f, -10.0f},
                                                 .hi = {40.0f, 12.5f, 10.0f}, .reach = 12.0f},
                         &scene));
    gi_gpu_t g;
    CHECK(gi_gpu_make(&g, &v));
    gi_bind_t on = gi_gpu_bind(&g), off = {0};
    gfx_program_t prog = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/gi_eval.comp", .label = "gi_eval"});
    CHECK(prog.id != 0);

    static float items[N][2][4], got[N][4], want[N][4];
    core_rng_t rng;
    core_rng_seed(&rng, 5, 1);
    for (int i = 0; i < N; i++) {
        float x = core_rng_range(&rng, -38.0f, 38.0f), z = core_rng_range(&rng, -9.0f, 9.0f);
        float y = terrain(NULL, x, z) + core_rng_range(&rng, 0.0f, 3.0f);
        float n[3] = {core_rng_range(&rng, -1, 1), core_rng_range(&rng, -1, 1), core_rng_range(&rng, -1, 1)};
        float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) + 1e-6f;
        float p[3] = {x, y, z}, u[3] = {n[0] / l, n[1] / l, n[2] / l};
        memcpy(items[i][0], p, sizeof p);
        memcpy(items[i][1], u, sizeof u);
        items[i][0][3] = items[i][1][3] = 0.0f;
        gi_volume_ambient(&v, p, u, want[i]);
    }
    eval(prog, &on, 0, (const float (*)[4])items, N, got);
    double worst = 0.0, spread = 0.0;
    for (int i = 0; i < N; i++)
        for (int c = 0; c < 3; c++) {
            worst = fmax(worst, fabs(got[i][c] - want[i][c]));
            spread = fmax(spread, fabs(want[i][c] - want[0][c]));
        }
    printf("gi_ambient, GLSL vs C twin (%d points): worst %.2g (values spread %.3f)\n", N, worst, spread);
    CHECK(worst < 1e-3); /* half-float texels (11-bit mantissa) of values up to ~0.7: a quarter of an 8-bit step */
    CHECK(spread > 0.1);

    /* A card facing the camera at the valley's bottom and at the peak. */
    float cards[2][2][4] = {{{-20.0f, 0.3f, 0.0f, 0.0f}, {0.0f}}, {{20.0f, 0.3f, 0.0f, 0.0f}, {0.0f}}};
    for (int k = 0; k < 2; k++) {
        float dx = -cards[k][0][0], dz = 30.0f, l = sqrtf(dx * dx + dz * dz);
        cards[k][1][0] = dx / l;
        cards[k][1][2] = dz / l;
    }
    float lit[2][4], plain[2][4];
    eval(prog, &on, 1, (const float (*)[4])cards, 2, lit);
    eval(prog, &off, 1, (const float (*)[4])cards, 2, plain);
    printf("billboard card, GI on: valley %.3f %.3f %.3f, peak %.3f %.3f %.3f; GI off: %.3f, %.3f (green)\n",
           lit[0][0], lit[0][1], lit[0][2], lit[1][0], lit[1][1], lit[1][2], plain[0][1], plain[1][1]);
    for (int c = 0; c < 3; c++) {
        CHECK(lit[0][c] < lit[1][c] - 0.01f);
        CHECK_NEAR(plain[0][c], plain[1][c], 1e-6);
    }
    gfx_program_destroy(&prog);
    gi_gpu_destroy(&g);
    gi_volume_free(&v);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

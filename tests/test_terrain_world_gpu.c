/* test_terrain_world_gpu: world_height / world_normal of
 * common/world_height.glsl against their C twin terrain_world_height at
 * 4096 random points of a 4 km world of amplitude 30 m (and 64 beyond its
 * square): heights within 1e-3 m, normals within 1e-3 (float rounding,
 * GPU sqrt/division and fused multiply-adds). The program is configured
 * only by its uniforms (terrain_world_gpu): those of another seed, or none
 * set (a flat ground at 0), must miss by metres (the comparison compares
 * something). */
#include "common/bindings_tests.glsl"
#include "gfx/gfx.h"
#include "terrain/terrain.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>

enum { N = 4096 + 64 };

static float pts[N][2], got[N][4];

/* Runs world_eval.comp with world g's uniforms (NULL: none set); false
 * when the program does not build. */
static bool eval_gpu(const terrain_world_t *g)
{
    gfx_program_t prog = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/world_eval.comp", .label = "world_eval"});
    if (!prog.id) return false;
    if (g) {
        terrain_world_gpu_t w = terrain_world_gpu(g);
        gfx_world_height_uniforms(prog, w.keys, TERRAIN_WORLD_LAYERS, w.height);
    }
    gfx_buffer_t bp = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof pts, .data = pts, .label = "world.pts"});
    gfx_buffer_t bo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof got, .label = "world.out"});
    glUseProgram(prog.id);
    glUniform1ui(gfx_uniform(prog, "u_count"), N);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN, bp.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_OUT, bo.id);
    glDispatchCompute((N + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    memset(got, 0, sizeof got);
    bool ok = gfx_buffer_read(bo, 0, sizeof got, got);
    gfx_buffer_destroy(&bp);
    gfx_buffer_destroy(&bo);
    gfx_program_destroy(&prog);
    return ok;
}

/* Worst height and normal differences of got against w. */
static void compare(const terrain_world_t *w, double *dh, double *dn)
{
    *dh = *dn = 0.0;
    for (int i = 0; i < N; i++) {
        vec3 n;
        float h = terrain_world_height(w, pts[i][0], pts[i][1], n);
        *dh = fmax(*dh, fabs(got[i][3] - h));
        for (int c = 0; c < 3; c++) *dn = fmax(*dn, fabs(got[i][c] - n[c]));
    }
}

int main(void)
{
    test_gl_init();
    core_rng_t rng;
    core_rng_seed(&rng, 21, 4);
    for (int i = 0; i < N; i++) {
        float r = i < 4096 ? 2048.0f : 3000.0f;
        pts[i][0] = core_rng_range(&rng, -r, r);
        pts[i][1] = core_rng_range(&rng, -r, r);
    }
    terrain_world_t w = terrain_world_make(&(terrain_desc_t){.type = TERRAIN_WORLD, .size = 4096, .height = 30}, 77);
    CHECK(eval_gpu(&w));
    double dh, dn;
    compare(&w, &dh, &dn);
    printf("world_height.glsl vs terrain_world_height (%d points, 4 km, 30 m): worst height %.2g m, normal %.2g\n", N,
           dh, dn);
    CHECK(dh < 1e-3);
    CHECK(dn < 1e-3);

    terrain_world_t other = w;
    other.seed[0] ^= 1u;
    CHECK(eval_gpu(&other));
    compare(&w, &dh, &dn);
    printf("with the uniforms of another seed: worst height %.2g m\n", dh);
    CHECK(dh > 1.0);

    CHECK(eval_gpu(NULL));
    compare(&w, &dh, &dn);
    printf("with no uniforms set: worst height %.2g m\n", dh);
    CHECK(dh > 1.0);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

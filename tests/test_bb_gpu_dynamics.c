/* test_bb_gpu_dynamics: many frames of the collision (eq. 1-7) and recovery
 * (eq. 8) passes of Orthmann et al. 2009 with a fast sphere and varying dt:
 * roots never move, no NaN/Inf, pool bookkeeping stays consistent; then,
 * with the sphere gone, every deformed billboard recovers: the mesh stored at
 * release equals the CPU wind pose (< 1 mm), the slots return to the pool and
 * the leaves go IDLE. A field with an 8-slot pool checks the non-blocking
 * pool readback: bb_field_update never waits, yet within a few updates the
 * late stats (bb_field_stats without wait) reach the exact refused count and
 * exhaustion is logged as a warning. Also prints per-pass timings. */
#include "test.h"
#include "test_gl.h"

#include "bb_gpu_test_util.h"

#include <string.h>

/* A fast sphere (mesh, radius) over 60 frames of varying dt from *time on:
 * roots stay, every value finite, the pool counts what is deformed. */
static void check_moving(bb_field_t *f, const terrain_mesh_t *terrain, const test_mesh_t *mesh, float radius,
                         float *time)
{
    test_readback_t rb = test_readback_make(f);
    const bb_field_desc_t *d = &rb.info.desc;
    int n = rb.info.billboards, nm = rb.info.mesh_vertices;
    bb_point_t *pts = rb.pts;
    int N = d->subdiv[0];
    int max_deformed = 0, bad_roots = 0, nonfinite = 0;
    double max_root = 0;
    for (int frame = 0; frame < 60; frame++) {
        float dt = (frame % 3 == 0) ? 1.0f / 15.0f : (frame % 3 == 1 ? 1.0f / 60.0f : 1.0f / 30.0f);
        *time += dt;
        /* 6 m/s zig-zag across the field, bouncing between x = -3.5 and 3.5 */
        float s = fmodf(*time * 6.0f, 14.0f), x = s < 7.0f ? s - 3.5f : 10.5f - s, z = 1.5f * sinf(*time * 3.0f);
        float c[3] = {x, terrain_height_at(terrain, x, z, NULL) + 0.25f, z};
        collide_object_t o = test_object(mesh, c, radius);
        gfx_timer_frame_begin();
        bb_field_update(f, test_set(&o, 1), *time, dt);
        if (frame % 6 != 5) continue;
        test_readback_read(f, &rb, true);
        int deformed = 0;
        for (int i = 0; i < n; i++) {
            const float *pf = (const float *)&pts[i];
            for (int k = 0; k < 13; k++) nonfinite += k != 10 && k != 11 && !isfinite(pf[k]); /* floats only */
            if (pts[i].pad[0] == BB_NO_SLOT) continue;
            deformed++;
            bb_mesh_t cpu;
            test_cpu_mesh(d, &pts[i], *time, &cpu);
            const float *g = test_readback_mesh(&rb, pts[i].pad[0]);
            for (int v = 0; v < nm; v++) {
                for (int k = 0; k < 3; k++) nonfinite += !isfinite(g[4 * v + k]);
                if (v < N)
                    for (int k = 0; k < 3; k++) {
                        double e = fabs(g[4 * v + k] - cpu.rest[v][k]);
                        max_root = fmax(max_root, e);
                        bad_roots += e > 1e-5;
                    }
            }
            bb_mesh_free(&cpu);
        }
        bb_stats_t st;
        bb_field_stats(f, true, &st);
        CHECK(st.deformed == deformed);
        max_deformed = deformed > max_deformed ? deformed : max_deformed;
    }
    printf("moving sphere: up to %d deformed, max root drift %.3g m, %d bad roots, %d non-finite values\n",
           max_deformed, max_root, bad_roots, nonfinite);
    CHECK(max_deformed > 20);
    CHECK(bad_roots == 0 && nonfinite == 0);

    test_readback_free(&rb);
}

/* Recovery: no objects any more. Track every deformed billboard until it
 * is released and compare the released mesh with the CPU wind pose. */
static void check_recovery(bb_field_t *f, float *time)
{
    test_readback_t rb = test_readback_make(f);
    const bb_field_desc_t *d = &rb.info.desc;
    int n = rb.info.billboards, nm = rb.info.mesh_vertices;
    bb_point_t *pts = rb.pts;
    test_readback_read(f, &rb, false);
    uint32_t *slot = malloc(sizeof *slot * (size_t)n);
    for (int i = 0; i < n; i++) slot[i] = pts[i].pad[0];
    double max_release = 0, max_before = 0;
    int released = 0;
    for (int frame = 0; frame < 40; frame++) {
        float dt = 1.0f / 30.0f;
        *time += dt;
        gfx_timer_frame_begin();
        bb_field_update(f, NULL, *time, dt);
        test_readback_read(f, &rb, true);
        for (int i = 0; i < n; i++) {
            if (slot[i] == BB_NO_SLOT) continue;
            bb_mesh_t cpu;
            test_cpu_mesh(d, &pts[i], *time, &cpu);
            const float *g = test_readback_mesh(&rb, slot[i]);
            double e = 0;
            for (int v = 0; v < nm; v++)
                e = fmax(e, sqrt(glm_vec3_distance2((float *)&g[4 * v], cpu.pos[v])));
            bb_mesh_free(&cpu);
            if (pts[i].pad[0] == BB_NO_SLOT) {
                CHECK(pts[i].state == BB_STATE_IDLE);
                max_release = fmax(max_release, e);
                released++;
                slot[i] = BB_NO_SLOT;
            } else if (pts[i].recover_time < 1.5f * dt) {
                max_before = fmax(max_before, e);
            }
        }
    }
    bb_stats_t st;
    bb_field_stats(f, true, &st);
    uint32_t hdr[2];
    CHECK(bb_field_read(f, BB_DATA_POOL, 0, 2, hdr));
    printf("recovery: %d released, max |mesh - wind pose| at release %.3g m, one frame before %.3g m; "
           "%d deformed left, free %u of %d, leaves colliding %d recovering %d idle %d\n",
           released, max_release, max_before, st.deformed, hdr[0], st.pool_capacity, st.leaves[1], st.leaves[2],
           st.leaves[0]);
    CHECK(released > 20);
    CHECK(max_release < 1e-3);
    /* One frame before release the stored mesh is (dt/T)^3-close to the
     * wind pose of the previous frame; the wind moved since, so allow the
     * wind's per-frame travel. */
    CHECK(max_before < 5e-3);
    CHECK(st.deformed == 0 && hdr[0] == (uint32_t)st.pool_capacity && st.pool_exhausted == 0);
    CHECK(st.leaves[BB_NODE_COLLIDING] == 0 && st.leaves[BB_NODE_RECOVERING] == 0);

    free(slot);
    test_readback_free(&rb);
}

/* Pool exhaustion through the non-blocking readback: an 8-slot pool. */
static void check_pool_readback(const terrain_mesh_t *terrain, const test_mesh_t *mesh, float radius,
                                float recover_time, float *time)
{
    bb_field_t *small = bb_field_make(&(bb_field_desc_t){.terrain = terrain, .seed = 5, .density = 36,
                                                         .octree_depth = 3, .cube_res = 32, .recover_time = recover_time,
                                                         .max_deformed = 8, .layout = {.size = 32, .clump_size = 32}});
    CHECK(small);
    int warns = core_log_warn_count();
    bb_stats_t late = {0}, exact = {0};
    for (int frame = 0; frame < 12; frame++) {
        *time += 1.0f / 30.0f;
        float x = -2.0f + 0.3f * (float)frame, c[3] = {x, terrain_height_at(terrain, x, 0.0f, NULL) + 0.25f, 0.0f};
        collide_object_t o = test_object(mesh, c, radius);
        bb_field_update(small, test_set(&o, 1), *time, 1.0f / 30.0f);
    }
    bb_field_stats(small, true, &exact);
    /* No more GPU work: updates only poll, so the late numbers settle. */
    for (int frame = 0; frame < 6 && late.pool_exhausted != exact.pool_exhausted; frame++) {
        glFinish();
        bb_field_update(small, NULL, *time, 0.0f);
        bb_field_stats(small, false, &late);
    }
    printf("8-slot pool: exact %d deformed, %d refused; late %d deformed, %d refused; %d warnings\n",
           exact.deformed, exact.pool_exhausted, late.deformed, late.pool_exhausted, core_log_warn_count() - warns);
    CHECK(exact.deformed == 8 && exact.pool_exhausted > 0);
    CHECK(late.pool_exhausted == exact.pool_exhausted && late.deformed == exact.deformed);
    CHECK(core_log_warn_count() > warns);
    bb_field_destroy(small);

}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    terrain_mesh_t terrain;
    CHECK(terrain_make_heightfield(&terrain, &(terrain_desc_t){.size = 8, .resolution = 8, .height = 0.3f}, 5));
    const float T = 0.5f;
    bb_field_t *f = bb_field_make(&(bb_field_desc_t){.terrain = &terrain, .seed = 5, .density = 36, .octree_depth = 3,
                                                     .cube_res = 32, .recover_time = T, .max_deformed = 512,
                                                     .layout = {.size = 32, .clump_size = 32}});
    CHECK(f);
    collide_shape_t sc = {.type = COLLIDE_SHAPE_SPHERE, .radius = 0.45f};
    test_mesh_t mesh;
    test_mesh_make(&mesh, &sc);
    float time = 0;
    check_moving(f, &terrain, &mesh, sc.radius, &time);
    check_recovery(f, &time);
    check_pool_readback(&terrain, &mesh, sc.radius, T, &time);

    gfx_timer_flush();
    for (int i = 0; i < gfx_timer_count(); i++)
        printf("timer %-12s median %.3f ms, mean %.3f ms\n", gfx_timer_name(i), gfx_timer_median_ms(i),
               gfx_timer_avg_ms(i));

    bb_field_destroy(f);
    test_mesh_destroy(&mesh);
    terrain_free(&terrain);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

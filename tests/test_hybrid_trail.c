/* test_hybrid_trail: a trail made in the blade representation survives the
 * camera moving away (the tile turns to billboards) and back (blades again)
 * through the hand-over of src/hybrid/hybrid_slope.h, in scenes/tiny.json:
 *   a) blades -> billboards: when the camera leaves, the recovering tile
 *      frees its slot and its slope cells equal the CPU twin
 *      (blade_tiles_pose, hybrid_slope_add / _resolve) of the slot's blades
 *      as read back just before;
 *   b) the billboards draw the cells: the far view with the cells differs
 *      from the same frame with the cells switched off;
 *   c) billboards -> blades: when the camera comes back the tile takes a
 *      slot seeded from the cells and the deformed billboards of the moment
 *      (sums captured from the source callback); every seeded blade, after
 *      the update's one physics step, equals the CPU twin
 *      (hybrid_slope_apply, blade_ref_validate, blade_ref_step_one), no NaN;
 *   d) the blades of the trail's cells are still pressed down after coming
 *      back, against their undisturbed pose.
 * With keep_state (no hand-over) the tile would keep its slot instead. */
#include "measure/measure.h"
#include "world/world_harness.h"
#include "eval/eval.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <string.h>

static hybrid_slope_sum_t *g_bb_sums;
static int g_source_calls;

/* The world's source (bb_field_add_slopes), then a blocking copy of the
 * sums for the CPU twin of the seeding. */
static void capture_source(void *user, const hybrid_slope_grid_t *grid, gfx_buffer_t sums)
{
    world_t *w = user;
    bb_field_add_slopes(measure_drivers(w).billboards, grid, sums);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_buffer_read(sums, 0, (size_t)grid->nx * grid->nz * sizeof(hybrid_slope_sum_t), g_bb_sums);
    g_source_calls++;
}

/* Tip height along up over blade height. */
static double up_height(const blade_t *b)
{
    float d[3] = {b->v2[0] - b->v0[0], b->v2[1] - b->v0[1], b->v2[2] - b->v0[2]};
    return (d[0] * b->up[0] + d[1] * b->up[1] + d[2] * b->up[2]) / b->v1[3];
}

/* Mean tip height over blade height of a slot's real blades. */
static double mean_height(world_t *w, int slot)
{
    blade_tiles_t *bt = measure_drivers(w).tiles;
    uint32_t B = blade_tiles_info(bt).template_blades;
    blade_t *b = malloc(B * sizeof *b);
    blade_tiles_read_slot(bt, slot, b, NULL);
    double sum = 0;
    int n = 0;
    for (uint32_t i = 0; i < B; i++) {
        if (b[i].v1[3] <= 0.0f) continue;
        float d[3] = {b[i].v2[0] - b[i].v0[0], b[i].v2[1] - b[i].v0[1], b[i].v2[2] - b[i].v0[2]};
        sum += (d[0] * b[i].up[0] + d[1] * b[i].up[1] + d[2] * b[i].up[2]) / b[i].v1[3];
        n++;
    }
    free(b);
    return n ? sum / n : 1.0;
}

static void run(world_t *w, int *frame, int count, const float cam[3])
{
    for (int i = 0; i < count; i++, (*frame)++) {
        world_set_camera(w, cam);
        world_update(w, (float)(*frame + 1) / 60.0f, 1.0f / 60.0f);
    }
}

/* A heavy ball rolls once along z = 0.5 through the tile at (1, 0.5),
 * then leaves the field. */
static void ball_once(scene_desc_t *s, void *user)
{
    (void)user;
    scene_path_t *p = &s->colliders[0].path;
    p->count = 3;
    p->keys[0] = (scene_path_key_t){0.0f, {-3.5f, 0.3f, 0.5f}};
    p->keys[1] = (scene_path_key_t){1.5f, {3.5f, 0.3f, 0.5f}};
    p->keys[2] = (scene_path_key_t){1.6f, {30.0f, 0.3f, 30.0f}};
}

static void unit(const float a[3], const float b[3], float out[3])
{
    float d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
    float l = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (int c = 0; c < 3; c++) out[c] = l > 1e-6f ? d[c] / l : 0.0f;
}

#define CHANGE_LEVELS 24

/* Pixels whose largest channel difference exceeds CHANGE_LEVELS. */
static int changed_pixels(const core_image_t *a, const core_image_t *b)
{
    int n = 0;
    for (int i = 0; i < a->w * a->h; i++) {
        int worst = 0;
        for (int c = 0; c < a->channels && c < 3; c++) {
            int d = abs(a->px[i * a->channels + c] - b->px[i * b->channels + c]);
            worst = d > worst ? d : worst;
        }
        n += worst > CHANGE_LEVELS;
    }
    return n;
}

static core_image_t render(world_t *w, gfx_target_t *t, float time)
{
    cam_t cam = {.position = {1.0f, 2.5f, 7.5f}, .target = {1.0f, 0.0f, 0.5f}, .fov = 50.0f};
    cam_defaults(&cam);
    grass_view_t v;
    world_view_make(&v, &cam, t->w, t->h, time, 1.0f / 60.0f);
    gfx_target_bind(t);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    world_draw(w, &v, t);
    core_image_t img = {0};
    CHECK(gfx_target_read(t, &img));
    return img;
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    world_t *w;
    CHECK(world_load(&(world_options_t){.scene = "scenes/tiny.json", .mode = SCENE_MODE_HYBRID, .mode_set = true},
                     &w) == 0);
    CHECK(world_setup(w, &(world_setup_t){.tweak = ball_once}));
    CHECK(world_make_gpu(w));
    CHECK(measure_drivers(w).tiles);
    blade_tiles_t *bt = measure_drivers(w).tiles;
    blade_tiles_info_t bi = blade_tiles_info(bt);
    const hybrid_slope_grid_t *sg = &bi.slope_grid;
    size_t ncells = (size_t)sg->nx * sg->nz;
    g_bb_sums = calloc(ncells, sizeof *g_bb_sums);
    blade_tiles_set_slope_source(bt, capture_source, w);
    int tile = hybrid_tile_at(bi.grid, 1.0f, 0.5f);
    CHECK(tile >= 0);
    /* near: the tile is blades; far (xz 5.5 m from the tile, switch 4 m,
     * hysteresis 1 m): billboards */
    const float near_cam[3] = {1.0f, 1.5f, 2.0f}, far_cam[3] = {1.0f, 2.5f, 7.5f};
    int frame = 0;
    run(w, &frame, 100, near_cam); /* the ball passes */
    const hybrid_tile_t *t = &bi.grid->tiles[tile];
    CHECK(t->rep == HYBRID_REP_BLADE);
    CHECK(t->state == HYBRID_RECOVERING && t->slot >= 0);
    int slot = t->slot;
    double pressed = mean_height(w, slot);
    uint32_t B = bi.template_blades;
    blade_t *before = malloc(B * sizeof *before), *seeded = malloc(B * sizeof *seeded);
    float *eta = malloc(B * sizeof *eta), *eta_seeded = malloc(B * sizeof *eta_seeded);
    blade_tiles_read_slot(bt, slot, before, eta);

    /* a) blades -> billboards */
    run(w, &frame, 1, far_cam);
    bi = blade_tiles_info(bt);
    CHECK(t->rep == HYBRID_REP_BILLBOARD);
    CHECK_MSG(t->slot < 0 && t->state == HYBRID_IDLE, "slot %d state %d after the hand-over", t->slot, t->state);
    CHECK(blade_tiles_stats(bt, false).handovers >= 1);
    hybrid_slope_sum_t *sums = calloc(ncells, sizeof *sums);
    for (uint32_t k = 0; k < B; k++) {
        if (before[k].v1[3] <= 0.0f) continue;
        blade_t pose;
        blade_tiles_pose(bt, tile, k, &pose);
        float d[3], dp[3], off[2];
        unit(before[k].v2, before[k].v0, d);
        unit(pose.v2, pose.v0, dp);
        hybrid_slope_offset(d, dp, off);
        int c = hybrid_slope_cell_at(sg, before[k].v0[0], before[k].v0[2]);
        CHECK(c >= 0);
        hybrid_slope_add(&sums[c], off, eta[k]);
    }
    hybrid_slope_cell_t *cells = malloc(ncells * sizeof *cells);
    blade_tiles_read_slopes(bt, cells);
    int cpt = bi.desc.slope_cells_per_tile, ti = tile % bi.grid->nx, tj = tile / bi.grid->nx;
    double worst = 0, deepest = 0;
    int compared = 0;
    for (int j = 0; j < cpt; j++)
        for (int i = 0; i < cpt; i++) {
            int c = (tj * cpt + j) * sg->nx + ti * cpt + i;
            hybrid_slope_cell_t ref = hybrid_slope_resolve(&sums[c], bi.time);
            CHECK_MSG(ref.count == cells[c].count, "cell %d: %g blades on the GPU, %g on the CPU", c, cells[c].count,
                      ref.count);
            double e = fmax(fmax(fabs(ref.t[0] - cells[c].t[0]), fabs(ref.t[1] - cells[c].t[1])),
                            fmax(fabs(ref.m - cells[c].m), fabs(ref.eta - cells[c].eta)));
            worst = fmax(worst, e);
            deepest = fmax(deepest, cells[c].m);
            CHECK_MSG(fabsf(cells[c].tau - bi.time) < 1e-6f, "cell %d written at %.7f s, hand-over at %.7f s", c,
                      cells[c].tau, bi.time);
            compared += ref.count > 0;
        }
    printf("a) hand-over: %d cells of tile %d, GPU vs CPU twin %.2g (mean |o| up to %.3f)\n", compared, tile, worst,
           deepest);
    CHECK(compared >= cpt * cpt / 2);
    CHECK(worst < 2e-3);
    CHECK(deepest > 0.1); /* the trail is in the cells: the test compares something */

    /* b) the billboards draw the cells */
    gfx_target_t target = gfx_target_make(&(gfx_target_desc_t){.w = 160, .h = 120, .samples = 4, .label = "trail"});
    float now = (float)frame / 60.0f;
    core_image_t with = render(w, &target, now);
    hybrid_slope_cell_t *none = calloc(ncells, sizeof *none);
    blade_tiles_read_slopes(bt, cells);
    blade_tiles_write_slopes(bt, none); /* the same frame without the cells */
    core_image_t without = render(w, &target, now);
    blade_tiles_write_slopes(bt, cells);
    free(none);
    double mad = eval_image_mad(&with, &without);
    int changed = changed_pixels(&with, &without);
    printf("b) far view with vs without the slope cells: %d pixels changed by > %d levels, mean abs difference "
           "%.4f\n",
           changed, CHANGE_LEVELS, mad);
    CHECK(changed >= 20);
    core_image_free(&with);
    core_image_free(&without);
    gfx_target_destroy(&target);

    /* c) billboards -> blades */
    run(w, &frame, 19, far_cam);
    CHECK(t->rep == HYBRID_REP_BILLBOARD && t->slot < 0);
    blade_tiles_read_slopes(bt, cells);
    int calls = g_source_calls;
    run(w, &frame, 1, near_cam);
    bi = blade_tiles_info(bt);
    CHECK(t->rep == HYBRID_REP_BLADE);
    CHECK_MSG(t->slot >= 0 && t->state == HYBRID_RECOVERING, "slot %d state %d after coming back", t->slot,
              t->state);
    CHECK(blade_tiles_stats(bt, false).seeded >= 1 && g_source_calls == calls + 1);
    blade_tiles_read_slot(bt, t->slot, seeded, eta_seeded);
    blade_env_t env = blade_env_defaults(&bi.env);
    double v2_err = 0, eta_err = 0;
    int moved = 0;
    bool finite = true;
    for (uint32_t k = 0; k < B; k++) {
        blade_t ref;
        blade_tiles_pose(bt, tile, k, &ref);
        float eta_ref = 0.0f;
        int c = hybrid_slope_cell_at(sg, ref.v0[0], ref.v0[2]);
        if (ref.v1[3] > 0.0f && c >= 0) {
            hybrid_slope_cell_t m = cells[c];
            float wgt = m.count > 0 ? hybrid_slope_weight(bi.time - m.tau, bi.desc.slope_recover) : 0.0f;
            hybrid_slope_cell_t use = m;
            float eta0 = m.eta;
            if (g_bb_sums[c].count > 0) {
                hybrid_slope_cell_t bb = hybrid_slope_resolve(&g_bb_sums[c], 0.0f);
                if (bb.m > wgt * m.m) use = bb, wgt = 1.0f, eta0 = 0.0f;
            }
            float a = ref.v0[3], up[3] = {ref.up[0], ref.up[1], ref.up[2]};
            float dd[3] = {cosf(a), 0.0f, sinf(a)}, dot = dd[0] * up[0] + dd[1] * up[1] + dd[2] * up[2];
            float wd[3] = {dd[0] - up[0] * dot, dd[1] - up[1] * dot, dd[2] - up[2] * dot};
            float front[3] = {up[1] * wd[2] - up[2] * wd[1], up[2] * wd[0] - up[0] * wd[2],
                              up[0] * wd[1] - up[1] * wd[0]};
            float fl = sqrtf(front[0] * front[0] + front[2] * front[2]);
            float f[2] = {fl > 1e-6f ? front[0] / fl : 1.0f, fl > 1e-6f ? front[2] / fl : 0.0f};
            float dir[3], nd[3], len;
            unit(ref.v2, ref.v0, dir);
            len = sqrtf((ref.v2[0] - ref.v0[0]) * (ref.v2[0] - ref.v0[0]) +
                        (ref.v2[1] - ref.v0[1]) * (ref.v2[1] - ref.v0[1]) +
                        (ref.v2[2] - ref.v0[2]) * (ref.v2[2] - ref.v0[2]));
            hybrid_slope_apply(dir, f, &use, wgt, nd);
            for (int q = 0; q < 3; q++) ref.v2[q] = ref.v0[q] + len * nd[q];
            blade_ref_validate(&ref, measure_drivers(w).blade_env->length_mode);
            eta_ref = wgt * eta0;
            moved += wgt * use.m > 0.05f;
        }
        blade_ref_step_one(&ref, &eta_ref, &env, NULL); /* the ball is gone; the update simulates the new slot once */
        for (int q = 0; q < 3; q++) {
            v2_err = fmax(v2_err, fabs(ref.v2[q] - seeded[k].v2[q]));
            finite = finite && isfinite(seeded[k].v2[q]) && isfinite(seeded[k].v1[q]);
        }
        eta_err = fmax(eta_err, fabs(eta_ref - eta_seeded[k]));
    }
    printf("c) seeding: %u blades, %d bent by the cells, v2 GPU vs CPU twin %.2g m, eta %.2g\n", B, moved, v2_err,
           eta_err);
    CHECK(finite);
    CHECK(moved > 0);
    CHECK(v2_err < 2e-3);
    CHECK(eta_err < 1e-4);

    /* d) still pressed after coming back: blades of the cells the trail
     * crossed (mean |o| > 0.3 at the hand-over) against their undisturbed
     * pose at the same time */
    run(w, &frame, 4, near_cam);
    blade_tiles_read_slot(bt, t->slot, seeded, NULL);
    double h_before = 0, h_back = 0, h_pose = 0;
    int n_trail = 0;
    for (uint32_t k = 0; k < B; k++) {
        int c = hybrid_slope_cell_at(sg, before[k].v0[0], before[k].v0[2]);
        if (before[k].v1[3] <= 0.0f || c < 0 || cells[c].m <= 0.3f) continue;
        blade_t pose;
        blade_tiles_pose(bt, tile, k, &pose);
        h_before += up_height(&before[k]);
        h_back += up_height(&seeded[k]);
        h_pose += up_height(&pose);
        n_trail++;
    }
    CHECK(n_trail > 0);
    h_before /= n_trail, h_back /= n_trail, h_pose /= n_trail;
    printf("d) tile %d, %d trail blades: mean tip height / h after the pass %.3f, after away and back (0.42 s) "
           "%.3f, undisturbed pose %.3f; whole tile %.3f -> %.3f\n",
           tile, n_trail, h_before, h_back, h_pose, pressed, mean_height(w, t->slot));
    CHECK(h_before < h_pose - 0.2);
    CHECK(h_back < h_pose - 0.1);
    free(before);
    free(seeded);
    free(eta);
    free(eta_seeded);
    free(sums);
    free(cells);
    free(g_bb_sums);
    world_destroy(w);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

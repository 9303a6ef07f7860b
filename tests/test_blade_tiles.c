/* test_blade_tiles: the tiled blade field (Fan et al. 2015 activation over
 * Jahrmann & Wimmer 2017 blades, src/blade/blade_tiles.h) on small fields:
 *   a) no pop: the blades of an idle tile as drawn from the templates
 *      (procedural pose, read back from the draw buffer) equal the slot
 *      state right after activation; roots equal the CPU twin and
 *      terrain_height_at; the procedural pose is a fixed point of the
 *      physics under static wind (a slot left alone for 1 s barely moves);
 *   b) physics only on active slots: pool slots outside the dispatch list
 *      keep their bytes; a dispatched slot equals blade_ref_step (eq. 3-13)
 *      with ALL spheres (so the per-tile sphere lists lose nothing); the
 *      slots dispatched per frame are the same for a 16 m and a 64 m
 *      field (16x the tiles) with the same ball;
 *   c) a ball crossing tiles: ACTIVE exactly where the brute-force
 *      hybrid test (spheres grown by the blade reach) says; released by
 *      measured motion before the timeout; a 2-slot pool reports
 *      exhaustion;
 *   d) over the run: no NaN, v0 bit-identical since activation, curve
 *      length within 2% of the height (the ball is swept: each step's
 *      sphere carries its travel, in the GPU and the CPU step alike);
 *   e) swept collision: a ball moving 1.5 m per step (5 diameters, 90 m/s
 *      at 60 Hz) bends at least 90 % of the blades along its path at some
 *      step;
 *   f) distance thinning keeps coverage (blade_lod.h, the WIDTH rule from
 *      2 m, no end fade, as the hybrid draws them): with the distance test
 *      on, every drawn blade is a survivor of blade_ref_cull_one and is
 *      drawn its width factor times its pose's width; per 2 m ring of the
 *      tiles' distance (the eye distance) the drawn blades' summed width is
 *      within 10 % of all the blades' (thinning alone leaves a quarter of
 *      it in the last ring);
 *   g) the orientation test of widened blades: with it and the distance
 *      test on, the drawn blades of every listed tile are exactly those
 *      the CPU keeps (distance survivors of blade_ref_cull_one whose
 *      |dir_c . dir_b| is within blade_ref_lod_orientation of the
 *      threshold and their width factor), and some of them the plain
 *      threshold would have culled;
 *   h) the hardware path's draw lists: the tile list goes nearest first
 *      (core_box_dist2 nondecreasing), and a cull split at the fade start
 *      draws the same blades as one without (same ids) in two lists: roots
 *      up to the fade start first (the opaque draw), farther ones after
 *      (the fade's draw), both non-empty;
 *   i) occlusion: a wall in the depth texture (its left half at the depth
 *      of a point 6 m ahead of the camera) hides part of the field; with
 *      frustum, distance and occlusion tests on, the drawn blades are
 *      those blade_ref_cull_one keeps with the same depth (as NDC), the
 *      per-test counts equal the CPU's, and the counts add up: survivors +
 *      culled + the blades of tiles the CPU frustum test dropped = the
 *      blade tiles' blades. Without the depth texture exactly the occluded
 *      blades come back (so the test fails if the occlusion test is
 *      missing). */
#include "blade/blade_tiles.h"
#include "collide_test_util.h"
#include "terrain_test_util.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>

#define B_MAX 1024

static terrain_mesh_t make_terrain(float size, int res, bool flat)
{
    terrain_mesh_t m;
    CHECK(terrain_make_heightfield(&m, &(terrain_desc_t){.size = size, .resolution = res, .height = 0.4f}, 7));
    if (flat) test_terrain_flatten(&m);
    return m;
}

static blade_tiles_desc_t tiles_desc(const terrain_mesh_t *m, int pool, float speed)
{
    blade_tiles_desc_t d = {
        .terrain = m,
        .tile_size = 2.0f,
        .population = {.density = 64.0f, .height = {0.3f, 0.5f}, .width = {0.02f, 0.03f}, .stiffness = {8.0f, 12.0f}},
        .seed = 3,
        .pool_slots = pool,
        .switch_distance = 12.0f,
        .cull = {.disable = BLADE_CULL_ORIENTATION | BLADE_CULL_FRUSTUM | BLADE_CULL_DISTANCE}};
    d.winds[0] = blade_wind_wave(1.0f, 0.4f, 1.5f, 6.0f, speed);
    d.wind_count = 1;
    return d;
}

static blade_tiles_t *make_tiles(const terrain_mesh_t *m, int pool, float speed)
{
    blade_tiles_desc_t d = tiles_desc(m, pool, speed);
    return blade_tiles_make(&d);
}

static blade_env_t make_env(float time, float dt)
{
    return (blade_env_t){.dt = dt, .time = time, .gravity = 1.0f};
}

/* The test camera at cam looking at the origin. */
static void view_proj(const float cam[3], mat4 vp)
{
    mat4 view, proj;
    glm_lookat((float *)cam, (vec3){0, 0, 0}, (vec3){0, 1, 0}, view);
    glm_perspective(glm_rad(60.0f), 1.0f, 0.05f, 100.0f, proj);
    glm_mat4_mul(proj, view, vp);
}

static void draw_occluded(blade_tiles_t *t, const float cam[3], float fade_start, float fade_end, GLuint depth)
{
    blade_draw_desc_t dd = {.fade_start = fade_start, .fade_end = fade_end};
    mat4 vp;
    view_proj(cam, vp);
    memcpy(dd.view.viewproj, vp, sizeof vp);
    memcpy(dd.view.camera, cam, sizeof dd.view.camera);
    blade_tiles_draw(t, &dd, depth);
}

static void draw_faded(blade_tiles_t *t, const float cam[3], float fade_start, float fade_end)
{
    draw_occluded(t, cam, fade_start, fade_end, 0);
}

static void draw_all(blade_tiles_t *t, const float cam[3]) { draw_faded(t, cam, 0.0f, 0.0f); }

static float dist3(const float *a, const float *b)
{
    float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrtf(dx * dx + dy * dy + dz * dz);
}

/* ---- a) ------------------------------------------------------------------ */
static void test_no_pop(void)
{
    terrain_mesh_t m = make_terrain(16.0f, 32, false);
    blade_tiles_t *t = make_tiles(&m, 8, 0.0f);
    CHECK(t);
    blade_tiles_info_t ti = blade_tiles_info(t);
    uint32_t B = ti.template_blades;
    CHECK(B == 256);
    int tile = hybrid_tile_at(ti.grid, 1.0f, 1.0f);
    const float cam[3] = {1.0f, 3.0f, 6.0f};
    blade_env_t env = make_env(1.0f, 1.0f / 60.0f);
    blade_tiles_update(t, cam, NULL, &env);
    draw_all(t, cam);
    blade_t *drawn = malloc(ti.draw_capacity * sizeof *drawn);
    uint32_t *ids = malloc(ti.draw_capacity * sizeof *ids);
    blade_t idle[B_MAX], slot_b[B_MAX], again[B_MAX];
    memset(idle, 0, sizeof idle);
    uint32_t n = blade_tiles_read_drawn(t, drawn, ids), found = 0;
    for (uint32_t i = 0; i < n; i++)
        if (ids[i] / B == (uint32_t)tile) idle[ids[i] % B] = drawn[i], found++;
    CHECK_MSG(found == 64 * 4, "tile %d drew %u blades (expected the 256 of the template)", tile, found);

    /* roots: GPU placement = CPU twin = terrain_height_at */
    int tmpl, sym;
    blade_tiles_instance(t, tile, &tmpl, &sym);
    blade_t template_b[B_MAX];
    blade_tiles_read_template(t, tmpl, template_b);
    float worst_root = 0, worst_ground = 0, bend = 0;
    for (uint32_t k = 0; k < B; k++) {
        const blade_t *tb = &template_b[k];
        if (tb->v1[3] <= 0) continue;
        float root[3], up[3];
        blade_tiles_root(t, tile, (float[2]){tb->v0[0], tb->v0[2]}, root, up);
        worst_root = fmaxf(worst_root, dist3(root, idle[k].v0));
        worst_ground = fmaxf(worst_ground, fabsf(terrain_height_at(&m, root[0], root[2], NULL) - root[1]));
        float rest[3] = {idle[k].v0[0] + idle[k].up[0] * idle[k].v1[3], idle[k].v0[1] + idle[k].up[1] * idle[k].v1[3],
                         idle[k].v0[2] + idle[k].up[2] * idle[k].v1[3]};
        bend += dist3(rest, idle[k].v2) / (float)found;
    }
    printf("a) roots: GPU vs CPU twin %.2g m, vs terrain_height_at %.2g m; mean tip bend of the pose %.3f m\n",
           worst_root, worst_ground, bend);
    CHECK(worst_root < 1e-5f);
    CHECK(worst_ground < 1e-5f);
    CHECK(bend > 0.01f); /* the pose is not the rest pose: the test compares something */

    /* activate the tile with a sphere above its blades (touches the grown
     * bound, not the blades): init + one step at the same time */
    float top = m.aabb_max[1] + ti.reach;
    const float ball[1][4] = {{1.0f, top + 0.4f, 1.0f, 0.1f}};
    blade_tiles_update(t, cam, test_sphere_set(ball, 1), &env);
    blade_tiles_stats_t st = blade_tiles_stats(t, true);
    CHECK(st.active == 1 && st.slots_used == 1);
    int slot = ti.grid->tiles[tile].slot;
    CHECK(slot >= 0);
    blade_tiles_read_slot(t, slot, slot_b, NULL);
    draw_all(t, cam);
    n = blade_tiles_read_drawn(t, drawn, ids);
    for (uint32_t i = 0; i < n; i++)
        if (ids[i] / B == (uint32_t)tile) again[ids[i] % B] = drawn[i];
    float pop = 0, pop_drawn = 0;
    for (uint32_t k = 0; k < B; k++) {
        if (idle[k].v1[3] <= 0) continue;
        for (int c = 0; c < 3; c++) {
            pop = fmaxf(pop, dist3(&idle[k].v0[0] + 4 * c, &slot_b[k].v0[0] + 4 * c));
            pop_drawn = fmaxf(pop_drawn, dist3(&idle[k].v0[0] + 4 * c, &again[k].v0[0] + 4 * c));
        }
    }
    printf("a) pop at activation: idle drawn vs slot %.2g m, vs drawn from the slot %.2g m\n", pop, pop_drawn);
    CHECK(pop < 5e-5f);
    CHECK(pop_drawn < 5e-5f);

    /* fixed point: 60 steps of 1/60 s under the static wind */
    env.dt = 1.0f / 60.0f;
    for (int f = 0; f < 60; f++) {
        env.time += env.dt;
        blade_tiles_update(t, cam, test_sphere_set(ball, 1), &env);
    }
    blade_t later[B_MAX];
    blade_tiles_read_slot(t, slot, later, NULL);
    float drift = 0;
    for (uint32_t k = 0; k < B; k++)
        if (slot_b[k].v1[3] > 0) drift = fmaxf(drift, dist3(slot_b[k].v2, later[k].v2));
    printf("a) a slot left alone for 1 s under static wind moved its tips by at most %.2g m\n", drift);
    CHECK(drift < 2e-4f);
    free(drawn);
    free(ids);
    blade_tiles_destroy(t);
    terrain_free(&m);
}

/* ---- b, c, d: a ball through the field -------------------------------------- */
#define BALL_FRAMES 300
#define RUN_FRAMES 700

typedef struct run_t {
    int dispatched[RUN_FRAMES];
    int max_active, releases, timeouts;
    float worst_ref, worst_len;
    int ref_over, ref_blades, frozen_checked;
    bool nan, v0_moved, idle_written, active_mismatch;
} run_t;

static void ball_at(int f, float out[4])
{
    float x = -5.0f + 10.0f * (float)f / (float)BALL_FRAMES;
    out[0] = x, out[1] = 0.3f, out[2] = 0.5f, out[3] = 0.45f;
}

static void run_ball(float size, int res, run_t *r, bool check_ref)
{
    memset(r, 0, sizeof *r);
    terrain_mesh_t m = make_terrain(size, res, true);
    blade_tiles_t *t = make_tiles(&m, 16, 0.0f);
    CHECK(t);
    blade_tiles_info_t ti = blade_tiles_info(t);
    uint32_t B = ti.template_blades;
    int S = ti.desc.pool_slots, ntiles = ti.grid->nx * ti.grid->nz;
    size_t pool_n = (size_t)S * B;
    blade_t *before = malloc(pool_n * sizeof *before), *after = malloc(pool_n * sizeof *after);
    float *eta_before = malloc(pool_n * sizeof(float)), *eta_gpu = malloc(B * sizeof(float));
    blade_t *v0_at = malloc(pool_n * sizeof *v0_at);
    int *v0_owner = malloc((size_t)S * sizeof(int));
    int *recover_start = malloc((size_t)ntiles * sizeof(int));
    for (int s = 0; s < S; s++) v0_owner[s] = -1;
    for (int i = 0; i < ntiles; i++) recover_start[i] = -1;
    const float cam[3] = {0.0f, 3.0f, 6.0f};
    for (int f = 0; f < RUN_FRAMES; f++) {
        blade_env_t env = make_env((float)f / 60.0f, 1.0f / 60.0f);
        float ball[1][4], prev[4], sweep[1][3];
        ball_at(f, ball[0]);
        ball_at(f > 0 ? f - 1 : 0, prev);
        for (int k = 0; k < 3; k++) sweep[0][k] = prev[k] - ball[0][k];
        int nb = f < BALL_FRAMES ? 1 : 0;
        bool probe = f % 10 == 5;
        int owner_before[64];
        if (probe) {
            blade_tiles_read_pool(t, before);
            for (int s = 0; s < S; s++) {
                owner_before[s] = blade_tiles_slot_owner(t, s);
                blade_tiles_read_slot(t, s, NULL, &eta_before[(size_t)s * B]);
            }
        }
        blade_tiles_update(t, cam, test_swept_set((const float (*)[4])ball, (const float (*)[3])sweep, nb), &env);
        blade_tiles_stats_t st = blade_tiles_stats(t, false);
        r->dispatched[f] = st.slots_dispatched;
        r->max_active = st.active > r->max_active ? st.active : r->max_active;
        /* c) activation = brute force on the grown spheres (the bounding
         * sphere of the swept ball's capsule) */
        hybrid_object_t obj = {{ball[0][0] + 0.5f * sweep[0][0], ball[0][1] + 0.5f * sweep[0][1],
                                ball[0][2] + 0.5f * sweep[0][2],
                                ball[0][3] + 0.5f * sqrtf(sweep[0][0] * sweep[0][0] + sweep[0][1] * sweep[0][1] +
                                                          sweep[0][2] * sweep[0][2]) +
                                    ti.reach}};
        int live = 0;
        for (int i = 0; i < ntiles; i++) {
            const hybrid_tile_t *tl = &ti.grid->tiles[i];
            bool touched = nb && hybrid_tile_touched_brute(ti.grid, i, &obj, 1);
            if ((tl->state == HYBRID_ACTIVE) != touched) r->active_mismatch = true;
            if ((tl->slot >= 0) != (tl->state != HYBRID_IDLE)) r->active_mismatch = true;
            live += tl->slot >= 0;
            if (tl->state == HYBRID_RECOVERING && recover_start[i] < 0) recover_start[i] = f;
            if (tl->state != HYBRID_RECOVERING && recover_start[i] >= 0) {
                if (tl->state == HYBRID_IDLE) {
                    r->releases++;
                    if (f - recover_start[i] >= 60 * 5) r->timeouts++;
                }
                recover_start[i] = -1;
            }
        }
        if (live != st.slots_dispatched) r->active_mismatch = true;
        if (!probe) continue;
        blade_tiles_read_pool(t, after);
        for (int s = 0; s < S; s++) {
            int o = blade_tiles_slot_owner(t, s);
            blade_t *a = &after[(size_t)s * B], *b = &before[(size_t)s * B];
            if (o < 0) {
                /* b) free slots are never written */
                if (memcmp(a, b, B * sizeof *a) != 0) r->idle_written = true;
                v0_owner[s] = -1;
                continue;
            }
            /* d) invariants */
            if (v0_owner[s] != o) {
                memcpy(&v0_at[(size_t)s * B], a, B * sizeof *a);
                v0_owner[s] = o;
            }
            for (uint32_t k = 0; k < B; k++) {
                if (a[k].v1[3] <= 0) continue;
                for (int c = 0; c < 16; c++)
                    if (!isfinite((&a[k].v0[0])[c])) r->nan = true;
                if (memcmp(a[k].v0, v0_at[(size_t)s * B + k].v0, sizeof a[k].v0) != 0) r->v0_moved = true;
                float len = blade_ref_curve_length(&a[k], 64);
                r->worst_len = fmaxf(r->worst_len, fabsf(len - a[k].v1[3]) / a[k].v1[3]);
            }
            r->frozen_checked++;
            /* b) the step of a slot that kept its tile equals the CPU
             * reference with every sphere */
            if (!check_ref || owner_before[s] != o) continue;
            blade_env_t ce = env;
            ce.winds[0] = blade_tiles_info(t).env.winds[0];
            ce.wind_count = 1;
            float *eta = &eta_before[(size_t)s * B];
            blade_ref_step(b, eta, B, &ce, test_swept_set((const float (*)[4])ball, (const float (*)[3])sweep, nb));
            blade_tiles_read_slot(t, s, NULL, eta_gpu);
            for (uint32_t k = 0; k < B; k++) {
                if (b[k].v1[3] <= 0) continue;
                float d = fmaxf(dist3(b[k].v2, a[k].v2), dist3(b[k].v1, a[k].v1));
                d = fmaxf(d, fabsf(eta[k] - eta_gpu[k]));
                r->ref_blades++;
                if (d > 1e-4f) r->ref_over++;
                else r->worst_ref = fmaxf(r->worst_ref, d);
            }
        }
    }
    free(before);
    free(after);
    free(eta_before);
    free(eta_gpu);
    free(v0_at);
    free(v0_owner);
    free(recover_start);
    blade_tiles_destroy(t);
    terrain_free(&m);
}

static void test_ball(void)
{
    static run_t small, large;
    run_ball(16.0f, 32, &small, true);
    run_ball(64.0f, 128, &large, false);
    printf("b) CPU reference vs GPU slots: %d blade steps, worst %.2g m, %d over 1e-4 m\n", small.ref_blades,
           small.worst_ref, small.ref_over);
    CHECK(small.ref_blades > 1000);
    CHECK(small.worst_ref < 2e-5f);
    CHECK(small.ref_over * 200 <= small.ref_blades); /* branch-boundary blades (fma contraction) */
    CHECK(!small.idle_written && !large.idle_written);
    int same = 0, peak = 0, total_s = 0, total_l = 0;
    for (int f = 0; f < RUN_FRAMES; f++) {
        same += small.dispatched[f] == large.dispatched[f];
        peak = small.dispatched[f] > peak ? small.dispatched[f] : peak;
        total_s += small.dispatched[f];
        total_l += large.dispatched[f];
    }
    printf("b) slots dispatched, 16 m (64 tiles) vs 64 m (1024 tiles): peak %d, total %d vs %d, %d/%d frames "
           "equal\n",
           peak, total_s, total_l, same, RUN_FRAMES);
    /* Releases follow the measured motion, read back 1-2 frames late
     * whenever the copy is ready: on llvmpipe every frame matches, on an
     * H100 a release can land a frame earlier or later. The work must
     * still be the same to within that jitter. */
    CHECK(same >= RUN_FRAMES * 9 / 10);
    CHECK(abs(total_s - total_l) * 20 <= total_s);
    CHECK(peak >= 4 && peak <= 8);
    printf("c) max active %d, releases %d (by timeout %d), activation mismatches: %s\n", small.max_active,
           small.releases, small.timeouts, small.active_mismatch || large.active_mismatch ? "yes" : "none");
    CHECK(!small.active_mismatch && !large.active_mismatch);
    CHECK(small.releases >= 5 && small.timeouts == 0);
    CHECK(small.dispatched[RUN_FRAMES - 1] == 0);
    printf("d) %d slot checks: NaN %s, v0 moved %s, worst |len - h| / h %.4f\n", small.frozen_checked,
           small.nan ? "yes" : "no", small.v0_moved ? "yes" : "no", small.worst_len);
    CHECK(!small.nan && !small.v0_moved && small.frozen_checked > 50);
    CHECK(small.worst_len < 0.02f);
}

/* ---- e) ------------------------------------------------------------------ */
#define FAST_STEPS 9
#define FAST_STEP 1.5f

static void test_fast_ball(void)
{
    terrain_mesh_t m = make_terrain(16.0f, 32, true);
    blade_tiles_desc_t d = {
        .terrain = &m,
        .tile_size = 2.0f,
        .population = {.density = 64.0f, .height = {0.3f, 0.5f}, .width = {0.02f, 0.03f}, .stiffness = {8.0f, 12.0f}},
        .seed = 3,
        .pool_slots = 64,
        .switch_distance = 12.0f,
        .cull = {.disable = BLADE_CULL_ORIENTATION | BLADE_CULL_FRUSTUM | BLADE_CULL_DISTANCE}};
    blade_tiles_t *t = blade_tiles_make(&d); /* no wind */
    CHECK(t);
    blade_tiles_info_t ti = blade_tiles_info(t);
    uint32_t B = ti.template_blades;
    int S = ti.desc.pool_slots, ntiles = ti.grid->nx * ti.grid->nz;
    blade_t *pool = malloc((size_t)S * B * sizeof *pool);
    unsigned char *bent = calloc((size_t)ntiles * B, 1), *path = calloc((size_t)ntiles * B, 1);
    float from = -6.0f, z = 0.5f;
    for (int f = 0; f < FAST_STEPS; f++) {
        blade_env_t env = {.dt = 1.0f / 60.0f, .time = (float)f / 60.0f, .gravity_off = true};
        const float ball[1][4] = {{from + FAST_STEP * (float)f, 0.3f, z, 0.3f}};
        const float sweep[1][3] = {{f > 0 ? -FAST_STEP : 0.0f, 0.0f, 0.0f}};
        blade_tiles_update(t, (float[3]){0, 3, 6}, test_swept_set(ball, sweep, 1), &env);
        blade_tiles_read_pool(t, pool);
        for (int s = 0; s < S; s++) {
            int o = blade_tiles_slot_owner(t, s);
            for (uint32_t k = 0; o >= 0 && k < B; k++) {
                const blade_t *b = &pool[(size_t)s * B + k];
                float h = b->v1[3];
                if (h <= 0.0f) continue;
                size_t id = (size_t)o * B + k;
                path[id] = b->v0[0] > from + 0.3f && b->v0[0] < -from - 0.3f && fabsf(b->v0[2] - z) < 0.15f;
                float rest[3] = {b->v0[0] + b->up[0] * h, b->v0[1] + b->up[1] * h, b->v0[2] + b->up[2] * h};
                if (dist3(b->v2, rest) > 0.2f * h) bent[id] = 1;
            }
        }
    }
    long on_path = 0, hit = 0;
    for (size_t i = 0; i < (size_t)ntiles * B; i++) {
        on_path += path[i];
        hit += path[i] && bent[i];
    }
    double coverage = on_path ? (double)hit / (double)on_path : 0.0;
    printf("e) ball r 0.3 m moving %.1f m per step: %ld of %ld blades on its path bent (%.3f)\n", FAST_STEP, hit,
           on_path, coverage);
    CHECK(on_path > 100);
    CHECK(coverage >= 0.9);
    free(pool);
    free(bent);
    free(path);
    blade_tiles_destroy(t);
    terrain_free(&m);
}

static void test_exhaustion(void)
{
    terrain_mesh_t m = make_terrain(16.0f, 32, true);
    blade_tiles_t *t = make_tiles(&m, 2, 0.0f);
    CHECK(t);
    int warns = core_log_warn_count();
    const float ball[1][4] = {{0.0f, 0.3f, 0.0f, 0.5f}}; /* on a tile corner: 4 tiles */
    blade_env_t env = make_env(0.0f, 1.0f / 60.0f);
    blade_tiles_update(t, (float[3]){0, 3, 6}, test_sphere_set(ball, 1), &env);
    blade_tiles_stats_t st = blade_tiles_stats(t, true);
    printf("c) pool of 2 slots, 4 tiles touched: active %d, slots %d/%d, denied %d, warnings %d\n", st.active,
           st.slots_used, st.slots_total, st.pool_denied, core_log_warn_count() - warns);
    CHECK(st.active == 2 && st.slots_used == 2 && st.pool_denied == 2);
    CHECK(core_log_warn_count() > warns);
    blade_tiles_destroy(t);
    terrain_free(&m);
}

/* The thinning of f), g) and i): from 2 m on (WIDTH), no end fade. */
static const blade_lod_t thin_lod = {.start = 2.0f, .width_px = 20.0f, .no_fade = true};

/* f) and g): a 16 m field of 2 m tiles, cut and thinned to 10 m (thin_lod),
 * the tests `disable` names off, drawn once from `cam`; the drawn blades
 * and their ids into *drawn and *ids (draw_capacity each), their count
 * returned. */
static uint32_t draw_thinned(blade_tiles_t **t, terrain_mesh_t *m, uint32_t disable, const float cam[3],
                             blade_t **drawn, uint32_t **ids)
{
    *m = make_terrain(16.0f, 32, true);
    *t = make_tiles(m, 8, 0.0f);
    CHECK(*t);
    blade_tiles_info_t ti = blade_tiles_info(*t);
    blade_cull_desc_t cull = ti.desc.cull;
    cull.disable = disable;
    cull.max_distance = 10.0f;
    cull.orientation_threshold = 0.9f;
    blade_tiles_set_cull(*t, &cull);
    blade_tiles_set_lod(*t, &thin_lod, 0.0f);
    blade_env_t env = make_env(1.0f, 1.0f / 60.0f);
    blade_tiles_update(*t, cam, NULL, &env);
    draw_all(*t, cam);
    *drawn = malloc(ti.draw_capacity * sizeof **drawn);
    *ids = malloc(ti.draw_capacity * sizeof **ids);
    return blade_tiles_read_drawn(*t, *drawn, *ids);
}

/* ---- f) ------------------------------------------------------------------ */
static void test_lod_width(void)
{
    terrain_mesh_t m;
    blade_tiles_t *t;
    const float cam[3] = {-7.5f, 2.0f, -7.5f};
    blade_t *drawn;
    uint32_t *ids;
    uint32_t n = draw_thinned(&t, &m, BLADE_CULL_ORIENTATION | BLADE_CULL_FRUSTUM, cam, &drawn, &ids);
    blade_tiles_info_t ti = blade_tiles_info(t);
    uint32_t B = ti.template_blades;
    blade_cull_desc_t cull = ti.desc.cull;
    memcpy(cull.view.camera, cam, sizeof cull.view.camera);
    enum { RINGS = 4 }; /* 2-4 .. 8-10 m: the camera is 2 m up */
    double all[RINGS] = {0}, kept[RINGS] = {0}, thin[RINGS] = {0};
    float worst = 0.0f;
    int not_survivor = 0;
    bool *listed = calloc((size_t)ti.grid->nx * (size_t)ti.grid->nz, sizeof *listed);
    for (uint32_t i = 0; i < n; i++) {
        blade_t pose;
        blade_tiles_pose(t, (int)(ids[i] / B), ids[i] % B, &pose);
        listed[ids[i] / B] = true;
        float factor = 0.0f;
        not_survivor += blade_ref_cull_one(&pose, ids[i] % B, &cull, &factor) != BLADE_CULL_VISIBLE;
        float d = blade_ref_cull_distance(&pose, &cull);
        float want = pose.v2[3] * factor;
        worst = fmaxf(worst, fabsf(drawn[i].v2[3] - want) / want);
        int r = (int)(d / 2.0f) - 1;
        if (r >= 0 && r < RINGS) kept[r] += drawn[i].v2[3], thin[r] += pose.v2[3];
    }
    /* every blade of the tiles that were drawn, as if nothing were thinned */
    for (int tile = 0; tile < ti.grid->nx * ti.grid->nz; tile++) {
        if (!listed[tile]) continue;
        for (uint32_t k = 0; k < B; k++) {
            blade_t pose;
            blade_tiles_pose(t, tile, k, &pose);
            if (pose.v1[3] <= 0.0f) continue;
            int r = (int)(blade_ref_cull_distance(&pose, &cull) / 2.0f) - 1;
            if (r >= 0 && r < RINGS) all[r] += pose.v2[3];
        }
    }
    printf("f) %u blades drawn, %d not survivors of the CPU cull, width vs CPU twin worst %.2g (relative)\n", n,
           not_survivor, worst);
    CHECK(n > 0 && not_survivor == 0);
    CHECK(worst < 1e-4f);
    for (int r = 0; r < RINGS; r++) {
        printf("f) distance %d-%d m: drawn width / all blades' width %.3f (unwidened %.3f)\n", 2 * r + 2,
               2 * r + 4, kept[r] / all[r], thin[r] / all[r]);
        CHECK(all[r] > 0.0 && fabs(kept[r] / all[r] - 1.0) < 0.1);
    }
    CHECK(thin[RINGS - 1] / all[RINGS - 1] < 0.5); /* the last ring is thinned: the test compares something */
    free(listed);
    free(drawn);
    free(ids);
    blade_tiles_destroy(t);
    terrain_free(&m);
}

/* ---- g) ------------------------------------------------------------------ */
static void test_lod_orientation(void)
{
    terrain_mesh_t m;
    blade_tiles_t *t;
    const float cam[3] = {-7.5f, 2.0f, -7.5f};
    blade_t *drawn;
    uint32_t *ids;
    uint32_t n = draw_thinned(&t, &m, BLADE_CULL_FRUSTUM, cam, &drawn, &ids);
    blade_tiles_info_t ti = blade_tiles_info(t);
    uint32_t B = ti.template_blades;
    int tiles = ti.grid->nx * ti.grid->nz;
    int *gpu = calloc((size_t)tiles, sizeof *gpu);
    for (uint32_t i = 0; i < n; i++) gpu[ids[i] / B]++;
    blade_cull_desc_t cull = ti.desc.cull;
    cull.disable = BLADE_CULL_FRUSTUM | BLADE_CULL_ORIENTATION;
    memcpy(cull.view.camera, cam, sizeof cull.view.camera);
    int mismatched_tiles = 0, rescued = 0, expected = 0;
    for (int tile = 0; tile < tiles; tile++) {
        if (!gpu[tile]) continue;
        int want = 0;
        for (uint32_t k = 0; k < B; k++) {
            blade_t pose;
            blade_tiles_pose(t, tile, k, &pose);
            float factor = 0.0f;
            if (pose.v1[3] <= 0.0f || blade_ref_cull_one(&pose, k, &cull, &factor) != BLADE_CULL_VISIBLE) continue;
            float g[3] = {pose.v0[0] - cam[0], pose.v0[1] - cam[1], pose.v0[2] - cam[2]};
            float along = g[0] * pose.up[0] + g[1] * pose.up[1] + g[2] * pose.up[2];
            for (int c = 0; c < 3; c++) g[c] -= pose.up[c] * along;
            float d = sqrtf(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
            float width_dir[3], front[3];
            blade_ref_frame(&pose, width_dir, front);
            float c = fabsf(g[0] * width_dir[0] + g[1] * width_dir[1] + g[2] * width_dir[2]) / d;
            float tk = blade_ref_lod_orientation(0.9f, factor);
            if (c > tk) continue;
            want++;
            rescued += c > 0.9f;
        }
        expected += want;
        mismatched_tiles += abs(want - gpu[tile]) > 1; /* one blade of slack: c at the threshold in float */
    }
    printf("g) %u blades drawn, %d expected by the CPU, %d kept only for their width, %d tiles differ\n", n,
           expected, rescued, mismatched_tiles);
    CHECK(n > 0 && mismatched_tiles == 0);
    CHECK(abs((int)n - expected) <= 2);
    CHECK(rescued > 0);
    free(gpu);
    free(drawn);
    free(ids);
    blade_tiles_destroy(t);
    terrain_free(&m);
}

/* ---- h) ------------------------------------------------------------------ */
static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

static void test_draw_lists(void)
{
    terrain_mesh_t m = make_terrain(16.0f, 32, false);
    blade_tiles_t *t = make_tiles(&m, 8, 0.0f);
    CHECK(t);
    blade_tiles_info_t ti = blade_tiles_info(t);
    const float cam[3] = {-5.0f, 2.0f, 3.0f}, fade_start = 6.0f;
    blade_env_t env = make_env(1.0f, 1.0f / 60.0f);
    blade_tiles_update(t, cam, NULL, &env);
    blade_t *drawn = malloc(ti.draw_capacity * sizeof *drawn);
    uint32_t *ids = malloc(ti.draw_capacity * sizeof *ids), *ids_split = malloc(ti.draw_capacity * sizeof *ids);

    draw_all(t, cam);
    uint32_t n = blade_tiles_read_drawn(t, drawn, ids);
    uint32_t *list = malloc((size_t)ti.max_draw_tiles * 2 * sizeof *list);
    int listed = blade_tiles_read_tile_list(t, list), unordered = 0;
    float last = 0.0f;
    for (int k = 0; k < listed; k++) {
        const hybrid_tile_t *tile = &ti.grid->tiles[list[2 * k]];
        float d2 = core_box_dist2(cam, tile->min, tile->max);
        unordered += d2 < last;
        last = d2;
    }

    draw_faded(t, cam, fade_start, fade_start + 2.0f);
    uint32_t n_split = blade_tiles_read_drawn(t, drawn, ids_split), near = 0, misplaced = 0;
    bool beyond = false;
    for (uint32_t i = 0; i < n_split; i++) {
        bool far = dist3(drawn[i].v0, cam) > fade_start;
        misplaced += beyond && !far; /* an opaque blade after the fade list began */
        beyond = beyond || far;
        near += !far;
    }
    qsort(ids, n, sizeof *ids, cmp_u32);
    qsort(ids_split, n_split, sizeof *ids_split, cmp_u32);
    bool same = n == n_split && memcmp(ids, ids_split, n * sizeof *ids) == 0;
    printf("h) %d tiles listed, %d out of distance order; %u blades drawn, split at %.0f m: %u opaque, %u fading, "
           "%u out of place, same ids as unsplit: %s\n",
           listed, unordered, n, fade_start, near, n_split - near, misplaced, same ? "yes" : "no");
    CHECK(listed > 4 && unordered == 0);
    CHECK(same);
    CHECK(near > 0 && near < n_split && misplaced == 0);

    /* Grouped per workgroup (the compute rasterizer's cull): the same
     * blades. A draw buffer a third as large, placed either way, holds a
     * third of the survivors, each once and each a survivor, and counts
     * the rest. */
    blade_draw_desc_t cd = {0};
    mat4 vp;
    view_proj(cam, vp);
    memcpy(cd.view.viewproj, vp, sizeof cd.view.viewproj);
    memcpy(cd.view.camera, cam, sizeof cd.view.camera);
    blade_tiles_cull(t, &cd, 0, true);
    uint32_t n_grouped = blade_tiles_read_drawn(t, drawn, ids_split);
    qsort(ids_split, n_grouped, sizeof *ids_split, cmp_u32);
    bool same_grouped = n_grouped == n && memcmp(ids, ids_split, n * sizeof *ids) == 0;
    printf("h) grouped: %u blades drawn, same ids: %s\n", n_grouped, same_grouped ? "yes" : "no");
    CHECK(same_grouped);
    blade_tiles_desc_t dc = tiles_desc(&m, 8, 0.0f);
    dc.draw_capacity = n / 3;
    blade_tiles_t *tc = blade_tiles_make(&dc);
    CHECK(tc);
    core_log_set_quiet(true);
    blade_tiles_update(tc, cam, NULL, &env);
    for (int grouped = 0; grouped < 2; grouped++) {
        cd.fade_start = fade_start, cd.fade_end = fade_start + 2.0f;
        blade_tiles_cull(tc, &cd, 0, grouped);
        uint32_t n_cap = blade_tiles_read_drawn(tc, drawn, ids_split), strangers = 0, twice = 0;
        blade_tiles_stats_t sc = blade_tiles_stats(tc, true);
        qsort(ids_split, n_cap, sizeof *ids_split, cmp_u32);
        for (uint32_t i = 0; i < n_cap; i++) {
            twice += i > 0 && ids_split[i] == ids_split[i - 1];
            strangers += bsearch(&ids_split[i], ids, n, sizeof *ids, cmp_u32) == NULL;
        }
        printf("h) %s, draw capacity %u of %u survivors: %u drawn, %u counted over, %u twice, %u not survivors\n",
               grouped ? "grouped" : "a place per blade, split", dc.draw_capacity, n, n_cap, sc.draw_overflow, twice,
               strangers);
        CHECK(n_cap == dc.draw_capacity && sc.draw_overflow == n - n_cap && sc.blades_drawn == n_cap);
        CHECK(twice == 0 && strangers == 0);
    }
    blade_tiles_destroy(tc);
    core_log_set_quiet(false);
    free(list);
    free(drawn);
    free(ids);
    free(ids_split);
    blade_tiles_destroy(t);
    terrain_free(&m);
}

/* ---- i) ------------------------------------------------------------------ */
#define DEPTH_SIDE 64

static void test_occlusion(void)
{
    terrain_mesh_t m = make_terrain(16.0f, 32, true);
    blade_tiles_t *t = make_tiles(&m, 8, 0.0f);
    CHECK(t);
    blade_tiles_info_t ti = blade_tiles_info(t);
    blade_cull_desc_t tiles_cull = ti.desc.cull;
    tiles_cull.disable = BLADE_CULL_ORIENTATION; /* the tiles' own rule for widened blades: test g */
    tiles_cull.max_distance = 10.0f;
    blade_tiles_set_cull(t, &tiles_cull);
    blade_tiles_set_lod(t, &thin_lod, 0.0f);
    ti = blade_tiles_info(t);
    const float cam[3] = {-7.5f, 2.0f, -7.5f};
    blade_env_t env = make_env(1.0f, 1.0f / 60.0f);
    blade_tiles_update(t, cam, NULL, &env);
    uint32_t B = ti.template_blades;

    /* the wall: the left half of the image at the window depth of the
     * point 6 m ahead of the camera, the right half open (depth 1) */
    mat4 vp;
    view_proj(cam, vp);
    vec3 ahead;
    glm_vec3_normalize_to((vec3){-cam[0], -cam[1], -cam[2]}, ahead);
    vec4 p = {cam[0] + 6.0f * ahead[0], cam[1] + 6.0f * ahead[1], cam[2] + 6.0f * ahead[2], 1.0f}, clip;
    glm_mat4_mulv(vp, p, clip);
    float wall = 0.5f * clip[2] / clip[3] + 0.5f;
    static float window[DEPTH_SIDE * DEPTH_SIDE], ndc[DEPTH_SIDE * DEPTH_SIDE];
    for (int y = 0; y < DEPTH_SIDE; y++)
        for (int x = 0; x < DEPTH_SIDE; x++) {
            window[y * DEPTH_SIDE + x] = x < DEPTH_SIDE / 2 ? wall : 1.0f;
            ndc[y * DEPTH_SIDE + x] = 2.0f * window[y * DEPTH_SIDE + x] - 1.0f;
        }
    gfx_texture_t depth = gfx_texture_make(&(gfx_texture_desc_t){
        .w = DEPTH_SIDE, .h = DEPTH_SIDE, .format = GL_R32F, .filter = GL_NEAREST, .data = window,
        .upload_format = GL_RED, .upload_type = GL_FLOAT, .label = "tiles.test_depth"});
    CHECK(depth.id != 0);

    draw_occluded(t, cam, 0.0f, 0.0f, depth.id);
    blade_t *drawn = malloc(ti.draw_capacity * sizeof *drawn);
    uint32_t *ids = malloc(ti.draw_capacity * sizeof *ids);
    uint32_t n = blade_tiles_read_drawn(t, drawn, ids);
    blade_tiles_stats_t st = blade_tiles_stats(t, true);
    uint32_t *list = malloc((size_t)ti.max_draw_tiles * 2 * sizeof *list);
    int listed = blade_tiles_read_tile_list(t, list), ntiles = ti.grid->nx * ti.grid->nz;

    /* the CPU twin over the listed tiles, with the same depth */
    blade_cull_desc_t cull = ti.desc.cull;
    memcpy(cull.view.camera, cam, sizeof cull.view.camera);
    memcpy(cull.view.viewproj, vp, sizeof cull.view.viewproj);
    cull.depth = ndc;
    cull.depth_w = cull.depth_h = DEPTH_SIDE;
    unsigned char *want = calloc((size_t)ntiles * B, 1), *got = calloc((size_t)ntiles * B, 1);
    uint32_t cpu[4] = {0}, cpu_visible = 0;
    for (int k = 0; k < listed; k++)
        for (uint32_t b = 0; b < B; b++) {
            blade_t pose;
            blade_tiles_pose(t, (int)list[2 * k], b, &pose);
            int why = blade_ref_cull_one(&pose, b, &cull, NULL);
            if (why == BLADE_CULL_VISIBLE) {
                want[list[2 * k] * B + b] = 1;
                cpu_visible++;
            }
            for (int test = 0; test < 4; test++) cpu[test] += why == 1 << test; /* BLADE_CULL_ORIENTATION .. */
        }
    for (uint32_t i = 0; i < n; i++) got[ids[i]] = 1;
    int differ = 0;
    for (size_t i = 0; i < (size_t)ntiles * B; i++) differ += want[i] != got[i];
    /* every blade of the blade-representation tiles */
    uint32_t blade_tiles_blades = 0, counted = st.blades_drawn + st.tile_culled;
    for (int i = 0; i < ntiles; i++) {
        if (ti.grid->tiles[i].rep != HYBRID_REP_BLADE) continue;
        int tmpl, sym;
        blade_tiles_instance(t, i, &tmpl, &sym);
        blade_tiles_blades += ti.template_real[tmpl];
    }
    for (int k = 0; k < 4; k++) counted += st.culled[k];
    printf("i) wall at window depth %.4f over the left half: GPU culled (orientation frustum distance occlusion "
           "tile) %u %u %u %u %u, drawn %u; CPU %u %u %u %u, visible %u; %d blades differ; %u of the blade tiles' "
           "%u blades accounted for\n",
           wall, st.culled[0], st.culled[1], st.culled[2], st.culled[3], st.tile_culled, n, cpu[0], cpu[1], cpu[2],
           cpu[3], cpu_visible, differ, counted, blade_tiles_blades);
    CHECK(n == st.blades_drawn);
    CHECK(cpu[3] > 100 && cpu_visible > 100);
    CHECK(differ <= 2); /* blades whose points sit on the wall's depth, in float */
    for (int k = 0; k < 4; k++) CHECK(abs((int)st.culled[k] - (int)cpu[k]) <= 2);
    CHECK(st.tile_culled > 0 && counted == blade_tiles_blades);

    /* without the depth texture the occluded blades come back */
    draw_occluded(t, cam, 0.0f, 0.0f, 0);
    uint32_t n_open = blade_tiles_read_drawn(t, drawn, ids);
    blade_tiles_stats_t open = blade_tiles_stats(t, true);
    printf("i) without the depth texture: %u drawn (%u more), occlusion count %u\n", n_open, n_open - n,
           open.culled[3]);
    CHECK(open.culled[3] == 0 && n_open == n + st.culled[3]);
    gfx_texture_destroy(&depth);
    free(want);
    free(got);
    free(list);
    free(drawn);
    free(ids);
    blade_tiles_destroy(t);
    terrain_free(&m);
}

int main(void)
{
    test_gl_init();
    gfx_target_t target = gfx_target_make(&(gfx_target_desc_t){.w = 32, .h = 32, .samples = 1, .label = "tiles.test"});
    gfx_target_bind(&target);
    test_no_pop();
    test_ball();
    test_fast_ball();
    test_exhaustion();
    test_lod_width();
    test_lod_orientation();
    test_draw_lists();
    test_occlusion();
    /* a mesh terrain is rejected */
    terrain_mesh_t mesh = make_terrain(8.0f, 8, true);
    mesh.grid_res = 0;
    int errors = core_log_error_count();
    blade_tiles_t *t = blade_tiles_make(&(blade_tiles_desc_t){.terrain = &mesh});
    CHECK(!t);
    blade_tiles_destroy(t);
    CHECK(core_log_error_count() == errors + 1);
    mesh.grid_res = 8;
    terrain_free(&mesh);
    gfx_target_destroy(&target);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

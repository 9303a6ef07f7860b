/* test_hybrid: tile representation hysteresis, activation against a
 * brute-force recount along a scripted path, pool exhaustion reported,
 * recovery by timeout and by measured motion, the hand-over rules (a
 * recovering billboard tile frees its slot for the slope cells; a blade tile
 * within `memory` of its hand-over takes a seeded slot; keep_state turns it
 * off) and the slope cell arithmetic of hybrid_slope.h. */
#include "hybrid/hybrid.h"
#include "hybrid/hybrid_slope.h"
#include "core/core.h"
#include "test.h"

#include <math.h>
#include <stdlib.h>

int main(void)
{
    core_log_set_quiet(true);
    hybrid_grid_t g;
    hybrid_desc_t d = {.min_x = -20, .min_z = -20, .size_x = 40, .size_z = 40, .tile_size = 4,
                       .switch_distance = 10, .hysteresis = 1, .recover_timeout = 2, .pool_slots = 8};
    CHECK(hybrid_grid_make(&g, &d));
    CHECK(g.nx == 10 && g.nz == 10);
    CHECK(hybrid_tile_at(&g, -20, -20) == 0 && hybrid_tile_at(&g, 19.9f, 19.9f) == 99);
    CHECK(hybrid_tile_at(&g, 20.1f, 0) == -1);

    /* Representation: near tiles are blades; a camera oscillating by less
     * than the hysteresis around the boundary flips nothing. */
    float cam[3] = {0, 2, 0};
    hybrid_grid_update(&g, cam, NULL, 0, NULL, 0.1f);
    int t_near = hybrid_tile_at(&g, 1, 1), t_far = hybrid_tile_at(&g, 19, 19);
    CHECK(g.tiles[t_near].rep == HYBRID_REP_BLADE && g.tiles[t_far].rep == HYBRID_REP_BILLBOARD);
    int edge = hybrid_tile_at(&g, 13, 1); /* nearest point x = 12 */
    for (int f = 0; f < 40; f++) {
        cam[0] = 1.5f + 0.4f * sinf((float)f); /* distance to the tile 10.1 .. 10.9 */
        hybrid_grid_update(&g, cam, NULL, 0, NULL, 0.1f);
        CHECK(g.stats.rep_switches == 0 || f == 0);
    }
    (void)edge;
    cam[0] = 8; /* well inside */
    hybrid_grid_update(&g, cam, NULL, 0, NULL, 0.1f);
    CHECK(g.tiles[edge].rep == HYBRID_REP_BLADE);
    cam[0] = 0.5f; /* distance 11.5 > 10 + 1 */
    hybrid_grid_update(&g, cam, NULL, 0, NULL, 0.1f);
    CHECK(g.tiles[edge].rep == HYBRID_REP_BILLBOARD);

    /* Activation vs brute force along a path; states follow the rules. */
    hybrid_object_t obj[2];
    int ever_active = 0;
    for (int f = 0; f < 400; f++) {
        float t = (float)f * 0.05f;
        obj[0] = (hybrid_object_t){{-18 + 1.8f * t, 0.5f, -3, 0.8f}};
        obj[1] = (hybrid_object_t){{5, 0.5f, -18 + 1.5f * t, 0.5f}};
        hybrid_grid_update(&g, cam, obj, 2, NULL, 0.05f);
        for (int i = 0; i < g.nx * g.nz; i++) {
            bool touched = hybrid_tile_touched_brute(&g, i, obj, 2);
            CHECK_MSG(touched == (g.tiles[i].object_count > 0), "frame %d tile %d", f, i);
            if (touched) CHECK(g.tiles[i].state == HYBRID_ACTIVE && g.tiles[i].slot >= 0);
            if (g.tiles[i].state == HYBRID_IDLE) CHECK(g.tiles[i].slot < 0);
            ever_active += touched;
        }
        CHECK(g.stats.pool_denied == 0);
        CHECK(g.stats.slots_used == g.stats.active + g.stats.recovering);
    }
    CHECK(ever_active > 0);
    /* After the objects are gone, the timeout returns every tile to IDLE. */
    for (int f = 0; f < 50; f++) hybrid_grid_update(&g, cam, NULL, 0, NULL, 0.05f);
    CHECK(g.stats.active == 0 && g.stats.recovering == 0 && g.stats.slots_used == 0);

    /* Measured motion below epsilon ends recovery early. */
    obj[0] = (hybrid_object_t){{1, 0.5f, 1, 0.5f}};
    hybrid_grid_update(&g, cam, obj, 1, NULL, 0.05f);
    int ti = hybrid_tile_at(&g, 1, 1);
    CHECK(g.tiles[ti].state == HYBRID_ACTIVE);
    float *motion = calloc((size_t)(g.nx * g.nz), sizeof(float));
    for (int i = 0; i < g.nx * g.nz; i++) motion[i] = 0.05f;
    hybrid_grid_update(&g, cam, NULL, 0, motion, 0.05f);
    CHECK(g.tiles[ti].state == HYBRID_RECOVERING);
    hybrid_grid_update(&g, cam, NULL, 0, motion, 0.05f);
    CHECK(g.tiles[ti].state == HYBRID_RECOVERING);
    motion[ti] = 1e-4f;
    hybrid_grid_update(&g, cam, NULL, 0, motion, 0.05f);
    CHECK(g.tiles[ti].state == HYBRID_IDLE && g.tiles[ti].slot < 0);
    free(motion);

    /* Pool exhaustion is reported, not hidden: a big object over 16+ tiles
     * with 8 slots. */
    int warns = core_log_warn_count();
    obj[0] = (hybrid_object_t){{0, 0.5f, 0, 9.0f}};
    hybrid_grid_update(&g, cam, obj, 1, NULL, 0.05f);
    CHECK(g.stats.slots_used == 8 && g.stats.pool_denied > 0);
    CHECK(core_log_warn_count() == warns + 1);
    hybrid_grid_free(&g);

    /* Hand-over: a tile touched while drawn as billboards simulates (ACTIVE);
     * when the object leaves it hands over and frees its slot; brought near
     * within `memory` seconds it takes a slot to be seeded; later, not. */
    for (int keep = 0; keep < 2; keep++) {
        hybrid_desc_t dh = d;
        dh.memory = 1.0f;
        dh.keep_state = keep;
        CHECK(hybrid_grid_make(&g, &dh));
        float far_cam[3] = {-19, 2, -19}, near_cam[3] = {11, 2, 11};
        obj[0] = (hybrid_object_t){{10, 0.5f, 10, 0.5f}};
        int th = hybrid_tile_at(&g, 10, 10);
        hybrid_grid_update(&g, far_cam, obj, 1, NULL, 0.05f);
        CHECK(g.tiles[th].rep == HYBRID_REP_BILLBOARD && g.tiles[th].state == HYBRID_ACTIVE);
        int slot = g.tiles[th].slot;
        hybrid_grid_update(&g, far_cam, NULL, 0, NULL, 0.05f);
        if (keep) {
            CHECK(g.tiles[th].state == HYBRID_RECOVERING && g.tiles[th].slot == slot);
            CHECK(g.tiles[th].handover_slot < 0 && g.stats.handovers == 0);
            hybrid_grid_free(&g);
            continue;
        }
        CHECK_MSG(g.tiles[th].handover_slot == slot && g.tiles[th].slot < 0 && g.tiles[th].state == HYBRID_IDLE,
                  "hand-over slot %d slot %d state %d", g.tiles[th].handover_slot, g.tiles[th].slot,
                  g.tiles[th].state);
        CHECK(g.stats.handovers == 1 && g.stats.slots_used == 0);
        hybrid_grid_update(&g, far_cam, NULL, 0, NULL, 0.05f);
        CHECK(g.tiles[th].handover_slot < 0 && g.stats.handovers == 0); /* once */
        hybrid_grid_update(&g, near_cam, NULL, 0, NULL, 0.05f);
        CHECK(g.tiles[th].rep == HYBRID_REP_BLADE && g.tiles[th].seed && g.tiles[th].slot >= 0);
        CHECK(g.tiles[th].state == HYBRID_RECOVERING && g.stats.seeded == 1);
        /* settles: IDLE, and its memory is spent (the blades were newest) */
        float *mo = calloc((size_t)(g.nx * g.nz), sizeof(float));
        hybrid_grid_update(&g, near_cam, NULL, 0, mo, 0.05f);
        CHECK(g.tiles[th].state == HYBRID_IDLE && g.tiles[th].slot < 0 && !g.tiles[th].seed);
        hybrid_grid_update(&g, near_cam, NULL, 0, mo, 0.05f);
        CHECK(g.tiles[th].slot < 0 && g.stats.seeded == 0);
        /* hand over again, wait past the memory, come back: nothing to seed */
        hybrid_grid_update(&g, far_cam, obj, 1, NULL, 0.05f);
        hybrid_grid_update(&g, far_cam, NULL, 0, NULL, 0.05f);
        CHECK(g.stats.handovers == 1);
        for (int f = 0; f < 25; f++) hybrid_grid_update(&g, far_cam, NULL, 0, NULL, 0.05f);
        hybrid_grid_update(&g, near_cam, NULL, 0, NULL, 0.05f);
        CHECK(g.tiles[th].slot < 0 && g.stats.seeded == 0);
        free(mo);
        hybrid_grid_free(&g);
    }

    /* Slope cells: addressing, exact fixed-point means, eq. 8 weight, and
     * the reconstruction (unit length; w = 0 gives the pose; an aligned
     * cell gives its mean; a cancelled one its magnitude along the
     * fallback). */
    hybrid_slope_grid_t sg = hybrid_slope_grid(-8, -8, 2, 8, 8, 4);
    CHECK(sg.nx == 32 && sg.nz == 32 && fabsf(sg.cell - 0.5f) < 1e-7f);
    CHECK(hybrid_slope_cell_at(&sg, -8, -8) == 0 && hybrid_slope_cell_at(&sg, 7.9f, 7.9f) == 32 * 32 - 1);
    CHECK(hybrid_slope_cell_at(&sg, 8.1f, 0) == -1 && hybrid_slope_cell_at(&sg, 0, -8.1f) == -1);
    hybrid_slope_sum_t sum = {0};
    float o1[2] = {0.5f, 0.0f}, o2[2] = {-0.5f, 0.0f};
    hybrid_slope_add(&sum, o1, 0.25f);
    hybrid_slope_add(&sum, o2, 0.75f);
    hybrid_slope_cell_t cell = hybrid_slope_resolve(&sum, 3.0f);
    CHECK(cell.count == 2 && cell.t[0] == 0.0f && cell.m == 0.5f && cell.eta == 0.5f && cell.tau == 3.0f);
    CHECK(hybrid_slope_weight(0, 2) == 1.0f && hybrid_slope_weight(2, 2) == 0.0f);
    CHECK(fabsf(hybrid_slope_weight(1, 2) - 0.125f) < 1e-7f && hybrid_slope_weight(-1, 2) == 1.0f);
    float pose[3] = {0.1f, sqrtf(1.0f - 0.01f), 0.0f}, fb[2] = {0.0f, 1.0f}, out[3];
    hybrid_slope_apply(pose, fb, &cell, 0.0f, out);
    CHECK(fabsf(out[0] - pose[0]) < 1e-6f && fabsf(out[1] - pose[1]) < 1e-6f && fabsf(out[2]) < 1e-6f);
    hybrid_slope_apply(pose, fb, &cell, 1.0f, out); /* cancelled: M along the fallback */
    CHECK(fabsf(out[0] - 0.1f) < 1e-6f && fabsf(out[2] - 0.5f) < 1e-6f);
    CHECK(fabsf(out[0] * out[0] + out[1] * out[1] + out[2] * out[2] - 1.0f) < 1e-5f);
    hybrid_slope_cell_t aligned = {.t = {0.3f, 0.4f}, .m = 0.5f, .count = 1};
    hybrid_slope_apply(pose, fb, &aligned, 1.0f, out);
    CHECK(fabsf(out[0] - 0.4f) < 1e-6f && fabsf(out[2] - 0.4f) < 1e-6f);
    hybrid_slope_cell_t flat = {.t = {2.0f, 0.0f}, .m = 2.0f, .count = 1};
    hybrid_slope_apply(pose, fb, &flat, 1.0f, out); /* clamped below the horizon */
    CHECK(out[1] > 0.0f && fabsf(out[0] - HYBRID_SLOPE_MAX_TILT) < 1e-6f);
    TEST_END();
}

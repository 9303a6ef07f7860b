/* test_hybrid_window: the window grid of the open world (hybrid.h,
 * desc.window) against the whole-field grid on the same walk. Every tile
 * the window holds is the field tile its coordinates name, at the index
 * hybrid_tile_at gives; representation, state and object lists equal the
 * whole grid's tile; tiles streamed in come back IDLE with a new epoch; a
 * touched tile carried out of the window keeps its slot away from it
 * (stats.detached), takes it back when it returns in time
 * (stats.reattached) and frees it after recover_timeout away, or once its
 * measured motion dies down (hybrid_grid_settle_away); the held
 * tile count does not depend on the field. */
#include "hybrid/hybrid.h"
#include "core/core.h"
#include "test.h"

#include <math.h>
#include <stdlib.h>

enum { WINDOW = 16, OBJECTS = 6 };

static void range_of(void *user, const float min_xz[2], const float max_xz[2], float y[2])
{
    (void)user;
    y[0] = -0.01f * (min_xz[0] + min_xz[1]);
    y[1] = y[0] + 0.02f * (max_xz[0] - min_xz[0]);
}

int main(void)
{
    core_log_set_quiet(true);
    hybrid_desc_t d = {.min_x = -200, .min_z = -200, .size_x = 400, .size_z = 400, .tile_size = 4,
                       .switch_distance = 12, .hysteresis = 1, .recover_timeout = 2, .pool_slots = 256,
                       .memory = 0.5f};
    hybrid_grid_t whole, win;
    CHECK(hybrid_grid_make(&whole, &d));
    hybrid_desc_t dw = d;
    dw.window = WINDOW;
    CHECK(hybrid_grid_make(&win, &dw));
    CHECK(win.nx == WINDOW && win.nz == WINDOW && whole.nx == 100);

    /* Walk 120 s across the field; objects within 8 m of the camera. */
    uint32_t rng = 7;
    long streamed = 0;
    for (int f = 0; f < 1200; f++) {
        float t = 0.1f * (float)f;
        float cam[3] = {-150.0f + 2.5f * t, 2.0f, -100.0f + 60.0f * sinf(0.05f * t)};
        hybrid_object_t obj[OBJECTS];
        for (int k = 0; k < OBJECTS; k++) {
            rng = core_hash_u32(rng + (uint32_t)k);
            float a = core_hash_float(rng) * 6.2831853f, r = 8.0f * core_hash_float(core_hash_u32(rng));
            obj[k] = (hybrid_object_t){{cam[0] + r * cosf(a), 0.0f, cam[2] + r * sinf(a), 0.7f}};
        }
        hybrid_grid_update(&whole, cam, obj, OBJECTS, NULL, 0.1f);
        hybrid_grid_update(&win, cam, obj, OBJECTS, NULL, 0.1f);
        streamed += win.stats.streamed;
        for (int i = 0; i < WINDOW * WINDOW; i++) {
            const hybrid_tile_t *a = &win.tiles[i];
            int gi = a->coord[0], gj = a->coord[1];
            CHECK_MSG(gi >= win.base[0] && gi < win.base[0] + WINDOW && gj >= win.base[1] &&
                          gj < win.base[1] + WINDOW,
                      "frame %d tile %d outside the window", f, i);
            CHECK_MSG((gj % WINDOW) * WINDOW + gi % WINDOW == i, "frame %d tile %d at the wrong index", f, i);
            if (!a->present) continue;
            float cx = 0.5f * (a->min[0] + a->max[0]), cz = 0.5f * (a->min[2] + a->max[2]);
            CHECK_MSG(hybrid_tile_at(&win, cx, cz) == i, "frame %d tile %d not found by position", f, i);
            const hybrid_tile_t *b = &whole.tiles[gj * whole.nx + gi];
            CHECK_MSG(a->min[0] == b->min[0] && a->max[2] == b->max[2], "frame %d tile %d box", f, i);
            CHECK_MSG(a->rep == b->rep && a->state == b->state && (a->slot >= 0) == (b->slot >= 0) &&
                          a->object_count == b->object_count,
                      "frame %d tile (%d, %d): window rep %d state %d slot %d objects %d, whole %d %d %d %d", f,
                      gi, gj, a->rep, a->state, a->slot, a->object_count, b->rep, b->state, b->slot,
                      b->object_count);
        }
    }
    CHECK_MSG(streamed > 1000, "only %ld tiles streamed in", streamed);
    CHECK(whole.stats.pool_denied == 0 && win.stats.pool_denied == 0);

    /* A touched tile carried out of the window keeps its slot away from
     * it, comes back to it, and frees it after recover_timeout away. */
    float cam[3] = {0.0f, 2.0f, 0.0f}, far_cam[3] = {40.0f, 2.0f, 0.0f};
    hybrid_object_t ball = {{1.0f, 0.0f, 1.0f, 0.5f}};
    for (int f = 0; f < 30; f++) hybrid_grid_update(&win, cam, NULL, 0, NULL, 0.1f); /* the walk's tiles settle */
    CHECK(win.stats.away == 0 && win.free_count == win.desc.pool_slots);
    hybrid_grid_update(&win, cam, &ball, 1, NULL, 0.1f);
    int ti = hybrid_tile_at(&win, 1.0f, 1.0f);
    CHECK(ti >= 0 && win.tiles[ti].state == HYBRID_ACTIVE && win.tiles[ti].slot >= 0);
    int slot = win.tiles[ti].slot, free_before = win.free_count;
    uint32_t epoch = win.tiles[ti].epoch;
    hybrid_grid_update(&win, far_cam, NULL, 0, NULL, 0.1f);
    CHECK_MSG(win.stats.detached == 1 && win.stats.away == 1 && win.free_count == free_before,
              "leaving: detached %d, away %d, free %d -> %d", win.stats.detached, win.stats.away, free_before,
              win.free_count);
    CHECK(hybrid_tile_at(&win, 1.0f, 1.0f) == -1);
    CHECK(win.tiles[ti].epoch == epoch + 1 && win.tiles[ti].state == HYBRID_IDLE && win.tiles[ti].slot < 0);
    hybrid_grid_update(&win, cam, NULL, 0, NULL, 0.1f);
    ti = hybrid_tile_at(&win, 1.0f, 1.0f);
    CHECK_MSG(win.stats.reattached == 1 && win.tiles[ti].slot == slot && win.tiles[ti].state == HYBRID_RECOVERING &&
                  win.tiles[ti].reattached && win.stats.away == 0,
              "back: reattached %d, slot %d (was %d), state %d", win.stats.reattached, win.tiles[ti].slot, slot,
              win.tiles[ti].state);
    hybrid_grid_update(&win, far_cam, NULL, 0, NULL, 0.1f);
    CHECK(win.stats.away == 1);
    float away_for = 0.0f;
    while (win.stats.away > 0 && away_for < 10.0f) {
        hybrid_grid_update(&win, far_cam, NULL, 0, NULL, 0.1f);
        away_for += 0.1f;
    }
    CHECK_MSG(win.stats.away == 0 && win.free_count == free_before + 1 && away_for > 1.0f &&
                  away_for <= win.desc.recover_timeout + 0.2f,
              "away for %.1f s (timeout %.1f), free %d", away_for, win.desc.recover_timeout, win.free_count);
    hybrid_grid_update(&win, cam, NULL, 0, NULL, 0.1f);
    CHECK(win.stats.reattached == 0 && win.tiles[hybrid_tile_at(&win, 1.0f, 1.0f)].slot < 0);

    /* Away tiles end their recovery early once their slot's motion dies
     * down (hybrid_grid_settle_away), as in the window. */
    hybrid_grid_update(&win, cam, &ball, 1, NULL, 0.1f);
    int held = win.tiles[hybrid_tile_at(&win, 1.0f, 1.0f)].slot;
    hybrid_grid_update(&win, far_cam, NULL, 0, NULL, 0.1f);
    CHECK(held >= 0 && win.stats.away == 1);
    float *motion = malloc(sizeof(float) * (size_t)win.desc.pool_slots);
    for (int k = 0; k < win.desc.pool_slots; k++) motion[k] = 1.0f;
    hybrid_grid_settle_away(&win, motion);
    hybrid_grid_update(&win, far_cam, NULL, 0, NULL, 0.1f);
    CHECK_MSG(win.stats.away == 1, "moving away tile freed early");
    motion[held] = 0.5f * win.desc.motion_epsilon;
    hybrid_grid_settle_away(&win, motion);
    hybrid_grid_update(&win, far_cam, NULL, 0, NULL, 0.1f);
    CHECK_MSG(win.stats.away == 0 && win.free_count == win.desc.pool_slots, "settled away tile kept: away %d",
              win.stats.away);
    free(motion);

    /* The tile range callback sets the boxes of tiles streamed in. */
    hybrid_desc_t dr = dw;
    dr.tile_range = range_of;
    hybrid_grid_t ranged;
    CHECK(hybrid_grid_make(&ranged, &dr));
    hybrid_grid_update(&ranged, (float[3]){33.0f, 0.0f, -71.0f}, NULL, 0, NULL, 0.1f);
    int tr = hybrid_tile_at(&ranged, 33.0f, -71.0f);
    CHECK(tr >= 0);
    float y[2];
    range_of(NULL, (float[2]){ranged.tiles[tr].min[0], ranged.tiles[tr].min[2]},
             (float[2]){ranged.tiles[tr].max[0], ranged.tiles[tr].max[2]}, y);
    CHECK(ranged.tiles[tr].min[1] == y[0] && ranged.tiles[tr].max[1] == y[1] + ranged.desc.grass_height);

    /* Held tiles do not depend on the field's size. */
    hybrid_desc_t big = dw;
    big.size_x = big.size_z = 4096;
    hybrid_grid_t huge;
    CHECK(hybrid_grid_make(&huge, &big));
    CHECK(huge.nx * huge.nz == WINDOW * WINDOW && huge.field_nx == 1024);
    hybrid_grid_free(&huge);
    hybrid_grid_free(&ranged);
    hybrid_grid_free(&whole);
    hybrid_grid_free(&win);
    TEST_END();
}

/* test_hybrid: tile representation hysteresis, activation against a
 * brute-force recount along a scripted path, pool exhaustion reported, and
 * recovery by timeout and by measured motion. */
#include "hybrid/hybrid.h"
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
    TEST_END();
}

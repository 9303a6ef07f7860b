/* test_tiles_stream: the tiled blade field streamed around the camera (a
 * window of tiles, blade_tiles_desc_t.window; docs/WORLD.md), walked across
 * tile borders on llvmpipe:
 *   a) the window draws exactly the blades the whole-field grid draws at
 *      every camera position of a walk across the field (bit-identical,
 *      sorted by root), while tiles stream in and out;
 *   b) a tile streamed out and in again is regenerated bit-identical;
 *   c) a touched tile keeps its slot and state while it stays in the
 *      window (camera moved a tile, state bytes unchanged) and drops them
 *      when it leaves (the pool gets the slot back);
 *   d) GPU bytes stay flat over the walk and do not depend on the field's
 *      size (a window over a 48 m and a 480 m field). */
#include "blade/blade_tiles.h"
#include "collide_test_util.h"
#include "test.h"
#include "test_gl.h"

#include <stdlib.h>
#include <string.h>

#define SWITCH 6.0f
#define WINDOW 11

static blade_tiles_t *make_tiles(const terrain_mesh_t *m, int window)
{
    blade_tiles_desc_t d = {.terrain = m, .window = window, .tile_size = 2.0f, .density = 24.0f,
                            .height_min = 0.3f, .height_max = 0.5f, .width_min = 0.02f, .width_max = 0.03f,
                            .stiffness_min = 8.0f, .stiffness_max = 12.0f, .seed = 5, .pool_slots = 16,
                            .switch_distance = SWITCH, .keep_state = true,
                            .cull = {.disable = BLADE_CULL_ORIENTATION | BLADE_CULL_FRUSTUM | BLADE_CULL_DISTANCE}};
    d.winds[0] = blade_wind_wave(1.0f, 0.4f, 1.5f, 6.0f, 1.0f);
    d.wind_count = 1;
    return blade_tiles_make(&d);
}

static int cmp_blade(const void *pa, const void *pb)
{
    const blade_t *a = pa, *b = pb;
    for (int c = 0; c < 3; c++)
        if (a->v0[c] != b->v0[c]) return a->v0[c] < b->v0[c] ? -1 : 1;
    return 0;
}

/* Updates at `time`, draws everything in blade representation, returns the
 * drawn blades sorted by root (count in *n; caller frees). */
static blade_t *drawn_at(blade_tiles_t *t, const float cam[3], float time, float dt, const collide_set_t *set,
                         uint32_t *n)
{
    blade_env_t env = {.dt = dt, .time = time, .gravity = 1.0f};
    blade_tiles_update(t, cam, set, &env);
    blade_draw_desc_t dd = {.time = time};
    mat4 vp;
    glm_mat4_identity(vp);
    memcpy(dd.view_proj, vp, sizeof vp);
    memcpy(dd.camera, cam, sizeof dd.camera);
    blade_tiles_draw(t, &dd, 0);
    blade_tiles_info_t ti = blade_tiles_info(t);
    blade_t *b = malloc(ti.draw_capacity * sizeof *b);
    *n = blade_tiles_read_drawn(t, b, NULL);
    qsort(b, *n, sizeof *b, cmp_blade);
    return b;
}

static bool same_blades(const blade_t *a, uint32_t na, const blade_t *b, uint32_t nb)
{
    return na == nb && memcmp(a, b, na * sizeof *a) == 0;
}

int main(void)
{
    test_gl_init();
    terrain_mesh_t m;
    CHECK(terrain_make_heightfield(&m, &(terrain_desc_t){.size = 48, .resolution = 48, .height = 0.6f}, 11));
    blade_tiles_t *whole = make_tiles(&m, 0), *win = make_tiles(&m, WINDOW);
    CHECK(whole && win);
    CHECK(blade_tiles_info(win).grid->nx == WINDOW && blade_tiles_info(whole).grid->nx == 24);
    size_t bytes0 = blade_tiles_stats(win, true).gpu_bytes;

    /* a) a walk across the field; the eye inside the tiles' height range
     * so both grids measure the same horizontal distances. */
    long streamed = 0;
    int positions = 0;
    for (float x = -20.0f; x <= 20.0f; x += 1.3f, positions++) {
        float cam[3] = {x, 0.2f + terrain_height_at(&m, x, 0.4f * x, NULL), 0.4f * x};
        uint32_t na, nb;
        blade_t *a = drawn_at(whole, cam, 1.0f, 0.0f, NULL, &na);
        blade_t *b = drawn_at(win, cam, 1.0f, 0.0f, NULL, &nb);
        streamed += blade_tiles_info(win).grid->stats.streamed;
        CHECK_MSG(na > 0 && same_blades(a, na, b, nb), "at x %.1f: whole grid drew %u blades, window %u", x, na,
                  nb);
        free(a);
        free(b);
    }
    printf("a) %d positions, %ld tiles streamed in, drawn blades identical\n", positions, streamed);
    CHECK(streamed > 50);

    /* b) streamed out and in again */
    float home[3] = {3.0f, 0.2f + terrain_height_at(&m, 3.0f, 3.0f, NULL), 3.0f};
    float away[3] = {-18.0f, 1.0f, -18.0f};
    uint32_t n0, n1, n2;
    free(drawn_at(win, away, 2.0f, 0.0f, NULL, &n2));
    blade_t *first = drawn_at(win, home, 2.0f, 0.0f, NULL, &n0);
    free(drawn_at(win, away, 2.0f, 0.0f, NULL, &n2));
    CHECK(blade_tiles_info(win).grid->stats.streamed > 0);
    blade_t *again = drawn_at(win, home, 2.0f, 0.0f, NULL, &n1);
    CHECK_MSG(n0 > 0 && same_blades(first, n0, again, n1), "regenerated %u vs %u blades differ", n0, n1);
    free(first);
    free(again);

    /* c) a touched tile keeps its state while in the window */
    const float ball[1][4] = {{3.0f, home[1] - 0.1f, 3.0f, 0.25f}};
    for (int f = 0; f < 10; f++)
        free(drawn_at(win, home, 2.0f + 0.02f * (float)f, 0.02f, test_sphere_set(ball, 1), &n0));
    blade_tiles_info_t ti = blade_tiles_info(win);
    int tile = hybrid_tile_at(ti.grid, 3.0f, 3.0f);
    CHECK(tile >= 0 && ti.grid->tiles[tile].slot >= 0);
    int slot = ti.grid->tiles[tile].slot;
    uint32_t B = ti.template_blades;
    blade_t *before = malloc(B * sizeof *before), *after = malloc(B * sizeof *after);
    blade_tiles_read_slot(win, slot, before, NULL);
    float step[3] = {home[0] + 2.0f, home[1], home[2] + 2.0f};
    free(drawn_at(win, step, 2.2f, 0.0f, NULL, &n0));
    CHECK(ti.grid->stats.streamed > 0 && ti.grid->tiles[tile].slot == slot &&
          ti.grid->tiles[tile].state == HYBRID_RECOVERING);
    blade_tiles_read_slot(win, slot, after, NULL);
    CHECK_MSG(memcmp(before, after, B * sizeof *before) == 0, "the slot's state changed when the window moved");
    blade_t *pool = malloc(16 * (size_t)B * sizeof *pool);
    blade_tiles_read_pool(win, pool);
    free(drawn_at(win, away, 2.2f, 0.0f, NULL, &n0));
    CHECK_MSG(ti.grid->stats.dropped >= 1 && ti.grid->stats.slots_used == 0,
              "leaving the window: %d dropped, %d slots still used", ti.grid->stats.dropped,
              ti.grid->stats.slots_used);
    free(pool);
    free(before);
    free(after);

    /* d) flat memory */
    CHECK(blade_tiles_stats(win, true).gpu_bytes == bytes0);
    terrain_mesh_t big;
    CHECK(terrain_make_heightfield(&big, &(terrain_desc_t){.size = 480, .resolution = 48, .height = 0.6f}, 11));
    blade_tiles_t *far = make_tiles(&big, WINDOW);
    CHECK(far);
    size_t far_bytes = blade_tiles_stats(far, true).gpu_bytes;
    printf("d) window GPU bytes: %zu over a 48 m field, %zu over a 480 m field (whole 48 m grid %zu)\n", bytes0,
           far_bytes, blade_tiles_stats(whole, true).gpu_bytes);
    CHECK(far_bytes == bytes0);
    blade_tiles_destroy(far);
    blade_tiles_destroy(whole);
    blade_tiles_destroy(win);
    terrain_free(&big);
    terrain_free(&m);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

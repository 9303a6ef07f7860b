/* test_tiles_stream: the tiled blade field streamed around the camera (a
 * window of tiles, blade_tiles_desc_t.window; docs/WORLD.md), walked across
 * tile borders on llvmpipe:
 *   a) the window draws exactly the blades the whole-field grid draws at
 *      every camera position of a walk across the field (bit-identical,
 *      sorted by root), while tiles stream in and out;
 *   b) a tile streamed out and in again is regenerated bit-identical;
 *   c) a touched tile keeps its slot and state in the window and away
 *      from it: carried out of the window and back it recovers as a twin
 *      field's tile that never left (bit-identical slot state);
 *   d) GPU bytes stay flat over the walk and do not depend on the field's
 *      size (a window over a 48 m and a 480 m field);
 *   e) on world terrains (terrain_world.h) of 1 and 4 km: the same GPU
 *      bytes, and every drawn root on the ground of terrain_height_at
 *      (the GLSL twin of the height function) at a camera 1.5 km out. */
#include "blade/blade_tiles.h"
#include "collide_test_util.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SWITCH 6.0f
#define WINDOW 11

static blade_tiles_t *make_tiles(const terrain_mesh_t *m, int window)
{
    blade_tiles_desc_t d = {
        .terrain = m,
        .window = window,
        .tile_size = 2.0f,
        .population = {.density = 24.0f, .height = {0.3f, 0.5f}, .width = {0.02f, 0.03f}, .stiffness = {8.0f, 12.0f}},
        .seed = 5,
        .pool_slots = 16,
        .switch_distance = SWITCH,
        .keep_state = true,
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
    blade_draw_desc_t dd = {.view.time = time};
    mat4 vp;
    glm_mat4_identity(vp);
    memcpy(dd.view.viewproj, vp, sizeof vp);
    memcpy(dd.view.camera, cam, sizeof dd.view.camera);
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
    gfx_target_t target = gfx_target_make(&(gfx_target_desc_t){.w = 32, .h = 32, .samples = 1, .label = "stream.test"});
    gfx_target_bind(&target);
    blade_tiles_t *whole = make_tiles(&m, 0), *win = make_tiles(&m, WINDOW), *twin = make_tiles(&m, WINDOW);
    CHECK(whole && win && twin);
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

    /* c) a touched tile keeps its state while in the window and away from
     * it: two fields touched alike step alike, one with the camera a tile
     * away, then far away (the tile leaves the window) and back. */
    const float ball[1][4] = {{3.0f, home[1] - 0.1f, 3.0f, 0.25f}};
    float step[3] = {home[0] + 2.0f, home[1], home[2] + 2.0f};
    for (int f = 0; f < 30; f++) {
        float time = 2.0f + 0.02f * (float)f;
        const collide_set_t *set = f < 10 ? test_sphere_set(ball, 1) : NULL;
        const float *cam = f < 5 ? home : f < 10 ? step : f < 20 ? away : home;
        free(drawn_at(win, cam, time, 0.02f, set, &n0));
        free(drawn_at(twin, home, time, 0.02f, f < 10 ? test_sphere_set(ball, 1) : NULL, &n0));
        if (f == 10) CHECK(blade_tiles_info(win).grid->stats.away >= 1);
    }
    blade_tiles_info_t ti = blade_tiles_info(win), tt = blade_tiles_info(twin);
    blade_tiles_stats_t ws = blade_tiles_stats(win, true);
    CHECK_MSG(ws.detached_total >= 1 && ws.reattached_total >= 1, "left keeping a slot %ld, back %ld",
              ws.detached_total, ws.reattached_total);
    int tile = hybrid_tile_at(ti.grid, 3.0f, 3.0f), tile_twin = hybrid_tile_at(tt.grid, 3.0f, 3.0f);
    CHECK(tile >= 0 && tile_twin >= 0 && ti.grid->tiles[tile].slot >= 0 && tt.grid->tiles[tile_twin].slot >= 0);
    uint32_t B = ti.template_blades;
    blade_t *kept = malloc(B * sizeof *kept), *ref = malloc(B * sizeof *ref);
    blade_tiles_read_slot(win, ti.grid->tiles[tile].slot, kept, NULL);
    blade_tiles_read_slot(twin, tt.grid->tiles[tile_twin].slot, ref, NULL);
    CHECK_MSG(memcmp(kept, ref, B * sizeof *kept) == 0,
              "the touched tile's state changed when it left the window and came back");
    int bent = 0;
    for (uint32_t k = 0; k < B; k++) bent += fabsf(kept[k].v2[1] - kept[k].v1[1]) > 0.02f;
    CHECK_MSG(bent > 0, "the ball bent no blade: the comparison compares nothing");
    free(kept);
    free(ref);

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

    /* e) world terrains */
    size_t world_bytes[2];
    for (int k = 0; k < 2; k++) {
        terrain_mesh_t w;
        CHECK(terrain_make_world(&w, &(terrain_desc_t){.type = TERRAIN_WORLD, .size = k ? 4096.0f : 1024.0f,
                                                       .height = 30.0f},
                                 11));
        blade_tiles_t *wt = make_tiles(&w, 0);
        CHECK(wt);
        if (!wt) break;
        world_bytes[k] = blade_tiles_stats(wt, true).gpu_bytes;
        float x = k ? 1500.0f : 400.0f, z = -0.7f * x;
        float cam[3] = {x, 0.2f + terrain_height_at(&w, x, z, NULL), z};
        uint32_t nw;
        blade_t *b = drawn_at(wt, cam, 1.0f, 0.0f, NULL, &nw);
        float worst = 0.0f, worst_up = 0.0f;
        for (uint32_t i = 0; i < nw; i++) {
            vec3 n;
            worst = fmaxf(worst, fabsf(terrain_height_at(&w, b[i].v0[0], b[i].v0[2], n) - b[i].v0[1]));
            worst_up = fmaxf(worst_up, glm_vec3_distance(n, b[i].up));
        }
        printf("e) %.0f m world: window %d tiles, %u blades drawn, roots vs terrain_height_at %.2g m, up %.2g; "
               "%zu GPU bytes\n",
               w.world.size, blade_tiles_info(wt).desc.window, nw, worst, worst_up, world_bytes[k]);
        CHECK(nw > 1000 && worst < 2e-3f && worst_up < 1e-3f);
        free(b);
        blade_tiles_destroy(wt);
        terrain_free(&w);
    }
    CHECK(world_bytes[0] == world_bytes[1]);
    blade_tiles_destroy(whole);
    blade_tiles_destroy(win);
    blade_tiles_destroy(twin);
    gfx_target_destroy(&target);
    terrain_free(&big);
    terrain_free(&m);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

/* test_hybrid_trail: a trail made in the blade representation survives the
 * camera moving away (the tile turns to billboards) and back (blades again):
 * the tile keeps its simulation slot and its pressed-down blades while it is
 * drawn as billboards, and the blades are still down when it is drawn as
 * blades again. */
#include "app/app_world.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <string.h>

/* Mean tip height over blade height of a slot's real blades. */
static double mean_height(const app_world_t *w, int slot)
{
    uint32_t B = w->tiles.template_blades;
    blade_t *b = malloc(B * sizeof *b);
    blade_tiles_read_slot(&w->tiles, slot, b, NULL);
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

static void run(app_world_t *w, int *frame, int count, const float cam[3])
{
    for (int i = 0; i < count; i++, (*frame)++) {
        memcpy(w->camera, cam, sizeof w->camera);
        app_world_update(w, (float)(*frame + 1) / 60.0f, 1.0f / 60.0f);
    }
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    app_options_t o = {.scene = "scenes/tiny.json", .headless = true, .mode = APP_MODE_HYBRID};
    app_world_t *w = calloc(1, sizeof *w);
    CHECK(app_world_load(w, &o) == 0);
    /* A heavy ball rolls once along z = 0.5 through the tile at (1, 0.5),
     * then leaves the field. */
    scene_path_t *p = &w->scene.colliders[0].path;
    p->count = 3;
    p->keys[0] = (scene_path_key_t){0.0f, {-3.5f, 0.3f, 0.5f}};
    p->keys[1] = (scene_path_key_t){1.5f, {3.5f, 0.3f, 0.5f}};
    p->keys[2] = (scene_path_key_t){1.6f, {30.0f, 0.3f, 30.0f}};
    CHECK(app_world_make_gpu(w));
    CHECK(w->have_tiles);
    int tile = hybrid_tile_at(&w->tiles.grid, 1.0f, 0.5f);
    CHECK(tile >= 0);
    const float near_cam[3] = {1.0f, 1.5f, 2.0f}, far_cam[3] = {0.0f, 30.0f, 60.0f};
    int frame = 0;
    run(w, &frame, 100, near_cam); /* the ball passes */
    const hybrid_tile_t *t = &w->tiles.grid.tiles[tile];
    CHECK(t->rep == HYBRID_REP_BLADE);
    CHECK(t->slot >= 0);
    int slot = t->slot;
    double pressed = mean_height(w, slot);
    run(w, &frame, 20, far_cam); /* away: billboards there */
    CHECK(t->rep == HYBRID_REP_BILLBOARD);
    CHECK_MSG(t->slot == slot, "slot %d -> %d while drawn as billboards", slot, t->slot);
    run(w, &frame, 5, near_cam); /* back: blades again */
    CHECK(t->rep == HYBRID_REP_BLADE && t->slot == slot);
    double back = mean_height(w, slot);
    printf("tile %d slot %d: mean tip height / h after the pass %.3f, after away and back (0.42 s) %.3f\n", tile,
           slot, pressed, back);
    CHECK(pressed < 0.8);
    CHECK(back < 0.9);
    app_world_destroy(w);
    free(w);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

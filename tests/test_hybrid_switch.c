/* test_hybrid_switch: moving the camera across the hybrid switch distance
 * gives no frame-to-frame image jump beyond what the camera motion itself
 * gives. The camera dollies back across the blade/billboard band of
 * scenes/tiny.json (switch distance 4 m) in 48 frames; the largest mean
 * absolute difference between consecutive frames in hybrid mode is compared
 * with the same dolly in blade-only mode (no switch). Both maxima are
 * printed (the per-frame series too). */
#include "measure/measure.h"
#include "world/world_harness.h"
#include "eval/eval.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>

/* The ball parked off the field. */
static void park_ball(scene_desc_t *s, void *user)
{
    (void)user;
    s->colliders[0].path.count = 1;
    glm_vec3_copy((vec3){40.0f, 0.4f, 40.0f}, s->colliders[0].path.keys[0].position);
}

static double max_jump(scene_mode_t mode, double *series)
{
    world_t *w;
    CHECK(world_load(&(world_options_t){.scene = "scenes/tiny.json"}, &w) == 0);
    CHECK(world_setup(w, &(world_setup_t){.mode = mode, .mode_set = true, .tweak = park_ball}));
    CHECK(world_make_gpu(w));
    gfx_target_t t = gfx_target_make(&(gfx_target_desc_t){.w = 128, .h = 96, .samples = 4, .label = "switch"});
    core_image_t prev = {0}, cur = {0};
    double worst = 0;
    for (int f = 0; f < 48; f++) {
        float d = 1.5f + 5.0f * (float)f / 47.0f; /* horizontal distance to the origin: 1.5 .. 6.5 m */
        cam_t cam = {.position = {0.0f, 1.6f, d}, .target = {0.0f, 0.2f, d - 4.0f}, .fov = 60.0f};
        cam_defaults(&cam);
        world_update(w, (float)(f + 1) / 60.0f, 1.0f / 60.0f);
        grass_view_t v;
        world_view_make(&v, &cam, t.w, t.h, (float)(f + 1) / 60.0f, 1.0f / 60.0f);
        gfx_target_bind(&t);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glEnable(GL_DEPTH_TEST);
        world_draw(w, &v, &t);
        CHECK(gfx_target_read(&t, &cur));
        if (prev.px) {
            double m = eval_image_mad(&prev, &cur);
            series[f] = m;
            if (m > worst) worst = m;
        }
        core_image_free(&prev);
        prev = cur;
        memset(&cur, 0, sizeof cur);
    }
    core_image_free(&prev);
    gfx_target_destroy(&t);
    world_destroy(w);
    return worst;
}

/* The first update, before any draw: the tile under the scene's camera is
 * drawn as blades (tiny.json with the camera 0.5 m up over the corner tile
 * [2, 4]^2, within the tile's box, and a switch distance of 1.5 m, so that
 * tile is a billboard tile seen from the origin). It was a billboard tile when the tiles took the
 * origin for the camera until the first draw, and the first frame of
 * meadow_large showed bare ground near the camera. */
static void camera_over_corner(scene_desc_t *s, void *user)
{
    (void)user;
    s->grass.switch_distance = 1.5f;
    glm_vec3_copy((vec3){3.0f, 0.5f, 3.0f}, s->camera.position);
}

static void first_update_near_tiles(void)
{
    world_t *w;
    CHECK(world_load(&(world_options_t){.scene = "scenes/tiny.json"}, &w) == 0);
    CHECK(world_setup(w, &(world_setup_t){.mode = SCENE_MODE_HYBRID, .mode_set = true, .tweak = camera_over_corner}));
    CHECK(world_make_gpu(w));
    world_update(w, 1.0f / 60.0f, 1.0f / 60.0f);
    const hybrid_grid_t *g = blade_tiles_info(measure_drivers(w).tiles).grid;
    int under = hybrid_tile_at(g, 3.0f, 3.0f);
    CHECK(under >= 0);
    printf("first update: tile under the camera drawn as %s\n",
           g->tiles[under].rep == HYBRID_REP_BLADE ? "blades" : "billboards");
    CHECK(g->tiles[under].rep == HYBRID_REP_BLADE);
    world_destroy(w);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    first_update_near_tiles();
    double sh[48] = {0}, sb[48] = {0};
    double hybrid = max_jump(SCENE_MODE_HYBRID, sh);
    double blade = max_jump(SCENE_MODE_BLADE, sb);
    printf("frame-to-frame mean abs difference (x1000), frames 1..47:\n  hybrid:");
    for (int f = 1; f < 48; f++) printf(" %.0f", sh[f] * 1000);
    printf("\n  blade: ");
    for (int f = 1; f < 48; f++) printf(" %.0f", sb[f] * 1000);
    printf("\nmax jump: hybrid %.4f, blade-only %.4f\n", hybrid, blade);
    CHECK(hybrid > 0 && blade > 0);
    CHECK(hybrid <= 1.5 * blade + 0.005);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

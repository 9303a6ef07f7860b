/* test_world_prefetch: every program the world prefetches (the tiles',
 * the billboards' and the ring's, the compute rasterizer's) is taken by
 * the make or the frame's draw that needs it (the canopy match's), in
 * each mode, on a world terrain
 * and on a heightfield, on the compute path: none is built twice and
 * none is left to drop. A prefetch whose desc drifts from its make's (a
 * define, a stage, the objects a collide pass takes) fails here. */
#include "gfx/gfx.h"
#include "test.h"
#include "test_gl.h"
#include "world/world.h"
#include "world/world_harness.h"

static void run(const char *scene, scene_mode_t mode)
{
    gfx_program_stats_t before = gfx_program_stats();
    world_t *w = NULL;
    CHECK(world_load(&(world_options_t){.scene = scene, .width = 160, .height = 90, .mode = mode, .mode_set = true,
                                        .raster = 1 + SCENE_RASTER_COMPUTE},
                     &w) == 0);
    CHECK(w && world_make_gpu(w));
    const scene_desc_t *s = world_info(w).scene;
    gfx_target_t t = gfx_target_make(&(gfx_target_desc_t){.w = 160, .h = 90, .samples = s->msaa, .label = "prefetch"});
    cam_t cam;
    scene_camera_init(s, &cam);
    grass_view_t v;
    world_view_make(&v, &cam, t.w, t.h, 0.0f, 1.0f / 60.0f);
    world_update(w, 1.0f / 60.0f, 1.0f / 60.0f);
    /* a frame's own draw: the canopy match (blades ending in the canopy)
     * runs in those alone */
    gfx_target_bind(&t);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    world_draw(w, &v, &t);
    gfx_program_stats_t after = gfx_program_stats();
    int issued = after.prefetched - before.prefetched, taken = after.taken - before.taken;
    int left = gfx_programs_prefetch_drop();
    printf("%s, %s: %d programs prefetched, %d taken, %d left\n", scene, scene_mode_name(mode), issued, taken, left);
    CHECK(issued > 0);
    CHECK(taken == issued);
    CHECK(left == 0);
    gfx_target_destroy(&t);
    world_destroy(w);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    const char *scenes[] = {"scenes/bench/world_1km.json", "scenes/tiny.json"};
    const scene_mode_t modes[] = {SCENE_MODE_HYBRID, SCENE_MODE_BLADE, SCENE_MODE_BILLBOARD};
    for (int k = 0; k < 2; k++)
        for (int m = 0; m < 3; m++) run(scenes[k], modes[m]);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

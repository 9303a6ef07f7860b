/* test_blade_tiles_render: golden image of the tiled blade field (Fan et
 * al. 2015 tiles over Jahrmann & Wimmer 2017 blades): a 16 m heightfield
 * of 2 m tiles, a ball rolled through it for 2 s; the tiles it touched are
 * simulated (their trail is pressed down, eta decaying slowly), the rest
 * are drawn from the templates in the procedural wind pose. Golden
 * tests/golden/blade_tiles_trail.png (MEADOW_UPDATE_GOLDEN=1). Also prints
 * the GPU memory of a meadow_large-sized field (200 x 200 m, 250
 * blades/m^2, 8 m tiles, switch 25 m) from the buffer sizes, next to the
 * full-field blade_gpu (10.3M blades x (blade_t + eta + survivor index)). */
#include "blade/blade_tiles.h"
#include "collide_test_util.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>

static void memory_report(void)
{
    terrain_mesh_t big = {.grid_res = 256, .grid_size = 200.0f};
    for (int templates = 4; templates <= 8; templates += 4) {
        uint32_t per = 0;
        size_t bytes = blade_tiles_estimate_bytes(&(blade_tiles_desc_t){.terrain = &big, .tile_size = 8.0f,
                                                                        .template_count = templates,
                                                                        .density = 250.0f, .pool_slots = 64,
                                                                        .switch_distance = 25.0f},
                                                  &per);
        printf("memory: 200x200 m, 250 /m^2, 8 m tiles, %d templates of %u blades, 64 slots: %.1f MB\n", templates,
               per, (double)bytes / 1e6);
        CHECK(bytes < 512u * 1000u * 1000u);
    }
    double full = 10.3e6 * (double)(sizeof(blade_t) + 2 * sizeof(float));
    printf("memory: full-field blade_gpu of 10.3M blades: %.1f MB\n", full / 1e6);
}

int main(void)
{
    test_gl_init();
    memory_report();
    terrain_mesh_t m;
    CHECK(terrain_make_heightfield(&m, &(terrain_desc_t){.size = 16.0f, .resolution = 32, .height = 0.3f}, 11));
    blade_tiles_t t;
    blade_tiles_desc_t d = {.terrain = &m, .tile_size = 2.0f, .density = 200.0f, .height_min = 0.25f,
                            .height_max = 0.45f, .width_min = 0.02f, .width_max = 0.035f, .stiffness_min = 8.0f,
                            .stiffness_max = 12.0f, .seed = 5, .pool_slots = 16, .switch_distance = 7.0f};
    d.winds[0] = blade_wind_wave(1.0f, 0.3f, 1.0f, 5.0f, 1.5f);
    d.wind_count = 1;
    CHECK(blade_tiles_make(&t, &d));
    const float eye[3] = {3.2f, 1.5f, 0.9f}, at[3] = {-2.0f, 0.0f, -0.2f};
    float h = 0.35f;
    blade_env_t env = {.gravity = 1.0f, .collision_gain = 1.0f / (0.01f * h * h), .collision_decay = 0.1f};
    for (int f = 0; f < 120; f++) {
        env.time = (float)f / 60.0f;
        env.dt = 1.0f / 60.0f;
        float x = -3.5f + 4.5f * (float)f / 120.0f;
        float ball[1][4] = {{x, terrain_height_at(&m, x, 0.0f, NULL) + 0.3f, 0.0f, 0.45f}};
        blade_tiles_update(&t, eye, test_sphere_set((const float (*)[4])ball, 1), &env);
    }
    gfx_target_t target = gfx_target_make(&(gfx_target_desc_t){.w = 160, .h = 96, .label = "tiles_render.target"});
    mat4 view, proj, vp;
    glm_lookat((float *)eye, (float *)at, (vec3){0, 1, 0}, view);
    glm_perspective(glm_rad(55.0f), 160.0f / 96.0f, 0.05f, 100.0f, proj);
    glm_mat4_mul(proj, view, vp);
    blade_draw_desc_t dd = {.time = env.time};
    memcpy(dd.view_proj, vp, sizeof vp);
    memcpy(dd.camera, eye, sizeof dd.camera);
    gfx_timer_frame_begin();
    gfx_target_bind(&target);
    glClearColor(0.30f, 0.24f, 0.16f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    blade_tiles_draw(&t, &dd);
    core_image_t img = {0};
    CHECK(gfx_target_read(&target, &img));
    blade_tiles_stats_t st = blade_tiles_stats(&t, true);
    printf("render: tiles %d (blade rep %d, drawn %d), active %d, recovering %d, slots %d/%d, blades drawn %u, "
           "GPU %.1f MB\n",
           st.tiles, st.blade_tiles, st.tiles_drawn, st.active, st.recovering, st.slots_used, st.slots_total,
           st.blades_drawn, (double)st.gpu_bytes / 1e6);
    CHECK(st.slots_used >= 4 && st.pool_denied == 0);
    CHECK(st.blades_drawn > 3000 && st.draw_overflow == 0);
    CHECK(gfx_memory_bytes() >= st.gpu_bytes);
    CHECK(test_image_check(&img, "blade_tiles_trail", NULL));
    core_image_free(&img);
    gfx_target_destroy(&target);
    blade_tiles_destroy(&t);
    terrain_free(&m);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

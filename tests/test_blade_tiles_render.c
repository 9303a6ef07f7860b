/* test_blade_tiles_render: golden image of the tiled blade field (Fan et
 * al. 2015 tiles over Jahrmann & Wimmer 2017 blades): a 16 m heightfield
 * of 2 m tiles, a ball rolled through it for 2 s; the tiles it touched are
 * simulated (their trail is pressed down, eta decaying slowly), the rest
 * are drawn from the templates in the procedural wind pose. Golden
 * tests/golden/blade_tiles_trail.png (MEADOW_UPDATE_GOLDEN=1). The same
 * field drawn through the tessellation stages (blade_tiles_desc_t.tessellate)
 * against the pulled strips, with and without the fade band: same blades,
 * same covered share to 0.01, image difference within a mean of 0.1 level
 * and 0.1 % of pixels over 24 levels (both paths build blade_lod segments:
 * measured mean 0.001, max 13, no pixel over 24). Also prints
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
        size_t bytes = blade_tiles_estimate_bytes(&(blade_tiles_desc_t){.terrain = &big,
                                                                        .tile_size = 8.0f,
                                                                        .template_count = templates,
                                                                        .population = {.density = 250.0f},
                                                                        .pool_slots = 64,
                                                                        .switch_distance = 25.0f},
                                                  &per);
        printf("memory: 200x200 m, 250 /m^2, 8 m tiles, %d templates of %u blades, 64 slots: %.1f MB\n", templates,
               per, (double)bytes / 1e6);
        CHECK(bytes < 512u * 1000u * 1000u);
    }
    double full = 10.3e6 * (double)(sizeof(blade_t) + 2 * sizeof(float));
    printf("memory: full-field blade_gpu of 10.3M blades: %.1f MB\n", full / 1e6);
}

/* The field of the golden, drawn by `tessellate`'s path, after `frames`
 * updates with the ball rolling from x = -3.5 m at `speed` m per frame. */
static blade_tiles_t *make_field(const terrain_mesh_t *m, bool tessellate, float density, const float eye[3],
                                 int frames, float speed, blade_env_t *env)
{
    blade_tiles_desc_t d = {.terrain = m,
                            .tile_size = 2.0f,
                            .population = {.density = density,
                                           .height = {0.25f, 0.45f},
                                           .width = {0.02f, 0.035f},
                                           .stiffness = {8.0f, 12.0f}},
                            .seed = 5,
                            .pool_slots = 16,
                            .switch_distance = 7.0f,
                            .tessellate = tessellate};
    d.winds[0] = blade_wind_wave(1.0f, 0.3f, 1.0f, 5.0f, 1.5f);
    d.wind_count = 1;
    blade_tiles_t *t = blade_tiles_make(&d);
    CHECK(t);
    float h = 0.35f;
    *env = (blade_env_t){.gravity = 1.0f, .collision_gain = 1.0f / (0.01f * h * h), .collision_decay = 0.1f};
    for (int f = 0; t && f < frames; f++) {
        env->time = (float)f / 60.0f;
        env->dt = 1.0f / 60.0f;
        float x = -3.5f + speed * (float)f;
        float ball[1][4] = {{x, terrain_height_at(m, x, 0.0f, NULL) + 0.3f, 0.0f, 0.45f}};
        blade_tiles_update(t, eye, test_sphere_set((const float (*)[4])ball, 1), env);
    }
    return t;
}

/* One frame of t into target (cleared to soil), read back into img; a
 * fade band when fade_end > fade_start. */
static void render(blade_tiles_t *t, const gfx_target_t *target, const float eye[3], const float at[3], float time,
                   float fade_start, float fade_end, core_image_t *img)
{
    mat4 view, proj, vp;
    glm_lookat((float *)eye, (float *)at, (vec3){0, 1, 0}, view);
    glm_perspective(glm_rad(55.0f), (float)target->w / (float)target->h, 0.05f, 100.0f, proj);
    glm_mat4_mul(proj, view, vp);
    blade_draw_desc_t dd = {.view.time = time, .fade_start = fade_start, .fade_end = fade_end};
    memcpy(dd.view.viewproj, vp, sizeof vp);
    memcpy(dd.view.camera, eye, sizeof dd.view.camera);
    gfx_timer_frame_begin();
    gfx_target_bind(target);
    glClearColor(0.30f, 0.24f, 0.16f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    blade_tiles_draw(t, &dd, 0);
    CHECK(gfx_target_read(target, img));
}

/* Share of the pixels the grass covers: any channel more than 8 levels
 * from the soil that render() clears to. */
static double covered(const core_image_t *img)
{
    static const int soil[3] = {77, 61, 41};
    long n = 0;
    for (size_t i = 0; i < (size_t)img->w * (size_t)img->h; i++) {
        const uint8_t *p = &img->px[4 * i];
        n += abs(p[0] - soil[0]) > 8 || abs(p[1] - soil[1]) > 8 || abs(p[2] - soil[2]) > 8;
    }
    return (double)n / ((double)img->w * (double)img->h);
}

/* The tessellated tiles against the pulled ones, with and without the
 * fade band (two indirect draws, the BLADE_FADE program's sample mask).
 * The ball rests on the field for 0.5 s: its tiles stay active, so both
 * fields hold the same state (a rolling ball's tiles are released by the
 * motion read back whenever the copy is ready, which differs between two
 * fields), with slots and idle tiles in view. A third of the golden's
 * density: llvmpipe (Mesa 22.3) draws garbage from about 2,100 to 3,000
 * patches per draw on (5,486 blades in one draw: mean difference 5.5,
 * 15 % of pixels failing; the same draw cut into draws of at most 2,048
 * patches: mean 0.001, max 6), so every draw here stays below 2,048. */
static void compare_paths(const terrain_mesh_t *m, const gfx_target_t *target, const float eye[3], const float at[3])
{
    blade_env_t env;
    double t0 = plat_time();
    blade_tiles_t *pull = make_field(m, false, 64.0f, eye, 30, 0.0f, &env);
    blade_tiles_t *tess = make_field(m, true, 64.0f, eye, 30, 0.0f, &env);
    static const float fades[2][2] = {{0.0f, 0.0f}, {3.0f, 5.0f}};
    for (int f = 0; f < 2; f++) {
        core_image_t a = {0}, b = {0};
        render(pull, target, eye, at, env.time, fades[f][0], fades[f][1], &a);
        render(tess, target, eye, at, env.time, fades[f][0], fades[f][1], &b);
        blade_tiles_stats_t sp = blade_tiles_stats(pull, true), st = blade_tiles_stats(tess, true);
        double grass_a = covered(&a), grass_b = covered(&b);
        test_image_result_t r = test_image_diff(&a, &b, &(test_image_cmp_t){.mean_threshold = 0.1,
                                                                           .fail_budget = 0.001},
                                                NULL);
        printf("tess vs pull%s: blades %u / %u, covered %.4f / %.4f, mean diff %.3f, max %d, failing pixels "
               "(> 24) %.4f\n",
               f ? " (fade 3-5 m)" : "", st.blades_drawn, sp.blades_drawn, grass_b, grass_a, r.mean_diff,
               r.max_diff, r.fail_fraction);
        CHECK(st.blades_drawn == sp.blades_drawn && st.blades_drawn > 1000 && st.blades_drawn <= 2048);
        CHECK(grass_a > 0.1 && fabs(grass_a - grass_b) < 0.01);
        CHECK(r.pass);
        core_image_free(&a);
        core_image_free(&b);
    }
    printf("tess vs pull: %.2f s\n", plat_time() - t0);
    blade_tiles_destroy(pull);
    blade_tiles_destroy(tess);
}

int main(void)
{
    test_gl_init();
    memory_report();
    terrain_mesh_t m;
    CHECK(terrain_make_heightfield(&m, &(terrain_desc_t){.size = 16.0f, .resolution = 32, .height = 0.3f}, 11));
    blade_env_t env;
    const float eye[3] = {3.2f, 1.5f, 0.9f}, at[3] = {-2.0f, 0.0f, -0.2f};
    blade_tiles_t *t = make_field(&m, false, 200.0f, eye, 120, 4.5f / 120.0f, &env);
    gfx_target_t target = gfx_target_make(&(gfx_target_desc_t){.w = 160, .h = 96, .label = "tiles_render.target"});
    core_image_t img = {0};
    render(t, &target, eye, at, env.time, 0.0f, 0.0f, &img);
    blade_tiles_stats_t st = blade_tiles_stats(t, true);
    printf("render: tiles %d (blade rep %d, drawn %d), active %d, recovering %d, slots %d/%d, blades drawn %u, "
           "GPU %.1f MB\n",
           st.tiles, st.blade_tiles, st.tiles_drawn, st.active, st.recovering, st.slots_used, st.slots_total,
           st.blades_drawn, (double)st.gpu_bytes / 1e6);
    CHECK(st.slots_used >= 4 && st.pool_denied == 0);
    CHECK(st.blades_drawn > 3000 && st.draw_overflow == 0);
    CHECK(gfx_memory_bytes() >= st.gpu_bytes);
    CHECK(test_image_check(&img, "blade_tiles_trail", NULL));
    core_image_free(&img);
    compare_paths(&m, &target, eye, at);
    gfx_target_destroy(&target);
    blade_tiles_destroy(t);
    terrain_free(&m);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

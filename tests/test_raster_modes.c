/* test_raster_modes: the compute rasterizer draws the same grass as the
 * hardware path. scenes/tiny.json with 4x MSAA at 512x288, in billboard,
 * blade and hybrid modes, once per path (same seed, time and camera): the
 * grass covers the same share of the image, its mean colour agrees, and
 * the images agree pixel by pixel on average (grass blades are thin, so
 * single pixels may differ at edges: the check is on means), and the ball
 * (drawn by the hardware in both) shows the same number of pixels: grass in
 * front of it hides it and it hides the grass behind it alike. Then
 * scenes/meadow.json at its 1280x720 (hybrid, characters; at 320x180 the
 * sub-pixel blades alias differently on the two sample patterns and 1 - SSIM
 * is 0.11, at 640x360 0.065): 1 - SSIM at most 0.05
 * and a mean absolute channel difference of at most 3 (of 255). Writes
 * every image to the test output folder. Also: the frame target fits the
 * rasterizer (world_fit_target). The two images of a pair are never
 * identical (different sample patterns): identical ones mean one path drew
 * both, as when the pair asked for auto and hw (llvmpipe's auto is hw). */
#include "app/app.h"
#include "measure/measure_session.h"
#include "eval/eval.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <string.h>

static bool is_ball(const uint8_t *p)
{
    return p[0] > p[1] + 60 && p[0] > p[2] + 60;
}

/* Pixels of the red ball in a, and pixels that are ball in one image only. */
static int ball_pixels(const core_image_t *a, const core_image_t *b, int *differ)
{
    int n = 0;
    *differ = 0;
    for (size_t i = 0; i < (size_t)a->w * (size_t)a->h; i++) {
        n += is_ball(a->px + i * 4);
        *differ += is_ball(a->px + i * 4) != is_ball(b->px + i * 4);
    }
    return n;
}

/* Renders the scene both ways; img[0] hardware, img[1] compute. */
static void render_pair(const char *scene, scene_mode_t mode, bool mode_set, int frames,
                        void (*tweak)(scene_desc_t *, void *), core_image_t img[2])
{
    for (int r = 0; r < 2; r++) {
        app_options_t o = {.scene = scene, .headless = true,
                           .raster = 1 + (r ? SCENE_RASTER_COMPUTE : SCENE_RASTER_HW)};
        measure_session_desc_t d = {.world = app_world_options(&o),
                                    .mode = mode, .mode_set = mode_set, .frames = frames, .tweak = tweak};
        CHECK(measure_session_run(&d, &img[r], NULL) == 0);
        char path[1200];
        const char *base = strrchr(scene, '/') ? strrchr(scene, '/') + 1 : scene;
        snprintf(path, sizeof path, "%s/%.*s_%s_%s.png", test_out_dir(), (int)strcspn(base, "."), base,
                 scene_mode_name(mode), r ? "compute" : "hw");
        core_image_write_png(&img[r], path);
    }
}

/* 4x MSAA at 512x288. */
static void msaa4(scene_desc_t *s, void *user)
{
    (void)user;
    s->msaa = 4;
    s->size[0] = 512;
    s->size[1] = 288;
}


/* world_fit_target: single-sampled with the compute rasterizer, the
 * scene's msaa (16 here: clamped to the GL's maximum) with the hardware
 * path, and a target that fits is kept, not remade each frame. */
static void check_fit_target(void)
{
    world_t *w;
    CHECK(world_load(&(world_options_t){.scene = "scenes/tiny.json"}, &w) == 0);
    CHECK(world_setup(w, &(world_setup_t){.msaa = 16}));
    for (int r = 0; r < 2; r++) {
        world_set_raster(w, r == 1);
        gfx_target_t t = {.w = 64, .h = 32};
        CHECK(world_fit_target(w, &t, "fit"));
        CHECK_MSG(t.samples == (r ? 1 : gfx_target_samples(16)), "%s path: %d samples", r ? "compute" : "hw",
                  t.samples);
        long made = gfx_objects_made();
        CHECK(world_fit_target(w, &t, "fit") && world_fit_target(w, &t, "fit"));
        CHECK_MSG(gfx_objects_made() == made, "%s path: a fitting target was remade", r ? "compute" : "hw");
        world_set_raster(w, r == 0);
        CHECK(world_fit_target(w, &t, "fit") && gfx_objects_made() > made);
        gfx_target_destroy(&t);
    }
    world_destroy(w);
    printf("fit target: hardware %d samples, compute 1; kept while it fits\n", gfx_target_samples(16));
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    check_fit_target();
    static const scene_mode_t modes[3] = {SCENE_MODE_BILLBOARD, SCENE_MODE_BLADE, SCENE_MODE_HYBRID};
    for (int m = 0; m < 3; m++) {
        core_image_t img[2];
        double cov[2], rgb[2][3];
        render_pair("scenes/tiny.json", modes[m], true, 6, msaa4, img);
        for (int r = 0; r < 2; r++) cov[r] = test_grass_pixels(&img[r], rgb[r]);
        int differ, ball = ball_pixels(&img[0], &img[1], &differ);
        printf("%-9s ball pixels %d, ball in one image only %d\n", scene_mode_name(modes[m]), ball, differ);
        CHECK(ball > 300 && differ <= ball / 10);
        double dcol = fabs(rgb[0][0] - rgb[1][0]) + fabs(rgb[0][1] - rgb[1][1]) + fabs(rgb[0][2] - rgb[1][2]);
        test_image_result_t diff = test_image_diff(&img[0], &img[1], &(test_image_cmp_t){0}, NULL);
        printf("%-9s grass share hw %.3f compute %.3f, grass colour L1 %.3f, mean channel difference %.2f\n",
               scene_mode_name(modes[m]), cov[0], cov[1], dcol, diff.mean_diff);
        CHECK(cov[0] > 0.05 && cov[1] > 0.05);
        CHECK(fabs(cov[1] / cov[0] - 1.0) < 0.1);
        CHECK(dcol < 0.03);
        CHECK(diff.mean_diff < 5.0);
        CHECK_MSG(diff.mean_diff > 0.0, "%s: identical images, one path drew both", scene_mode_name(modes[m]));
        core_image_free(&img[0]);
        core_image_free(&img[1]);
    }
    core_image_t img[2];
    render_pair("scenes/meadow.json", SCENE_MODE_HYBRID, false, 8, NULL, img);
    double dssim = 1.0 - eval_image_ssim(&img[0], &img[1]);
    test_image_result_t diff = test_image_diff(&img[0], &img[1], &(test_image_cmp_t){0}, NULL);
    printf("meadow.json (1280x720): 1 - SSIM %.4f, mean channel difference %.2f\n", dssim, diff.mean_diff);
    CHECK(dssim <= 0.05);
    CHECK(diff.mean_diff <= 3.0);
    core_image_free(&img[0]);
    core_image_free(&img[1]);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

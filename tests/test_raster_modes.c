/* test_raster_modes: the compute rasterizer draws the same grass as the
 * hardware path. scenes/tiny.json with 4x MSAA at 256x144, in billboard,
 * blade and hybrid modes, once per path (same seed, time and camera): the
 * grass covers the same share of the image, its mean colour agrees, and
 * the images agree pixel by pixel on average (grass blades are thin, so
 * single pixels may differ at edges: the check is on means). Writes both
 * images to the test output folder. */
#include "app/app_world.h"
#include "bench/bench.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <string.h>

static void msaa4(scene_desc_t *s, void *user)
{
    (void)user;
    s->msaa = 4;
    s->size[0] = 256;
    s->size[1] = 144;
}

/* Share of grass pixels (green clearly above red) and their mean colour. */
static double grass(const core_image_t *img, double rgb[3])
{
    double n = 0.0;
    rgb[0] = rgb[1] = rgb[2] = 0.0;
    for (size_t i = 0; i < (size_t)img->w * (size_t)img->h; i++) {
        const uint8_t *p = img->px + i * 4;
        if (p[1] <= p[0] + 25) continue;
        for (int k = 0; k < 3; k++) rgb[k] += p[k] / 255.0;
        n += 1.0;
    }
    for (int k = 0; k < 3; k++) rgb[k] /= n > 0.0 ? n : 1.0;
    return n / ((double)img->w * img->h);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    static const scene_mode_t modes[3] = {SCENE_MODE_BILLBOARD, SCENE_MODE_BLADE, SCENE_MODE_HYBRID};
    for (int m = 0; m < 3; m++) {
        core_image_t img[2];
        double cov[2], rgb[2][3];
        for (int r = 0; r < 2; r++) {
            app_options_t o = {.scene = "scenes/tiny.json", .headless = true, .raster = 1 + r};
            bench_session_desc_t d = {.opts = &o, .mode = modes[m], .mode_set = true, .frames = 6, .tweak = msaa4};
            CHECK(bench_session_run(&d, &img[r], NULL) == 0);
            cov[r] = grass(&img[r], rgb[r]);
            char path[1200];
            snprintf(path, sizeof path, "%s/%s_%s.png", test_out_dir(), scene_mode_name(modes[m]), r ? "compute" : "hw");
            core_image_write_png(&img[r], path);
        }
        double dcol = fabs(rgb[0][0] - rgb[1][0]) + fabs(rgb[0][1] - rgb[1][1]) + fabs(rgb[0][2] - rgb[1][2]);
        test_image_result_t diff = test_image_diff(&img[0], &img[1], &(test_image_cmp_t){0}, NULL);
        printf("%-9s grass share hw %.3f compute %.3f, grass colour L1 %.3f, mean channel difference %.2f\n",
               scene_mode_name(modes[m]), cov[0], cov[1], dcol, diff.mean_diff);
        CHECK(cov[0] > 0.05 && cov[1] > 0.05);
        CHECK(fabs(cov[1] / cov[0] - 1.0) < 0.1);
        CHECK(dcol < 0.03);
        CHECK(diff.mean_diff < 5.0);
        core_image_free(&img[0]);
        core_image_free(&img[1]);
    }
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

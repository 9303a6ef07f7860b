/* test_app_golden: the whole program renders scenes/tiny.json headless at a
 * fixed seed, time, camera and size; the frame matches the golden image, and
 * a second run gives a byte-identical frame (determinism); every pixel is
 * drawn (new targets start magenta). It skips only when
 * no GL 4.5 context can be made; once one can, any non-zero exit of app_run
 * (renderer failure, GL errors) fails the test. */
#include "app/app.h"
#include "test.h"
#include "test_gl.h"

#include <stdlib.h>
#include <string.h>

static bool render(const char *dir, core_image_t *img)
{
    /* new targets start magenta (gfx_desc_t.poison): a pixel the frame does
     * not draw (world_frame clears only the depth) fails the golden */
    setenv("MEADOW_GFX_POISON", "1", 1);
    char frames[] = "4", size[] = "160x96", every[] = "4", out[512], mode[] = "hybrid";
    snprintf(out, sizeof out, "%s", dir);
    char *argv[] = {"meadow", "--headless", "--quiet", "--scene", "scenes/tiny.json", "--frames", frames,
                    "--size", size, "--screenshot-every", every, "--mode", mode, "--out", out,
                    "--raster", "hw"}; /* the goldens are the hardware path's (the default, auto, measures) */
    app_options_t o;
    char err[256];
    if (app_parse_args((int)(sizeof argv / sizeof argv[0]), argv, &o, err, sizeof err) != 0) return false;
    int rc = app_run(&o, NULL);
    if (rc != 0) {
        fprintf(stderr, "app_run exited %d\n", rc);
        return false;
    }
    char path[600];
    snprintf(path, sizeof path, "%s/shot-000004.png", dir);
    return core_image_load(img, path, 4);
}

int main(void)
{
    test_gl_require_context();
    char a[400], b[400];
    snprintf(a, sizeof a, "%s/run-a", test_out_dir());
    snprintf(b, sizeof b, "%s/run-b", test_out_dir());
    core_image_t ia, ib;
    CHECK(render(a, &ia));
    CHECK(render(b, &ib));
    CHECK(ia.w == 160 && ia.h == 96);
    CHECK(ia.px && ib.px && memcmp(ia.px, ib.px, (size_t)ia.w * (size_t)ia.h * 4) == 0);
    CHECK(test_image_check(&ia, "app_tiny", NULL));
    core_image_free(&ia);
    core_image_free(&ib);
    TEST_END();
}

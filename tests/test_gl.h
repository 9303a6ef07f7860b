/* test_gl: shared kit for GL tests: a headless EGL context (skip with exit 77
 * when none exists), leak and GL-error checks at shutdown, and the golden
 * image comparison (per-pixel threshold, mean threshold, failing-pixel
 * budget; writes actual.png and diff.png on failure; MEADOW_UPDATE_GOLDEN=1
 * rewrites the golden). */
#ifndef MEADOW_TEST_GL_H
#define MEADOW_TEST_GL_H

#include "core/core.h"
#include "gfx/gfx.h"
#include "platform/plat.h"

/* Creates the context (EGL, debug callback on) and gfx; exits 77 if no GL
 * 4.5 context can be made. */
void test_gl_init(void);
/* For tests that make their own context (through app_run): creates and
 * destroys one EGL context, and exits 77 if none can be made. After it, a
 * failure to render is a failure, not a skip. */
void test_gl_require_context(void);
/* Returns the number of problems: GL errors seen, objects still alive. */
int test_gl_shutdown(void);

typedef struct test_image_cmp_t {
    int pixel_threshold;   /* a pixel fails if any channel differs by more; default 24 */
    double mean_threshold; /* mean absolute channel difference bound; default 2.0 */
    double fail_budget;    /* allowed fraction of failing pixels; default 0.01 */
} test_image_cmp_t;

typedef struct test_image_result_t {
    double mean_diff;
    double fail_fraction;
    int max_diff;
    bool pass;
} test_image_result_t;

/* Compares two same-size RGBA images. */
test_image_result_t test_image_diff(const core_image_t *a, const core_image_t *b, const test_image_cmp_t *cmp,
                                    core_image_t *diff_out);
/* Compares against tests/golden/<name>.png. Returns true on pass. */
bool test_image_check(const core_image_t *actual, const char *name, const test_image_cmp_t *cmp);
/* Grass pixels of an RGBA image (green clearly above red, as the grass
 * and not the soil or sky): their share of the image, and their mean
 * colour (0..1) in rgb. */
double test_grass_pixels(const core_image_t *img, double rgb[3]);
/* Directory for test artefacts ($MEADOW_TEST_OUT or /tmp/meadow-test). */
const char *test_out_dir(void);

#endif

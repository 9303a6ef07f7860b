/* test_gl: implementation of the shared GL test kit (see test_gl.h). */
#include "test_gl.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void make_context(void)
{
    char err[1024];
    plat_desc_t desc = {.backend = PLAT_BACKEND_EGL, .width = 256, .height = 256, .debug = true};
    if (!plat_init(&desc, err, sizeof err)) {
        fprintf(stderr, "SKIP: no GL 4.5 context: %s\n", err);
        exit(77);
    }
}

void test_gl_init(void)
{
    make_context();
    plat_install_debug_callback();
    gfx_init_desc(&(gfx_desc_t){.poison = true});
}

void test_gl_require_context(void)
{
    make_context();
    plat_shutdown();
}

int test_gl_shutdown(void)
{
    int problems = 0;
    if (gfx_live_objects() != 0) {
        fprintf(stderr, "test_gl: %d GL object(s) still alive\n", gfx_live_objects());
        problems++;
    }
    gfx_shutdown(true);
    if (plat_gl_error_count() != 0) {
        fprintf(stderr, "test_gl: %d GL error(s) reported by the driver\n", plat_gl_error_count());
        problems++;
    }
    plat_shutdown();
    return problems;
}

const char *test_out_dir(void)
{
    const char *d = getenv("MEADOW_TEST_OUT");
    d = d && *d ? d : "/tmp/meadow-test";
    core_fs_mkdirs(d);
    return d;
}

static int iabs(int x) { return x < 0 ? -x : x; }

test_image_result_t test_image_diff(const core_image_t *a, const core_image_t *b, const test_image_cmp_t *cmp_in,
                                    core_image_t *diff_out)
{
    test_image_cmp_t cmp = cmp_in ? *cmp_in : (test_image_cmp_t){0};
    if (!cmp.pixel_threshold) cmp.pixel_threshold = 24;
    if (cmp.mean_threshold == 0) cmp.mean_threshold = 2.0;
    if (cmp.fail_budget == 0) cmp.fail_budget = 0.01;
    test_image_result_t r = {0};
    if (a->w != b->w || a->h != b->h || a->channels != 4 || b->channels != 4) {
        fprintf(stderr, "test_image: size mismatch %dx%dx%d vs %dx%dx%d\n", a->w, a->h, a->channels, b->w, b->h,
                b->channels);
        r.mean_diff = 255;
        r.fail_fraction = 1;
        return r;
    }
    if (diff_out) core_image_alloc(diff_out, a->w, a->h, 4);
    size_t n = (size_t)a->w * (size_t)a->h, fails = 0;
    double sum = 0;
    for (size_t i = 0; i < n; i++) {
        int m = 0;
        for (int c = 0; c < 3; c++) {
            int d = iabs((int)a->px[i * 4 + c] - (int)b->px[i * 4 + c]);
            sum += d;
            if (d > m) m = d;
        }
        if (m > r.max_diff) r.max_diff = m;
        if (m > cmp.pixel_threshold) fails++;
        if (diff_out && diff_out->px) {
            uint8_t v = (uint8_t)(m * 4 > 255 ? 255 : m * 4);
            diff_out->px[i * 4 + 0] = v;
            diff_out->px[i * 4 + 1] = m > cmp.pixel_threshold ? 0 : v / 2;
            diff_out->px[i * 4 + 2] = m > cmp.pixel_threshold ? 0 : v / 2;
            diff_out->px[i * 4 + 3] = 255;
        }
    }
    r.mean_diff = sum / (double)(n * 3);
    r.fail_fraction = (double)fails / (double)n;
    r.pass = r.mean_diff <= cmp.mean_threshold && r.fail_fraction <= cmp.fail_budget;
    return r;
}

bool test_image_check(const core_image_t *actual, const char *name, const test_image_cmp_t *cmp)
{
    char rel[256], golden[1024], path[1024];
    snprintf(rel, sizeof rel, "tests/golden/%s.png", name);
    bool have = core_fs_resolve(rel, golden, sizeof golden);
    const char *upd = getenv("MEADOW_UPDATE_GOLDEN");
    if (upd && *upd == '1') {
        snprintf(golden, sizeof golden, "%s/%s", MEADOW_SOURCE_DIR, rel);
        bool ok = core_image_write_png(actual, golden);
        fprintf(stderr, "test_image: golden %s %s\n", golden, ok ? "updated" : "NOT written");
        return ok;
    }
    snprintf(path, sizeof path, "%s/%s.actual.png", test_out_dir(), name);
    core_image_write_png(actual, path);
    if (!have) {
        fprintf(stderr, "test_image: no golden %s (set MEADOW_UPDATE_GOLDEN=1 to create it); actual in %s\n", rel,
                path);
        return false;
    }
    core_image_t gold, diff = {0};
    if (!core_image_load(&gold, golden, 4)) return false;
    test_image_result_t r = test_image_diff(actual, &gold, cmp, &diff);
    fprintf(stderr, "test_image: %s: mean %.3f, failing %.4f%%, max %d -> %s\n", name, r.mean_diff,
            r.fail_fraction * 100.0, r.max_diff, r.pass ? "pass" : "FAIL");
    if (!r.pass && diff.px) {
        snprintf(path, sizeof path, "%s/%s.diff.png", test_out_dir(), name);
        core_image_write_png(&diff, path);
        fprintf(stderr, "test_image: wrote %s/%s.actual.png and %s\n", test_out_dir(), name, path);
    }
    core_image_free(&gold);
    core_image_free(&diff);
    return r.pass;
}

double test_grass_pixels(const core_image_t *img, double rgb[3])
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

/* test_bb_gpu_gi: the billboards' global illumination end to end, on both
 * rasterizer paths (bb_quad.vert + bb_render.frag, bb_raster.comp): a
 * field compiled with it (desc.gi) and lit by a neutral volume (a constant
 * sky AMBIENT_UP over open ground, bounce AMBIENT_DOWN: exactly the
 * hemispheric ambient, per vertex instead of per fragment) draws the image
 * it draws with GI off, to a small mean; lit by a dark volume (no sky, no
 * bounce) it draws a clearly darker one. Fails when a path drops the
 * per-vertex ambient. */
#include "test.h"
#include "test_gl.h"

#include "bb_gpu_test_util.h"
#include "gi_test_util.h"

static void draw(bb_field_t *f, const gfx_target_t *tgt, raster_t *r, const gi_bind_t *gi, core_image_t *out)
{
    mat4 vp;
    vec3 eye = {0.0f, 4.5f, 4.0f};
    test_view(eye, vp);
    bb_draw_desc_t d = test_draw_desc(vp, eye, 0.5f);
    d.gi = *gi;
    test_draw_path(f, tgt, r, &d);
    CHECK(gfx_target_read(tgt, out));
}

static double mean(const core_image_t *img)
{
    double s = 0.0;
    for (int i = 0; i < img->w * img->h; i++) s += img->px[4 * i] + img->px[4 * i + 1] + img->px[4 * i + 2];
    return s / (3.0 * img->w * img->h);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    terrain_mesh_t terrain;
    bb_field_desc_t desc;
    CHECK(test_small_field(&terrain, &desc));
    desc.gi = true;
    bb_field_t *f = bb_field_make(&desc);
    CHECK(f);
    gfx_target_t tgt = gfx_target_make(&(gfx_target_desc_t){.w = 192, .h = 128, .samples = 4, .label = "bb.test"});
    raster_t r;
    CHECK(raster_make(&r, &(raster_desc_t){.w = 192, .h = 128}));
    const float up[3] = GI_AMBIENT_UP, down[3] = GI_AMBIENT_DOWN, black[3] = {1e-6f, 1e-6f, 1e-6f};
    gi_gpu_t neutral, dark;
    const float lo[3] = {-5.0f, -1.0f, -5.0f}, hi[3] = {5.0f, 2.0f, 5.0f};
    CHECK(test_gi_sky(&neutral, lo, hi, up, down));
    CHECK(test_gi_sky(&dark, lo, hi, black, black));
    gi_bind_t off = {0}, b_neutral = gi_gpu_bind(&neutral), b_dark = gi_gpu_bind(&dark);
    for (int path = 0; path < 2; path++) {
        raster_t *rp = path ? &r : NULL;
        core_image_t a, b, c;
        draw(f, &tgt, rp, &off, &a);
        draw(f, &tgt, rp, &b_neutral, &b);
        draw(f, &tgt, rp, &b_dark, &c);
        test_image_result_t same = test_image_diff(&a, &b, &(test_image_cmp_t){0}, NULL);
        printf("%s: GI off mean %.2f; neutral volume %.2f (mean diff %.3f, max %d); dark volume %.2f\n",
               path ? "compute" : "hardware", mean(&a), mean(&b), same.mean_diff, same.max_diff, mean(&c));
        CHECK(same.mean_diff < 0.5);
        CHECK(mean(&c) < mean(&a) - 5.0);
        core_image_free(&a);
        core_image_free(&b);
        core_image_free(&c);
    }
    gi_gpu_destroy(&neutral);
    gi_gpu_destroy(&dark);
    raster_destroy(&r);
    gfx_target_destroy(&tgt);
    bb_field_destroy(f);
    terrain_free(&terrain);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

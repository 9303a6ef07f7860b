/* test_bb_gpu_occlusion: occlusion culling of billboard batches (Orthmann
 * et al. 2009 sec. 6; bb_occlude.c). A field with it on draws the same
 * image as the same field with it off and skips no leaf while nothing hides
 * it; behind a wall (the depth buffer cleared to 0.05 before the draw:
 * everything is nearer) its leaves' boxes pass no sample and the next draws
 * skip every leaf in the frustum; once the wall is gone the skipped leaves
 * come back within three draws, image equal to the reference again. */
#include "test.h"
#include "test_gl.h"

#include "bb_gpu_test_util.h"

#include <string.h>

static void draw(bb_field_t *f, const gfx_target_t *tgt, const mat4 vp, const vec3 eye, float clear_depth)
{
    bb_draw_desc_t d = test_draw_desc(vp, eye, 0.5f);
    gfx_target_bind(tgt);
    glClearColor(0.33f, 0.27f, 0.2f, 1.0f);
    glClearDepth(clear_depth);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glClearDepth(1.0);
    gfx_timer_frame_begin();
    bb_field_draw(f, &d);
    glFinish();
}

static int max_diff(const core_image_t *a, const core_image_t *b)
{
    int m = 0;
    for (int i = 0; i < 4 * a->w * a->h; i++) m = abs(a->px[i] - b->px[i]) > m ? abs(a->px[i] - b->px[i]) : m;
    return m;
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    terrain_mesh_t terrain;
    bb_field_desc_t desc;
    CHECK(test_small_field(&terrain, &desc));
    bb_field_t *plain = bb_field_make(&desc);
    CHECK(plain);
    desc.occlusion = true;
    bb_field_t *culled = bb_field_make(&desc);
    CHECK(culled);
    gfx_target_t tgt = gfx_target_make(&(gfx_target_desc_t){.w = 192, .h = 128, .samples = 4, .label = "bb.test"});
    mat4 vp;
    vec3 eye = {0.0f, 4.5f, 4.0f};
    test_view(eye, vp);

    core_image_t ref, img;
    draw(plain, &tgt, vp, eye, 1.0f);
    CHECK(gfx_target_read(&tgt, &ref));
    bb_stats_t st;
    for (int frame = 0; frame < 3; frame++) {
        draw(culled, &tgt, vp, eye, 1.0f);
        bb_field_stats(culled, true, &st);
        CHECK(st.occluded == 0);
    }
    CHECK(gfx_target_read(&tgt, &img));
    CHECK(max_diff(&img, &ref) == 0);
    core_image_free(&img);

    int hidden = 0;
    for (int frame = 0; frame < 3; frame++) {
        draw(culled, &tgt, vp, eye, 0.05f);
        bb_field_stats(culled, true, &st);
        hidden = st.occluded > hidden ? st.occluded : hidden;
    }
    int leaves = st.occlusion_hidden;
    printf("behind the wall: %d leaves skipped by a draw, %d hidden\n", hidden, leaves);
    CHECK(hidden > 10);
    CHECK(hidden == leaves);

    int back = -1;
    for (int frame = 0; frame < 3 && back < 0; frame++) {
        draw(culled, &tgt, vp, eye, 1.0f);
        CHECK(gfx_target_read(&tgt, &img));
        if (max_diff(&img, &ref) == 0) back = frame + 1;
        core_image_free(&img);
    }
    printf("wall gone: the image is the reference again after %d draws\n", back);
    CHECK(back > 0);

    core_image_free(&ref);
    gfx_target_destroy(&tgt);
    bb_field_destroy(plain);
    bb_field_destroy(culled);
    terrain_free(&terrain);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

/* test_bb_gpu_render: golden image of the billboard grass of Orthmann et
 * al. 2009 after a sphere rolled through it: the trail of pushed-out,
 * still-recovering billboards must be visible. Rendered at 192x128 with 4x
 * MSAA and alpha-to-coverage (tests/golden/bb_trail.png; regenerate with
 * MEADOW_UPDATE_GOLDEN=1). The compute rasterizer (bb_raster.comp) draws
 * the same trail: the deformed meshes' triangles, some queued for the
 * group pass (a mesh shares one quad's in-thread budget), agree with the
 * hardware path (llvmpipe: mean difference 1.78; 2.91 when the group pass
 * drops the mesh triangles). Also checks the distance fade hides near
 * grass. */
#include "test.h"
#include "test_gl.h"

#include "bb_gpu_test_util.h"

#include <string.h>

static void draw(bb_field_t *f, const gfx_target_t *tgt, const mat4 vp, const vec3 eye, float time, float fs,
                 float fe)
{
    bb_draw_desc_t d = test_draw_desc(vp, eye, time);
    d.fade_start = fs;
    d.fade_end = fe;
    gfx_target_bind(tgt);
    glClearColor(0.33f, 0.27f, 0.2f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    bb_field_draw(f, &d);
}

static double green(const core_image_t *img)
{
    double g = 0;
    for (int i = 0; i < img->w * img->h; i++) g += img->px[4 * i + 1] - img->px[4 * i];
    return g / (img->w * img->h);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    terrain_mesh_t terrain;
    bb_field_desc_t desc;
    CHECK(test_small_field(&terrain, &desc));
    desc.cube_res = 32;
    desc.recover_time = 30;
    bb_field_t *f = bb_field_make(&desc);
    CHECK(f);
    collide_shape_t sc = {.type = COLLIDE_SHAPE_SPHERE, .radius = 0.5f};
    test_mesh_t mesh;
    test_mesh_make(&mesh, &sc);
    float time = 0;
    for (int frame = 0; frame < 24; frame++) {
        time += 1.0f / 30.0f;
        float x = -3.5f + 7.0f * (float)frame / 23.0f, z = 0.5f;
        float c[3] = {x, terrain_height_at(&terrain, x, z, NULL) + 0.5f, z};
        collide_object_t o = test_object(&mesh, c, sc.radius);
        gfx_timer_frame_begin();
        bb_field_update(f, test_set(&o, 1), time, 1.0f / 30.0f);
    }
    bb_stats_t st;
    bb_field_stats(f, true, &st);
    printf("%d billboards, %d deformed after the roll\n", st.billboards, st.deformed);
    CHECK(st.deformed > 50);

    gfx_target_t tgt = gfx_target_make(&(gfx_target_desc_t){.w = 192, .h = 128, .samples = 4, .label = "bb.test"});
    mat4 vp;
    vec3 eye = {0.0f, 4.5f, 4.0f};
    test_view(eye, vp);
    gfx_timer_frame_begin();
    draw(f, &tgt, vp, eye, time, 0, 0);
    core_image_t img;
    CHECK(gfx_target_read(&tgt, &img));
    CHECK(test_image_check(&img, "bb_trail", NULL));
    double g_full = green(&img);

    raster_t r;
    CHECK(raster_make(&r, &(raster_desc_t){.w = 192, .h = 128}));
    bb_draw_desc_t d = test_draw_desc(vp, eye, time);
    gfx_target_bind(&tgt);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    raster_begin(&r, &tgt);
    CHECK(bb_field_raster(f, &r, &d));
    raster_end(&r, &tgt);
    raster_stats_t rs;
    raster_read_stats(&r, &rs);
    core_image_t comp;
    CHECK(gfx_target_read(&tgt, &comp));
    test_image_cmp_t bound = {.mean_threshold = 2.3, .fail_budget = 0.025};
    test_image_result_t cmp = test_image_diff(&img, &comp, &bound, NULL);
    printf("compute path: %u triangles queued, mean difference %.2f, %.1f %% of pixels over 24, green-red %.2f\n",
           rs.large, cmp.mean_diff, 100.0 * cmp.fail_fraction, green(&comp));
    CHECK(rs.large > 0 && rs.overflow == 0);
    CHECK(cmp.pass);
    CHECK(fabs(green(&comp) - g_full) < 2.0);
    core_image_free(&comp);
    raster_destroy(&r);

    /* Distance fade: everything nearer than 20 m is invisible. */
    draw(f, &tgt, vp, eye, time, 20, 25);
    core_image_t faded;
    CHECK(gfx_target_read(&tgt, &faded));
    double g_fade = green(&faded);
    printf("mean green-red: full %.2f, faded %.2f\n", g_full, g_fade);
    CHECK(g_full > g_fade + 5.0);
    CHECK(fabs(g_fade - (0.27 - 0.33) * 255) < 1.0);
    gfx_timer_flush();
    for (int i = 0; i < gfx_timer_count(); i++)
        printf("timer %-12s median %.3f ms\n", gfx_timer_name(i), gfx_timer_median_ms(i));

    core_image_free(&img);
    core_image_free(&faded);
    gfx_target_destroy(&tgt);
    bb_field_destroy(f);
    test_mesh_destroy(&mesh);
    terrain_free(&terrain);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

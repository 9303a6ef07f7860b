/* test_app_modes: the hybrid field's two representations agree, and mode
 * switches keep the simulation consistent.
 * 1. The same seed gives the same layout: a top-down coverage mask of
 *    billboard mode and of blade mode (grass vs ground per 8x8 block)
 *    agree in most blocks, and both have clearings where the other has;
 *    the mean colour of their grass pixels agrees too (the session draws
 *    with no debug overlay: world_view_make fills every view field). Top
 *    down, "grass" is green above red, the terrain's turf included.
 * 2. Seen from the side as hybrid mode shows billboards
 *    (tests/data/scenes/metric.json: 5 m up, looking 11 m ahead), grass
 *    being what differs from the grass-free view (eval_image's rule):
 *    the billboards' grass fraction is within SIDE_COVERAGE of the
 *    blades' and their mean grass colour within CIE76 Delta E SIDE_DELTA_E
 *    (the three views go to test_out_dir() as side_*.png).
 *    With grass.width_printed (eq. 24 as printed: blades under 6 px drawn
 *    as quads) over 5 % of the blade view's pixels move by more than 8
 *    levels: the key reaches the blades (the grass fraction, 0.87, is
 *    saturated there).
 * 3. Switching modes at run time resets nothing: blade state keeps evolving
 *    across billboard -> blade -> hybrid, with no NaN, roots fixed. */
#include "measure/measure.h"
#include "world/world_harness.h"
#include "app/app.h"
#include "measure/measure_session.h"
#include "eval/eval_image.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void top_down(scene_desc_t *s, void *user)
{
    (void)user;
    s->camera.path.count = 0;
    glm_vec3_copy((vec3){0.0f, 9.0f, 0.01f}, s->camera.position);
    glm_vec3_zero(s->camera.target);
    s->camera.fov = 50.0f;
    s->size[0] = s->size[1] = 192;
    s->colliders[0].path.count = 1; /* park the ball off the field */
    glm_vec3_copy((vec3){40.0f, 0.4f, 40.0f}, s->colliders[0].path.keys[0].position);
}

/* Side view: billboards' grass fraction and mean grass colour (CIE76
 * Delta E) may differ from the blades' by this much. */
#define SIDE_COVERAGE 0.05
#define SIDE_DELTA_E 2.0

/* The grass-free view: a blade field too thin to hold a blade. */
static void no_grass(scene_desc_t *s, void *user)
{
    (void)user;
    s->grass.population.density = 1e-7f;
}

/* Eq. 24 as printed from 6 px over 2 px (grass.width_printed). */
static void width_printed(scene_desc_t *s, void *user)
{
    (void)user;
    s->grass.width_printed[0] = 6.0f;
    s->grass.width_printed[1] = 2.0f;
}

/* Over the pixels where bg shows the ground (not the sky: blue below
 * green), grass being what differs from bg by more than 8 levels in a
 * channel: the grass fraction, and the grass's mean colour in CIELAB (mean
 * in linear light). The sky is left out: there the billboards' tops blend
 * their mipmapped alpha with it (docs/BILLBOARDS.md). */
static double side_grass(const core_image_t *img, const core_image_t *bg, double lab[3])
{
    double rgb[3] = {0, 0, 0}, n = 0.0, ground = 0.0;
    for (size_t i = 0; i < (size_t)img->w * (size_t)img->h; i++) {
        const uint8_t *p = img->px + i * 4, *q = bg->px + i * 4;
        if (q[2] >= q[1]) continue;
        ground += 1.0;
        if (abs(p[0] - q[0]) <= 8 && abs(p[1] - q[1]) <= 8 && abs(p[2] - q[2]) <= 8) continue;
        for (int k = 0; k < 3; k++) rgb[k] += eval_srgb_to_linear(p[k]);
        n += 1.0;
    }
    for (int k = 0; k < 3; k++) rgb[k] /= n > 0.0 ? n : 1.0;
    eval_linear_to_lab(rgb, lab);
    return n / (ground > 0.0 ? ground : 1.0);
}

static void side_view(void)
{
    app_options_t o = {.scene = "tests/data/scenes/metric.json", .headless = true};
    core_image_t bg, bb, bl;
    measure_session_desc_t d = {.world = app_world_options(&o),
                                .mode = SCENE_MODE_BLADE, .mode_set = true, .frames = 4, .tweak = no_grass};
    CHECK(measure_session_run(&d, &bg, NULL) == 0);
    d.tweak = NULL;
    CHECK(measure_session_run(&d, &bl, NULL) == 0);
    core_image_t bp;
    d.tweak = width_printed;
    CHECK(measure_session_run(&d, &bp, NULL) == 0);
    d.tweak = NULL;
    d.mode = SCENE_MODE_BILLBOARD;
    CHECK(measure_session_run(&d, &bb, NULL) == 0);
    double lb[3], ll[3];
    double cb = side_grass(&bb, &bg, lb), cl = side_grass(&bl, &bg, ll);
    size_t moved = 0, npx = (size_t)bl.w * (size_t)bl.h;
    for (size_t i = 0; i < npx; i++)
        moved += abs(bl.px[4 * i] - bp.px[4 * i]) > 8 || abs(bl.px[4 * i + 1] - bp.px[4 * i + 1]) > 8 ||
                 abs(bl.px[4 * i + 2] - bp.px[4 * i + 2]) > 8;
    printf("side view: grass.width_printed [6, 2] moves %zu of %zu pixels by more than 8 levels\n", moved, npx);
    CHECK(moved > npx / 20);
    core_image_free(&bp);
    double de = sqrt((lb[0] - ll[0]) * (lb[0] - ll[0]) + (lb[1] - ll[1]) * (lb[1] - ll[1]) +
                     (lb[2] - ll[2]) * (lb[2] - ll[2]));
    printf("side view: grass fraction billboard %.3f, blade %.3f; grass colour L*a*b* billboard (%.1f %.1f %.1f), "
           "blade (%.1f %.1f %.1f), Delta E %.2f\n",
           cb, cl, lb[0], lb[1], lb[2], ll[0], ll[1], ll[2], de);
    const char *names[3] = {"side_background.png", "side_blade.png", "side_billboard.png"};
    const core_image_t *imgs[3] = {&bg, &bl, &bb};
    for (int i = 0; i < 3; i++) {
        char path[512];
        snprintf(path, sizeof path, "%s/%s", test_out_dir(), names[i]);
        core_image_write_png(imgs[i], path);
    }
    CHECK(fabs(cb - cl) < SIDE_COVERAGE);
    CHECK(de < SIDE_DELTA_E);
    core_image_free(&bg);
    core_image_free(&bb);
    core_image_free(&bl);
}

/* Fraction of grass pixels per 8x8 block (grass: green clearly above red). */
static void coverage(const core_image_t *img, float *blocks, int nb)
{
    memset(blocks, 0, sizeof(float) * (size_t)(nb * nb));
    int bs = img->w / nb;
    for (int y = 0; y < nb * bs; y++)
        for (int x = 0; x < nb * bs; x++) {
            const uint8_t *p = img->px + ((size_t)y * (size_t)img->w + (size_t)x) * 4;
            if (p[1] > p[0] + 25) blocks[(y / bs) * nb + x / bs] += 1.0f / (float)(bs * bs);
        }
}

int main(void)
{
    /* A view made over garbage has every field defined (overlay off). */
    grass_view_t view;
    memset(&view, 0xA5, sizeof view);
    world_view_make(&view, &(cam_t){.position = {0, 1, 5}, .fov = 60.0f, .near = 0.1f, .far = 100.0f}, 64, 32, 1.0f, 0.5f);
    CHECK(view.overlay == 0 && view.width == 64 && view.time == 1.0f);

    test_gl_init();
    core_log_set_quiet(true);
    app_options_t o = {.scene = "scenes/tiny.json", .headless = true};
    core_image_t bb, bl;
    measure_session_desc_t d = {.world = app_world_options(&o),
                                .mode = SCENE_MODE_BILLBOARD, .mode_set = true, .frames = 2,
                              .tweak = top_down};
    CHECK(measure_session_run(&d, &bb, NULL) == 0);
    d.mode = SCENE_MODE_BLADE;
    CHECK(measure_session_run(&d, &bl, NULL) == 0);
    enum { NB = 12 };
    float cb[NB * NB], cl[NB * NB];
    coverage(&bb, cb, NB);
    coverage(&bl, cl, NB);
    /* Blocks that are clearly grass or clearly ground in one mode. */
    int agree = 0, decided = 0;
    double mb = 0, ml = 0, sbb = 0, sll = 0, sbl = 0;
    for (int i = 0; i < NB * NB; i++) {
        mb += cb[i];
        ml += cl[i];
    }
    mb /= NB * NB;
    ml /= NB * NB;
    for (int i = 0; i < NB * NB; i++) {
        sbb += (cb[i] - mb) * (cb[i] - mb);
        sll += (cl[i] - ml) * (cl[i] - ml);
        sbl += (cb[i] - mb) * (cl[i] - ml);
        bool gb = cb[i] > mb, gl = cl[i] > ml;
        decided++;
        agree += gb == gl;
    }
    double corr = sbl / sqrt(sbb * sll + 1e-12);
    printf("coverage: billboard mean %.2f, blade mean %.2f, block correlation %.2f, agreement %d/%d\n", mb, ml, corr,
           agree, decided);
    CHECK(mb > 0.05 && ml > 0.05);
    CHECK(corr > 0.5);
    CHECK(agree >= decided * 7 / 10);
    double gb[3], gl[3];
    test_grass_pixels(&bb, gb);
    test_grass_pixels(&bl, gl);
    double dcol = fabs(gb[0] - gl[0]) + fabs(gb[1] - gl[1]) + fabs(gb[2] - gl[2]);
    printf("grass colour: billboard (%.3f %.3f %.3f), blade (%.3f %.3f %.3f), L1 difference %.3f\n", gb[0], gb[1],
           gb[2], gl[0], gl[1], gl[2], dcol);
    CHECK(dcol < 0.03);
    core_image_free(&bb);
    core_image_free(&bl);
    side_view();

    /* Live switches: blade mode builds the full field; billboard and
     * hybrid (tiles) come and go around it without resetting it. */
    world_t *w;
    world_options_t wo = app_world_options(&o);
    CHECK(world_load(&wo, &w) == 0);
    CHECK(world_make_gpu(w));
    CHECK(measure_drivers(w).tiles && measure_drivers(w).billboards && !measure_drivers(w).blades);
    world_set_mode(w, SCENE_MODE_BLADE);
    CHECK(measure_drivers(w).blades);
    int f = 0;
    for (int i = 0; i < 10; i++, f++) world_update(w, (float)(f + 1) / 60.0f, 1.0f / 60.0f);
    size_t n = blade_gpu_info(measure_drivers(w).blades).padded_count;
    blade_t *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    blade_gpu_read_blades(measure_drivers(w).blades, a, NULL);
    static const scene_mode_t seq[4] = {SCENE_MODE_BILLBOARD, SCENE_MODE_HYBRID, SCENE_MODE_BLADE,
                                        SCENE_MODE_BILLBOARD};
    for (int k = 0; k < 4; k++) {
        world_set_mode(w, seq[k]);
        for (int i = 0; i < 20; i++, f++) world_update(w, (float)(f + 1) / 60.0f, 1.0f / 60.0f);
    }
    blade_gpu_read_blades(measure_drivers(w).blades, b, NULL);
    int moved = 0, bad = 0;
    for (size_t i = 0; i < n; i++) {
        if (a[i].v1[3] <= 0.0f) continue;
        bad += memcmp(a[i].v0, b[i].v0, sizeof a[i].v0) != 0;
        for (int c = 0; c < 3; c++) bad += !isfinite(b[i].v2[c]);
        moved += fabsf(a[i].v2[0] - b[i].v2[0]) + fabsf(a[i].v2[2] - b[i].v2[2]) > 1e-4f;
    }
    printf("mode switches: %d blades moved (wind, ball), %d bad\n", moved, bad);
    CHECK(bad == 0 && moved > 0);
    world_info_t wi = world_info(w);
    CHECK(wi.billboards && wi.blades && wi.tiles && wi.mode == SCENE_MODE_BILLBOARD);
    free(a);
    free(b);
    world_destroy(w);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

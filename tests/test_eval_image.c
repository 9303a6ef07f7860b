/* test_eval_image: the placement-invariant image error (eval_image.h,
 * docs/METRICS.md "Image error") can tell good from bad.
 * 1. Synthetic images: the same random dots placed with another seed score
 *    well below a 10 % colour shift or half the dots; identical images
 *    score 0; mismatched sizes are refused.
 * 2. Calibration on llvmpipe (tests/data/scenes/metric.json, 320x180):
 *    the reference (blades, maximum tessellation, no culling) against the
 *    reference with another placement seed (grass_tuning_t.placement_seed)
 *    gives the noise floor F, which is small; blade tessellation caps 1, 2,
 *    3, 5, 10 rank monotonically; billboards with their colour shifted by
 *    10 % (image space, see below) or a quarter fewer billboards
 *    (grass.billboard_density x 0.75) score above 3 F against the plain
 *    billboards. */
#include "app/app.h"
#include "measure/measure_session.h"
#include "eval/eval.h"
#include "eval/eval_image.h"
#include "test.h"
#include "test_gl.h"

#include <stdlib.h>
#include <string.h>

/* ---- synthetic ------------------------------------------------------------ */

static const uint8_t ground[4] = {90, 70, 45, 255};

/* 2 x 5 px "blades" of colour c over the ground, jittered in 8 x 8 px
 * cells (like seeded grass: random, but evenly spread); a cell holds one
 * with probability `keep`. */
static void dots(core_image_t *img, uint64_t seed, float keep, const uint8_t c[4])
{
    core_rng_t rng;
    core_rng_seed(&rng, seed, 1);
    core_image_alloc(img, 192, 128, 4);
    core_image_fill(img, 0, 0, img->w, img->h, ground);
    for (int y = 0; y < img->h; y += 8)
        for (int x = 0; x < img->w; x += 8) {
            int dx = (int)(core_rng_float(&rng) * 6.0f), dy = (int)(core_rng_float(&rng) * 3.0f);
            if (core_rng_float(&rng) < keep) core_image_fill(img, x + dx, y + dy, 2, 5, c);
        }
}

static double score(const core_image_t *a, const core_image_t *b, const core_image_t *bg, eval_image_error_t *e)
{
    eval_image_error_t tmp;
    e = e ? e : &tmp;
    CHECK(eval_image_error(a, b, &(eval_image_desc_t){.background = bg}, e));
    return e->score;
}

static void synthetic(void)
{
    static const uint8_t green[4] = {40, 110, 30, 255}, green90[4] = {36, 99, 27, 255};
    core_image_t bg, a, b, shifted, half;
    core_image_alloc(&bg, 192, 128, 4);
    core_image_fill(&bg, 0, 0, bg.w, bg.h, ground);
    dots(&a, 1, 1.0f, green);
    dots(&b, 2, 1.0f, green);
    dots(&shifted, 1, 1.0f, green90);
    dots(&half, 1, 0.5f, green);
    eval_image_error_t e;
    CHECK(score(&a, &a, &bg, &e) == 0.0 && e.colour == 0.0 && e.coverage == 0.0 && e.structure == 0.0);
    double moved = score(&b, &a, &bg, NULL), colour = score(&shifted, &a, &bg, &e);
    printf("synthetic: moved %.3f, colour -10%% %.3f (dE %.2f), half the dots %.3f\n", moved, colour, e.colour,
           score(&half, &a, &bg, NULL));
    CHECK(moved < 0.15);
    CHECK(colour > 3.0 * moved && e.colour > 1.0);
    CHECK(score(&half, &a, &bg, &e) > 3.0 * moved && e.coverage > 0.05);
    /* Without a background there is no coverage term. */
    CHECK(eval_image_error(&half, &a, NULL, &e) && e.coverage == 0.0 && e.score > 0.0);
    core_image_t small;
    core_image_alloc(&small, 96, 128, 4);
    CHECK(!eval_image_error(&small, &a, NULL, &e) && e.score == 0.0);
    eval_image_desc_t d = eval_image_desc_defaults(NULL);
    CHECK(d.block == 0 && d.levels == 2 && d.grass_threshold == 8 && d.colour_scale == 2.3);
    core_image_free(&small);
    core_image_free(&bg);
    core_image_free(&a);
    core_image_free(&b);
    core_image_free(&shifted);
    core_image_free(&half);
}

/* ---- rendered ------------------------------------------------------------- */

typedef struct knob_t {
    float density, billboard_density; /* factors; 0 = 1 */
} knob_t;

static void tweak(scene_desc_t *s, void *user)
{
    const knob_t *k = user;
    if (k->density > 0) s->grass.population.density *= k->density;
    if (k->billboard_density > 0) s->grass.billboard_density *= k->billboard_density;
}

static core_image_t render(scene_mode_t mode, bool reference, grass_tuning_t tuning, knob_t knob)
{
    app_options_t o = {.scene = "tests/data/scenes/metric.json", .headless = true};
    measure_session_desc_t d = {.world = app_world_options(&o),
                                .mode = mode, .mode_set = true, .frames = 4, .reference = reference,
                              .msaa = reference ? 8 : 0, .tuning = tuning, .tweak = tweak, .user = &knob};
    core_image_t img = {0};
    if (measure_session_run(&d, &img, NULL) != 0) {
        fprintf(stderr, "render failed\n");
        exit(1);
    }
    return img;
}

static void rendered(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    core_image_t ref = render(SCENE_MODE_BLADE, true, (grass_tuning_t){0}, (knob_t){0});
    /* The grass-free view: a blade field too thin to hold a blade. */
    core_image_t bg = render(SCENE_MODE_BLADE, true, (grass_tuning_t){0}, (knob_t){.density = 1e-7f});
    core_image_t other = render(SCENE_MODE_BLADE, true, (grass_tuning_t){.placement_seed = 1234}, (knob_t){0});
    eval_image_error_t e;
    double floor = score(&other, &ref, &bg, &e), empty = score(&bg, &ref, &bg, NULL);
    printf("floor %.3f (dE %.3f, coverage %.4f, structure %.4f; 1 - SSIM %.3f), no grass %.3f\n", floor, e.colour,
           e.coverage, e.structure, 1.0 - eval_image_ssim(&other, &ref), empty);
    CHECK(floor > 0.0 && floor < 0.3);
    CHECK(empty > 10.0 * floor);

    static const int tess[] = {1, 2, 3, 5, 10};
    double prev = INFINITY;
    for (int i = 0; i < (int)(sizeof tess / sizeof tess[0]); i++) {
        core_image_t t = render(SCENE_MODE_BLADE, false, (grass_tuning_t){.tess_max = tess[i]}, (knob_t){0});
        double s = score(&t, &ref, &bg, &e);
        printf("tess %2d: %.3f (dE %.3f, coverage %.4f, structure %.4f; 1 - SSIM %.3f)\n", tess[i], s, e.colour,
               e.coverage, e.structure, 1.0 - eval_image_ssim(&t, &ref));
        CHECK_MSG(s < prev, "tess %d scores %.4f, not below the previous %.4f", tess[i], s, prev);
        prev = s;
        core_image_free(&t);
    }

    core_image_t bb = render(SCENE_MODE_BILLBOARD, false, (grass_tuning_t){0}, (knob_t){0});
    /* No knob tints billboards: their pixels (those the metric counts as
     * grass) are scaled by 0.9 in the rendered image. */
    core_image_t tinted = render(SCENE_MODE_BILLBOARD, false, (grass_tuning_t){0}, (knob_t){0});
    for (size_t i = 0; i < (size_t)tinted.w * (size_t)tinted.h; i++) {
        uint8_t *p = tinted.px + i * 4;
        const uint8_t *q = bg.px + i * 4;
        if (abs(p[0] - q[0]) > 8 || abs(p[1] - q[1]) > 8 || abs(p[2] - q[2]) > 8)
            for (int k = 0; k < 3; k++) p[k] = (uint8_t)(p[k] * 0.9f + 0.5f);
    }
    core_image_t quarter = render(SCENE_MODE_BILLBOARD, false, (grass_tuning_t){0}, (knob_t){.billboard_density = 0.75f});
    core_image_t moved = render(SCENE_MODE_BILLBOARD, false, (grass_tuning_t){.placement_seed = 1234}, (knob_t){0});
    double s_tint = score(&tinted, &bb, &bg, &e);
    printf("billboard colour x 0.9: %.3f (dE %.3f)\n", s_tint, e.colour);
    double s_quarter = score(&quarter, &bb, &bg, &e);
    printf("billboards x 0.75: %.3f (coverage %.4f)\n", s_quarter, e.coverage);
    double s_moved = score(&moved, &bb, &bg, &e);
    printf("billboards moved (placement seed): %.3f; billboard vs reference %.3f\n", s_moved,
           score(&bb, &ref, &bg, NULL));
    CHECK(s_tint > 3.0 * floor);
    CHECK(s_quarter > 3.0 * floor);
    /* The quarter also moves the billboards (the candidate grid spacing
     * changes): it must score above moving them alone. */
    CHECK(s_quarter > 1.5 * s_moved);
    core_image_free(&ref);
    core_image_free(&bg);
    core_image_free(&other);
    core_image_free(&bb);
    core_image_free(&tinted);
    core_image_free(&quarter);
    core_image_free(&moved);
    CHECK(test_gl_shutdown() == 0);
}

int main(void)
{
    synthetic();
    rendered();
    TEST_END();
}

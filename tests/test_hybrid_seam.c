/* test_hybrid_seam: the hybrid seam measure (measure_seam, docs/METRICS.md
 * "Hybrid seam") on llvmpipe, tests/data/scenes/metric.json in hybrid mode
 * with the switch at 10 m (the band in the middle of the view), 320x180,
 * 4 frames:
 * 1. The seam of the hybrid frame against its billboard-only reference:
 *    its coverage step stays within SEAM_COVERAGE (the tiles widen the
 *    blades their distance levels thin, blade_ref_lod_width).
 * 2. Its floor (measure_seam_floor): billboard-only frames of the same
 *    view with other placement seeds against the reference (no switch in
 *    either; only where the billboards stand differs), their mean below 1,
 *    and so is the hybrid seam (not clearly visible). Issue 16 asks for
 *    the seam within the floor; here it is on llvmpipe and not on the H100
 *    (docs/METRICS.md), so this guards the seam against getting clearly
 *    visible and prints both. The reference's
 *    own step (the view's change with distance, no reference) is printed:
 *    why the measure needs a reference.
 * 3. The measure follows a seam: the hybrid frame with its far side (the
 *    billboards beyond the band) 10 % darker in linear light moves Delta L*
 *    down by more than 1.
 * 4. Without billboards (grass.billboards none) the canopy seam compares the
 *    blades ending in the canopy with blades drawn across the band: both
 *    windows are counted, the near ones are the frame's own in both, and
 *    the reference's far window is what a world whose tiles reach past it
 *    draws there (within CANOPY_REF_DE), farther from the frame's canopy. */
#include "measure/measure.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <string.h>

/* The hybrid frame's coverage step may not exceed this (score 1). */
#define SEAM_COVERAGE 0.05
/* The canopy seam's reference against a world drawing blades that far:
 * Delta E of their far windows at most this (both idle tiles; measured
 * 0.000 on llvmpipe). */
#define CANOPY_REF_DE 0.3

/* The switch at `distance` m; without billboards (the canopy beyond) when
 * none. */
typedef struct tweak_t {
    float distance;
    bool none;
} tweak_t;

static void switch_at(scene_desc_t *s, void *user)
{
    const tweak_t *k = user;
    s->grass.switch_distance = k->distance;
    if (k->none) s->grass.billboards = SCENE_HYBRID_BILLBOARDS_NONE;
}

static world_t *make_world(float distance, bool no_billboards)
{
    world_t *w;
    tweak_t k = {distance, no_billboards};
    CHECK(world_load(&(world_options_t){.scene = "tests/data/scenes/metric.json"}, &w) == 0);
    CHECK(world_setup(w, &(world_setup_t){.mode = SCENE_MODE_HYBRID, .mode_set = true, .tweak = switch_at,
                                          .user = &k}));
    CHECK(world_make_gpu(w));
    for (int f = 0; f < 4; f++) world_update(w, (float)(f + 1) / 60.0f, 1.0f / 60.0f);
    return w;
}

static eval_seam_frame_t view_of(const measure_seam_frame_t *f) { return (eval_seam_frame_t){&f->img, f->dist, f->cls}; }

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    world_t *w = make_world(10.0f, false);
    const scene_desc_t *s = world_info(w).scene;
    gfx_target_t t = gfx_target_make(&(gfx_target_desc_t){.w = 320, .h = 180, .samples = s->msaa, .label = "seam"});
    cam_t cam;
    scene_camera_init(s, &cam);
    grass_view_t v;
    world_view_make(&v, &cam, t.w, t.h, 4.0f / 60.0f, 1.0f / 60.0f);
    eval_seam_desc_t d = measure_seam_desc(w);

    /* 1. The hybrid frame against its billboard-only reference. */
    measure_seam_frame_t hybrid, ref, bg;
    CHECK(measure_seam_frame_draw(w, &v, &t, SCENE_MODE_HYBRID, true, &hybrid));
    eval_seam_t e;
    CHECK(measure_seam(w, &v, &t, &e));
    printf("hybrid seam: score %.3f, Delta E %.3f, Delta L* %+.3f, coverage %.4f (grass near | far %.3f | %.3f, "
           "reference %.3f | %.3f; pixels %ld | %ld)\n",
           e.score, e.delta_e, e.delta_l, e.coverage, e.grass[0][0], e.grass[0][1], e.grass[1][0], e.grass[1][1],
           e.pixels[0][0], e.pixels[0][1]);
    CHECK(e.pixels[0][0] > 1000 && e.pixels[0][1] > 1000);
    CHECK(e.coverage <= SEAM_COVERAGE);

    /* 2. Floor: billboards only, other placements, against the reference. */
    measure_seam_floor_t fl;
    CHECK(measure_seam_floor(w, &v, &t, &fl));
    printf("floor (billboards, %d other placements, means): score %.3f (%.3f %.3f %.3f), Delta E %.3f, coverage "
           "%.4f\n",
           MEASURE_SEAM_FLOOR_PLACEMENTS, fl.mean.score, fl.score[0], fl.score[1], fl.score[2], fl.mean.delta_e,
           fl.mean.coverage);
    CHECK(fl.mean.score > 0.0 && fl.mean.score < 1.0);
    CHECK_MSG(e.score < 1.0, "the seam (%.3f) is clearly visible (floor %.3f)", e.score, fl.mean.score);
    CHECK(measure_seam_frame_draw(w, &v, &t, SCENE_MODE_BILLBOARD, true, &ref));
    CHECK(measure_seam_frame_draw(w, &v, &t, SCENE_MODE_HYBRID, false, &bg));
    measure_seam_frame_classify(&hybrid, &bg);
    measure_seam_frame_classify(&ref, &bg);
    eval_seam_frame_t fh = view_of(&hybrid), fr = view_of(&ref);
    /* Why a reference: the billboard-only frame's own step across the band
     * (no switch in it) is the view's change with distance. */
    eval_seam_t own;
    CHECK(eval_image_seam(&fr, NULL, &d, &own));
    printf("the reference's own step (no switch, no reference): score %.3f, Delta E %.3f, coverage %.4f\n",
           own.score, own.delta_e, own.coverage);

    /* 3. A darker far side: the measure follows. */
    eval_seam_t base, dark;
    CHECK(eval_image_seam(&fh, &fr, &d, &base));
    CHECK_NEAR(base.score, e.score, 1e-9);
    for (size_t i = 0; i < (size_t)hybrid.img.w * (size_t)hybrid.img.h; i++) {
        if (hybrid.dist[i] <= d.switch_distance + d.fade) continue;
        for (int c = 0; c < 3; c++) {
            uint8_t *p = &hybrid.img.px[i * 4 + (size_t)c];
            double lin = pow(*p / 255.0, 2.2) * 0.9;
            *p = (uint8_t)lrint(pow(lin, 1.0 / 2.2) * 255.0);
        }
    }
    CHECK(eval_image_seam(&fh, &fr, &d, &dark));
    printf("far side 10%% darker: Delta E %.3f -> %.3f, Delta L* %+.3f -> %+.3f\n", base.delta_e, dark.delta_e,
           base.delta_l, dark.delta_l);
    CHECK(dark.delta_l < base.delta_l - 1.0);

    measure_seam_frame_free(&hybrid);
    measure_seam_frame_free(&ref);
    measure_seam_frame_free(&bg);
    world_destroy(w);

    /* 4. No billboards: the blades end in the canopy at the switch. */
    w = make_world(10.0f, true);
    eval_seam_t c;
    CHECK(measure_drivers(w).billboards == NULL && world_info(w).canopy);
    CHECK(measure_canopy_seam(w, &v, &t, &c));
    double near_de = 0.0, far_de = 0.0;
    for (int k = 0; k < 3; k++) {
        near_de += (c.lab[0][0][k] - c.lab[1][0][k]) * (c.lab[0][0][k] - c.lab[1][0][k]);
        far_de += (c.lab[0][1][k] - c.lab[1][1][k]) * (c.lab[0][1][k] - c.lab[1][1][k]);
    }
    printf("blades to canopy: score %.3f, Delta E %.3f, coverage %.4f; frame vs blades across the band Delta E "
           "near %.3f, far %.3f; pixels %ld | %ld\n",
           c.score, c.delta_e, c.coverage, sqrt(near_de), sqrt(far_de), c.pixels[0][0], c.pixels[0][1]);
    CHECK(c.pixels[0][0] > 100 && c.pixels[0][1] > 100);
    CHECK_MSG(near_de == 0.0, "nearer than the band the reference is the frame: Delta E %.3f", sqrt(near_de));
    world_destroy(w);
    /* The same far window in a world whose blades reach past it. */
    float reach = measure_canopy_seam_reach(d.switch_distance);
    w = make_world(reach, true);
    measure_seam_frame_t past, past_bg;
    CHECK(measure_seam_frame_draw(w, &v, &t, SCENE_MODE_HYBRID, true, &past));
    CHECK(measure_seam_frame_draw(w, &v, &t, SCENE_MODE_HYBRID, false, &past_bg));
    measure_seam_frame_classify(&past, &past_bg);
    eval_seam_t o;
    CHECK(eval_image_seam(&(eval_seam_frame_t){&past.img, past_bg.dist, past.cls}, NULL, &d, &o));
    double ref_de = 0.0;
    for (int k = 0; k < 3; k++) ref_de += (o.lab[0][1][k] - c.lab[1][1][k]) * (o.lab[0][1][k] - c.lab[1][1][k]);
    printf("far window: blades to %.0f m against the reference Delta E %.3f (the frame's canopy %.3f)\n",
           (double)reach, sqrt(ref_de), sqrt(far_de));
    CHECK_MSG(sqrt(ref_de) <= CANOPY_REF_DE, "the reference's far window is not blades: Delta E %.3f", sqrt(ref_de));
    CHECK(sqrt(far_de) > sqrt(ref_de));
    measure_seam_frame_free(&past);
    measure_seam_frame_free(&past_bg);
    gfx_target_destroy(&t);
    world_destroy(w);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

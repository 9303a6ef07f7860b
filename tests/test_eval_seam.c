/* test_eval_seam: the hybrid seam measure (eval_image_seam, docs/METRICS.md
 * "Hybrid seam") on synthetic frames: rows at distances 20 m (top) to 4 m
 * (bottom), switch distance 12 m. A uniform frame scores ~0; a step in
 * colour across the band scores its Delta E (the Delta E eval_image_error
 * gives the two flat colours) and half the step half of it; a step in
 * coverage scores its grass fraction step; a change with distance that the
 * reference shows too scores ~0, a step on top of it the step; random
 * texture with the same statistics on both sides stays small; a window
 * without pixels is refused. */
#include "eval/eval_image.h"
#include "test.h"

#include <math.h>
#include <string.h>

enum { W = 240, H = 180 };

static const uint8_t green[3] = {60, 120, 40}, ground[3] = {110, 85, 60};

static float row_dist(int y) { return 20.0f - 16.0f * ((float)y + 0.5f) / (float)H; }

typedef struct frame_t {
    core_image_t img;
    float dist[W * H];
    uint8_t cls[W * H];
} frame_t;

/* Colour of a pixel at distance d: `near` up to the band, `far` beyond it,
 * a linear ramp inside the band (the cross-fade); grass with probability
 * cover_near / cover_far, else ground; `noise` adds uniform noise of that
 * many levels. */
typedef struct pattern_t {
    uint8_t near[3], far[3];
    float cover_near, cover_far;
    int noise;
} pattern_t;

static void fill(frame_t *f, const pattern_t *p, uint64_t seed)
{
    core_rng_t rng;
    core_rng_seed(&rng, seed, 3);
    core_image_free(&f->img);
    CHECK(core_image_alloc(&f->img, W, H, 4));
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            size_t i = (size_t)y * W + (size_t)x;
            float d = row_dist(y), t = fminf(fmaxf((d - 11.0f) / 2.0f, 0.0f), 1.0f);
            bool grass = core_rng_float(&rng) < (d > 12.0f ? p->cover_far : p->cover_near);
            for (int c = 0; c < 3; c++) {
                float v = grass ? (1.0f - t) * p->near[c] + t * p->far[c] : ground[c];
                v += p->noise ? (core_rng_float(&rng) - 0.5f) * (float)p->noise : 0.0f;
                f->img.px[i * 4 + (size_t)c] = (uint8_t)fminf(fmaxf(roundf(v), 0.0f), 255.0f);
            }
            f->img.px[i * 4 + 3] = 255;
            f->dist[i] = d;
            f->cls[i] = grass ? EVAL_SEAM_GRASS : EVAL_SEAM_GROUND;
        }
}

static eval_seam_frame_t view(const frame_t *f) { return (eval_seam_frame_t){&f->img, f->dist, f->cls}; }

static eval_seam_t seam(const frame_t *f, const frame_t *ref, float s)
{
    eval_seam_t e;
    eval_seam_frame_t a = view(f), b = ref ? view(ref) : (eval_seam_frame_t){0};
    CHECK(eval_image_seam(&a, ref ? &b : NULL, &(eval_seam_desc_t){.switch_distance = s}, &e));
    return e;
}

/* A fog-like change with distance: every pixel moved towards grey 200 by
 * 2 % per metre beyond 4 m. */
static void fog(frame_t *f)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++)
            for (int c = 0; c < 3; c++) {
                uint8_t *v = &f->img.px[((size_t)y * W + (size_t)x) * 4 + (size_t)c];
                *v = (uint8_t)lrintf((float)*v + (200.0f - (float)*v) * 0.02f * (row_dist(y) - 4.0f));
            }
}

/* eval_image_error's colour term of two flat colours: their Delta E. */
static double flat_delta_e(const uint8_t a[3], const uint8_t b[3])
{
    core_image_t ia, ib;
    CHECK(core_image_alloc(&ia, 16, 16, 3) && core_image_alloc(&ib, 16, 16, 3));
    for (int i = 0; i < 256; i++) memcpy(ia.px + i * 3, a, 3), memcpy(ib.px + i * 3, b, 3);
    eval_image_error_t e;
    CHECK(eval_image_error(&ia, &ib, NULL, &e));
    core_image_free(&ia);
    core_image_free(&ib);
    return e.colour;
}

int main(void)
{
    static frame_t f, r;
    eval_seam_desc_t d = eval_seam_desc_defaults(NULL);
    CHECK(d.fade == 1.0f && d.window == 3.0f && d.colour_scale == 2.3 && d.coverage_scale == 0.05);

    /* Uniform: no step at all. */
    pattern_t p = {.near = {60, 120, 40}, .far = {60, 120, 40}, .cover_near = 1.0f, .cover_far = 1.0f};
    fill(&f, &p, 1);
    eval_seam_t e = seam(&f, NULL, 12.0f);
    printf("uniform: score %.2g, Delta E %.2g, coverage %.2g, pixels %ld | %ld\n", e.score, e.delta_e, e.coverage,
           e.pixels[0][0], e.pixels[0][1]);
    CHECK(e.score < 1e-9 && e.pixels[0][0] > 1000 && e.pixels[0][1] > 1000);
    CHECK_NEAR(e.grass[0][0], 1.0, 1e-12);

    /* A 10 % darker far side: Delta E as for the two flat colours. */
    pattern_t step = p;
    for (int c = 0; c < 3; c++) step.far[c] = (uint8_t)lrintf(0.9f * green[c]);
    fill(&f, &step, 1);
    e = seam(&f, NULL, 12.0f);
    double want = flat_delta_e(step.near, step.far);
    printf("10%% step: Delta E %.3f (flat colours %.3f), Delta L* %.3f, score %.2f\n", e.delta_e, want, e.delta_l,
           e.score);
    CHECK(fabs(e.delta_e - want) < 1e-6 * want && e.delta_l < 0.0 && e.score > 1.0);
    /* Half the step, half the measure. */
    pattern_t half = p;
    for (int c = 0; c < 3; c++) half.far[c] = (uint8_t)lrintf(0.95f * green[c]);
    fill(&f, &half, 1);
    eval_seam_t eh = seam(&f, NULL, 12.0f);
    printf("5%% step: Delta E %.3f\n", eh.delta_e);
    CHECK(eh.delta_e > 0.4 * e.delta_e && eh.delta_e < 0.6 * e.delta_e);

    /* Coverage 0.8 near, 0.5 far. */
    pattern_t cover = p;
    cover.cover_near = 0.8f;
    cover.cover_far = 0.5f;
    fill(&f, &cover, 2);
    e = seam(&f, NULL, 12.0f);
    printf("coverage step: coverage %.3f (grass %.3f | %.3f), Delta E %.2f, score %.2f\n", e.coverage, e.grass[0][0],
           e.grass[0][1], e.delta_e, e.score);
    CHECK(fabs(e.coverage - 0.3) < 0.02 && e.score > 5.0);

    /* A change with distance (fog) counts alone, but not against a
     * reference that shows it too; a step on top of it still counts. */
    fill(&f, &p, 1);
    fog(&f);
    e = seam(&f, NULL, 12.0f);
    fill(&r, &p, 4);
    fog(&r);
    eval_seam_t ef = seam(&f, &r, 12.0f);
    fill(&f, &step, 1);
    fog(&f);
    eval_seam_t es = seam(&f, &r, 12.0f);
    printf("fog: alone Delta E %.3f, against a fogged reference %.3g; 10%% step under fog %.3f\n", e.delta_e,
           ef.delta_e, es.delta_e);
    CHECK(e.score > 1.0 && ef.score < 1e-9 && es.delta_e > 0.7 * want);

    /* Texture (coverage 0.7 and 40 levels of noise) with the same
     * statistics on both sides and in the reference: small. */
    pattern_t tex = p;
    tex.cover_near = tex.cover_far = 0.7f;
    tex.noise = 40;
    fill(&f, &tex, 3);
    fill(&r, &tex, 5);
    e = seam(&f, &r, 12.0f);
    printf("texture, no step: score %.3f, Delta E %.3f, coverage %.4f\n", e.score, e.delta_e, e.coverage);
    CHECK(e.score < 0.3);

    /* A window beyond the frame, no counted pixel, or another size: refused. */
    eval_seam_frame_t a = view(&f), b = view(&r);
    CHECK(!eval_image_seam(&a, NULL, &(eval_seam_desc_t){.switch_distance = 19.5f}, &e));
    CHECK(e.score == 0.0 && e.pixels[0][0] == 0);
    core_image_t small;
    CHECK(core_image_alloc(&small, 8, 8, 4));
    b.img = &small;
    CHECK(!eval_image_seam(&a, &b, &(eval_seam_desc_t){.switch_distance = 12.0f}, &e));
    core_image_free(&small);
    memset(f.cls, EVAL_SEAM_SKIP, sizeof f.cls);
    CHECK(!eval_image_seam(&a, NULL, &(eval_seam_desc_t){.switch_distance = 12.0f}, &e));
    core_image_free(&f.img);
    core_image_free(&r.img);
    TEST_END();
}

/* test_eval: SSIM and MAD on known images, heatmap, Pareto front (with and
 * without measured spreads), least
 * squares line. */
#include "eval/eval.h"
#include "test.h"

#include <math.h>
#include <string.h>

int main(void)
{
    core_image_t a, b, h;
    CHECK(core_image_alloc(&a, 32, 32, 4) && core_image_alloc(&b, 32, 32, 4));
    core_rng_t rng;
    core_rng_seed(&rng, 1, 1);
    for (int i = 0; i < 32 * 32 * 4; i++) a.px[i] = (uint8_t)(core_rng_u32(&rng) & 255);
    memcpy(b.px, a.px, 32 * 32 * 4);
    CHECK_NEAR(eval_image_ssim(&a, &b), 1.0, 1e-9);
    CHECK_NEAR(eval_image_mad(&a, &b), 0.0, 1e-12);
    for (int i = 0; i < 32 * 32 * 4; i++) b.px[i] = (uint8_t)(255 - a.px[i]);
    CHECK(eval_image_ssim(&a, &b) < 0.0); /* inverted noise is anti-correlated */
    memset(b.px, 0, 32 * 32 * 4);
    for (int i = 0; i < 32 * 32; i++) b.px[i * 4 + 0] = b.px[i * 4 + 1] = b.px[i * 4 + 2] = 51;
    memset(a.px, 0, 32 * 32 * 4);
    CHECK_NEAR(eval_image_mad(&a, &b), 0.2, 1e-9);
    CHECK(eval_image_heatmap(&a, &b, 51, &h));
    CHECK(h.px[0] >= 254 && h.px[1] >= 254 && h.px[2] >= 254);
    core_image_free(&h);
    double x[5] = {1, 2, 3, 2, 4}, y[5] = {5, 3, 1, 4, 0.5};
    bool f[5];
    eval_pareto(x, y, 5, f);
    CHECK(f[0] && f[1] && f[2] && !f[3] && f[4]);
    /* With spreads: zero spreads give eval_pareto's front; a point cheaper
     * by the 0.6 ms at 0.00009 more error (within the error's
     * spread 0.001) removes the other (blade_x1 against blade_x1_tess);
     * two points apart by less than the spread in both stay. */
    bool g[5];
    eval_pareto_noise(x, y, NULL, NULL, 5, g);
    CHECK(memcmp(f, g, sizeof f) == 0);
    double px[3] = {2.13, 2.73, 2.20}, py[3] = {0.33772, 0.33763, 0.33770}, pex[3] = {0.01, 0.01, 0.1},
           pey[3] = {0.001, 0.001, 0.001};
    bool h3[3];
    eval_pareto(px, py, 3, h3);
    CHECK(h3[0] && h3[1] && h3[2]);
    eval_pareto_noise(px, py, pex, pey, 3, h3);
    CHECK(h3[0] && !h3[1] && h3[2]);
    double slope, icpt, lx[4] = {1, 2, 4, 8}, ly[4] = {2.5, 4.5, 8.5, 16.5}, noisy[4] = {3, 4, 9, 16};
    CHECK(fabs(eval_linear_fit(lx, ly, 4, &slope, &icpt) - 1.0) < 1e-12 && fabs(slope - 2.0) < 1e-12 &&
          fabs(icpt - 0.5) < 1e-12);
    double r2 = eval_linear_fit(lx, noisy, 4, &slope, &icpt);
    CHECK(r2 > 0.9 && r2 < 1.0 && slope > 1.5 && slope < 2.0);
    CHECK(eval_linear_fit(lx, (double[4]){1, 1, 1, 1}, 4, &slope, &icpt) == 0.0 && slope == 0.0 && icpt == 1.0);
    core_image_free(&a);
    core_image_free(&b);
    TEST_END();
}

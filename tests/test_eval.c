/* test_eval: SSIM and MAD on known images, heatmap, Pareto front, least
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

/* test_measure: the GL-free parts of the bench's measures
 * (docs/METRICS.md): measure_percentile (the 95th percentile of depths and
 * over-push) and measure_bb_pose_deviation (billboard_springs' shape
 * deviation from the finest configuration): zero against itself, growing
 * with the offset, a billboard deformed on one side only counting against
 * zero offsets. */
#include "measure/measure_metrics.h"
#include "test.h"

#include <string.h>

/* A pose of n billboards (indices idx), every sample offset by (d, 0, 0). */
static void make_pose(measure_bb_pose_t *p, const int *idx, int n, float d)
{
    p->count = n;
    p->index = malloc(sizeof *p->index * (size_t)n);
    p->off = calloc((size_t)n, sizeof *p->off);
    for (int i = 0; i < n; i++) {
        p->index[i] = idx[i];
        for (int s = 0; s < MEASURE_POSE_SAMPLES; s++) p->off[i][s][0] = d;
    }
}

int main(void)
{
    double v[5] = {5, 1, 4, 2, 3};
    CHECK_NEAR(measure_percentile(v, 5, 0.5), 3.0, 1e-12);
    CHECK_NEAR(measure_percentile(v, 5, 0.95), 4.8, 1e-12);
    CHECK_NEAR(measure_percentile(v, 5, 1.0), 5.0, 1e-12);
    CHECK(measure_percentile(v, 0, 0.95) == 0.0);

    measure_bb_pose_t a, b, c, none = {0};
    const int ia[3] = {2, 5, 9}, ic[2] = {5, 11};
    make_pose(&a, ia, 3, 0.1f);
    make_pose(&b, ia, 3, 0.3f);
    make_pose(&c, ic, 2, 0.1f);
    CHECK_NEAR(measure_bb_pose_deviation(&a, &a), 0.0, 1e-12);
    CHECK_NEAR(measure_bb_pose_deviation(&a, &b), 0.2, 1e-6);
    CHECK(measure_bb_pose_deviation(&b, &none) > measure_bb_pose_deviation(&a, &none));
    /* union {2, 5, 9, 11}: 2 and 9 against zero (0.1), 5 equal (0), 11 against zero (0.1) */
    CHECK_NEAR(measure_bb_pose_deviation(&a, &c), 0.3 / 4.0, 1e-6);
    CHECK(measure_bb_pose_deviation(&none, &none) == 0.0);
    measure_bb_pose_free(&a);
    measure_bb_pose_free(&b);
    measure_bb_pose_free(&c);
    TEST_END();
}

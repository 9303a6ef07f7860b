/* test_bench_lod: the rule that picks the default chain from the chart's
 * rows (bench_lod_pick): the cheapest within both budgets, rows over the
 * memory or the error left out, blade and billboard rows never picked,
 * and the fallbacks when nothing is within the budgets. */
#include "bench/bench_lod.h"
#include "test.h"

int main(void)
{
    /* meadow_large's compute rows from the H200's 300-frame chart */
    const bench_lod_row_t rows[] = {
        {false, 3.00, 0.158, 878.3}, /* blade mode: the most accurate, never a pick */
        {true, 2.22, 0.367, 336.0},  /* tiles to 40 m: cheapest, over the error */
        {true, 2.40, 0.360, 361.5},  /* tiles to 50 m */
        {true, 2.57, 0.328, 390.1},  /* tiles to 60 m: the pick */
        {true, 2.97, 0.294, 447.8},  /* tiles to 80 m: over the memory */
        {true, 4.45, 0.472, 392.0},  /* billboards to 60 m */
        {false, 5.03, 0.875, 235.5}, /* billboard mode */
    };
    int n = (int)(sizeof rows / sizeof rows[0]);
    bool met = false;
    CHECK(bench_lod_pick(rows, n, BENCH_LOD_ERROR, BENCH_LOD_GPU_MB, &met) == 3 && met);
    /* a looser error budget takes the cheaper tiles to 40 m */
    CHECK(bench_lod_pick(rows, n, 0.37, BENCH_LOD_GPU_MB, &met) == 1 && met);
    /* more memory lets the tiles to 80 m in only where they are the cheapest within the error */
    CHECK(bench_lod_pick(rows, n, 0.30, 500.0, &met) == 4 && met);
    CHECK(bench_lod_pick(rows, n, 0.30, BENCH_LOD_GPU_MB, &met) == 3 && !met);
    /* nothing within the memory: the least error of all, not met */
    CHECK(bench_lod_pick(rows, n, BENCH_LOD_ERROR, 100.0, &met) == 4 && !met);
    /* no candidate */
    CHECK(bench_lod_pick(rows, 1, BENCH_LOD_ERROR, BENCH_LOD_GPU_MB, &met) == -1 && !met);
    TEST_END();
}

/* bench_lod: the default chain's pick from measured rows (bench_lod.h). */
#include "bench/bench_lod.h"

int bench_lod_pick(const bench_lod_row_t *rows, int n, double max_error, double max_mb, bool *met)
{
    int best = -1, least_fit = -1, least = -1;
    for (int i = 0; i < n; i++) {
        const bench_lod_row_t *r = &rows[i];
        if (!r->candidate) continue;
        if (least < 0 || r->error < rows[least].error) least = i;
        if (r->gpu_mb > max_mb) continue;
        if (least_fit < 0 || r->error < rows[least_fit].error) least_fit = i;
        if (r->error <= max_error && (best < 0 || r->wall_ms < rows[best].wall_ms)) best = i;
    }
    *met = best >= 0;
    return best >= 0 ? best : least_fit >= 0 ? least_fit : least;
}

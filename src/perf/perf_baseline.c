/* bench_baseline: `meadow bench --baseline FILE`: every pass median of a
 * perf run (perf.c, measured now or read with --from) against a
 * committed perf.json (docs/perf/h100.json). A pass is slower when
 *     now > base x (1 + PERF_BASELINE_SLOWER_FRAC) + PERF_BASELINE_SLOWER_MS
 * (the fraction covers run-to-run spread of long passes, the constant the
 * timer noise of short ones) and faster when
 *     now < base x (1 - PERF_BASELINE_SLOWER_FRAC) - PERF_BASELINE_SLOWER_MS.
 * Slower passes fail the check (exit 1); faster ones suggest updating the
 * baseline; runs and passes on one side only are listed. Timings of two
 * renderers are not comparable: a renderer mismatch refuses (exit 2)
 * unless forced. */
#include "perf/perf.h"

#include "measure/measure.h"
#include "measure/measure_session.h"

#include <stdio.h>
#include <string.h>

static int find_pass(const perf_run_t *r, const char *name)
{
    for (int k = 0; k < r->pass_count; k++)
        if (strcmp(r->pass_name[k], name) == 0) return k;
    return -1;
}

typedef enum verdict_t { SAME = 0, SLOWER, FASTER } verdict_t;

static verdict_t judge(double now, double base)
{
    if (now > base * (1.0 + PERF_BASELINE_SLOWER_FRAC) + PERF_BASELINE_SLOWER_MS) return SLOWER;
    if (now < base * (1.0 - PERF_BASELINE_SLOWER_FRAC) - PERF_BASELINE_SLOWER_MS) return FASTER;
    return SAME;
}

/* Rows of one verdict as a table under a heading; returns their count. */
static int print_rows(const perf_t *cur, const perf_t *base, verdict_t want, const char *heading)
{
    int n = 0;
    for (int i = 0; i < base->run_count; i++) {
        const perf_run_t *b = &base->runs[i], *c = perf_find(cur, b->name);
        if (!c) continue;
        for (int k = 0; k < b->pass_count; k++) {
            int j = find_pass(c, b->pass_name[k]);
            if (j < 0 || judge(c->pass_ms[j], b->pass_ms[k]) != want) continue;
            if (n++ == 0)
                printf("\n%s than the baseline by more than %.0f %% + %.2f ms:\n\n"
                       "| run | pass | baseline ms | now ms | change | %s ms |\n| --- | --- | --- | --- | --- | --- |\n",
                       heading, 100.0 * PERF_BASELINE_SLOWER_FRAC, PERF_BASELINE_SLOWER_MS,
                       want == SLOWER ? "limit" : "bound");
            double bound = want == SLOWER
                               ? b->pass_ms[k] * (1.0 + PERF_BASELINE_SLOWER_FRAC) + PERF_BASELINE_SLOWER_MS
                               : b->pass_ms[k] * (1.0 - PERF_BASELINE_SLOWER_FRAC) - PERF_BASELINE_SLOWER_MS;
            printf("| %s | %s | %.4f | %.4f | %+.1f %% | %.4f |\n", b->name, b->pass_name[k], b->pass_ms[k],
                   c->pass_ms[j], b->pass_ms[k] > 0 ? 100.0 * (c->pass_ms[j] / b->pass_ms[k] - 1.0) : 0.0, bound);
        }
    }
    return n;
}

/* Runs and passes of `have` that `other` lacks, one line each; returns their count. */
static int print_one_sided(const perf_t *have, const perf_t *other, const char *what)
{
    int n = 0;
    for (int i = 0; i < have->run_count; i++) {
        const perf_run_t *r = &have->runs[i], *o = perf_find(other, r->name);
        if (!o) {
            printf("%s run: %s (%d passes)\n", what, r->name, r->pass_count);
            n++;
            continue;
        }
        for (int k = 0; k < r->pass_count; k++)
            if (find_pass(o, r->pass_name[k]) < 0) {
                printf("%s pass: %s %s (%.4f ms)\n", what, r->name, r->pass_name[k], r->pass_ms[k]);
                n++;
            }
    }
    return n;
}

int perf_baseline_check(const perf_t *cur, const perf_t *base, const char *base_path, bool force)
{
    if (strcmp(cur->renderer, base->renderer) != 0) {
        if (!force) {
            core_log_error("%s was measured on '%s', this run on '%s': their timings cannot be compared "
                           "(--force compares them anyway)",
                           base_path, base->renderer, cur->renderer);
            return 2;
        }
        core_log_warn("baseline: comparing '%s' with '%s' (--force)", cur->renderer, base->renderer);
    }
    if (cur->frames != base->frames || cur->quick != base->quick)
        core_log_warn("baseline: %s ran %d frames%s, this run %d%s", base_path, base->frames,
                      base->quick ? " (--quick)" : "", cur->frames, cur->quick ? " (--quick)" : "");
    int compared = 0;
    for (int i = 0; i < base->run_count; i++) {
        const perf_run_t *b = &base->runs[i], *c = perf_find(cur, b->name);
        if (!c) continue;
        if (c->fell_back != b->fell_back)
            core_log_warn("baseline: %s %s the hardware path here, not in the baseline", c->name,
                          c->fell_back ? "fell back to" : "did not fall back to");
        for (int k = 0; k < b->pass_count; k++) compared += find_pass(c, b->pass_name[k]) >= 0;
    }
    printf("baseline %s: %s, %s, %d frames\nthis run: %s, %s, %d frames\n", base_path, base->renderer, base->date,
           base->frames, cur->renderer, cur->date, cur->frames);
    int slower = print_rows(cur, base, SLOWER, "Slower");
    int faster = print_rows(cur, base, FASTER, "Faster");
    printf("\n");
    int missing = print_one_sided(base, cur, "missing");
    int added = print_one_sided(cur, base, "new");
    printf("baseline: %d pass medians compared: %d slower, %d faster, %d missing, %d new\n", compared, slower, faster,
           missing, added);
    if (faster)
        printf("note: %d pass(es) got faster; if that is meant, update the baseline (copy this run's perf.json to "
               "%s) and say why in the commit\n",
               faster, base_path);
    if (slower) {
        core_log_error("%d pass median(s) slower than %s by more than %.0f %% + %.2f ms", slower, base_path,
                       100.0 * PERF_BASELINE_SLOWER_FRAC, PERF_BASELINE_SLOWER_MS);
        return 1;
    }
    return 0;
}

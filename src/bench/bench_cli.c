/* bench_cli: the command line of `meadow bench` and `meadow compare`. The
 * harness's own options are a table here; every other option goes to the
 * program's parser (bench_program_t: app_parse_option, from src/main.c), so
 * both commands take --scene, --frames, --size, --mode, --out and the rest. Bad values and options
 * that do not combine get one line naming them (exit 2). */
#include "bench/bench.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

#include "core/core.h"

/* The harness's options: a flag (bool at `at`) when `empty` is NULL, else
 * a non-empty value of at most CORE_PATH_MAX - 1 bytes (const char * at
 * `at`; `empty` names what an empty one would be: "OPTION: empty WHAT"). */
static const struct {
    const char *name, *empty;
    size_t at;
} bench_opts[] = {
    {"--quick", NULL, offsetof(bench_options_t, quick)},
    {"--stability", NULL, offsetof(bench_options_t, stability)},
    {"--case", "case name", offsetof(bench_options_t, stability_case)},
    {"--chart", "chart name", offsetof(bench_options_t, chart)},
    {"--rows", "label prefixes", offsetof(bench_options_t, rows)},
    {"--scaling", NULL, offsetof(bench_options_t, scaling)},
    {"--video", NULL, offsetof(bench_options_t, video)},
    {"--report", "folder name", offsetof(bench_options_t, report)},
    {"--perf", "path", offsetof(bench_options_t, perf)},
    {"--baseline", "path", offsetof(bench_options_t, baseline)},
    {"--from", "path", offsetof(bench_options_t, perf_from)},
    {"--doc", "path", offsetof(bench_options_t, doc)},
    {"--force", NULL, offsetof(bench_options_t, force)},
    {"--papers", "folder name", offsetof(bench_options_t, papers)},
};
#define BENCH_OPT_COUNT (int)(sizeof bench_opts / sizeof bench_opts[0])

/* `meadow bench --help`: the harness's options, then the program's. */
static void print_usage(const bench_program_t *program)
{
    printf("usage: meadow bench [options]     speed-vs-accuracy sweep, stability, scaling, report\n"
           "       meadow compare [options]   the same frame in every mode against the reference\n"
           "  --quick               bench: small sweep for CI\n"
           "  --video               compare: record each mode as PNG frames and an mp4 (ffmpeg)\n"
           "  --stability           bench: run the stability suite (where each method breaks)\n"
           "  --case NAME           bench --stability: run only the case NAME (e.g. resting_blade)\n"
           "  --chart NAME          bench: run only the sweep's configurations of chart NAME (e.g. modes)\n"
           "  --rows P1,P2          bench --chart: only its configurations whose label starts with P1 or P2\n"
           "  --scaling             bench: tile simulation time vs field size and vs active tiles\n"
           "  --report DIR          bench: sweep + stability + scaling + compare, charts and RESULTS.md into DIR\n"
           "  --perf DIR            bench: bench scenes x {hw, compute}, pass medians to DIR/perf.json,\n"
           "                        regenerates docs/PERFORMANCE.md's measured section (--quick: tiny scenes)\n"
           "  --baseline FILE       bench: run (or --from) and compare every pass median with FILE; exit 1\n"
           "                        when one is slower by more than 15 %% + 0.02 ms\n"
           "  --from FILE           bench --perf/--baseline: use a saved perf.json instead of running\n"
           "  --doc FILE            bench --perf: the doc to regenerate (default docs/PERFORMANCE.md; none\n"
           "                        with --quick)\n"
           "  --force               bench --baseline: compare even when the renderers differ\n"
           "  --papers DIR          bench: blade ablations, billboard cost vs colliding leaves, papers table into\n"
           "                        DIR (with --report: the paper scenes, into RESULTS.md too; else --scene: that\n"
           "                        scene's ablations alone)\n"
           "and the program's options (--out default: out/bench for bench, out for compare):\n");
    program->usage();
}

static int find_option(const char *arg)
{
    for (int k = 0; k < BENCH_OPT_COUNT; k++)
        if (strcmp(arg, bench_opts[k].name) == 0) return k;
    return -1;
}

bool bench_is_option(const char *arg)
{
    return find_option(arg) >= 0;
}

/* How the options combine; 2 after err when they do not. */
static int check_options(const bench_options_t *o, char *err, size_t err_size)
{
    bool bench = !o->compare, perf = o->perf || o->baseline;
    const char *why = NULL;
    if ((perf || o->perf_from || o->doc || o->force) && !bench)
        why = "--perf, --baseline, --from, --doc and --force are options of `meadow bench`";
    else if ((o->perf_from || o->doc) && !perf)
        why = o->doc ? "--doc needs --perf or --baseline (see --help)"
                     : "--from needs --perf or --baseline (see --help)";
    else if (o->force && !o->baseline)
        why = "--force needs --baseline (see --help)";
    else if (o->stability_case && (!bench || !o->stability))
        why = "--case needs `meadow bench --stability` (see --help)";
    else if (o->rows && !o->chart)
        why = "--rows needs --chart (see --help)";
    else if (o->chart && (!bench || o->stability || o->scaling || o->report || perf))
        why = "--chart needs `meadow bench` without --stability, --scaling, --report or --perf";
    else if (o->papers && (!bench || perf || o->chart))
        why = "--papers needs `meadow bench` without --perf, --baseline or --chart";
    else if (perf && (o->report || o->stability || o->scaling))
        why = "--perf and --baseline cannot be combined with --report, --stability or --scaling";
    if (!why) return 0;
    snprintf(err, err_size, "%s", why);
    return 2;
}

int bench_parse_options(int argc, char **argv, const bench_program_t *program, bench_options_t *o, char *err,
                        size_t err_size)
{
    memset(o, 0, sizeof *o);
    o->compare = strcmp(argv[1], "compare") == 0;
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            print_usage(program);
            return 1;
        }
        int k = find_option(a);
        if (k < 0) {
            int st = program->option(argc, argv, &i, program->user, err, err_size);
            if (st == 1 || st == 2) return st;
            if (st == 3) {
                snprintf(err, err_size, "unknown option '%s' (see --help)", a);
                return 2;
            }
            continue;
        }
        char *slot = (char *)o + bench_opts[k].at;
        if (!bench_opts[k].empty) {
            *(bool *)slot = true;
            continue;
        }
        if (i + 1 >= argc) {
            snprintf(err, err_size, "option %s needs a value (see --help)", a);
            return 2;
        }
        const char *v = argv[++i];
        if (!*v) {
            snprintf(err, err_size, "%s: empty %s", a, bench_opts[k].empty);
            return 2;
        }
        if (strlen(v) >= CORE_PATH_MAX) {
            snprintf(err, err_size, "%s: %zu bytes, more than the %d this program keeps", a, strlen(v),
                     CORE_PATH_MAX - 1);
            return 2;
        }
        *(const char **)slot = v;
    }
    return check_options(o, err, err_size);
}

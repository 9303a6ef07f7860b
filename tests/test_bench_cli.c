/* test_bench_cli: `meadow bench` and `meadow compare` parse their own
 * options (bench_parse_options) and hand the program's to the program's
 * parser (app_parse_option, as src/main.c gives it); each bad value or
 * combination gets one line naming the option; the harness's options are
 * known as its own (bench_is_option). */
#include "app/app.h"
#include "bench/bench.h"
#include "test.h"

#include <string.h>

static app_options_t app;

static int program_option(int argc, char **argv, int *i, void *opts, char *err, size_t err_size)
{
    return (int)app_parse_option(argc, argv, i, opts, err, err_size);
}

static int parse(bench_options_t *o, char *err, int n, char **argv)
{
    err[0] = 0;
    memset(&app, 0, sizeof app);
    bench_program_t program = {.option = program_option, .usage = app_print_options, .user = &app};
    return bench_parse_options(n, argv, &program, o, err, 256);
}

int main(void)
{
    bench_options_t o;
    char err[256];
    char *quick[] = {"meadow", "bench", "--quick", "--frames", "10", "--scene", "s.json", "--chart", "modes",
                     "--rows", "tiles,blade"};
    CHECK(parse(&o, err, 11, quick) == 0 && !o.compare && o.quick && strcmp(o.chart, "modes") == 0 &&
          strcmp(o.rows, "tiles,blade") == 0);
    CHECK(app.frames == 10 && app.frames_set && strcmp(app.scene, "s.json") == 0);
    char *video[] = {"meadow", "compare", "--video", "--mode", "blade"};
    CHECK(parse(&o, err, 5, video) == 0 && o.compare && o.video && app.mode == APP_MODE_BLADE);
    char *perf[] = {"meadow", "bench", "--perf", "p", "--baseline", "b.json", "--from", "f.json", "--force"};
    CHECK(parse(&o, err, 9, perf) == 0 && strcmp(o.perf, "p") == 0 && strcmp(o.baseline, "b.json") == 0 &&
          strcmp(o.perf_from, "f.json") == 0 && o.force);

    struct {
        int n;
        char *argv[6];
        const char *msg;
    } bad[] = {
        {4, {"meadow", "compare", "--perf", "p"}, "options of `meadow bench`"},
        {4, {"meadow", "bench", "--from", "p.json"}, "--from needs --perf or --baseline"},
        {4, {"meadow", "bench", "--doc", "d.md"}, "--doc needs --perf or --baseline"},
        {5, {"meadow", "bench", "--perf", "p", "--force"}, "--force needs --baseline"},
        {4, {"meadow", "bench", "--baseline", ""}, "--baseline: empty path"},
        {5, {"meadow", "bench", "--perf", "p", "--scaling"}, "cannot be combined"},
        {4, {"meadow", "bench", "--case", "resting_blade"}, "--case needs `meadow bench --stability`"},
        {5, {"meadow", "bench", "--chart", "modes", "--stability"}, "--chart needs `meadow bench` without"},
        {4, {"meadow", "bench", "--rows", "tiles"}, "--rows needs --chart"},
        {6, {"meadow", "bench", "--papers", "d", "--chart", "modes"}, "--papers needs `meadow bench` without"},
        {3, {"meadow", "bench", "--report"}, "option --report needs a value"},
        {4, {"meadow", "compare", "--chart", "modes"}, "--chart needs `meadow bench`"},
        {4, {"meadow", "bench", "--frames", "0"}, "1..10000000 (scene key frames)"},
        {3, {"meadow", "bench", "--bogus"}, "unknown option '--bogus'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++)
        CHECK_MSG(parse(&o, err, bad[i].n, bad[i].argv) == 2 && strstr(err, bad[i].msg), "case %zu -> '%s'", i,
                  err);
    CHECK(bench_is_option("--perf") && bench_is_option("--video") && bench_is_option("--case"));
    CHECK(!bench_is_option("--frames") && !bench_is_option("--help") && !bench_is_option("bench"));
    TEST_END();
}

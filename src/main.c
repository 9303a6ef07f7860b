/* main: entry point of the meadow program (see app.h and --help), above
 * both modules it runs: the program (src/app) or its evaluation harness
 * (src/bench). */
#include "app/app.h"
#include "bench/bench.h"

#include "character/character_load.h"
#include "core/core.h"

int main(int argc, char **argv)
{
    app_options_t opts;
    char err[512];
    int rc = app_parse_args(argc, argv, &opts, err, sizeof err);
    if (rc == 1) return 0;
    if (rc == 2) {
        core_log_error("%s", err);
        return 2;
    }
    if (opts.list_clips) return character_print_clips(opts.list_clips, stdout) ? 0 : 2;
    app_signal_install();
    core_log_set_quiet(opts.quiet);
    switch (opts.command) {
    case APP_CMD_COMPARE: return bench_compare(&opts);
    case APP_CMD_BENCH: return bench_run(&opts);
    default: return app_run(&opts, bench_compare_write);
    }
}

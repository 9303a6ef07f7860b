/* main: entry point of the meadow program, above both modules it runs:
 * `meadow bench ...` and `meadow compare ...` go to the evaluation harness
 * (src/bench, which parses its own options and the program's), everything
 * else to the program (src/app, see app.h and --help). */
#include "app/app.h"
#include "bench/bench.h"

#include <string.h>

#include "character/character_load.h"
#include "core/core.h"

/* The program's command line (app_parse_args); an unknown option that is
 * one of the harness's, or a first word that is no command, is named as
 * such. Returns 0, 1 (help printed) or 2 (err). */
static int parse_program(int argc, char **argv, app_options_t *o, char *err, size_t err_size)
{
    int rc = app_parse_args(argc, argv, o, err, err_size);
    const char *a = o->unknown_arg ? argv[o->unknown_arg] : NULL;
    if (rc == 2 && a && bench_is_option(a))
        snprintf(err, err_size, "'%s' is one of the options of `meadow bench` or `meadow compare` (see meadow "
                 "bench --help)", a);
    else if (rc == 2 && a && o->unknown_arg == 1 && a[0] != '-')
        snprintf(err, err_size, "unknown command '%s' (expected bench or compare; see --help)", a);
    return rc;
}

int main(int argc, char **argv)
{
    char err[512] = "";
    bool harness = argc > 1 && (strcmp(argv[1], "bench") == 0 || strcmp(argv[1], "compare") == 0);
    bench_options_t b;
    app_options_t o;
    int rc = harness ? bench_parse_options(argc, argv, &b, err, sizeof err)
                     : parse_program(argc, argv, &o, err, sizeof err);
    if (rc == 1) return 0;
    if (rc == 2) {
        core_log_error("%s", err);
        return 2;
    }
    const app_options_t *a = harness ? &b.app : &o;
    if (a->list_clips) return character_print_clips(a->list_clips, stdout) ? 0 : 2;
    app_signal_install();
    core_log_set_quiet(a->quiet);
    if (!harness) return app_run(&o, bench_compare_write);
    return b.compare ? bench_compare(&b) : bench_run(&b);
}

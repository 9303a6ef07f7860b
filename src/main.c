/* main: entry point of the meadow program, above both modules it runs:
 * `meadow bench ...` and `meadow compare ...` go to the evaluation harness
 * (src/bench, which parses its own options and hands the rest to the
 * program's parser given here), everything else to the program (src/app,
 * see app.h and --help). The harness takes the program's options as
 * world options (app_world_options) and includes nothing of app. */
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

/* bench_program_t.option: the program's parser of one option, its codes
 * those of app_option_status_t. */
_Static_assert(APP_OPTION_TAKEN == 0 && APP_OPTION_EXIT == 1 && APP_OPTION_BAD == 2 && APP_OPTION_UNKNOWN == 3,
               "bench_program_t.option's return codes");
static int program_option(int argc, char **argv, int *i, void *opts, char *err, size_t err_size)
{
    return (int)app_parse_option(argc, argv, i, opts, err, err_size);
}

/* `meadow bench ...` and `meadow compare ...`: the harness's options into
 * *b, the program's into *o, then what the harness takes of the latter. */
static int parse_harness(int argc, char **argv, bench_options_t *b, app_options_t *o, char *err, size_t err_size)
{
    memset(o, 0, sizeof *o);
    bench_program_t program = {.option = program_option, .usage = app_print_options, .user = o};
    int rc = bench_parse_options(argc, argv, &program, b, err, err_size);
    b->world = app_world_options(o);
    b->frames = o->frames;
    b->frames_set = o->frames_set;
    b->out = o->out;
    b->interrupted = app_interrupted;
    return rc;
}

int main(int argc, char **argv)
{
    char err[512] = "";
    bool harness = argc > 1 && (strcmp(argv[1], "bench") == 0 || strcmp(argv[1], "compare") == 0);
    bench_options_t b;
    app_options_t o;
    int rc = harness ? parse_harness(argc, argv, &b, &o, err, sizeof err)
                     : parse_program(argc, argv, &o, err, sizeof err);
    if (rc == 1) return 0;
    if (rc == 2) {
        core_log_error("%s", err);
        return 2;
    }
    if (o.list_clips) return character_print_clips(o.list_clips, stdout) ? 0 : 2;
    app_signal_install();
    core_log_set_quiet(o.quiet);
    if (!harness) return app_run(&o, bench_compare_write);
    return b.compare ? bench_compare(&b) : bench_run(&b);
}

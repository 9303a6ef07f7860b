/* app: the meadow program: command line, main loop, world (terrain, grass,
 * colliders, characters), HUD, screenshots and the run summary. `meadow
 * bench` and `meadow compare` are the evaluation harness in src/bench. */
#ifndef MEADOW_APP_H
#define MEADOW_APP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "world/world.h"

typedef enum app_mode_t {
    APP_MODE_SCENE = 0, /* whatever the scene file says */
    APP_MODE_BILLBOARD,
    APP_MODE_BLADE,
    APP_MODE_HYBRID,
} app_mode_t;

/* Parsed command line: the program's options (`meadow bench` and `meadow
 * compare` take them too, with their own: bench_options_t, src/bench). Zero
 * means "not given" (the scene or the defaults decide). Bounds are checked
 * by app_parse_option. */
typedef struct app_options_t {
    const char *scene;        /* default scenes/meadow.json */
    bool headless;            /* force EGL */
    int frames;               /* default: 300 headless, unlimited windowed */
    bool frames_set;
    uint64_t seed;            /* as the scene key seed, 0..2^32-1 */
    bool seed_set;
    int width, height;        /* --size WxH, each side as the scene key size (16..16384) */
    const char *out;          /* default "out" */
    int screenshot_every;     /* default: frames/3 headless (3 shots), 0 windowed */
    bool screenshot_every_set; /* --screenshot-every given (0: never) */
    app_mode_t mode;
    const char *character;    /* --character PATH: replaces the scene's models */
    const char *clip;         /* --clip NAME|INDEX|START:END */
    float character_height;   /* --character-height M: every character's height; 0 = automatic */
    const char *list_clips;   /* --list-clips MODEL: print its clips and exit */
    int blade_render;         /* --blade-render: 0 = the scene's, else 1 + scene_blade_render_t */
    int raster;               /* --raster: 0 = the scene's, else 1 + scene_raster_t */
    int raster_samples;       /* --raster-samples 1|4: compute rasterizer samples per pixel; 0 = the scene's */
    bool floor;               /* --floor: measure the hardware floor at the end */
    bool view_cards;          /* --view-cards: billboards whose clump appearance follows the view
                                 (bb_view_desc_t.on, docs/BILLBOARDS.md) */
    bool montage;             /* --montage: end a headless run with the mode montage */
    int overlay;              /* --overlay 0..3: debug overlay at start (key O cycles) */
    bool quiet;
    bool frame_log;           /* --frame-log: OUT/frames.csv, a row per frame (app_trace.h) */
    int unknown_arg;          /* set by app_parse_args: argv index of the unknown option it
                                 refused, 0 when none */
} app_options_t;


/* What the world takes of the options (world_load). */
world_options_t app_world_options(const app_options_t *o);

/* What app_parse_option made of argv[*i]. */
typedef enum app_option_status_t {
    APP_OPTION_TAKEN = 0, /* one of the program's; *i is at its value if it has one */
    APP_OPTION_EXIT,      /* --help or --scene-keys: printed, exit 0 */
    APP_OPTION_BAD,       /* err holds one line saying which and why: exit 2 */
    APP_OPTION_UNKNOWN,   /* not one of the program's options; nothing changed */
} app_option_status_t;

/* Parses the one option at argv[*i] into opts (the caller zeroes opts
 * first); the parser of `meadow bench` (src/bench) hands it every option
 * that is not its own. */
app_option_status_t app_parse_option(int argc, char **argv, int *i, app_options_t *opts, char *err, size_t err_size);
/* The whole command line argv[1..] as options of the program. Returns 0 to
 * run, 1 when --help or --scene-keys printed, 2 on a bad argument (err
 * holds one line: an unknown option is "unknown option 'X' (see --help)",
 * its index in opts->unknown_arg). */
int app_parse_args(int argc, char **argv, app_options_t *opts, char *err, size_t err_size);
/* `meadow --help`: the usage line, the program's options and its keys. */
void app_print_usage(void);
/* The program's options alone, one or two lines each (`meadow bench
 * --help` lists them after its own). */
void app_print_options(void);

/* Ctrl-C / SIGTERM / SIGHUP: the first one asks long runs to stop after the
 * current frame or configuration and write what they have (app_signal.c). */
void app_signal_install(void);
bool app_interrupted(void);

/* What --montage ends a headless run with, in the run's GL context: the
 * `meadow compare` montage of the world of the run's options
 * (app_world_options), frame `frames`, into `out` (bench_compare_write,
 * src/bench). Returns 0 or 1. */
typedef int (*app_montage_fn)(const world_options_t *world, const char *out, int frames);

/* The HUD's pass timings (app_hud.c): one line per pass that ran within
 * the last APP_HUD_STALE_FRAMES frames; passes that no longer run (after a
 * mode switch) are left out. Writes at most size bytes to buf (NUL
 * terminated when size > 0) and returns the length written. */
#define APP_HUD_STALE_FRAMES 30
/* Frames summary.txt's frame times and the frame log (app_trace.h) keep:
 * the latest this many. */
#define APP_FRAME_HISTORY 16384
typedef struct app_hud_pass_t {
    const char *name;
    double ms;        /* latest timing */
    int frames_since; /* frames since the pass last ran (0: this frame) */
} app_hud_pass_t;
int app_hud_timings(const app_hud_pass_t *passes, int count, char *buf, size_t size);

/* Runs the program; returns the process exit code: 0, 1 (a failure), 2 (bad
 * input) or APP_EXIT_INTERRUPTED (SIGINT, SIGTERM or SIGHUP ended the run
 * early; the summary was written and says frames done of asked). `montage` may be
 * NULL when opts->montage is false. */
#define APP_EXIT_INTERRUPTED 130
int app_run(const app_options_t *opts, app_montage_fn montage);

#endif

/* app: the meadow program: command line, main loop, world (terrain, grass,
 * colliders, characters), HUD, screenshots and the run summary. `meadow
 * bench` and `meadow compare` are the evaluation harness in src/bench. */
#ifndef MEADOW_APP_H
#define MEADOW_APP_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef enum app_mode_t {
    APP_MODE_SCENE = 0, /* whatever the scene file says */
    APP_MODE_BILLBOARD,
    APP_MODE_BLADE,
    APP_MODE_HYBRID,
} app_mode_t;

typedef enum app_command_t {
    APP_CMD_RUN = 0,
    APP_CMD_BENCH,
    APP_CMD_COMPARE,
} app_command_t;

/* Parsed command line. Zero means "not given" (the scene or the defaults
 * decide). Bounds are checked by app_parse_args. */
typedef struct app_options_t {
    app_command_t command;
    const char *scene;        /* default scenes/meadow.json */
    bool headless;            /* force EGL */
    int frames;               /* default: 300 headless, unlimited windowed */
    bool frames_set;
    uint64_t seed;
    bool seed_set;
    int width, height;        /* --size WxH, 16..8192 */
    const char *out;          /* default "out" */
    int screenshot_every;     /* default: frames/3 headless (3 shots), 0 windowed */
    app_mode_t mode;
    const char *character;    /* --character PATH: replaces the scene's models */
    const char *clip;         /* --clip NAME|INDEX|START:END */
    int blade_render;         /* 0 = vertex pulling (default), 1 = tessellation */
    int raster;               /* --raster: 0 = the scene's, else 1 + scene_raster_t */
    int raster_samples;       /* --raster-samples 1|4: compute rasterizer samples per pixel; 0 = 4 */
    bool quick;               /* bench --quick */
    bool floor;               /* --floor: measure the hardware floor at the end */
    bool stability;           /* bench --stability: the stability suite only */
    bool scaling;             /* bench --scaling: tile simulation vs field size and active tiles only */
    bool montage;             /* --montage: end a headless run with the mode montage */
    bool video;               /* compare --video: a clip per mode (ffmpeg) */
    int overlay;              /* --overlay 0..3: debug overlay at start (key O cycles) */
    const char *report;       /* bench --report DIR: sweep + stability + compare, RESULTS.md into DIR */
    bool quiet;
} app_options_t;

#define APP_MAX_FRAMES 10000000
#define APP_MAX_SIZE 8192
#define APP_MIN_SIZE 16

/* Returns 0 to run, 1 when --help was printed, 2 on a bad argument (err
 * holds one line saying which and why). */
int app_parse_args(int argc, char **argv, app_options_t *opts, char *err, size_t err_size);
void app_print_usage(void);

/* Ctrl-C / SIGTERM: the first one asks long runs to stop after the current
 * frame or configuration and write what they have (app_signal.c). */
void app_signal_install(void);
bool app_interrupted(void);

/* What --montage ends a headless run with, in the run's GL context: the
 * `meadow compare` montage of frame `frames` into `out` (bench_compare_write,
 * src/bench). Returns 0 or 1. */
typedef int (*app_montage_fn)(const app_options_t *opts, const char *out, int frames);

/* Runs the program; returns the process exit code. `montage` may be NULL
 * when opts->montage is false. */
int app_run(const app_options_t *opts, app_montage_fn montage);

#endif

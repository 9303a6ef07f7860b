/* app_cli: parsing and validation of the meadow command line. Every bad
 * value gets one line naming the option, the value and the allowed range;
 * options that set a scene value (--frames, --seed, --size,
 * --raster-samples) take their range from the scene's key table. */
#include "app/app.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "character/character_import.h"
#include "scene/scene.h"
#include "scene/scene_fields.h"

void app_print_usage(void)
{
    printf("usage: meadow [bench|compare] [options]\n"
           "  --scene FILE          scene description (default scenes/meadow.json)\n"
           "  --headless            render offscreen through EGL (automatic without a display)\n"
           "  --frames N            frames to run (default 300 headless, unlimited in a window)\n"
           "  --seed N              random seed, 0..4294967295 (default: the scene's)\n"
           "  --size WxH            framebuffer size, %d..%d per side (default: the scene's)\n"
           "  --out DIR             output folder for screenshots and summary (default out)\n"
           "  --screenshot-every N  write a PNG every N frames (default: 3 per headless run)\n"
           "  --mode M              billboard | blade | hybrid (default: the scene's)\n"
           "  --character PATH      walk this assimp-loadable model through the field\n"
           "  --clip SPEC           clip by name, index or frame range START:END\n"
           "  --character-height M  fit every character to M metres tall (0.01..1000; default: automatic)\n"
           "  --list-clips MODEL    print MODEL's clips (name, duration, keys) and exit\n"
           "  --blade-render R      pull (vertex pulling) | tess (tessellation shaders), blade mode and the\n"
           "                        hybrid's tiles; default: the scene's (pull)\n"
           "  --raster R            hw (hardware pipeline) | compute (compute rasterizer) | auto (faster\n"
           "                        of the two, measured at start-up); default: the scene's (hw)\n"
           "  --raster-samples N    compute rasterizer samples per pixel: 4 (default, the 4x MSAA pattern) or 1\n"
           "  --quick               bench: small sweep for CI\n"
           "  --floor               end the run by timing its triangle count with trivial shaders\n"
           "  --view-cards          billboards whose clump appearance follows the view and the wind\n"
           "  --montage             headless: end with compare.png, the last frame in every mode\n"
           "  --overlay N           debug overlay: 0 off, 1 tile/leaf state, 2 LOD, 3 collision strength\n"
           "  --video               compare: record each mode as PNG frames and an mp4 (ffmpeg)\n"
           "  --stability           bench: run the stability suite (where each method breaks)\n"
           "  --case NAME           bench --stability: run only the case NAME (e.g. resting_blade)\n"
           "  --chart NAME          bench: run only the sweep's configurations of chart NAME (e.g. modes)\n"
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
           "  --quiet               only warnings and errors\n"
           "  --scene-keys          print the scene file keys (markdown, docs/SCENES.md)\n"
           "  --help                this text\n"
           "keys: WASD/QE move, arrows look, Shift fast, P pause, N single step, F12/C screenshot,\n"
           "      F wireframe, 1/2/3 billboard/blade/hybrid, R hardware/compute raster, O overlays (state, LOD,\n"
           "      collision), H HUD, Esc quit\n",
           (int)scene_field_find(SCENE_SEC_ROOT, "size")->lo, (int)scene_field_find(SCENE_SEC_ROOT, "size")->hi);
}

static bool parse_int(const char *s, long lo, long hi, long *out)
{
    if (!s || !*s) return false;
    errno = 0;
    char *end;
    long v = strtol(s, &end, 10);
    if (errno || *end || v < lo || v > hi) return false;
    *out = v;
    return true;
}

/* The value of an option that sets top-level scene key `key`: what the key
 * accepts (scene_field_accepts, the scene's one limit table), 0 excepted
 * where 0 would mean "the default" (give no option for that). On failure
 * err says "OPTION 'VALUE': expected ... (scene key KEY)". */
static bool scene_option(const char *opt, const char *v, const char *key, long *out, char *err, size_t err_size)
{
    const scene_field_t *f = scene_field_find(SCENE_SEC_ROOT, key);
    char why[160];
    long n;
    if (parse_int(v, LONG_MIN, LONG_MAX, &n) && scene_field_accepts(f, (double)n, why, sizeof why) &&
        !(n == 0 && (f->flags & SCENE_FIELD_ZERO_OK))) {
        *out = n;
        return true;
    }
    if (f->flags & SCENE_FIELD_ENDS)
        snprintf(err, err_size, "%s '%s': expected %.10g or %.10g (scene key %s)", opt, v, f->lo, f->hi, key);
    else
        snprintf(err, err_size, "%s '%s': expected an integer in %.10g..%.10g (scene key %s)", opt, v, f->lo, f->hi,
                 key);
    return false;
}

/* --size WxH: each side what the scene key size accepts. */
static bool size_option(const char *v, app_options_t *o, char *err, size_t err_size)
{
    const scene_field_t *f = scene_field_find(SCENE_SEC_ROOT, "size");
    char extra, why[160];
    long w, h;
    if (sscanf(v, "%ldx%ld%c", &w, &h, &extra) == 2 && w != 0 && h != 0 &&
        scene_field_accepts(f, (double)w, why, sizeof why) && scene_field_accepts(f, (double)h, why, sizeof why)) {
        o->width = (int)w;
        o->height = (int)h;
        return true;
    }
    snprintf(err, err_size, "--size '%s': expected WxH with each side in %.10g..%.10g (scene key size)", v, f->lo,
             f->hi);
    return false;
}

int app_parse_args(int argc, char **argv, app_options_t *o, char *err, size_t err_size)
{
    memset(o, 0, sizeof *o);
    int i = 1;
    if (argc > 1 && argv[1][0] != '-') {
        if (strcmp(argv[1], "bench") == 0) o->command = APP_CMD_BENCH;
        else if (strcmp(argv[1], "compare") == 0) o->command = APP_CMD_COMPARE;
        else {
            snprintf(err, err_size, "unknown command '%s' (expected bench or compare; see --help)", argv[1]);
            return 2;
        }
        i = 2;
    }
    for (; i < argc; i++) {
        const char *a = argv[i];
        const char *v = i + 1 < argc ? argv[i + 1] : NULL;
        long n;
#define NEED_VALUE()                                                              \
    do {                                                                          \
        if (!v) {                                                                 \
            snprintf(err, err_size, "option %s needs a value (see --help)", a); \
            return 2;                                                             \
        }                                                                         \
        i++;                                                                      \
    } while (0)
/* NEED_VALUE, and the value may not be empty ("OPTION: empty WHAT"). */
#define NEED_NONEMPTY(what)                                                       \
    do {                                                                          \
        NEED_VALUE();                                                             \
        if (!*v) {                                                                \
            snprintf(err, err_size, "%s: empty %s", a, what);                     \
            return 2;                                                             \
        }                                                                         \
    } while (0)
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            app_print_usage();
            return 1;
        } else if (strcmp(a, "--scene-keys") == 0) {
            char *md = scene_keys_markdown();
            if (!md) {
                snprintf(err, err_size, "--scene-keys: out of memory");
                return 2;
            }
            fputs(md, stdout);
            free(md);
            return 1;
        } else if (strcmp(a, "--headless") == 0) {
            o->headless = true;
        } else if (strcmp(a, "--quick") == 0) {
            o->quick = true;
        } else if (strcmp(a, "--floor") == 0) {
            o->floor = true;
        } else if (strcmp(a, "--view-cards") == 0) {
            o->view_cards = true;
        } else if (strcmp(a, "--montage") == 0) {
            o->montage = true;
        } else if (strcmp(a, "--overlay") == 0) {
            NEED_VALUE();
            if (!parse_int(v, 0, 3, &n)) {
                snprintf(err, err_size, "--overlay '%s': expected 0 (off), 1 (state), 2 (LOD) or 3 (collision)", v);
                return 2;
            }
            o->overlay = (int)n;
        } else if (strcmp(a, "--video") == 0) {
            o->video = true;
        } else if (strcmp(a, "--stability") == 0) {
            o->stability = true;
        } else if (strcmp(a, "--case") == 0) {
            NEED_NONEMPTY("case name");
            o->stability_case = v;
        } else if (strcmp(a, "--chart") == 0) {
            NEED_NONEMPTY("chart name");
            o->chart = v;
        } else if (strcmp(a, "--scaling") == 0) {
            o->scaling = true;
        } else if (strcmp(a, "--report") == 0) {
            NEED_NONEMPTY("folder name");
            o->report = v;
        } else if (strcmp(a, "--perf") == 0 || strcmp(a, "--baseline") == 0 || strcmp(a, "--from") == 0 ||
                   strcmp(a, "--doc") == 0) {
            NEED_NONEMPTY("path");
            const char **slot = a[2] == 'p' ? &o->perf : a[2] == 'b' ? &o->baseline : a[2] == 'f' ? &o->perf_from
                                                                                             : &o->doc;
            *slot = v;
        } else if (strcmp(a, "--papers") == 0) {
            NEED_NONEMPTY("folder name");
            o->papers = v;
        } else if (strcmp(a, "--force") == 0) {
            o->force = true;
        } else if (strcmp(a, "--quiet") == 0) {
            o->quiet = true;
        } else if (strcmp(a, "--scene") == 0) {
            NEED_VALUE();
            o->scene = v;
        } else if (strcmp(a, "--out") == 0) {
            NEED_NONEMPTY("folder name");
            o->out = v;
        } else if (strcmp(a, "--character") == 0) {
            NEED_VALUE();
            o->character = v;
        } else if (strcmp(a, "--clip") == 0) {
            NEED_VALUE();
            o->clip = v;
        } else if (strcmp(a, "--list-clips") == 0) {
            NEED_NONEMPTY("model path");
            o->list_clips = v;
        } else if (strcmp(a, "--character-height") == 0) {
            NEED_VALUE();
            char *end;
            double h = strtod(v, &end);
            if (end == v || *end || !(h >= 0.01 && h <= CHARACTER_IMPORT_MAX_FIT)) {
                snprintf(err, err_size, "--character-height '%s': expected metres in 0.01..%g", v,
                         (double)CHARACTER_IMPORT_MAX_FIT);
                return 2;
            }
            o->character_height = (float)h;
        } else if (strcmp(a, "--frames") == 0) {
            NEED_VALUE();
            if (!scene_option(a, v, "frames", &n, err, err_size)) return 2;
            o->frames = (int)n;
            o->frames_set = true;
        } else if (strcmp(a, "--screenshot-every") == 0) {
            NEED_VALUE();
            long most = (long)scene_field_find(SCENE_SEC_ROOT, "frames")->hi;
            if (!parse_int(v, 0, most, &n)) {
                snprintf(err, err_size, "--screenshot-every '%s': expected an integer in 0..%ld (0 = never)", v, most);
                return 2;
            }
            o->screenshot_every = (int)n;
            o->screenshot_every_set = true;
        } else if (strcmp(a, "--seed") == 0) {
            NEED_VALUE();
            if (!scene_option(a, v, "seed", &n, err, err_size)) return 2;
            o->seed = (uint32_t)n;
            o->seed_set = true;
        } else if (strcmp(a, "--size") == 0) {
            NEED_VALUE();
            if (!size_option(v, o, err, err_size)) return 2;
        } else if (strcmp(a, "--blade-render") == 0) {
            NEED_VALUE();
            if (strcmp(v, "pull") == 0) o->blade_render = 1 + SCENE_BLADE_RENDER_PULL;
            else if (strcmp(v, "tess") == 0) o->blade_render = 1 + SCENE_BLADE_RENDER_TESS;
            else {
                snprintf(err, err_size, "--blade-render '%s': expected pull or tess", v);
                return 2;
            }
        } else if (strcmp(a, "--raster") == 0) {
            NEED_VALUE();
            scene_raster_t r;
            if (!scene_raster_parse(v, &r)) {
                snprintf(err, err_size, "--raster '%s': expected hw, compute or auto", v);
                return 2;
            }
            o->raster = 1 + (int)r;
        } else if (strcmp(a, "--raster-samples") == 0) {
            NEED_VALUE();
            if (!scene_option(a, v, "raster_samples", &n, err, err_size)) return 2;
            o->raster_samples = (int)n;
        } else if (strcmp(a, "--mode") == 0) {
            NEED_VALUE();
            if (strcmp(v, "billboard") == 0) o->mode = APP_MODE_BILLBOARD;
            else if (strcmp(v, "blade") == 0) o->mode = APP_MODE_BLADE;
            else if (strcmp(v, "hybrid") == 0) o->mode = APP_MODE_HYBRID;
            else {
                snprintf(err, err_size, "--mode '%s': expected billboard, blade or hybrid", v);
                return 2;
            }
        } else {
            snprintf(err, err_size, "unknown option '%s' (see --help)", a);
            return 2;
        }
#undef NEED_VALUE
    }
    bool perf = o->perf || o->baseline;
    if ((perf || o->perf_from || o->doc || o->force) && o->command != APP_CMD_BENCH) {
        snprintf(err, err_size, "--perf, --baseline, --from, --doc and --force are options of `meadow bench`");
        return 2;
    }
    if ((o->perf_from || o->doc) && !perf) {
        snprintf(err, err_size, "%s needs --perf or --baseline (see --help)", o->doc ? "--doc" : "--from");
        return 2;
    }
    if (o->force && !o->baseline) {
        snprintf(err, err_size, "--force needs --baseline (see --help)");
        return 2;
    }
    if (o->stability_case && (o->command != APP_CMD_BENCH || !o->stability)) {
        snprintf(err, err_size, "--case needs `meadow bench --stability` (see --help)");
        return 2;
    }
    if (o->chart && (o->command != APP_CMD_BENCH || o->stability || o->scaling || o->report || perf)) {
        snprintf(err, err_size, "--chart needs `meadow bench` without --stability, --scaling, --report or --perf");
        return 2;
    }
    if (o->papers && (o->command != APP_CMD_BENCH || perf || o->chart)) {
        snprintf(err, err_size, "--papers needs `meadow bench` without --perf, --baseline or --chart");
        return 2;
    }
    if (perf && (o->report || o->stability || o->scaling)) {
        snprintf(err, err_size, "--perf and --baseline cannot be combined with --report, --stability or --scaling");
        return 2;
    }
    return 0;
}

/* app_cli: parsing and validation of the program's options (`meadow
 * bench` parses its own in src/bench/bench_cli.c and hands the rest here).
 * Every bad value gets one line naming the option, the value and the
 * allowed range;
 * options that set a scene value (--frames, --seed, --size,
 * --raster-samples, --character-height) take their range from the scene's
 * key table. */
#include "app/app.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "scene/scene.h"
#include "scene/scene_fields.h"

/* --help's defaults of the options that set a scene key are the key's
 * (its table row), so the two cannot drift apart (--raster said hw while
 * the key's default was auto); cli_errors.sh compares them with
 * --scene-keys. */
void app_print_options(void)
{
    const scene_field_t *frames = scene_field_find(SCENE_SEC_ROOT, "frames"),
                        *seed = scene_field_find(SCENE_SEC_ROOT, "seed"),
                        *size = scene_field_find(SCENE_SEC_ROOT, "size"),
                        *mode = scene_field_find(SCENE_SEC_ROOT, "mode"),
                        *height = scene_field_find(SCENE_SEC_CHARACTER, "height"),
                        *render = scene_field_find(SCENE_SEC_GRASS, "blade_render"),
                        *raster = scene_field_find(SCENE_SEC_ROOT, "raster"),
                        *samples = scene_field_find(SCENE_SEC_ROOT, "raster_samples");
    printf("  --scene FILE          scene description (default scenes/meadow.json)\n"
           "  --headless            render offscreen through EGL (automatic without a display)\n"
           "  --frames N            frames to run; default: the scene's (%g headless; unlimited in a window)\n"
           "  --seed N              random seed, %.0f..%.0f; default: the scene's (%g)\n"
           "  --size WxH            framebuffer size, %g..%g per side; default: the scene's (%gx%g)\n"
           "  --out DIR             output folder for screenshots and summary (default out)\n"
           "  --screenshot-every N  write a PNG every N frames (default: 3 per headless run)\n"
           "  --mode M              billboard | blade | hybrid; default: the scene's (%s)\n"
           "  --character PATH      walk this assimp-loadable model through the field\n"
           "  --clip SPEC           clip by name (a range of the scene's characters[].clips first), index\n"
           "                        or frame range START:END of the first clip (--list-clips: its ticks)\n"
           "  --character-height M  fit every character to M metres tall, %g..%g; default: the scene's\n"
           "                        (%g: automatic)\n"
           "  --list-clips MODEL    print MODEL's clips (name, duration, keys) and exit\n"
           "  --blade-render R      pull (vertex pulling) | tess (tessellation shaders), blade mode and the\n"
           "                        hybrid's tiles; default: the scene's (%s)\n"
           "  --raster R            hw (hardware pipeline) | compute (compute rasterizer) | auto (faster\n"
           "                        of the two, measured at start-up); default: the scene's (%s)\n"
           "  --raster-samples N    compute rasterizer samples per pixel: %g or %g (the 4x MSAA pattern);\n"
           "                        default: the scene's (%g)\n"
           "  --floor               end the run by timing its triangle count with trivial shaders\n"
           "  --view-cards          billboards whose clump appearance follows the view and the wind\n"
           "  --montage             headless: end with compare.png, the last frame in every mode\n"
           "  --overlay N           debug overlay: 0 off, 1 tile/leaf state, 2 LOD, 3 collision strength\n"
           "  --frame-log           also write frames.csv to --out: per frame its times, tile work and GPU passes\n"
           "  --quiet               only warnings and errors on the terminal, no summary (summary.txt and the\n"
           "                        other files are still written; bench --baseline still prints its comparison)\n"
           "  --scene-keys          print the scene file keys (markdown, docs/SCENES.md)\n"
           "  --help                this text\n",
           (double)frames->def[0], seed->lo, seed->hi, (double)seed->def[0], size->lo, size->hi,
           (double)size->def[0], (double)size->def[1], mode->names[0], height->lo, height->hi,
           (double)height->def[0], render->names[0], raster->names[0], samples->lo, samples->hi,
           (double)samples->def[0]);
}

void app_print_usage(void)
{
    printf("usage: meadow [options]\n"
           "       meadow bench|compare [options]   the evaluation harness (meadow bench --help)\n");
    app_print_options();
    printf("keys: WASD/QE move, arrows look, Shift fast, P pause, N single step, F12/C screenshot,\n"
           "      F wireframe, 1/2/3 billboard/blade/hybrid, R hardware/compute raster, O overlays (state, LOD,\n"
           "      collision), H HUD, Esc quit\n");
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

/* The options without a value. */
static bool flag_option(const char *a, app_options_t *o)
{
    if (strcmp(a, "--headless") == 0) o->headless = true;
    else if (strcmp(a, "--floor") == 0) o->floor = true;
    else if (strcmp(a, "--view-cards") == 0) o->view_cards = true;
    else if (strcmp(a, "--montage") == 0) o->montage = true;
    else if (strcmp(a, "--quiet") == 0) o->quiet = true;
    else if (strcmp(a, "--frame-log") == 0) o->frame_log = true;
    else return false;
    return true;
}

/* The options with a value; `empty` names what an empty value would be
 * when one is refused ("OPTION: empty WHAT"; NULL: the value's own check
 * refuses it), `longest` the most bytes of a value the program keeps (0:
 * no limit; a longer one was cut without a word): CORE_PATH_MAX's, or that
 * of the scene key the option replaces. */
static const struct {
    const char *name, *empty;
    size_t longest;
} value_options[] = {
    {"--scene", "path", CORE_PATH_MAX - 1},
    {"--out", "folder name", CORE_PATH_MAX - 1},
    {"--character", "model path", SCENE_PATH_MAX - 1}, /* characters[].model */
    {"--clip", "clip name, index or range", SCENE_NAME_MAX - 1}, /* characters[].clip */
    {"--list-clips", "model path", CORE_PATH_MAX - 1},
    {"--character-height", NULL, 0}, {"--frames", NULL, 0},         {"--screenshot-every", NULL, 0},
    {"--seed", NULL, 0},             {"--size", NULL, 0},           {"--blade-render", NULL, 0},
    {"--raster", NULL, 0},           {"--raster-samples", NULL, 0}, {"--mode", NULL, 0},
    {"--overlay", NULL, 0},
};

/* The options that name one of a few choices: --mode, --blade-render,
 * --raster, --overlay. */
static bool choice_option(const char *a, const char *v, app_options_t *o, char *err, size_t err_size)
{
    long n;
    if (strcmp(a, "--blade-render") == 0) {
        if (strcmp(v, "pull") == 0) o->blade_render = 1 + SCENE_BLADE_RENDER_PULL;
        else if (strcmp(v, "tess") == 0) o->blade_render = 1 + SCENE_BLADE_RENDER_TESS;
        else {
            snprintf(err, err_size, "--blade-render '%s': expected pull or tess", v);
            return false;
        }
    } else if (strcmp(a, "--raster") == 0) {
        scene_raster_t r;
        if (!scene_raster_parse(v, &r)) {
            snprintf(err, err_size, "--raster '%s': expected hw, compute or auto", v);
            return false;
        }
        o->raster = 1 + (int)r;
    } else if (strcmp(a, "--mode") == 0) {
        if (strcmp(v, "billboard") == 0) o->mode = APP_MODE_BILLBOARD;
        else if (strcmp(v, "blade") == 0) o->mode = APP_MODE_BLADE;
        else if (strcmp(v, "hybrid") == 0) o->mode = APP_MODE_HYBRID;
        else {
            snprintf(err, err_size, "--mode '%s': expected billboard, blade or hybrid", v);
            return false;
        }
    } else {
        if (!parse_int(v, 0, 3, &n)) {
            snprintf(err, err_size, "--overlay '%s': expected 0 (off), 1 (state), 2 (LOD) or 3 (collision)", v);
            return false;
        }
        o->overlay = (int)n;
    }
    return true;
}

/* Option a (one of value_options) with its value v; false after err. */
static bool value_option(const char *a, const char *v, app_options_t *o, char *err, size_t err_size)
{
    long n;
    if (strcmp(a, "--scene") == 0) {
        o->scene = v;
    } else if (strcmp(a, "--out") == 0) {
        o->out = v;
    } else if (strcmp(a, "--character") == 0) {
        o->character = v;
    } else if (strcmp(a, "--clip") == 0) {
        o->clip = v;
    } else if (strcmp(a, "--list-clips") == 0) {
        o->list_clips = v;
    } else if (strcmp(a, "--character-height") == 0) {
        const scene_field_t *f = scene_field_find(SCENE_SEC_CHARACTER, "height");
        char *end, why[160];
        double h = strtod(v, &end);
        if (end == v || *end || !(h > 0.0) || !scene_field_accepts(f, h, why, sizeof why)) {
            snprintf(err, err_size, "--character-height '%s': expected metres in %g..%g (scene key characters[].height)",
                     v, f->lo, f->hi);
            return false;
        }
        o->character_height = (float)h;
    } else if (strcmp(a, "--frames") == 0) {
        if (!scene_option(a, v, "frames", &n, err, err_size)) return false;
        o->frames = (int)n;
        o->frames_set = true;
    } else if (strcmp(a, "--screenshot-every") == 0) {
        long most = (long)scene_field_find(SCENE_SEC_ROOT, "frames")->hi;
        if (!parse_int(v, 0, most, &n)) {
            snprintf(err, err_size, "--screenshot-every '%s': expected an integer in 0..%ld (0 = never)", v, most);
            return false;
        }
        o->screenshot_every = (int)n;
        o->screenshot_every_set = true;
    } else if (strcmp(a, "--seed") == 0) {
        if (!scene_option(a, v, "seed", &n, err, err_size)) return false;
        o->seed = (uint32_t)n;
        o->seed_set = true;
    } else if (strcmp(a, "--size") == 0) {
        return size_option(v, o, err, err_size);
    } else if (strcmp(a, "--raster-samples") == 0) {
        if (!scene_option(a, v, "raster_samples", &n, err, err_size)) return false;
        o->raster_samples = (int)n;
    } else {
        return choice_option(a, v, o, err, err_size);
    }
    return true;
}

app_option_status_t app_parse_option(int argc, char **argv, int *i, app_options_t *o, char *err, size_t err_size)
{
    const char *a = argv[*i];
    if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
        app_print_usage();
        return APP_OPTION_EXIT;
    }
    if (strcmp(a, "--scene-keys") == 0) {
        char *md = scene_keys_markdown();
        if (!md) {
            snprintf(err, err_size, "--scene-keys: out of memory");
            return APP_OPTION_BAD;
        }
        fputs(md, stdout);
        free(md);
        return APP_OPTION_EXIT;
    }
    if (flag_option(a, o)) return APP_OPTION_TAKEN;
    size_t k = 0, count = sizeof value_options / sizeof value_options[0];
    while (k < count && strcmp(a, value_options[k].name) != 0) k++;
    if (k == count) return APP_OPTION_UNKNOWN;
    if (*i + 1 >= argc) {
        snprintf(err, err_size, "option %s needs a value (see --help)", a);
        return APP_OPTION_BAD;
    }
    const char *v = argv[++*i];
    if (value_options[k].empty && !*v) {
        snprintf(err, err_size, "%s: empty %s", a, value_options[k].empty);
        return APP_OPTION_BAD;
    }
    size_t len = strlen(v);
    if (value_options[k].longest && len > value_options[k].longest) {
        snprintf(err, err_size, "%s: %zu bytes, more than the %zu this program keeps", a, len,
                 value_options[k].longest);
        return APP_OPTION_BAD;
    }
    return value_option(a, v, o, err, err_size) ? APP_OPTION_TAKEN : APP_OPTION_BAD;
}

int app_parse_args(int argc, char **argv, app_options_t *o, char *err, size_t err_size)
{
    memset(o, 0, sizeof *o);
    for (int i = 1; i < argc; i++) {
        switch (app_parse_option(argc, argv, &i, o, err, err_size)) {
        case APP_OPTION_TAKEN: break;
        case APP_OPTION_EXIT: return 1;
        case APP_OPTION_BAD: return 2;
        case APP_OPTION_UNKNOWN:
            snprintf(err, err_size, "unknown option '%s' (see --help)", argv[i]);
            o->unknown_arg = i;
            return 2;
        }
    }
    return 0;
}

world_options_t app_world_options(const app_options_t *o)
{
    static const scene_mode_t modes[] = {[APP_MODE_SCENE] = SCENE_MODE_HYBRID,
                                         [APP_MODE_BILLBOARD] = SCENE_MODE_BILLBOARD,
                                         [APP_MODE_BLADE] = SCENE_MODE_BLADE,
                                         [APP_MODE_HYBRID] = SCENE_MODE_HYBRID};
    return (world_options_t){.scene = o->scene,
                             .seed = o->seed,
                             .seed_set = o->seed_set,
                             .width = o->width,
                             .height = o->height,
                             .mode = modes[o->mode],
                             .mode_set = o->mode != APP_MODE_SCENE,
                             .blade_render = o->blade_render,
                             .raster = o->raster,
                             .raster_samples = o->raster_samples,
                             .view_cards = o->view_cards,
                             .character = o->character,
                             .clip = o->clip,
                             .character_height = o->character_height};
}

/* bench_compare: `meadow compare` renders the same frame (scene, seed, time,
 * camera) in billboard, blade and hybrid modes and as the reference (blades
 * everywhere, maximum tessellation, no culling, 8x MSAA), then writes a
 * labelled montage, diff heatmaps against the reference, and the image
 * errors (eval_image's score against a grass-free view, MAD, SSIM) with GPU
 * frame times as JSON. */
#include "bench/bench_local.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eval/eval.h"
#include "eval/eval_image.h"
#include "platform/plat.h"

#define PANELS 4

/* The reference's grass-free view: a blade field too thin to hold a blade. */
static void no_grass(scene_desc_t *s, void *user)
{
    (void)user;
    s->grass.population.density = 1e-7f;
}

/* `meadow compare --video`: the scene in billboard, blade and hybrid modes as
 * PNG frames and an H.264 clip per mode (ffmpeg), written to `out`. */
static int write_clips(const world_options_t *o, const char *out, int frames);

int bench_compare(const bench_options_t *bo)
{
    char out[1024], err[1024];
    snprintf(out, sizeof out, "%s", bo->out ? bo->out : "out");
    if (!core_fs_check_writable_dir(out, err, sizeof err) || !core_fs_lock_dir(out, err, sizeof err)) {
        core_log_error("--out: %s", err);
        return 2;
    }
    if (!plat_init(&(plat_desc_t){.backend = PLAT_BACKEND_EGL}, err, sizeof err)) {
        core_log_error("no OpenGL 4.5 context: %s", err);
        return 1;
    }
    gfx_init();
    int rc = bo->video ? write_clips(&bo->world, out, bo->frames_set ? bo->frames : 120)
                      : bench_compare_write(&bo->world, out, bo->frames_set ? bo->frames : 60);
    gfx_shutdown(true);
    int gl_errors = plat_gl_error_count();
    plat_shutdown();
    if (gl_errors) {
        core_log_error("%d GL error(s) during compare", gl_errors);
        return 1;
    }
    return rc;
}

int bench_compare_write(const world_options_t *o, const char *out, int frames)
{
    char path[1200];
    static const struct {
        const char *name;
        scene_mode_t mode;
        bool reference;
    } panels[PANELS] = {{"billboard", SCENE_MODE_BILLBOARD, false},
                        {"blade", SCENE_MODE_BLADE, false},
                        {"hybrid", SCENE_MODE_HYBRID, false},
                        {"reference", SCENE_MODE_BLADE, true}};
    core_image_t img[PANELS] = {0}, empty = {0};
    measure_metrics_t met[PANELS];
    int rc = measure_session_run(&(measure_session_desc_t){.world = *o,
                                                           .mode = SCENE_MODE_BLADE, .mode_set = true,
                                                       .frames = frames, .reference = true, .msaa = 8, .tweak = no_grass},
                               &empty, NULL);
    for (int i = 0; i < PANELS && rc == 0; i++) {
        core_log_info("compare: %d/%d %s (%d frames)", i + 1, PANELS, panels[i].name, frames);
        measure_session_desc_t d = {.world = *o,
                                    .mode = panels[i].mode, .mode_set = true, .frames = frames,
                                  .reference = panels[i].reference, .msaa = panels[i].reference ? 8 : 0};
        rc = measure_session_run(&d, &img[i], &met[i]);
        if (rc == 0) {
            snprintf(path, sizeof path, "%s/compare-%s.png", out, panels[i].name);
            if (!core_image_write_png(&img[i], path)) rc = 1; /* logged with the path and why */
        }
    }
    if (rc == 0) {
        int w = img[0].w, h = img[0].h, label = 28;
        core_image_t montage, heat;
        core_image_alloc(&montage, w * PANELS, (h + label) * 2, 4);
        static const uint8_t bg[4] = {20, 20, 20, 255}, fg[4] = {255, 255, 255, 255};
        core_image_fill(&montage, 0, 0, montage.w, montage.h, bg);
        core_buf_t json = {0};
        core_buf_printf(&json, "{\n  \"scene\": \"%s\",\n  \"frames\": %d,\n  \"size\": [%d, %d],\n  \"panels\": [\n",
                        o->scene ? o->scene : "scenes/meadow.json", frames, w, h);
        for (int i = 0; i < PANELS; i++) {
            double mad = eval_image_mad(&img[i], &img[PANELS - 1]);
            double ssim = eval_image_ssim(&img[i], &img[PANELS - 1]);
            eval_image_error_t e;
            double error = eval_image_error(&img[i], &img[PANELS - 1], &(eval_image_desc_t){.background = &empty}, &e)
                               ? e.score
                               : -1.0;
            char text[160];
            snprintf(text, sizeof text, "%s  %.2f ms GPU\nerror %.3f  SSIM %.4f", panels[i].name, met[i].frame_ms,
                     error, ssim);
            core_image_text(&montage, i * w + 6, 4, 2, text, fg);
            core_image_blit(&montage, &img[i], i * w, label);
            if (eval_image_heatmap(&img[i], &img[PANELS - 1], 64, &heat)) {
                core_image_blit(&montage, &heat, i * w, 2 * label + h);
                core_image_free(&heat);
            }
            core_image_text(&montage, i * w + 6, h + label + 6, 2, "diff vs reference", fg);
            core_buf_printf(&json,
                            "    { \"mode\": \"%s\", \"gpu_ms\": %.4f, \"cpu_ms\": %.3f, \"image_error\": %.6f, "
                            "\"mad\": %.6f, \"ssim\": %.6f }%s\n",
                            panels[i].name, met[i].frame_ms, met[i].cpu_ms, error, mad, ssim,
                            i + 1 < PANELS ? "," : "");
        }
        core_buf_printf(&json, "  ]\n}\n");
        snprintf(path, sizeof path, "%s/compare.png", out);
        if (!core_image_write_png(&montage, path)) rc = 1;
        snprintf(path, sizeof path, "%s/compare.json", out);
        if (!core_buf_write(&json, path)) rc = 1;
        if (rc == 0) core_log_info("wrote %s/compare.png and compare.json", out);
        core_buf_free(&json);
        core_image_free(&montage);
    }
    for (int i = 0; i < PANELS; i++) core_image_free(&img[i]);
    core_image_free(&empty);
    return rc;
}

/* ---- clips ------------------------------------------------------------------- */

typedef struct clip_ctx_t {
    char dir[1100];
    int written;
    bool failed;
} clip_ctx_t;

static void clip_frame(const gfx_target_t *target, int frame, void *user)
{
    clip_ctx_t *c = user;
    char path[1200];
    core_image_t img;
    snprintf(path, sizeof path, "%s/frame_%05d.png", c->dir, frame);
    if (c->failed || !gfx_target_read(target, &img)) return;
    for (size_t i = 3; i < (size_t)img.w * (size_t)img.h * 4; i += 4) img.px[i] = 255;
    if (core_image_write_png(&img, path)) c->written++;
    else c->failed = true;
    core_image_free(&img);
}

static int write_clips(const world_options_t *o, const char *out, int frames)
{
    if (system("ffmpeg -version >/dev/null 2>&1") != 0) {
        core_log_error("compare --video: ffmpeg not found (install the Debian package ffmpeg)");
        return 2;
    }
    static const struct {
        const char *name;
        scene_mode_t mode;
    } modes[3] = {{"billboard", SCENE_MODE_BILLBOARD}, {"blade", SCENE_MODE_BLADE}, {"hybrid", SCENE_MODE_HYBRID}};
    for (int i = 0; i < 3; i++) {
        clip_ctx_t c = {0};
        snprintf(c.dir, sizeof c.dir, "%s/clip-%s", out, modes[i].name);
        if (!core_fs_mkdirs(c.dir)) return 1;
        core_log_info("clip %d/3: %s, %d frames", i + 1, modes[i].name, frames);
        measure_session_desc_t d = {.world = *o,
                                    .mode = modes[i].mode, .mode_set = true, .frames = frames};
        measure_session_hooks_t h = {.drawn = clip_frame, .user = &c};
        int rc = measure_session_run_hooks(&d, &h, NULL, NULL);
        if (rc) return rc;
        if (c.failed || c.written != frames) {
            core_log_error("clip %s: wrote %d of %d frames", modes[i].name, c.written, frames);
            return 1;
        }
        /* Encoded to a temporary name and renamed, like every other output. */
        char cmd[4096], tmp[1200], mp4[1200];
        snprintf(tmp, sizeof tmp, "%s/clip-%s.tmp.mp4", out, modes[i].name);
        snprintf(mp4, sizeof mp4, "%s/clip-%s.mp4", out, modes[i].name);
        snprintf(cmd, sizeof cmd,
                 "ffmpeg -loglevel error -y -framerate 60 -i '%s/frame_%%05d.png' -c:v libx264 -pix_fmt yuv420p "
                 "-vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' '%s'",
                 c.dir, tmp);
        if (system(cmd) != 0 || rename(tmp, mp4) != 0) {
            core_log_error("clip %s: ffmpeg failed (%s)", modes[i].name, cmd);
            remove(tmp);
            return 1;
        }
        core_log_info("wrote %s", mp4);
    }
    return 0;
}

/* app_run: the meadow main loop. Loads the scene, creates the context (a
 * window, or headless EGL), simulates with a fixed timestep, renders into an
 * MSAA target, writes screenshots and the run summary. */
#include "app/app.h"
#include "app/app_trace.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "measure/measure.h"
#include "platform/plat.h"
#include "scene/scene.h"
#include "scene/scene_fields.h"

/* ---- frame times ---------------------------------------------------------- */
#define APP_WARMUP_FRAMES 60
typedef struct app_frame_times_t {
    int warmup;                     /* frames left out at the start */
    double wall[APP_FRAME_HISTORY]; /* ms, frame end to frame end */
    double cpu[APP_FRAME_HISTORY];  /* ms, frame start to the last command submitted */
    double thread[APP_FRAME_HISTORY]; /* ms of the main thread's CPU time over the same span */
    int frame[APP_FRAME_HISTORY];   /* the frame's number in the run */
    int count, next;
    int shots;                      /* frames left out for writing a screenshot */
} app_frame_times_t;

typedef struct app_t {
    const app_options_t *opts;
    world_t *world;
    double stage_ms[WORLD_STAGES]; /* the world's, with the context and the first frame */
    gfx_target_t target;
    cam_t cam;
    bool follow_path;
    bool headless;
    bool paused, step_once, wireframe, hud;
    int overlay;
    int frames, shot_every, shots_written, shots_failed;
    bool shot_taken; /* the latest frame wrote a screenshot (left out of the frame times) */
    int done;         /* frames done */
    double t_frames;  /* plat_time at the start of the first frame */
    double submitted; /* plat_time once the frame was submitted (frame_drawn) */
    double submitted_cpu; /* plat_thread_time then */
    char shot_missing[64]; /* the first screenshot that could not be written */
    int frames_asked; /* --frames, when an interrupt ended the run early (frames: those done) */
    char out[1024];
    char shots[16][1100];
    double frame_ms_avg;
    double raster_calib_ms[2]; /* --raster auto: GPU ms of a frame, hardware and compute */
    double raster_calib_wall_ms; /* --raster auto: wall ms the measure took at start-up */
    app_frame_times_t times;
    grass_view_t last_view; /* of the frame in the target */
    bool last_hud;        /* the HUD, wireframe or an overlay is in it */
    double startup_draws, startup_ranges, startup_dispatches;
    app_trace_t *trace; /* --frame-log, else NULL */
} app_t;

/* ---- frame times -------------------------------------------------------------
 * What a user feels: wall-clock time from the end of one frame to the end of
 * the next, where a frame ends once at most WORLD_FRAMES_IN_FLIGHT frames are
 * unfinished on the GPU (gfx_frame_end, a fence wait as a swap chain would
 * block; no glFinish). In steady state that is the larger of the CPU and the
 * GPU time of a frame, and a stall in either shows. Beside it the CPU part:
 * frame start to the last command submitted (wall clock: a driver call that
 * blocks counts), and the main thread's CPU time over that span (what the
 * frame's CPU work costs). The first `warmup` frames
 * (first-use compiles, lazy allocations, the tiles' first activation) are
 * left out; the newest APP_FRAME_HISTORY frames are kept. */
static void frame_times_add(app_frame_times_t *ft, int frame, double wall_ms, double cpu_ms, double thread_ms)
{
    if (frame < ft->warmup) return;
    ft->frame[ft->next] = frame;
    ft->wall[ft->next] = wall_ms;
    ft->cpu[ft->next] = cpu_ms;
    ft->thread[ft->next] = thread_ms;
    ft->next = (ft->next + 1) % APP_FRAME_HISTORY;
    if (ft->count < APP_FRAME_HISTORY) ft->count++;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* p50, p95, p99 (nearest rank) and the worst of n samples. */
static void percentiles(const double *v, int n, double out[4])
{
    static double tmp[APP_FRAME_HISTORY];
    memcpy(tmp, v, sizeof *v * (size_t)n);
    qsort(tmp, (size_t)n, sizeof *tmp, cmp_double);
    static const double q[3] = {0.50, 0.95, 0.99};
    for (int k = 0; k < 3; k++) {
        int rank = (int)ceil(q[k] * n);
        out[k] = tmp[(rank > 0 ? rank : 1) - 1];
    }
    out[3] = tmp[n - 1];
}

static void handle_keys(app_t *app, float real_dt)
{
    if (plat_key_pressed(PLAT_KEY_ESCAPE)) plat_request_close();
    if (plat_key_pressed(PLAT_KEY_P)) app->paused = !app->paused;
    if (plat_key_pressed(PLAT_KEY_N)) app->step_once = true;
    if (plat_key_pressed(PLAT_KEY_F)) app->wireframe = !app->wireframe;
    if (plat_key_pressed(PLAT_KEY_H)) app->hud = !app->hud;
    if (plat_key_pressed(PLAT_KEY_O)) app->overlay = (app->overlay + 1) % 4;
    if (plat_key_pressed(PLAT_KEY_R)) {
        world_set_raster(app->world, !world_info(app->world).raster_compute);
        core_log_info("raster: %s", scene_raster_name(world_info(app->world).scene->raster));
    }
    static const scene_mode_t modes[3] = {SCENE_MODE_BILLBOARD, SCENE_MODE_BLADE, SCENE_MODE_HYBRID};
    static const plat_key_t mode_keys[3] = {PLAT_KEY_1, PLAT_KEY_2, PLAT_KEY_3};
    for (int i = 0; i < 3; i++)
        if (plat_key_pressed(mode_keys[i]) && world_info(app->world).mode != modes[i]) {
            world_set_mode(app->world, modes[i]);
            core_log_info("mode: %s", scene_mode_name(modes[i]));
        }
    float speed = (plat_key_down(PLAT_KEY_SHIFT) ? 15.0f : 4.0f) * real_dt;
    float fwd = (float)(plat_key_down(PLAT_KEY_W) - plat_key_down(PLAT_KEY_S));
    float right = (float)(plat_key_down(PLAT_KEY_D) - plat_key_down(PLAT_KEY_A));
    float up = (float)(plat_key_down(PLAT_KEY_E) - plat_key_down(PLAT_KEY_Q));
    float yaw = (float)(plat_key_down(PLAT_KEY_LEFT) - plat_key_down(PLAT_KEY_RIGHT)) * 1.5f * real_dt;
    float pitch = (float)(plat_key_down(PLAT_KEY_UP) - plat_key_down(PLAT_KEY_DOWN)) * 1.0f * real_dt;
    if (fwd != 0 || right != 0 || up != 0 || yaw != 0 || pitch != 0) {
        app->follow_path = false;
        cam_move(&app->cam, fwd * speed, right * speed, up * speed);
        cam_rotate(&app->cam, yaw, pitch);
    }
}

static void draw_hud(const app_t *app, double sim_time)
{
    world_info_t wi = world_info(app->world);
    char text[2048];
    static const char *overlays[4] = {"", "  [overlay: tile/leaf state]", "  [overlay: LOD]",
                                      "  [overlay: collision strength]"};
    int n = snprintf(text, sizeof text, "meadow  %s  %s raster  %.2f ms/frame  t=%.2fs%s%s\n",
                     scene_mode_name(wi.scene->mode), wi.raster_compute ? "compute" : "hw",
                     app->frame_ms_avg, sim_time, app->paused ? "  [paused]" : "", overlays[app->overlay]);
    app_hud_pass_t passes[GFX_TIMER_MAX_PASSES];
    int count = gfx_timer_count();
    for (int i = 0; i < count; i++)
        passes[i] = (app_hud_pass_t){gfx_timer_name(i), gfx_timer_last_ms(i), gfx_timer_frames_since(i)};
    if (n > 0 && n < (int)sizeof text) app_hud_timings(passes, count, text + n, sizeof text - (size_t)n);
    static const float white[4] = {1, 1, 1, 1}, shadow[4] = {0, 0, 0, 0.8f};
    gfx_text_draw(text, 11, 11, 2.0f, shadow);
    gfx_text_draw(text, 10, 10, 2.0f, white);
}

static void screenshot(app_t *app, int frame)
{
    char path[1100];
    snprintf(path, sizeof path, "%s/shot-%06d.png", app->out, frame);
    if (gfx_target_screenshot(&app->target, path)) {
        if (app->shots_written < 16) snprintf(app->shots[app->shots_written], sizeof app->shots[0], "%s", path);
        app->shots_written++;
        core_log_info("wrote %s", path);
    } else if (app->shots_failed++ == 0) {
        snprintf(app->shot_missing, sizeof app->shot_missing, "shot-%06d.png", frame);
    }
}

/* One error line naming what a run promised and could not write (the
 * summary, screenshots; disk full, a folder in the way); false when none. */
static bool report_missing(const app_t *app, bool summary_ok)
{
    if (summary_ok && app->shots_failed == 0) return false;
    char shots[160] = "";
    if (app->shots_failed)
        snprintf(shots, sizeof shots, "%s%d of %d screenshots (first %s)", summary_ok ? "" : " and ",
                 app->shots_failed, app->shots_failed + app->shots_written, app->shot_missing);
    core_log_error("%s: the run could not write %s%s; its output is incomplete", app->out,
                   summary_ok ? "" : "summary.txt", shots);
    return true;
}

/* Spikes against the frames around them (a hitch, not a heavier view):
 * each wall time over the median of the SPIKE_WINDOW frames centred on it;
 * the largest ratio, its frame, and how many frames exceed 1.5. The frames
 * in order, oldest first. */
#define SPIKE_WINDOW 61
static void spikes(const app_frame_times_t *ft, double *worst, int *worst_frame, int *over)
{
    static double ordered[APP_FRAME_HISTORY];
    int n = ft->count, first = n < APP_FRAME_HISTORY ? 0 : ft->next;
    for (int i = 0; i < n; i++) ordered[i] = ft->wall[(first + i) % APP_FRAME_HISTORY];
    *worst = 0.0;
    *worst_frame = -1;
    *over = 0;
    for (int i = 0; i < n; i++) {
        int lo = i - SPIKE_WINDOW / 2 < 0 ? 0 : i - SPIKE_WINDOW / 2;
        int hi = lo + SPIKE_WINDOW > n ? n : lo + SPIKE_WINDOW;
        lo = hi - SPIKE_WINDOW < 0 ? 0 : hi - SPIKE_WINDOW;
        double local[SPIKE_WINDOW];
        memcpy(local, &ordered[lo], sizeof *local * (size_t)(hi - lo));
        qsort(local, (size_t)(hi - lo), sizeof *local, cmp_double);
        double r = ordered[i] / local[(hi - lo) / 2];
        *over += r > 1.5;
        if (r > *worst) *worst = r, *worst_frame = i;
    }
    if (*worst_frame >= 0) *worst_frame = ft->frame[(first + *worst_frame) % APP_FRAME_HISTORY];
}

static int summary_frame_times(const app_t *app, char *buf, size_t size)
{
    const app_frame_times_t *ft = &app->times;
    if (ft->count == 0) return snprintf(buf, size, "frame times: no frame after the %d warm-up frames\n", ft->warmup);
    double w[4], c[4], th[4], spike;
    int spike_frame, spike_over;
    percentiles(ft->wall, ft->count, w);
    percentiles(ft->cpu, ft->count, c);
    percentiles(ft->thread, ft->count, th);
    spikes(ft, &spike, &spike_frame, &spike_over);
    int n = snprintf(buf, size,
                    "frame times after warm-up (%d frames left out, and %d that wrote a screenshot; %d frames, "
                    "at most %d in flight), ms:\n"
                    "  wall (CPU and GPU)  p50 %8.3f  p95 %8.3f  p99 %8.3f  worst %8.3f\n"
                    "  cpu (submit)        p50 %8.3f  p95 %8.3f  p99 %8.3f  worst %8.3f\n"
                    "  cpu (thread time)   p50 %8.3f  p95 %8.3f  p99 %8.3f  worst %8.3f\n"
                    "  p99/p50: %.2f (target <= 1.5: %s)\n",
                    ft->warmup, ft->shots, ft->count, WORLD_FRAMES_IN_FLIGHT, w[0], w[1], w[2], w[3], c[0], c[1], c[2], c[3], th[0], th[1], th[2], th[3],
                    w[2] / w[0], w[2] <= 1.5 * w[0] ? "met" : "missed");
    return n + snprintf(buf + n, size - (size_t)n,
                        "  spikes: worst frame %.2f x the median of the %d around it (frame %d); %d frames over "
                        "1.5 x (target: none)\n",
                        spike, SPIKE_WINDOW, spike_frame, spike_over);
}

static int summary_startup(const app_t *app, const measure_stats_t *st, char *buf, size_t size)
{
    /* The world times its own stages; the run the context and first frame. */
    double s[WORLD_STAGES], total = 0.0;
    for (int k = 0; k < WORLD_STAGES; k++) total += s[k] = app->stage_ms[k] + world_info(app->world).stage_ms[k];
    int n = snprintf(buf, size, "startup_ms (start of the run to the first frame done on the GPU): %.1f\n", total);
    for (int k = 0; k < WORLD_STAGES && n < (int)size - 160; k++) {
        n += snprintf(buf + n, size - (size_t)n, "  %-12s %9.1f", world_stage_name(k), s[k]);
        if (k == WORLD_STAGE_BILLBOARDS && st->billboards > 0) {
            n += snprintf(buf + n, size - (size_t)n, "  (");
            for (int b = 0; b < MEASURE_BB_STAGES; b++)
                n += snprintf(buf + n, size - (size_t)n, "%s%s %.1f", b ? ", " : "", measure_bb_stage_name(b),
                              st->bb_make_stage_ms[b]);
            n += snprintf(buf + n, size - (size_t)n, ")");
        }
        n += snprintf(buf + n, size - (size_t)n, "\n");
    }
    n += snprintf(buf + n, size - (size_t)n, "startup work: draw calls %.0f (ranges %.0f), dispatches %.0f\n",
                  app->startup_draws, app->startup_ranges, app->startup_dispatches);
    gfx_program_stats_t ps = gfx_program_stats();
    n += snprintf(buf + n, size - (size_t)n,
                  "startup programs: %d compiled and linked (%d prefetched, %d of those taken) in %.1f ms (slowest:",
                  ps.count, ps.prefetched, ps.taken, ps.ms);
    for (int i = 0; i < GFX_PROGRAM_SLOWEST && ps.slowest[i].ms > 0.0 && n < (int)size - 80; i++)
        n += snprintf(buf + n, size - (size_t)n, " %s %.1f", ps.slowest[i].label, ps.slowest[i].ms);
    n += snprintf(buf + n, size - (size_t)n, ")\n");
    return n < (int)size ? n : (int)size - 1;
}

/* Hybrid runs: the seam at the switch band of the last frame
 * (measure_seam; it draws the billboard-only reference into the target). */
static int summary_seam(app_t *app, char *buf, size_t size)
{
    world_t *w = app->world;
    world_info_t wi = world_info(w);
    if (wi.mode != SCENE_MODE_HYBRID || app->frames == 0) return 0;
    float sd = wi.scene->grass.switch_distance;
    eval_seam_t e;
    if (!wi.billboards && !app->last_hud && wi.canopy) {
        if (!measure_canopy_seam(w, &app->last_view, &app->target, &e))
            return snprintf(buf, size, "canopy seam at %.1f m: not measured (a side of the band shows no grass or "
                            "too few pixels, or the reference's tiles could not be made)\n", sd);
        /* The canopy blends its cover into its colour: every canopy pixel
         * differs from the bare ground and counts as grass, the blades' gaps
         * need not, so the coverage term compares unlike things; the colour
         * term is the seam. */
        double scale = eval_seam_desc_defaults(&(eval_seam_desc_t){.switch_distance = sd}).colour_scale;
        double colour = e.delta_e / scale, reach = measure_canopy_seam_reach(sd);
        int n = snprintf(buf, size,
                         "canopy seam at %.1f m (blades to the ground canopy, against blades drawn across the band to "
                         "%.0f m; band +-%.0f m, windows by the terrain's distance): colour score %.3f, Delta E %.3f, Delta "
                         "L* %+.3f; coverage step %.4f (score with it %.3f: the canopy counts every pixel as grass)\n",
                         sd, reach, GRASS_SWITCH_FADE, colour, e.delta_e, e.delta_l, e.coverage, e.score);
        if (n < (int)size)
            n += snprintf(buf + n, size - (size_t)n,
                          "  grass L*a*b* near | far: frame (%.2f %.2f %.2f) | (%.2f %.2f %.2f), blades (%.2f %.2f "
                          "%.2f) | (%.2f %.2f %.2f); pixels %ld | %ld\n"
                          "  all pixels (grass and ground): colour score %.3f, Delta E %.3f, Delta L* %+.3f; "
                          "L* near | far: frame %.2f | %.2f, blades %.2f | %.2f\n",
                          e.lab[0][0][0], e.lab[0][0][1], e.lab[0][0][2], e.lab[0][1][0], e.lab[0][1][1],
                          e.lab[0][1][2], e.lab[1][0][0], e.lab[1][0][1], e.lab[1][0][2], e.lab[1][1][0],
                          e.lab[1][1][1], e.lab[1][1][2], e.pixels[0][0], e.pixels[0][1],
                          e.delta_e_all / scale, e.delta_e_all, e.delta_l_all, e.lab_all[0][0][0], e.lab_all[0][1][0], e.lab_all[1][0][0],
                          e.lab_all[1][1][0]);
        ground_match_state_t m;
        bool matched = wi.scene->grass.canopy_match == SCENE_CANOPY_MATCH_ON && world_canopy_match(w, &m);
        if (n < (int)size && matched)
            n += snprintf(buf + n, size - (size_t)n, "  canopy match gain (on the stored colour, rgb): %.4f %.4f %.4f\n",
                          m.gain[0], m.gain[1], m.gain[2]);
        return n < (int)size ? n : (int)size - 1;
    }
    if (app->last_hud)
        return snprintf(buf, size, "hybrid seam at %.1f m: not measured (HUD, wireframe or overlay over the frame)\n",
                        sd);
    if (!measure_seam(w, &app->last_view, &app->target, &e))
        return snprintf(buf, size, "hybrid seam at %.1f m: not measured (a side of the band shows no grass or too few pixels)\n", sd);
    int n = snprintf(buf, size,
                     "hybrid seam at %.1f m (last frame against it drawn with billboards only; band +-%.0f m, "
                     "windows of 3 m; eval_image units, 1 = clearly visible): score %.3f\n"
                     "  Delta E %.3f, Delta L* %+.3f, coverage %.4f; windows near | far: grass %.3f | %.3f "
                     "(reference %.3f | %.3f), pixels %ld | %ld\n",
                     sd, GRASS_SWITCH_FADE, e.score, e.delta_e, e.delta_l, e.coverage, e.grass[0][0], e.grass[0][1],
                     e.grass[1][0], e.grass[1][1], e.pixels[0][0], e.pixels[0][1]);
    if (n < (int)size)
        n += snprintf(buf + n, size - (size_t)n,
                      "  grass L*a*b* near | far: frame (%.1f %.1f %.1f) | (%.1f %.1f %.1f), reference (%.1f %.1f "
                      "%.1f) | (%.1f %.1f %.1f)\n",
                      e.lab[0][0][0], e.lab[0][0][1], e.lab[0][0][2], e.lab[0][1][0], e.lab[0][1][1], e.lab[0][1][2],
                      e.lab[1][0][0], e.lab[1][0][1], e.lab[1][0][2], e.lab[1][1][0], e.lab[1][1][1], e.lab[1][1][2]);
    measure_seam_floor_t f;
    _Static_assert(MEASURE_SEAM_FLOOR_PLACEMENTS == 3, "the floor line prints three placements");
    if (n < (int)size && measure_seam_floor(w, &app->last_view, &app->target, &f))
        n += snprintf(buf + n, size - (size_t)n,
                      "  floor (billboards placed with %d other seeds, each against the reference; means): score "
                      "%.3f (%.3f %.3f %.3f), Delta E %.3f, coverage %.4f; the seam is %s the floor\n",
                      MEASURE_SEAM_FLOOR_PLACEMENTS, f.mean.score, f.score[0], f.score[1], f.score[2], f.mean.delta_e,
                      f.mean.coverage, e.score <= f.mean.score ? "within" : "above");
    if (n < (int)size && wi.canopy) {
        float cd = wi.scene->grass.canopy_distance;
        if (!measure_canopy_seam(w, &app->last_view, &app->target, &e))
            n += snprintf(buf + n, size - (size_t)n,
                          "canopy seam at %.1f m: not measured (a side of the band shows no grass or too few "
                          "pixels)\n",
                          cd);
        else
            n += snprintf(buf + n, size - (size_t)n,
                          "canopy seam at %.1f m (billboards to the ground canopy, against billboards to the "
                          "horizon; band +-%.0f m, windows by the terrain's distance): score %.3f, Delta E %.3f, "
                          "Delta L* %+.3f, coverage %.4f\n",
                          cd, GRASS_CANOPY_FADE, e.score, e.delta_e, e.delta_l, e.coverage);
    }
    return n < (int)size ? n : (int)size - 1;
}

/* Work counters (gfx_count) as means per frame over the run; passes with
 * no work are left out. */
static int summary_work(char *buf, size_t size)
{
    int frames = gfx_count_frames() > 0 ? gfx_count_frames() : 1;
    int n = snprintf(buf, size,
                     "work per frame (means over %d frames; counters, not timings):\n"
                     "  %-16s %10s %10s %10s %12s %12s %12s\n",
                     gfx_count_frames(), "pass", "draws", "ranges", "dispatches", "groups", "primitives",
                     "tf_written");
    double sum[GFX_COUNT_KINDS] = {0};
    for (int i = 0; i < gfx_count_pass_count() && n < (int)size - 160; i++) {
        double v[GFX_COUNT_KINDS], any = 0.0;
        for (int k = 0; k < GFX_COUNT_KINDS; k++) {
            v[k] = gfx_count_pass_total(i, k) / frames;
            sum[k] += v[k];
            any += v[k];
        }
        if (any == 0.0) continue;
        n += snprintf(buf + n, size - (size_t)n, "  %-16s %10.3f %10.3f %10.3f %12.3f %12.3f %12.3f\n",
                      gfx_count_pass_name(i), v[0], v[1], v[2], v[3], v[4], v[5]);
    }
    n += snprintf(buf + n, size - (size_t)n, "  %-16s %10.3f %10.3f %10.3f %12.3f %12.3f %12.3f\n", "total", sum[0],
                  sum[1], sum[2], sum[3], sum[4], sum[5]);
    n += snprintf(buf + n, size - (size_t)n, "items per frame:\n");
    for (int i = 0; i < gfx_count_item_count() && n < (int)size - 64; i++)
        n += snprintf(buf + n, size - (size_t)n, "  %-24s %14.3f\n", gfx_count_item_name(i),
                      gfx_count_item_total(i) / frames);
    return n < (int)size ? n : (int)size - 1;
}

/* What the world holds: the admission estimate, the hybrid's distances, a
 * world's tile window, the compute rasterizer's buffers, the characters. */
static int summary_world(world_t *w, char *buf, size_t size)
{
    world_info_t wi = world_info(w);
    const admit_t *ad = wi.admitted;
    int n = snprintf(buf, size, "gpu_memory_estimate_mb: %.1f (admission, before allocating:",
                     ad->gpu_total / (1024.0 * 1024.0));
    for (int k = 0; k < ADMIT_PARTS; k++)
        if (ad->gpu[k] > 0.0)
            n += snprintf(buf + n, size - (size_t)n, " %s %.1f", admit_part_name(k),
                          ad->gpu[k] / (1024.0 * 1024.0));
    n += snprintf(buf + n, size - (size_t)n, ")\n");
    if (wi.scene->mode == SCENE_MODE_HYBRID)
        n += snprintf(buf + n, size - (size_t)n, "hybrid distances: switch %.1f m, canopy %.1f m (%s)\n",
                      wi.scene->grass.switch_distance, wi.scene->grass.canopy_distance,
                      wi.lod_note[0] ? wi.lod_note : "the scene's; no grass.lod_table");
    n += measure_grass_lines(w, buf + n, size - (size_t)n);
    if (wi.characters && n < (int)size) {
        character_set_describe(wi.characters, buf + n, size - (size_t)n);
        n += (int)strlen(buf + n);
    }
    return n < (int)size ? n : (int)size - 1;
}

static bool write_summary(app_t *app, double wall_s)
{
    measure_stats_t st;
    measure_stats(app->world, &st);
    world_info_t wi = world_info(app->world);
    char interrupted[96] = "";
    if (app_interrupted())
        snprintf(interrupted, sizeof interrupted, " (interrupted: %d of %d asked)", app->frames, app->frames_asked);
    char calib[128] = "";
    if (app->raster_calib_ms[0] > 0.0)
        snprintf(calib, sizeof calib, " (auto: frame %.3f ms hw, %.3f ms compute; measured in %.0f ms at start-up)",
                 app->raster_calib_ms[0], app->raster_calib_ms[1], app->raster_calib_wall_ms);
    char buf[16384];
    int n = snprintf(buf, sizeof buf,
                     "meadow run summary\n"
                     "renderer: %s\n"
                     "gl_version: %s\n"
                     "platform: %s\n"
                     "scene: %s\n"
                     "mode: %s\nraster: %s%s\nseed: %u\nframes: %d%s\nsize: %dx%d\nmsaa: %d\n"
                     "wall_seconds: %.3f\nmean_frame_ms: %.3f\n"
                     "screenshots: %d\n"
                     "gpu passes after warm-up (median ms over the last <=256 frames, mean ms, max ms)%s:\n",
                     (const char *)glGetString(GL_RENDERER), (const char *)glGetString(GL_VERSION),
                     plat_backend_name(), app->opts->scene ? app->opts->scene : "scenes/meadow.json",
                     scene_mode_name(wi.scene->mode), wi.raster_compute ? "compute" : "hw", calib,
                     wi.scene->seed, app->frames, interrupted, app->target.w, app->target.h,
                     app->target.samples, wall_s, wall_s * 1000.0 / (app->frames ? app->frames : 1),
                     app->shots_written, gfx_timer_sync() ? ", each after glFinish (MEADOW_TIMER_SYNC)" : "");
    double frame_gpu = 0;
    for (int i = 0; i < gfx_timer_count() && n < (int)sizeof buf - 128; i++) {
        n += snprintf(buf + n, sizeof buf - (size_t)n, "  %-14s %9.4f %9.4f %9.4f\n", gfx_timer_name(i),
                      gfx_timer_median_ms(i), gfx_timer_avg_ms(i), gfx_timer_max_ms(i));
        if (strcmp(gfx_timer_name(i), "bb.generate") != 0) frame_gpu += gfx_timer_median_ms(i);
    }
    n += snprintf(buf + n, sizeof buf - (size_t)n,
                  "gpu_frame_ms (sum of pass medians): %.4f\n"
                  "gpu_memory_mb: %.1f\n"
                  "host_memory_mb: %.1f (peak resident)\n"
                  "blades: %ld\nblade_survivors: %ld\nblade_culled (orientation frustum distance occlusion "
                  "patch): %u %u %u %u %ld\n"
                  "tiles_culled (orientation frustum distance occlusion tile): %u %u %u %u %ld\n"
                  "billboards: %ld\nbillboards_deformed: %d\n"
                  "billboard generation (once): GPU %.3f ms, make %.1f ms\ncharacters: %d\n"
                  "blade_tiles (near) %d, active %d, recovering %d, state slots %d/%d, blades simulated %ld\n"
                  "tile hand-overs (run totals): blades -> billboards %ld, billboards -> blades %ld\n"
                  "grass_triangles_max: %ld\n",
                  frame_gpu, (double)gfx_memory_bytes() / (1024.0 * 1024.0), plat_peak_rss_mb(), st.blades, st.blade_survivors,
                  st.blade_culled[0], st.blade_culled[1], st.blade_culled[2], st.blade_culled[3],
                  st.blade_patch_culled, st.tiles_culled[0], st.tiles_culled[1], st.tiles_culled[2],
                  st.tiles_culled[3], st.tiles_tile_culled, st.billboards, st.bb_deformed, st.bb_generate_ms,
                  st.bb_make_ms, st.characters, st.tiles_blade,
                  st.tiles_active, st.tiles_recovering, st.tile_slots_used, st.tile_slots_total,
                  st.tile_blades_simulated, st.tile_handovers, st.tile_seeded, st.triangles);
    n += summary_world(app->world, buf + n, sizeof buf - (size_t)n);
    n += summary_frame_times(app, buf + n, sizeof buf - (size_t)n);
    n += summary_startup(app, &st, buf + n, sizeof buf - (size_t)n);
    n += summary_work(buf + n, sizeof buf - (size_t)n);
    if (app->opts->floor) {
        double floor_ms = measure_floor_ms(st.triangles, app->target.w, app->target.h, app->target.samples);
        int rs = wi.raster_samples ? wi.raster_samples : SCENE_DEFAULT_RASTER_SAMPLES;
        double cfloor_ms =
            measure_floor_compute_ms(st.triangles, app->target.w, app->target.h, app->target.samples, rs);
        n += snprintf(buf + n, sizeof buf - (size_t)n, "floor_ms (%ld trivial triangles): %.4f\nframe_over_floor: %.2f\n",
                      st.triangles, floor_ms, floor_ms > 0 ? frame_gpu / floor_ms : 0.0);
        n += snprintf(buf + n, sizeof buf - (size_t)n,
                      "compute_floor_ms (the same through the compute rasterizer, %d samples per pixel, with its "
                      "start and composite): %.4f\nframe_over_compute_floor: %.2f\n",
                      rs, cfloor_ms, cfloor_ms > 0 ? frame_gpu / cfloor_ms : 0.0);
    }
    /* Last: it draws again (after the timers and work counters were read). */
    n += summary_seam(app, buf + n, sizeof buf - (size_t)n);
    char path[1100];
    snprintf(path, sizeof path, "%s/summary.txt", app->out);
    bool written = core_fs_write_atomic(path, buf, (size_t)n);
    if (written) core_log_info("wrote %s", path);
    if (!app->opts->quiet) fputs(buf, stdout);
    return written;
}

/* After the world's draw of a frame, before pacing (world_frame_desc_t.drawn):
 * the HUD, the screenshot, the window. */
static void frame_drawn(world_t *w, const grass_view_t *v, gfx_target_t *target, void *user)
{
    (void)w;
    (void)target;
    app_t *app = user;
    if (app->hud) draw_hud(app, v->time);
    app->last_view = *v;
    app->last_hud = app->hud || app->wireframe || app->overlay;
    int frame = app->done + 1;
    bool shot = (app->shot_every && frame % app->shot_every == 0) || (!app->headless && plat_key_pressed(PLAT_KEY_C));
    if (shot) screenshot(app, frame);
    app->shot_taken = shot;
    if (!app->headless) {
        int fw, fh;
        plat_framebuffer_size(&fw, &fh);
        gfx_target_present(&app->target, fw, fh);
        plat_swap();
    }
    app->submitted = plat_time();
    app->submitted_cpu = plat_thread_time();
}

/* The frames (world_frame) until the run's count, a close or an
 * interrupt; app->done counts them. Returns 0, or 1 when the target or the
 * GPU failed (logged). */
static int run_frames(app_t *app)
{
    world_t *w = app->world;
    const scene_desc_t *s = world_info(w).scene;
    scene_clock_t clock;
    scene_clock_init(&clock, s->dt, app->headless);
    app->t_frames = plat_time();
    double last = app->t_frames, frame_end = app->t_frames, frame_end_cpu = plat_thread_time();
    while (!plat_should_close() && !app_interrupted() && (app->frames == 0 || app->done < app->frames)) {
        if (app->done == app->times.warmup) gfx_timer_skip_warmup();
        plat_poll_events();
        double now = plat_time(), real_dt = now - last;
        last = now;
        if (!app->headless) handle_keys(app, (float)real_dt);
        int steps;
        if (!app->paused) {
            steps = scene_clock_advance(&clock, real_dt);
        } else {
            /* Paused: time stands still; N advances exactly one step. */
            steps = app->step_once ? 1 : 0;
            clock.steps += (uint64_t)steps;
        }
        app->step_once = false;
        double marks[WORLD_FRAME_MARKS];
        /* The first frame is waited for: the end of start-up. */
        world_frame_desc_t fd = {.target = &app->target, .label = "main", .cam = &app->cam,
                               .follow_path = app->follow_path, .t = scene_clock_time(&clock), .dt = s->dt,
                               .steps = steps, .overlay = app->overlay, .wireframe = app->wireframe,
                               .drawn = frame_drawn, .user = app,
                               .in_flight = app->done == 0 ? 1 : WORLD_FRAMES_IN_FLIGHT, .marks = marks};
        world_frame_result_t r = world_frame(w, &fd);
        if (r == WORLD_FRAME_NO_TARGET) return 1;
        app->done++;
        app->frame_ms_avg = app->frame_ms_avg * 0.9 + real_dt * 1000.0 * 0.1;
        if (r == WORLD_FRAME_GPU_LOST) {
            core_log_error("giving up at frame %d: the GPU did not finish it", app->done);
            return 1;
        }
        double end = plat_time();
        if (app->done == 1) app->stage_ms[WORLD_STAGE_FIRST_FRAME] = (end - app->t_frames) * 1e3;
        app_trace_frame_t tf = {.frame = app->done, .wall_ms = (end - frame_end) * 1e3,
                                .submit_ms = (app->submitted - frame_end) * 1e3,
                                .thread_ms = (app->submitted_cpu - frame_end_cpu) * 1e3,
                                .screenshot = app->shot_taken, .marks = marks};
        app_trace_row(app->trace, w, &tf);
        if (app->shot_taken) app->times.shots++;
        else frame_times_add(&app->times, app->done - 1, tf.wall_ms, tf.submit_ms, tf.thread_ms);
        frame_end = end;
        frame_end_cpu = plat_thread_time();
        if (app->headless && app->done % 100 == 0) core_log_info("frame %d/%d", app->done, app->frames);
    }
    return 0;
}

/* The world's GPU side and the target, the `raster: auto` measure and the
 * start-up work counters; false when the renderer cannot be made. */
static bool start_world(app_t *app)
{
    world_t *w = app->world;
    /* The world first: its admission (admit) counts the target too. */
    bool ok = world_make_gpu(w) && world_fit_target(w, &app->target, "main");
    if (ok && world_info(w).scene->raster == SCENE_RASTER_AUTO)
        world_raster_auto(w, &app->cam, &app->target, app->raster_calib_ms, &app->raster_calib_wall_ms);
    gfx_count_flush();
    for (int i = 0; i < gfx_count_pass_count(); i++) {
        app->startup_draws += gfx_count_pass_total(i, GFX_COUNT_DRAWS);
        app->startup_ranges += gfx_count_pass_total(i, GFX_COUNT_DRAW_RANGES);
        app->startup_dispatches += gfx_count_pass_total(i, GFX_COUNT_DISPATCHES);
    }
    gfx_count_reset();
    /* Warm-up: a quarter of a fixed run, at most APP_WARMUP_FRAMES. */
    app->times.warmup = app->frames > 0 && app->frames / 4 < APP_WARMUP_FRAMES ? app->frames / 4 : APP_WARMUP_FRAMES;
    return ok;
}

int app_run(const app_options_t *o, app_montage_fn montage)
{
    assert(montage || !o->montage);
    app_t app = {.opts = o, .follow_path = true, .overlay = o->overlay};
    core_log_set_quiet(o->quiet);
    snprintf(app.out, sizeof app.out, "%s", o->out ? o->out : "out");
    char err[1024];
    if (!core_fs_check_writable_dir(app.out, err, sizeof err) || !core_fs_lock_dir(app.out, err, sizeof err)) {
        core_log_error("--out: %s", err);
        return 2;
    }
    double t_run = plat_time();
    world_options_t wo = app_world_options(o);
    int rc = world_load(&wo, &app.world);
    if (rc) return rc;
    world_t *w = app.world;
    const scene_desc_t *s = world_info(w).scene;
    plat_desc_t pd = {.backend = o->headless ? PLAT_BACKEND_EGL : PLAT_BACKEND_AUTO,
                      .width = s->size[0], .height = s->size[1]};
    if (!plat_init(&pd, err, sizeof err)) {
        core_log_error("no OpenGL 4.5 context: %s", err);
        world_destroy(w);
        return 1;
    }
    app.headless = plat_is_headless();
    app.frames = o->frames_set ? o->frames : (app.headless ? s->frames : 0);
    app.shot_every = o->screenshot_every;
    if (!o->screenshot_every_set && app.headless && app.frames >= 3)
        app.shot_every = app.frames / 3;
    app.hud = !app.headless;
    gfx_init();
    app.target = (gfx_target_t){.w = s->size[0], .h = s->size[1]};
    scene_camera_init(s, &app.cam);
    const double *stage = world_info(w).stage_ms;
    app.stage_ms[WORLD_STAGE_CONTEXT] =
        (plat_time() - t_run) * 1e3 - stage[WORLD_STAGE_SCENE] - stage[WORLD_STAGE_TERRAIN];
    bool ok = start_world(&app);
    if (!ok) {
        bool input_error = world_info(w).input_error;
        if (!input_error) core_log_error("cannot create the renderer (see messages above)");
        rc = input_error ? 2 : 1;
    }
    if (ok && o->frame_log) app.trace = app_trace_open(app.out);
    if (ok && run_frames(&app) != 0) {
        ok = false;
        rc = 1;
    }
    if (!app_trace_close(app.trace)) rc = rc ? rc : 1;
    if (app_interrupted()) core_log_warn("interrupted after %d frames; writing the summary", app.done);
    app.frames_asked = app.frames;
    app.frames = app.done;
    if (ok) {
        gfx_timer_flush();
        if (report_missing(&app, write_summary(&app, plat_time() - app.t_frames))) rc = 1;
    }
    if (ok && app.headless && o->montage) {
        /* The same frame in billboard, blade and hybrid modes (and the
         * reference), side by side: compare.png in the output folder. */
        int mframes = app.frames < 120 ? app.frames : 120;
        core_log_info("montage: rendering frame %d in every mode", mframes);
        if (montage(&wo, app.out, mframes) != 0) rc = 1;
    }
    world_destroy(w);
    gfx_target_destroy(&app.target);
    gfx_shutdown(ok); /* unused prefetches and leaks: news only after a run that went through */
    int gl_errors = plat_gl_error_count();
    plat_shutdown();
    if (gl_errors) {
        core_log_error("%d GL error(s) during the run", gl_errors);
        return 1;
    }
    return rc == 0 && app_interrupted() ? APP_EXIT_INTERRUPTED : rc;
}

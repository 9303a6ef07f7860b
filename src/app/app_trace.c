/* app_trace: `meadow --frame-log` writes OUT/frames.csv, one row per frame:
 * the frame's wall, submit and thread times (as summary.txt measures them),
 * whether it wrote a screenshot, the blade tiles' work of its update, the
 * CPU wall ms of the frame's steps (world_frame_desc_t.marks) and of the
 * simulation's parts (world_info_t.update_ms), then per timed pass its
 * latest GPU ms (`<pass>_ms`) and the CPU wall ms spent in its calls this
 * frame (`<pass>_cpu_ms`: where a blocking driver call sits). GPU timer
 * results arrive one to three frames late (gfx_timer_last_ms), so a GPU
 * column trails the frame it is written on; it reads empty where the pass
 * has not run in the frame or the TRACE_GPU_LAG before it (a timer keeps
 * its last result, which would otherwise repeat through every frame the
 * pass skips). Rows are kept in memory and written at the end, when every
 * pass is known: the last APP_FRAME_HISTORY frames, as summary.txt's times
 * (a longer run says how many it left out). A tool for finding hitches
 * (docs/METRICS.md, "Timing"). */
#include "app/app_trace.h"

#include "app/app.h"
#include "measure/measure.h"
#include "world/world.h"

#include "core/core.h"
#include "gfx/gfx.h"

#include <stdio.h>
#include <stdlib.h>

#define TRACE_PASSES GFX_TIMER_MAX_PASSES
/* Frames a GPU timer result may trail its pass (gfx_timer_last_ms). */
#define TRACE_GPU_LAG 3

/* The blade tiles' work of the frame's update (measure_grass_t). */
static const char *const stat_names[] = {"tiles_active", "tiles_recovering", "slots_simulated", "blades_simulated",
                                         "tiles_streamed"};
#define TRACE_STATS (int)(sizeof stat_names / sizeof stat_names[0])
/* The differences of the frame's WORLD_FRAME_MARKS marks, then the
 * WORLD_UPDATE_PARTS parts of its simulation steps. */
static const char *const step_names[] = {"timers", "steps", "target", "draw", "drawn", "update_objects",
                                         "update_billboards", "update_spheres", "update_blades"};
#define TRACE_STEPS (int)(sizeof step_names / sizeof step_names[0])
_Static_assert(sizeof step_names / sizeof step_names[0] == WORLD_FRAME_MARKS - 1 + WORLD_UPDATE_PARTS,
               "a name per frame step and update part");

typedef struct trace_row_t {
    int frame;
    bool screenshot;
    double ms[3];         /* wall, submit, thread */
    float step_ms[TRACE_STEPS]; /* CPU wall ms of the frame's steps (world_frame_desc_t.marks) */
    long stats[TRACE_STATS];
    float pass_ms[TRACE_PASSES]; /* GPU, latest result; -1: not run in the last TRACE_GPU_LAG + 1 frames */
    float cpu_ms[TRACE_PASSES];  /* CPU wall time in the pass's calls this frame */
} trace_row_t;

struct app_trace_t {
    char path[1100];
    trace_row_t *rows; /* a ring of APP_FRAME_HISTORY */
    long count;        /* rows added */
    long streamed_last; /* measure_grass_t.tiles_streamed_total of the previous row */
};

app_trace_t *app_trace_open(const char *out)
{
    app_trace_t *tr = calloc(1, sizeof *tr);
    if (tr) tr->rows = malloc(sizeof *tr->rows * APP_FRAME_HISTORY);
    if (!tr || !tr->rows) {
        core_log_warn("--frame-log: no memory for %d rows; no frames.csv", APP_FRAME_HISTORY);
        if (tr) free(tr);
        return NULL;
    }
    snprintf(tr->path, sizeof tr->path, "%s/frames.csv", out);
    return tr;
}

void app_trace_row(app_trace_t *tr, world_t *w, const app_trace_frame_t *fr)
{
    if (!tr) return;
    trace_row_t *r = &tr->rows[tr->count % APP_FRAME_HISTORY];
    tr->count++;
    world_info_t info = world_info(w);
    measure_grass_t ts;
    measure_grass(w, MEASURE_GRASS_TILES, false, &ts);
    *r = (trace_row_t){.frame = fr->frame, .screenshot = fr->screenshot,
                       .ms = {fr->wall_ms, fr->submit_ms, fr->thread_ms},
                       .stats = {ts.tiles_active, ts.tiles_recovering, ts.tile_slots_dispatched,
                                 ts.tile_blades_dispatched, ts.tiles_streamed_total - tr->streamed_last}};
    tr->streamed_last = ts.tiles_streamed_total;
    for (int k = 0; k < WORLD_FRAME_MARKS - 1; k++)
        r->step_ms[k] = fr->marks ? (float)((fr->marks[k + 1] - fr->marks[k]) * 1e3) : 0.0f;
    for (int k = 0; k < WORLD_UPDATE_PARTS; k++) r->step_ms[WORLD_FRAME_MARKS - 1 + k] = (float)info.update_ms[k];
    int passes = gfx_timer_count();
    for (int i = 0; i < TRACE_PASSES; i++) {
        bool recent = i < passes && gfx_timer_frames_since(i) <= TRACE_GPU_LAG;
        r->pass_ms[i] = recent ? (float)gfx_timer_last_ms(i) : -1.0f;
        r->cpu_ms[i] = i < passes ? (float)gfx_timer_cpu_ms(i) : -1.0f;
    }
}

static bool trace_write(const app_trace_t *tr, FILE *f)
{
    int passes = gfx_timer_count();
    fprintf(f, "frame,wall_ms,submit_ms,thread_ms,screenshot");
    for (int k = 0; k < TRACE_STATS; k++) fprintf(f, ",%s", stat_names[k]);
    for (int k = 0; k < TRACE_STEPS; k++) fprintf(f, ",%s_cpu_ms", step_names[k]);
    for (int i = 0; i < passes; i++) fprintf(f, ",%s_ms", gfx_timer_name(i));
    for (int i = 0; i < passes; i++) fprintf(f, ",%s_cpu_ms", gfx_timer_name(i));
    fprintf(f, "\n");
    long first = tr->count > APP_FRAME_HISTORY ? tr->count - APP_FRAME_HISTORY : 0;
    for (long k = first; k < tr->count; k++) {
        const trace_row_t *r = &tr->rows[k % APP_FRAME_HISTORY];
        fprintf(f, "%d,%.3f,%.3f,%.3f,%d", r->frame, r->ms[0], r->ms[1], r->ms[2], r->screenshot ? 1 : 0);
        for (int s = 0; s < TRACE_STATS; s++) fprintf(f, ",%ld", r->stats[s]);
        for (int m = 0; m < TRACE_STEPS; m++) fprintf(f, ",%.3f", (double)r->step_ms[m]);
        for (int i = 0; i < 2 * passes; i++) {
            float v = i < passes ? r->pass_ms[i] : r->cpu_ms[i - passes];
            if (v < 0.0f) fprintf(f, ",");
            else fprintf(f, ",%.3f", (double)v);
        }
        fprintf(f, "\n");
    }
    if (first > 0) core_log_info("--frame-log: frames.csv holds the last %d of %ld frames", APP_FRAME_HISTORY, tr->count);
    return !ferror(f);
}

bool app_trace_close(app_trace_t *tr)
{
    if (!tr) return true;
    FILE *f = fopen(tr->path, "w");
    bool ok = f && trace_write(tr, f);
    ok = f && fclose(f) == 0 && ok;
    if (!ok) core_log_warn("--frame-log: could not write %s", tr->path);
    free(tr->rows);
    free(tr);
    return ok;
}

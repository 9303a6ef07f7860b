/* gfx_timer: per-pass GPU timings with GL_TIME_ELAPSED queries in a ring of
 * GFX_TIMER_LATENCY frames. A slot is read only when its result is
 * available, so the CPU never waits on the GPU.
 *
 * Attribution: a driver may start a pass's timer while earlier work is
 * still in flight, so a pass that must wait for it (a transform-feedback
 * write into a buffer the previous frame's draw still reads) shows that
 * wait as its own time. With MEADOW_TIMER_SYNC=1 in the environment every
 * pass begins after glFinish: the frame is slower, each pass's time is its
 * own (docs/PERFORMANCE.md). */
#include "gfx/gfx_local.h"

/* This file's state in the current context (gfx_local.h). */
#define T (gfx_cur->timer)
#include "platform/plat.h"

#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GFX_HANG_TRIES 3 /* of 10 s each */


bool gfx_timer_sync(void)
{
    if (T.sync < 0) {
        const char *e = getenv("MEADOW_TIMER_SYNC");
        T.sync = e && strcmp(e, "1") == 0;
    }
    return T.sync == 1;
}

static void record(gfx_timer_pass_t *p, double ms)
{
    p->last = ms;
    p->max = ms > p->max ? ms : p->max;
    p->sum += ms;
    p->n++;
    p->hist[p->hist_i] = ms;
    p->hist_i = (p->hist_i + 1) % GFX_TIMER_HISTORY;
    if (p->hist_n < GFX_TIMER_HISTORY) p->hist_n++;
}

static void harvest(gfx_timer_pass_t *p, int slot, bool wait)
{
    if (!p->pending[slot]) return;
    GLint avail = 0;
    if (!wait) glGetQueryObjectiv(p->q[slot], GL_QUERY_RESULT_AVAILABLE, &avail);
    if (!wait && !avail) return;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(p->q[slot], GL_QUERY_RESULT, &ns);
    p->pending[slot] = false;
    if (p->frame_of[slot] >= T.first_frame) record(p, (double)ns * 1e-6);
}

void gfx_timer_frame_begin(void)
{
    gfx_count_frame();
    T.frame++;
    int slot = T.frame % GFX_TIMER_LATENCY;
    for (int i = 0; i < T.count; i++) {
        T.passes[i].cpu_ms = 0.0;
        for (int s = 0; s < GFX_TIMER_LATENCY; s++)
            if (s != slot) harvest(&T.passes[i], s, false);
        /* The slot about to be reused: its result is LATENCY frames old. */
        harvest(&T.passes[i], slot, false);
    }
}

const char *gfx_pass_name(gfx_pass_t kind)
{
    static const char *const names[GFX_PASS_KINDS] = {"terrain", "colliders", "character.skin", "character.draw", "bb.cubemaps", "bb.collide", "bb.recover", "bb.occlusion", "bb.ring", "bb.render", "bb.raster", "blade.physics", "blade.cull", "blade.draw", "blade.raster", "tiles.physics", "tiles.cull", "tiles.draw", "tiles.raster", "raster.init", "raster.composite", "canopy.match", "target.clear", "depth.resolve", "test"};
    return kind >= 0 && kind < GFX_PASS_KINDS ? names[kind] : "?";
}

void gfx_timer_begin(gfx_pass_t kind)
{
    const char *pass = gfx_pass_name(kind);
    if (gfx_timer_sync()) glFinish();
    gfx_count_pass_begin(pass);
    int i;
    for (i = 0; i < T.count; i++)
        if (strcmp(T.passes[i].name, pass) == 0) break;
    if (i == T.count) { /* a kind's first pass: room by GFX_PASS_KINDS <= GFX_TIMER_MAX_PASSES */
        gfx_timer_pass_t *p = &T.passes[T.count++];
        memset(p, 0, sizeof *p);
        snprintf(p->name, sizeof p->name, "%s", pass);
        glGenQueries(GFX_TIMER_LATENCY, p->q);
    }
    int slot = T.frame % GFX_TIMER_LATENCY;
    gfx_timer_pass_t *p = &T.passes[i];
    p->last_frame = T.frame;
    p->cpu_t0 = plat_time();
    T.cpu_open = i;
    if (p->pending[slot]) {
        /* Still in flight after LATENCY frames: drop this frame's sample
         * rather than stall. */
        return;
    }
    glBeginQuery(GL_TIME_ELAPSED, p->q[slot]);
    p->frame_of[slot] = T.frame;
    T.open = i;
}

void gfx_timer_end(void)
{
    gfx_count_pass_end();
    if (T.cpu_open >= 0) {
        gfx_timer_pass_t *c = &T.passes[T.cpu_open];
        c->cpu_ms += (plat_time() - c->cpu_t0) * 1e3;
        T.cpu_open = -1;
    }
    if (T.open < 0) return;
    glEndQuery(GL_TIME_ELAPSED);
    T.passes[T.open].pending[T.frame % GFX_TIMER_LATENCY] = true;
    T.open = -1;
}

int gfx_timer_count(void) { return T.count; }
const char *gfx_timer_name(int i) { return T.passes[i].name; }
double gfx_timer_last_ms(int i) { return T.passes[i].last; }
double gfx_timer_cpu_ms(int i) { return T.passes[i].cpu_ms; }
int gfx_timer_frames_since(int i) { return T.frame - T.passes[i].last_frame; }
double gfx_timer_max_ms(int i) { return T.passes[i].max; }
double gfx_timer_avg_ms(int i) { return T.passes[i].n ? T.passes[i].sum / (double)T.passes[i].n : 0.0; }

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double gfx_timer_median_ms(int i)
{
    gfx_timer_pass_t *p = &T.passes[i];
    if (!p->hist_n) return 0.0;
    double tmp[GFX_TIMER_HISTORY];
    memcpy(tmp, p->hist, sizeof(double) * (size_t)p->hist_n);
    qsort(tmp, (size_t)p->hist_n, sizeof(double), cmp_double);
    return tmp[p->hist_n / 2];
}

/* The timed passes of frame `frame` (when its queries are still in their
 * slots), comma separated: what a hung frame was running. */
static const char *frame_pass_names(int frame)
{
    static char names[512];
    names[0] = 0;
    size_t len = 0;
    int slot = frame % GFX_TIMER_LATENCY;
    for (int i = 0; i < T.count && len < sizeof names; i++)
        if (T.passes[i].frame_of[slot] == frame)
            len += (size_t)snprintf(names + len, sizeof names - len, "%s%s", len ? ", " : "", T.passes[i].name);
    return names[0] ? names : "(unknown)";
}

double gfx_frame_end(int in_flight)
{
    assert(in_flight >= 1 && in_flight <= GFX_TIMER_LATENCY);
    if (T.fence_count == GFX_TIMER_LATENCY) {
        glDeleteSync(T.fences[0]);
        memmove(T.fences, T.fences + 1, sizeof T.fences[0] * (GFX_TIMER_LATENCY - 1));
        T.fence_count--;
    }
    T.fences[T.fence_count++] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    double t0 = plat_time();
    int waits = 0;
    while (T.fence_count > in_flight - 1) {
        /* 10 s per try; a frame still unfinished after GFX_HANG_TRIES tries
         * is a hung GPU (or a lost context): give up instead of waiting forever. */
        GLenum r = glClientWaitSync(T.fences[0], GL_SYNC_FLUSH_COMMANDS_BIT, 10000000000ull);
        if (r == GL_TIMEOUT_EXPIRED || r == GL_WAIT_FAILED) {
            if (++waits < GFX_HANG_TRIES && r == GL_TIMEOUT_EXPIRED) {
                core_log_warn("gfx: a frame has not finished on the GPU after %d s", 10 * waits);
                continue;
            }
            core_log_error("gfx: a frame did not finish on the GPU (%s after %d s); passes timed this frame: %s",
                           r == GL_WAIT_FAILED ? "wait failed" : "timeout", 10 * waits, frame_pass_names(T.frame - T.fence_count + 1));
            return -1.0;
        }
        glDeleteSync(T.fences[0]);
        memmove(T.fences, T.fences + 1, sizeof T.fences[0] * (size_t)(T.fence_count - 1));
        T.fence_count--;
    }
    return plat_time() - t0;
}

void gfx_timer_flush(void)
{
    gfx_count_flush();
    for (int i = 0; i < T.count; i++)
        for (int s = 0; s < GFX_TIMER_LATENCY; s++) harvest(&T.passes[i], s, true);
}

static void clear_stats(void)
{
    for (int i = 0; i < T.count; i++) {
        gfx_timer_pass_t *p = &T.passes[i];
        p->sum = p->max = 0;
        p->n = 0;
        p->hist_n = p->hist_i = 0;
    }
}

void gfx_timer_reset_stats(void)
{
    gfx_timer_flush();
    clear_stats();
}

void gfx_timer_skip_warmup(void)
{
    clear_stats();
    T.first_frame = T.frame + 1;
}

void gfx_timer_shutdown(void)
{
    for (int k = 0; k < T.fence_count; k++) glDeleteSync(T.fences[k]);
    for (int i = 0; i < T.count; i++) glDeleteQueries(GFX_TIMER_LATENCY, T.passes[i].q);
    memset(&T, 0, sizeof T);
    T.open = -1;
}

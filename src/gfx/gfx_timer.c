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
#include "platform/plat.h"

#include <assert.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define GFX_HANG_TRIES 3 /* of 10 s each */

#define HISTORY 256

typedef struct pass_t {
    char name[32];
    GLuint q[GFX_TIMER_LATENCY];
    bool pending[GFX_TIMER_LATENCY];
    int frame_of[GFX_TIMER_LATENCY]; /* frame each slot's query ran in */
    int last_frame;                  /* frame the pass last began in */
    double last, sum, max;
    long n;
    double hist[HISTORY];
    int hist_n, hist_i;
    double cpu_ms, cpu_t0; /* CPU wall ms inside the pass this frame; its latest begin (s) */
} pass_t;

static struct {
    pass_t passes[GFX_TIMER_MAX_PASSES];
    int count;
    int frame;
    int open;
    int cpu_open; /* the pass between begin and end on the CPU clock, else -1 */
    int first_frame; /* samples of earlier frames are not recorded */
    GLsync fences[GFX_TIMER_LATENCY]; /* gfx_frame_end, oldest first */
    int fence_count;
    bool warned_full;
    int sync; /* -1 unread, else MEADOW_TIMER_SYNC */
} t = {.open = -1, .cpu_open = -1, .sync = -1};

bool gfx_timer_sync(void)
{
    if (t.sync < 0) {
        const char *e = getenv("MEADOW_TIMER_SYNC");
        t.sync = e && strcmp(e, "1") == 0;
    }
    return t.sync == 1;
}

static void record(pass_t *p, double ms)
{
    p->last = ms;
    p->max = ms > p->max ? ms : p->max;
    p->sum += ms;
    p->n++;
    p->hist[p->hist_i] = ms;
    p->hist_i = (p->hist_i + 1) % HISTORY;
    if (p->hist_n < HISTORY) p->hist_n++;
}

static void harvest(pass_t *p, int slot, bool wait)
{
    if (!p->pending[slot]) return;
    GLint avail = 0;
    if (!wait) glGetQueryObjectiv(p->q[slot], GL_QUERY_RESULT_AVAILABLE, &avail);
    if (!wait && !avail) return;
    GLuint64 ns = 0;
    glGetQueryObjectui64v(p->q[slot], GL_QUERY_RESULT, &ns);
    p->pending[slot] = false;
    if (p->frame_of[slot] >= t.first_frame) record(p, (double)ns * 1e-6);
}

void gfx_timer_frame_begin(void)
{
    gfx_count_frame();
    t.frame++;
    int slot = t.frame % GFX_TIMER_LATENCY;
    for (int i = 0; i < t.count; i++) {
        t.passes[i].cpu_ms = 0.0;
        for (int s = 0; s < GFX_TIMER_LATENCY; s++)
            if (s != slot) harvest(&t.passes[i], s, false);
        /* The slot about to be reused: its result is LATENCY frames old. */
        harvest(&t.passes[i], slot, false);
    }
}

void gfx_timer_begin(const char *pass)
{
    if (gfx_timer_sync()) glFinish();
    gfx_count_pass_begin(pass);
    int i;
    for (i = 0; i < t.count; i++)
        if (strcmp(t.passes[i].name, pass) == 0) break;
    if (i == t.count) {
        if (t.count == GFX_TIMER_MAX_PASSES) {
            if (!t.warned_full) core_log_warn("gfx: more than %d timed passes; '%s' not timed", GFX_TIMER_MAX_PASSES, pass);
            t.warned_full = true;
            return;
        }
        pass_t *p = &t.passes[t.count++];
        memset(p, 0, sizeof *p);
        snprintf(p->name, sizeof p->name, "%s", pass);
        glGenQueries(GFX_TIMER_LATENCY, p->q);
    }
    int slot = t.frame % GFX_TIMER_LATENCY;
    pass_t *p = &t.passes[i];
    p->last_frame = t.frame;
    p->cpu_t0 = plat_time();
    t.cpu_open = i;
    if (p->pending[slot]) {
        /* Still in flight after LATENCY frames: drop this frame's sample
         * rather than stall. */
        return;
    }
    glBeginQuery(GL_TIME_ELAPSED, p->q[slot]);
    p->frame_of[slot] = t.frame;
    t.open = i;
}

void gfx_timer_end(void)
{
    gfx_count_pass_end();
    if (t.cpu_open >= 0) {
        pass_t *c = &t.passes[t.cpu_open];
        c->cpu_ms += (plat_time() - c->cpu_t0) * 1e3;
        t.cpu_open = -1;
    }
    if (t.open < 0) return;
    glEndQuery(GL_TIME_ELAPSED);
    t.passes[t.open].pending[t.frame % GFX_TIMER_LATENCY] = true;
    t.open = -1;
}

int gfx_timer_count(void) { return t.count; }
const char *gfx_timer_name(int i) { return t.passes[i].name; }
double gfx_timer_last_ms(int i) { return t.passes[i].last; }
double gfx_timer_cpu_ms(int i) { return t.passes[i].cpu_ms; }
int gfx_timer_frames_since(int i) { return t.frame - t.passes[i].last_frame; }
double gfx_timer_max_ms(int i) { return t.passes[i].max; }
double gfx_timer_avg_ms(int i) { return t.passes[i].n ? t.passes[i].sum / (double)t.passes[i].n : 0.0; }

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double gfx_timer_median_ms(int i)
{
    pass_t *p = &t.passes[i];
    if (!p->hist_n) return 0.0;
    double tmp[HISTORY];
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
    for (int i = 0; i < t.count && len < sizeof names; i++)
        if (t.passes[i].frame_of[slot] == frame)
            len += (size_t)snprintf(names + len, sizeof names - len, "%s%s", len ? ", " : "", t.passes[i].name);
    return names[0] ? names : "(unknown)";
}

double gfx_frame_end(int in_flight)
{
    assert(in_flight >= 1 && in_flight <= GFX_TIMER_LATENCY);
    if (t.fence_count == GFX_TIMER_LATENCY) {
        glDeleteSync(t.fences[0]);
        memmove(t.fences, t.fences + 1, sizeof t.fences[0] * (GFX_TIMER_LATENCY - 1));
        t.fence_count--;
    }
    t.fences[t.fence_count++] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    double t0 = plat_time();
    int waits = 0;
    while (t.fence_count > in_flight - 1) {
        /* 10 s per try; a frame still unfinished after GFX_HANG_TRIES tries
         * is a hung GPU (or a lost context): give up instead of waiting forever. */
        GLenum r = glClientWaitSync(t.fences[0], GL_SYNC_FLUSH_COMMANDS_BIT, 10000000000ull);
        if (r == GL_TIMEOUT_EXPIRED || r == GL_WAIT_FAILED) {
            if (++waits < GFX_HANG_TRIES && r == GL_TIMEOUT_EXPIRED) {
                core_log_warn("gfx: a frame has not finished on the GPU after %d s", 10 * waits);
                continue;
            }
            core_log_error("gfx: a frame did not finish on the GPU (%s after %d s); passes timed this frame: %s",
                           r == GL_WAIT_FAILED ? "wait failed" : "timeout", 10 * waits, frame_pass_names(t.frame - t.fence_count + 1));
            return -1.0;
        }
        glDeleteSync(t.fences[0]);
        memmove(t.fences, t.fences + 1, sizeof t.fences[0] * (size_t)(t.fence_count - 1));
        t.fence_count--;
    }
    return plat_time() - t0;
}

void gfx_timer_flush(void)
{
    gfx_count_flush();
    for (int i = 0; i < t.count; i++)
        for (int s = 0; s < GFX_TIMER_LATENCY; s++) harvest(&t.passes[i], s, true);
}

static void clear_stats(void)
{
    for (int i = 0; i < t.count; i++) {
        pass_t *p = &t.passes[i];
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
    t.first_frame = t.frame + 1;
}

void gfx_timer_shutdown(void)
{
    for (int k = 0; k < t.fence_count; k++) glDeleteSync(t.fences[k]);
    for (int i = 0; i < t.count; i++) glDeleteQueries(GFX_TIMER_LATENCY, t.passes[i].q);
    memset(&t, 0, sizeof t);
    t.open = -1;
}

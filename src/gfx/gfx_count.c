/* gfx_count: work counters that do not depend on timing (see gfx.h). Draw
 * calls and dispatches are counted by the wrappers gfx.h puts in place of
 * epoxy's entry points and charged to the gfx_timer pass open at the time.
 * Each timer pass also runs a GL_PRIMITIVES_GENERATED and a
 * GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN query; finished queries are read
 * at the next frame's start only when their result is available, so the
 * CPU never waits, and none is ever dropped (a pending pair is never
 * reused: the pool grows instead), so totals are exact. */
#include "gfx/gfx_local.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { UNTIMED = 0 }; /* pass 0: work issued outside any timer pass */

typedef struct counter_t {
    char name[32];
    double total[GFX_COUNT_KINDS];
} counter_t;

typedef struct query_pair_t {
    GLuint q[2]; /* primitives generated, transform-feedback primitives written */
    int pass;
} query_pair_t;

static struct {
    counter_t passes[GFX_COUNT_MAX], items[GFX_COUNT_MAX];
    int pass_count, item_count;
    int open;           /* pass of the running queries, or -1 */
    query_pair_t running;
    query_pair_t *pending;
    int pending_count, pending_cap;
    query_pair_t *spare; /* read pairs, ready for reuse */
    int spare_count, spare_cap;
    int frames;
    bool warned_full;
} c = {.pass_count = 1, .passes = {{.name = "(untimed)"}}, .open = -1};

static int find(counter_t *table, int *count, const char *name)
{
    for (int i = 0; i < *count; i++)
        if (strcmp(table[i].name, name) == 0) return i;
    if (*count == GFX_COUNT_MAX) {
        if (!c.warned_full) core_log_warn("gfx: more than %d counters; '%s' not counted", GFX_COUNT_MAX, name);
        c.warned_full = true;
        return -1;
    }
    counter_t *e = &table[(*count)++];
    memset(e, 0, sizeof *e);
    snprintf(e->name, sizeof e->name, "%s", name);
    return *count - 1;
}

static counter_t *current(void) { return &c.passes[c.open >= 0 ? c.open : UNTIMED]; }

void gfx_count_draw(GLsizei ranges)
{
    counter_t *p = current();
    p->total[GFX_COUNT_DRAWS] += 1.0;
    p->total[GFX_COUNT_DRAW_RANGES] += (double)ranges;
}

void gfx_count_dispatch(uint64_t groups)
{
    counter_t *p = current();
    p->total[GFX_COUNT_DISPATCHES] += 1.0;
    p->total[GFX_COUNT_GROUPS] += (double)groups;
}

void gfx_count_add(const char *item, double n)
{
    int i = find(c.items, &c.item_count, item);
    if (i >= 0) c.items[i].total[0] += n;
}

static bool push(query_pair_t **arr, int *count, int *cap, query_pair_t v)
{
    if (*count == *cap) {
        int ncap = *cap ? 2 * *cap : 64;
        query_pair_t *n = realloc(*arr, sizeof *n * (size_t)ncap);
        if (!n) return false;
        *arr = n;
        *cap = ncap;
    }
    (*arr)[(*count)++] = v;
    return true;
}

static void harvest(bool wait);

/* Queries awaiting their results. Harvested at every gfx_timer_frame_begin;
 * a caller that never begins frames (a test driving the world directly)
 * must not grow the list without bound, so pass_end harvests too once it is
 * long: without waiting past PENDING_SOFT, waiting past PENDING_HARD. */
#define PENDING_SOFT 1024
#define PENDING_HARD 4096

void gfx_count_pass_begin(const char *pass)
{
    if (c.open >= 0) return;
    int i = find(c.passes, &c.pass_count, pass);
    if (i < 0) return;
    query_pair_t qp = {.pass = i};
    if (c.spare_count) qp = c.spare[--c.spare_count], qp.pass = i;
    else glGenQueries(2, qp.q);
    glBeginQuery(GL_PRIMITIVES_GENERATED, qp.q[0]);
    glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, qp.q[1]);
    c.running = qp;
    c.open = i;
}

void gfx_count_pass_end(void)
{
    if (c.open < 0) return;
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
    if (!push(&c.pending, &c.pending_count, &c.pending_cap, c.running)) {
        core_log_error("out of memory for counter queries");
        glDeleteQueries(2, c.running.q);
    }
    if (c.pending_count >= PENDING_SOFT) harvest(false);
    if (c.pending_count >= PENDING_HARD) harvest(true);
    c.open = -1;
}

/* Reads the pending pairs whose results are available (all of them when
 * `wait`), keeping the order of the rest. */
static void harvest(bool wait)
{
    int keep = 0;
    for (int k = 0; k < c.pending_count; k++) {
        query_pair_t qp = c.pending[k];
        GLint avail = 1;
        if (!wait) glGetQueryObjectiv(qp.q[1], GL_QUERY_RESULT_AVAILABLE, &avail);
        if (avail && !wait) glGetQueryObjectiv(qp.q[0], GL_QUERY_RESULT_AVAILABLE, &avail);
        if (!avail) {
            c.pending[keep++] = qp;
            continue;
        }
        GLuint64 v[2] = {0, 0};
        glGetQueryObjectui64v(qp.q[0], GL_QUERY_RESULT, &v[0]);
        glGetQueryObjectui64v(qp.q[1], GL_QUERY_RESULT, &v[1]);
        c.passes[qp.pass].total[GFX_COUNT_PRIMITIVES] += (double)v[0];
        c.passes[qp.pass].total[GFX_COUNT_TF_WRITTEN] += (double)v[1];
        if (!push(&c.spare, &c.spare_count, &c.spare_cap, qp)) glDeleteQueries(2, qp.q);
    }
    c.pending_count = keep;
}

void gfx_count_frame(void)
{
    harvest(false);
    c.frames++;
}

void gfx_count_flush(void) { harvest(true); }

void gfx_count_reset(void)
{
    gfx_count_flush();
    for (int i = 0; i < c.pass_count; i++) memset(c.passes[i].total, 0, sizeof c.passes[i].total);
    c.item_count = 0;
    c.frames = 0;
}

int gfx_count_frames(void) { return c.frames; }
int gfx_count_pass_count(void) { return c.pass_count; }
const char *gfx_count_pass_name(int i) { return c.passes[i].name; }
double gfx_count_pass_total(int i, int kind) { return c.passes[i].total[kind]; }
int gfx_count_item_count(void) { return c.item_count; }
const char *gfx_count_item_name(int i) { return c.items[i].name; }
double gfx_count_item_total(int i) { return c.items[i].total[0]; }

void gfx_count_shutdown(void)
{
    if (c.open >= 0) gfx_count_pass_end();
    for (int k = 0; k < c.pending_count; k++) glDeleteQueries(2, c.pending[k].q);
    for (int k = 0; k < c.spare_count; k++) glDeleteQueries(2, c.spare[k].q);
    free(c.pending);
    free(c.spare);
    memset(&c, 0, sizeof c);
    c.pass_count = 1;
    snprintf(c.passes[UNTIMED].name, sizeof c.passes[UNTIMED].name, "(untimed)");
    c.open = -1;
}

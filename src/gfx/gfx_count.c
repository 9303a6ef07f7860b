/* gfx_count: work counters that do not depend on timing (see gfx.h). Draw
 * calls and dispatches are counted by the wrappers gfx.h puts in place of
 * epoxy's entry points and charged to the gfx_timer pass open at the time.
 * Each timer pass also runs a GL_PRIMITIVES_GENERATED and a
 * GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN query; finished queries are read
 * at the next frame's start only when their result is available, so the
 * CPU never waits, and none is ever dropped (a pending pair is never
 * reused: the pool grows instead), so totals are exact. */
#include "gfx/gfx_local.h"

/* This file's state in the current context (gfx_local.h). */
#define C (gfx_cur->count)

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { UNTIMED = 0 }; /* pass 0: work issued outside any timer pass */

static int find(gfx_counter_t *table, int *count, const char *name)
{
    for (int i = 0; i < *count; i++)
        if (strcmp(table[i].name, name) == 0) return i;
    if (*count == GFX_COUNT_MAX) {
        if (!C.warned_full) core_log_warn("gfx: more than %d counters; '%s' not counted", GFX_COUNT_MAX, name);
        C.warned_full = true;
        return -1;
    }
    gfx_counter_t *e = &table[(*count)++];
    memset(e, 0, sizeof *e);
    snprintf(e->name, sizeof e->name, "%s", name);
    return *count - 1;
}

static gfx_counter_t *current(void) { return &C.passes[C.open >= 0 ? C.open : UNTIMED]; }

void gfx_count_draw(GLsizei ranges)
{
    gfx_counter_t *p = current();
    p->total[GFX_COUNT_DRAWS] += 1.0;
    p->total[GFX_COUNT_DRAW_RANGES] += (double)ranges;
}

void gfx_count_dispatch(uint64_t groups)
{
    gfx_counter_t *p = current();
    p->total[GFX_COUNT_DISPATCHES] += 1.0;
    p->total[GFX_COUNT_GROUPS] += (double)groups;
}

void gfx_count_add(const char *item, double n)
{
    int i = find(C.items, &C.item_count, item);
    if (i >= 0) C.items[i].total[0] += n;
}

static bool push(gfx_query_pair_t **arr, int *count, int *cap, gfx_query_pair_t v)
{
    if (*count == *cap) {
        int ncap = *cap ? 2 * *cap : 64;
        gfx_query_pair_t *n = realloc(*arr, sizeof *n * (size_t)ncap);
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
    if (C.open >= 0) return;
    int i = find(C.passes, &C.pass_count, pass);
    if (i < 0) return;
    gfx_query_pair_t qp = {.pass = i};
    if (C.spare_count) qp = C.spare[--C.spare_count], qp.pass = i;
    else glGenQueries(2, qp.q);
    glBeginQuery(GL_PRIMITIVES_GENERATED, qp.q[0]);
    glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, qp.q[1]);
    C.running = qp;
    C.open = i;
}

void gfx_count_pass_end(void)
{
    if (C.open < 0) return;
    glEndQuery(GL_PRIMITIVES_GENERATED);
    glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
    if (!push(&C.pending, &C.pending_count, &C.pending_cap, C.running)) {
        core_log_error("out of memory for counter queries");
        glDeleteQueries(2, C.running.q);
    }
    if (C.pending_count >= PENDING_SOFT) harvest(false);
    if (C.pending_count >= PENDING_HARD) harvest(true);
    C.open = -1;
}

/* Reads the pending pairs whose results are available (all of them when
 * `wait`), keeping the order of the rest. */
static void harvest(bool wait)
{
    int keep = 0;
    for (int k = 0; k < C.pending_count; k++) {
        gfx_query_pair_t qp = C.pending[k];
        GLint avail = 1;
        if (!wait) glGetQueryObjectiv(qp.q[1], GL_QUERY_RESULT_AVAILABLE, &avail);
        if (avail && !wait) glGetQueryObjectiv(qp.q[0], GL_QUERY_RESULT_AVAILABLE, &avail);
        if (!avail) {
            C.pending[keep++] = qp;
            continue;
        }
        GLuint64 v[2] = {0, 0};
        glGetQueryObjectui64v(qp.q[0], GL_QUERY_RESULT, &v[0]);
        glGetQueryObjectui64v(qp.q[1], GL_QUERY_RESULT, &v[1]);
        C.passes[qp.pass].total[GFX_COUNT_PRIMITIVES] += (double)v[0];
        C.passes[qp.pass].total[GFX_COUNT_TF_WRITTEN] += (double)v[1];
        if (!push(&C.spare, &C.spare_count, &C.spare_cap, qp)) glDeleteQueries(2, qp.q);
    }
    C.pending_count = keep;
}

void gfx_count_frame(void)
{
    harvest(false);
    C.frames++;
}

void gfx_count_flush(void) { harvest(true); }

void gfx_count_reset(void)
{
    gfx_count_flush();
    for (int i = 0; i < C.pass_count; i++) memset(C.passes[i].total, 0, sizeof C.passes[i].total);
    C.item_count = 0;
    C.frames = 0;
}

int gfx_count_frames(void) { return C.frames; }
int gfx_count_pass_count(void) { return C.pass_count; }
const char *gfx_count_pass_name(int i) { return C.passes[i].name; }
double gfx_count_pass_total(int i, int kind) { return C.passes[i].total[kind]; }
int gfx_count_item_count(void) { return C.item_count; }
const char *gfx_count_item_name(int i) { return C.items[i].name; }
double gfx_count_item_total(int i) { return C.items[i].total[0]; }

void gfx_count_shutdown(void)
{
    if (C.open >= 0) gfx_count_pass_end();
    for (int k = 0; k < C.pending_count; k++) glDeleteQueries(2, C.pending[k].q);
    for (int k = 0; k < C.spare_count; k++) glDeleteQueries(2, C.spare[k].q);
    free(C.pending);
    free(C.spare);
    memset(&C, 0, sizeof C);
    C.pass_count = 1;
    snprintf(C.passes[UNTIMED].name, sizeof C.passes[UNTIMED].name, "(untimed)");
    C.open = -1;
}

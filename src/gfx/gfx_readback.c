/* gfx_readback: fenced readback rings. GPU data (counters, draw commands,
 * per-slot measurements) is copied into one of `depth` small buffers and a
 * GL_TIMESTAMP query is written after the copies as its fence; later frames
 * read the slots whose fence has passed, so the CPU never waits for the GPU
 * unless asked to. The fences are reusable, labelled query objects rather
 * than per-frame GLsync objects, so the ring's GL objects are made once,
 * counted by gfx and released with it. */
#include "gfx/gfx_local.h"

#include <assert.h>
#include <stdio.h>
#include <string.h>

gfx_readback_t gfx_readback_make(size_t size, int depth, const char *label)
{
    assert(size > 0 && depth >= 1 && depth <= GFX_READBACK_MAX_DEPTH && label);
    gfx_readback_t r = {.depth = depth};
    char fence_label[128];
    snprintf(fence_label, sizeof fence_label, "%s.fence", label);
    for (int i = 0; i < depth; i++) {
        r.buf[i] = gfx_buffer_make(&(gfx_buffer_desc_t){.size = size, .readable = true, .label = label});
        r.fence[i] = r.buf[i].id ? gfx_query_make(GL_TIMESTAMP, fence_label) : 0;
        if (!r.fence[i]) {
            gfx_readback_destroy(&r);
            return r;
        }
    }
    return r;
}

void gfx_readback_destroy(gfx_readback_t *r)
{
    for (int i = 0; i < GFX_READBACK_MAX_DEPTH; i++) {
        if (r->buf[i].id) gfx_buffer_destroy(&r->buf[i]);
        if (r->fence[i]) gfx_query_destroy(&r->fence[i]);
    }
    memset(r, 0, sizeof *r);
}

bool gfx_readback_busy(const gfx_readback_t *r) { return r->pending[r->next]; }

void gfx_readback_copy(gfx_readback_t *r, gfx_buffer_t src, size_t src_offset, size_t dst_offset, size_t size)
{
    assert(dst_offset + size <= r->buf[r->next].size);
    glCopyNamedBufferSubData(src.id, r->buf[r->next].id, (GLintptr)src_offset, (GLintptr)dst_offset,
                             (GLsizeiptr)size);
}

int gfx_readback_fence(gfx_readback_t *r)
{
    int i = r->next;
    glQueryCounter(r->fence[i], GL_TIMESTAMP);
    r->pending[i] = true;
    r->next = (i + 1) % r->depth;
    return i;
}

/* Whether slot i's copies have completed; with wait, blocks until they have. */
static bool passed(const gfx_readback_t *r, int i, bool wait)
{
    if (wait) {
        GLuint64 t;
        glGetQueryObjectui64v(r->fence[i], GL_QUERY_RESULT, &t);
        return true;
    }
    GLint available = 0;
    glGetQueryObjectiv(r->fence[i], GL_QUERY_RESULT_AVAILABLE, &available);
    return available != 0;
}

int gfx_readback_poll(gfx_readback_t *r, bool wait)
{
    for (int k = 0; k < r->depth; k++) {
        int i = (r->next + k) % r->depth;
        if (!r->pending[i]) continue;
        if (!passed(r, i, wait)) return -1;
        r->pending[i] = false;
        return i;
    }
    return -1;
}

int gfx_readback_latest(gfx_readback_t *r, bool wait)
{
    for (int k = 1; k <= r->depth; k++) {
        int i = (r->next - k + r->depth) % r->depth;
        if (!r->pending[i] || !passed(r, i, wait)) continue;
        /* Older slots are stale now; newer ones still in flight are dropped
         * too (a later frame's copy supersedes them). */
        for (int j = 0; j < r->depth; j++) r->pending[j] = false;
        return i;
    }
    return -1;
}

void gfx_readback_read(const gfx_readback_t *r, int slot, size_t offset, size_t size, void *out)
{
    assert(slot >= 0 && slot < r->depth && offset + size <= r->buf[slot].size);
    gfx_buffer_read(r->buf[slot], offset, size, out);
}

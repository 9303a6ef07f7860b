/* gfx_readback: fenced readback rings. GPU data (counters, draw commands,
 * per-slot measurements) is copied into one of `depth` small buffers and a
 * fence (GLsync) is put after the copies; later frames read the slots whose
 * fence has signalled, so the CPU never waits for the GPU unless asked to.
 * The buffers stay mapped for reading (persistent, coherent): a read is a
 * memcpy, no GL call. glGetNamedBufferSubData, used before, made the H100
 * driver wait for the GPU even on a finished copy: in the world's hybrid,
 * frames with touched tiles spent 4.1 ms in blade_tiles_update against
 * 0.02 ms without (frames.csv, update_blades_cpu_ms), 661 of 6,660 frames. */
#include "gfx/gfx_local.h"

#include <assert.h>
#include <stdio.h>
#include <string.h>

gfx_readback_t gfx_readback_make(size_t size, int depth, const char *label)
{
    assert(size > 0 && depth >= 1 && depth <= GFX_READBACK_MAX_DEPTH && label);
    gfx_readback_t r = {.depth = depth};
    for (int i = 0; i < depth; i++) {
        r.buf[i] = gfx_buffer_make(
            &(gfx_buffer_desc_t){.size = size, .readable = true, .persistent = true, .label = label});
        if (!r.buf[i].id || !r.buf[i].mapped) {
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
        if (r->fence[i]) glDeleteSync(r->fence[i]);
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
    if (r->fence[i]) glDeleteSync(r->fence[i]); /* an unread copy, dropped */
    r->fence[i] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    r->pending[i] = true;
    r->next = (i + 1) % r->depth;
    return i;
}

/* Whether slot i's copies have completed; with wait, blocks until they
 * have. A passed fence is deleted. */
static bool passed(gfx_readback_t *r, int i, bool wait)
{
    GLenum res = glClientWaitSync(r->fence[i], GL_SYNC_FLUSH_COMMANDS_BIT, 0);
    while (wait && res == GL_TIMEOUT_EXPIRED) res = glClientWaitSync(r->fence[i], 0, 1000000000ull);
    if (res == GL_TIMEOUT_EXPIRED) return false;
    glDeleteSync(r->fence[i]);
    r->fence[i] = 0;
    return true;
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
    memcpy(out, (const char *)r->buf[slot].mapped + offset, size);
}

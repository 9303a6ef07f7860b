/* core_buf: a growable byte buffer, kept NUL-terminated so it doubles as a
 * string builder (CSV, JSON, Markdown, gnuplot scripts, shader sources,
 * glTF files), written out atomically at the end. */
#include "core.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Room for `extra` more bytes and the terminating NUL. Running out of memory
 * while building text is not recoverable here: logged, then abort(). */
static void reserve(core_buf_t *b, size_t extra)
{
    if (b->len + extra + 1 <= b->cap) return;
    size_t cap = b->cap ? b->cap : 4096;
    while (cap < b->len + extra + 1) cap *= 2;
    char *grown = realloc(b->data, cap);
    if (!grown) {
        core_log_error("core_buf: out of memory (%zu bytes)", cap);
        abort();
    }
    b->data = grown;
    b->cap = cap;
}

void core_buf_put(core_buf_t *b, const void *data, size_t size)
{
    reserve(b, size);
    memcpy(b->data + b->len, data, size);
    b->len += size;
    b->data[b->len] = 0;
}

void core_buf_printf(core_buf_t *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int need = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (need < 0) return;
    reserve(b, (size_t)need);
    va_start(ap, fmt);
    vsnprintf(b->data + b->len, (size_t)need + 1, fmt, ap);
    va_end(ap);
    b->len += (size_t)need;
}

const char *core_buf_str(const core_buf_t *b) { return b->data ? b->data : ""; }

bool core_buf_write(const core_buf_t *b, const char *path)
{
    return core_fs_write_atomic(path, core_buf_str(b), b->len);
}

void core_buf_free(core_buf_t *b)
{
    free(b->data);
    memset(b, 0, sizeof *b);
}

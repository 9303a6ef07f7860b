/* gfx_depth: the nearest depth sample of each pixel of a multisampled
 * target (shaders/gfx/depth_nearest.comp), for measures that need the
 * distance to the nearest visible surface of a pixel whichever sample it
 * covers. Its program is gfx-internal: labelled, created on first use,
 * released by gfx_shutdown. */
#include "gfx/gfx_local.h"

/* This file's state in the current context (gfx_local.h). */
#define DEPTH (gfx_cur->depth)

#include <stdlib.h>
#include <string.h>

#include "common/bindings_gfx.glsl"

static bool depth_init(void)
{
    if (DEPTH.prog || DEPTH.failed) return !DEPTH.failed;
    gfx_program_t p = gfx_program_make(&(gfx_program_desc_t){.cs = "gfx/depth_nearest.comp",
                                                             .label = "gfx.depth_nearest.program"});
    if (!p.id) {
        DEPTH.failed = true;
        return false;
    }
    /* Internal: keep out of the user object count. */
    gfx_untrack(GL_PROGRAM, p.id);
    DEPTH.prog = p.id;
    return true;
}

void gfx_depth_shutdown(void)
{
    if (DEPTH.prog) {
        gfx_uniforms_forget(DEPTH.prog);
        glDeleteProgram(DEPTH.prog);
    }
    memset(&DEPTH, 0, sizeof DEPTH);
}

bool gfx_target_read_depth_nearest(const gfx_target_t *t, float *out)
{
    if (!t->depth.id) return false;
    if (t->samples <= 1 || t->resolve_fbo == t->fbo) return gfx_target_read_depth(t, out);
    if (!depth_init()) return false;
    size_t n = (size_t)t->w * (size_t)t->h;
    gfx_buffer_t buf = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof(float) * n, .readable = true,
                                                            .label = "gfx.depth_nearest.buffer"});
    float *tmp = malloc(sizeof(float) * n);
    bool ok = buf.id && tmp;
    if (ok) {
        gfx_program_t gp = {.id = DEPTH.prog};
        glUseProgram(DEPTH.prog);
        glBindTextureUnit(GFX_TEX_DEPTH, t->depth.id);
        glUniform1i(gfx_uniform(gp, "u_samples"), t->samples);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GFX_BIND_NEAREST, buf.id);
        glDispatchCompute(((GLuint)t->w + 7u) / 8u, ((GLuint)t->h + 7u) / 8u, 1);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glBindTextureUnit(GFX_TEX_DEPTH, 0);
        ok = gfx_buffer_read(buf, 0, sizeof(float) * n, tmp);
    }
    if (ok) {
        size_t row = (size_t)t->w;
        for (int y = 0; y < t->h; y++)
            memcpy(out + (size_t)y * row, tmp + (size_t)(t->h - 1 - y) * row, sizeof(float) * row);
    }
    free(tmp);
    gfx_buffer_destroy(&buf);
    return ok;
}

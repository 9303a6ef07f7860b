/* gfx_text: HUD text with stb_easy_font quads, expanded to triangles and
 * drawn with shaders/gfx/text.{vert,frag}. Its GL objects are gfx-internal:
 * labelled, created on first use, released by gfx_shutdown. */
#include "gfx/gfx_local.h"

/* This file's state in the current context (gfx_local.h). */
#define TEXT (gfx_cur->text)

#include <stdlib.h>
#include <string.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-braces"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

#define MAX_CHARS 4096

static bool text_init(void)
{
    if (TEXT.prog || TEXT.failed) return !TEXT.failed;
    gfx_program_t p = gfx_program_make(&(gfx_program_desc_t){
        .vs = "gfx/text.vert", .fs = "gfx/text.frag", .label = "gfx.text.program"});
    if (!p.id) {
        TEXT.failed = true;
        return false;
    }
    /* Internal: keep out of the user object count. */
    gfx_untrack(GL_PROGRAM, p.id);
    TEXT.prog = p.id;
    glCreateVertexArrays(1, &TEXT.vao);
    glObjectLabel(GL_VERTEX_ARRAY, TEXT.vao, -1, "gfx.text.vao");
    glCreateBuffers(1, &TEXT.vbo);
    glNamedBufferStorage(TEXT.vbo, MAX_CHARS * 6 * 2 * sizeof(float) * 6, NULL, GL_DYNAMIC_STORAGE_BIT);
    glObjectLabel(GL_BUFFER, TEXT.vbo, -1, "gfx.text.vbo");
    glVertexArrayVertexBuffer(TEXT.vao, 0, TEXT.vbo, 0, 2 * sizeof(float));
    glEnableVertexArrayAttrib(TEXT.vao, 0);
    glVertexArrayAttribFormat(TEXT.vao, 0, 2, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(TEXT.vao, 0, 0);
    return true;
}

void gfx_text_shutdown(void)
{
    if (TEXT.prog) {
        gfx_uniforms_forget(TEXT.prog);
        glDeleteProgram(TEXT.prog);
    }
    if (TEXT.vao) glDeleteVertexArrays(1, &TEXT.vao);
    if (TEXT.vbo) glDeleteBuffers(1, &TEXT.vbo);
    memset(&TEXT, 0, sizeof TEXT);
}

void gfx_text_draw(const char *text, float x, float y, float scale, const float rgba[4])
{
    if (!text_init()) return;
    static char quads[MAX_CHARS * 4 * 16 * 4];
    static float tris[MAX_CHARS * 4 * 6 * 2];
    int nq = stb_easy_font_print(0, 0, (char *)text, NULL, quads, sizeof quads);
    int nv = 0;
    for (int q = 0; q < nq && nv + 6 <= (int)(sizeof tris / sizeof tris[0] / 2); q++) {
        static const int order[6] = {0, 1, 2, 0, 2, 3};
        for (int k = 0; k < 6; k++) {
            const float *v = (const float *)(quads + (size_t)(q * 4 + order[k]) * 16);
            tris[nv * 2 + 0] = x + v[0] * scale;
            tris[nv * 2 + 1] = y + v[1] * scale;
            nv++;
        }
    }
    if (!nv) return;
    GLint vp[4];
    glGetIntegerv(GL_VIEWPORT, vp);
    gfx_upload_raw(TEXT.vbo, 0, (size_t)nv * 2 * sizeof(float), tris);
    gfx_program_t gp = {.id = TEXT.prog};
    glUseProgram(TEXT.prog);
    glUniform2f(gfx_uniform(gp, "u_viewport"), (float)vp[2], (float)vp[3]);
    glUniform4fv(gfx_uniform(gp, "u_color"), 1, rgba);
    glDisable(GL_DEPTH_TEST);
    glBindVertexArray(TEXT.vao);
    glDrawArrays(GL_TRIANGLES, 0, nv);
    glBindVertexArray(0);
    glEnable(GL_DEPTH_TEST);
}

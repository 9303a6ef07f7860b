/* test_gfx_upload: gfx_buffer_update keeps command order. A long dispatch
 * puts the GPU behind; then, without any sync, each of ROWS rounds (more
 * than gfx's upload ring holds) uploads a new 2-word list into the same
 * buffer and queues a dispatch that copies it into its own row. Every row
 * must hold its own round's list: an update that reaches a dispatch queued
 * before it shows up as a row holding a later round's list (what the
 * hybrid tiles' init list suffered on the H100 with glNamedBufferSubData).
 * Also: more bytes than the ring holds, in uneven pieces, land intact, and
 * nothing leaks. On llvmpipe the spin is cut short (Mesa caps shader loop
 * iterations), so there the test checks the ring's addressing only. */
#include "common/bindings_tests.glsl"
#include "gfx/gfx.h"
#include "test.h"
#include "test_gl.h"

#include <stdlib.h>

#define ROWS 40000
#define LEN 2
#define ROUNDS_MODES 3

int main(void)
{
    test_gl_init();
    gfx_program_t p = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/upload_copy.comp", .label = "test.upload"});
    CHECK(p.id != 0);
    gfx_buffer_t src = gfx_buffer_make(&(gfx_buffer_desc_t){.size = LEN * 4, .dynamic = true, .label = "test.src"});
    size_t out_bytes = (1 + ROWS * LEN) * sizeof(uint32_t);
    gfx_buffer_t out = gfx_buffer_make(&(gfx_buffer_desc_t){.size = out_bytes, .label = "test.out"});
    CHECK(src.id && out.id);
    /* a) Rounds queued behind a long dispatch, more than the upload ring
     * holds; then submitted one by one (glFlush, or a query poll as
     * gfx_readback does). */
    const char *how[ROUNDS_MODES] = {"queued", "each submitted (glFlush)", "each submitted (query poll)"};
    uint32_t *res = malloc(out_bytes);
    GLuint q = gfx_query_make(GL_TIMESTAMP, "test.poll");
    CHECK(res && q);
    for (int mode = 0; mode < ROUNDS_MODES; mode++) {
        static const uint32_t zero = 0;
        glClearNamedBufferData(out.id, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        glUseProgram(p.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN, src.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_OUT, out.id);
        glUniform1ui(gfx_uniform(p, "u_len"), LEN);
        /* Long enough on the H100 (about 1 s) that the queued rounds wrap
         * the upload ring while the GPU is still spinning: only the ring's
         * fences keep later rounds' bytes from overwriting ones not yet
         * copied. */
        glUniform1ui(gfx_uniform(p, "u_iters"), mode == 0 ? 500000000u : 4000000u);
        glDispatchCompute(1, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        glUniform1ui(gfx_uniform(p, "u_iters"), 0u);
        for (uint32_t r = 0; r < ROWS; r++) {
            uint32_t list[LEN] = {r * 7u + 1u, r * 13u + 5u};
            gfx_buffer_update(src, 0, sizeof list, list);
            glUniform1ui(gfx_uniform(p, "u_row"), r);
            glDispatchCompute(1, 1, 1);
            if (mode == 1) glFlush();
            if (mode == 2) {
                GLint avail = 0;
                glQueryCounter(q, GL_TIMESTAMP);
                glGetQueryObjectiv(q, GL_QUERY_RESULT_AVAILABLE, &avail);
            }
        }
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        CHECK(gfx_buffer_read(out, 0, out_bytes, res));
        int wrong = 0, first = -1;
        for (uint32_t r = 0; r < ROWS; r++) {
            const uint32_t *row = res + 1 + r * LEN;
            if (row[0] != r * 7u + 1u || row[1] != r * 13u + 5u) {
                wrong++;
                if (first < 0) first = (int)r;
            }
        }
        if (wrong)
            fprintf(stderr, "%s: rows holding another round's list: %d of %d (first: row %d holds %u %u)\n", how[mode],
                    wrong, ROWS, first, res[1 + first * LEN], res[2 + first * LEN]);
        CHECK(wrong == 0);
        printf("a) %d dispatches, %s, each read its own upload (%d wrong)\n", ROWS, how[mode], wrong);
    }
    gfx_query_destroy(&q);

    /* b) More bytes than the ring holds, in uneven pieces, unpaced. */
    enum { BIG = 3 << 20, PIECE = 200003 };
    gfx_buffer_t big = gfx_buffer_make(&(gfx_buffer_desc_t){.size = BIG * 4, .label = "test.big"});
    uint32_t *data = malloc((size_t)BIG * 4), *back = malloc((size_t)BIG * 4);
    CHECK(big.id && data && back);
    for (int pass = 0; pass < 2; pass++) {
        for (int i = 0; i < BIG; i++) data[i] = (uint32_t)i * 2654435761u + (uint32_t)pass;
        for (size_t off = 0; off < (size_t)BIG * 4; off += PIECE) {
            size_t n = (size_t)BIG * 4 - off < PIECE ? (size_t)BIG * 4 - off : PIECE;
            gfx_buffer_update(big, off, n, (const char *)data + off);
        }
    }
    CHECK(gfx_buffer_read(big, 0, (size_t)BIG * 4, back));
    int bad = 0;
    for (int i = 0; i < BIG; i++) bad += back[i] != data[i];
    CHECK(bad == 0);
    printf("b) %.1f MB in %d-byte pieces twice over: %d words wrong, %ld ring waits\n", BIG * 4.0 / (1 << 20), PIECE,
           bad, gfx_upload_waits());
    free(data);
    free(back);
    free(res);
    gfx_buffer_destroy(&big);
    gfx_buffer_destroy(&src);
    gfx_buffer_destroy(&out);
    gfx_program_destroy(&p);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

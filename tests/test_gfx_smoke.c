/* test_gfx_smoke: a GL 4.5 context exists, shader errors name file:line,
 * #include works, an MSAA FBO resolves and reads back (colour, depth, the
 * nearest depth sample per pixel), timers report, a
 * readback ring returns its copies in order, gfx_uniform's cached
 * locations follow a program deleted and its name reused, a second gfx
 * context keeps its objects, programs and cached locations apart from the
 * first's and releases them when destroyed, and nothing leaks. */
#include "test.h"
#include "test_gl.h"

#include "gfx/gfx_local.h"

#include <math.h>
#include <string.h>

/* gfx_uniform against glGetUniformLocation: asked twice, after the
 * program's name is reused by one with other locations, after enough
 * names to start the table afresh, and for a name too long to cache. */
static void check_uniform_cache(void)
{
    const gfx_program_desc_t ab = {.cs = "tests/uniforms.comp", .defines = "#define UNIFORMS_AB 1\n"};
    gfx_program_t p = gfx_program_make(&ab);
    CHECK(p.id != 0);
    for (int k = 0; k < 2; k++) {
        CHECK(gfx_uniform(p, "u_a") == 2 && gfx_uniform(p, "u_b") == 3);
        CHECK(gfx_uniform(p, "u_missing") == -1);
    }
    GLuint old_id = p.id;
    CHECK(gfx_uniforms_cached(old_id) == 3);
    gfx_program_destroy(&p);
    CHECK(gfx_uniforms_cached(old_id) == 0); /* a reused name finds nothing stale */
    gfx_program_t q = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/uniforms.comp"});
    CHECK(q.id != 0);
    printf("uniform cache: program name %s after the delete\n", q.id == old_id ? "reused" : "not reused");
    CHECK(gfx_uniform(q, "u_b") == 7 && gfx_uniform(q, "u_a") == -1);
    char name[32];
    for (int i = 0; i < 5000; i++) {
        snprintf(name, sizeof name, "u_x%d", i);
        CHECK(gfx_uniform(q, name) == -1);
    }
    CHECK(gfx_uniform(q, "u_b") == 7 && gfx_uniform(q, "u_b") == glGetUniformLocation(q.id, "u_b"));
    CHECK(gfx_uniform(q, "u_name_longer_than_the_forty_seven_characters_cached") == -1);
    gfx_program_destroy(&q);
}

/* Two gfx contexts: what one makes the other does not hold. */
static void check_contexts(void)
{
    gfx_ctx_t *first = gfx_ctx_current();
    int live = gfx_live_objects();
    gfx_ctx_t *second = gfx_ctx_make(NULL);
    CHECK(second != NULL && gfx_ctx_current() == first);
    gfx_ctx_bind(second);
    CHECK(gfx_live_objects() == 0 && gfx_objects_made() == 0);
    gfx_buffer_t b = gfx_buffer_make(&(gfx_buffer_desc_t){.size = 256, .label = "test.second_ctx"});
    gfx_program_t p = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/uniforms.comp"});
    CHECK(b.id && p.id && gfx_live_objects() == 2 && gfx_uniform(p, "u_b") == 7 && gfx_uniforms_cached(p.id) == 1);
    gfx_ctx_bind(first);
    CHECK(gfx_live_objects() == live && gfx_uniforms_cached(p.id) == 0);
    GLuint buffer = b.id;
    gfx_ctx_destroy(second, false); /* releases what it still holds */
    CHECK(gfx_ctx_current() == first && !glIsBuffer(buffer) && gfx_live_objects() == live);
}

int main(void)
{
    test_gl_init();
    CHECK(epoxy_gl_version() >= 45);
    check_uniform_cache();
    check_contexts();

    /* Compile error: logged with file and line, program id 0. */
    int errs_before = core_log_error_count();
    gfx_program_t bad = gfx_program_make(&(gfx_program_desc_t){.vs = "tests/tri.vert", .fs = "tests/broken.frag"});
    CHECK(bad.id == 0);
    CHECK(core_log_error_count() > errs_before);
    char err[256];
    char *pp = gfx_shader_preprocess("tests/broken.frag", "#define X 1\n", err, sizeof err);
    CHECK(pp && strstr(pp, "TEST_INCLUDED") && strstr(pp, "#define X 1"));
    free(pp);
    CHECK(gfx_shader_preprocess("tests/missing.frag", NULL, err, sizeof err) == NULL);
    CHECK(strstr(err, "shaders/tests/missing.frag") != NULL);

    gfx_program_t prog = gfx_program_make(&(gfx_program_desc_t){.vs = "tests/tri.vert", .fs = "tests/tri.frag"});
    CHECK(prog.id != 0);

    /* A batch: the good program is made, the broken one is not, and the
     * batch says so. */
    const gfx_program_desc_t good = {.vs = "tests/tri.vert", .fs = "tests/tri.frag", .defines = "#define B 1\n"};
    const gfx_program_desc_t broken = {.vs = "tests/tri.vert", .fs = "tests/broken.frag"};
    gfx_program_t two[2];
    errs_before = core_log_error_count();
    CHECK(!gfx_programs_make(2, (gfx_program_desc_t[2]){good, broken}, two));
    CHECK(two[0].id != 0 && two[1].id == 0 && core_log_error_count() > errs_before);
    gfx_program_destroy(&two[0]);
    /* Prefetched programs are taken by a make with an equal desc (another
     * label), no other; one never made is dropped and counted. */
    gfx_program_stats_t st0 = gfx_program_stats();
    int made_before = st0.count;
    gfx_programs_prefetch(2, (gfx_program_desc_t[2]){good, broken});
    gfx_programs_prefetch(1, &good); /* already waiting: not issued twice */
    CHECK(gfx_program_stats().count == made_before);
    CHECK(gfx_program_stats().prefetched == st0.prefetched + 2);
    gfx_program_desc_t relabelled = good;
    relabelled.label = "smoke.prefetched";
    gfx_program_t taken = gfx_program_make(&relabelled);
    CHECK(taken.id != 0);
    CHECK(gfx_program_stats().count == made_before + 1);
    errs_before = core_log_error_count();
    CHECK(gfx_program_make(&broken).id == 0 && core_log_error_count() > errs_before);
    CHECK(gfx_program_stats().taken == st0.taken + 2);
    CHECK(gfx_programs_prefetch_drop() == 0);
    gfx_programs_prefetch(1, &(gfx_program_desc_t){.vs = "tests/tri.vert", .fs = "tests/tri.frag",
                                                   .defines = "#define UNUSED 1\n"});
    CHECK(gfx_programs_prefetch_drop() == 1);
    gfx_program_destroy(&taken);
    gfx_target_t tgt = gfx_target_make(&(gfx_target_desc_t){.w = 64, .h = 32, .samples = 4, .label = "smoke"});
    CHECK(tgt.fbo != 0 && tgt.resolve_fbo != 0 && tgt.resolve_fbo != tgt.fbo);
    GLuint vao = gfx_vertex_array_make("smoke.vao");

    for (int frame = 0; frame < 8; frame++) {
        gfx_timer_frame_begin();
        gfx_target_bind(&tgt);
        glClearColor(0.0f, 0.0f, 1.0f, 0.25f); /* target alpha is not image alpha */
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        gfx_timer_begin(GFX_PASS_TEST);
        glUseProgram(prog.id);
        glBindVertexArray(vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        gfx_timer_end();
    }
    core_image_t img;
    CHECK(gfx_target_read(&tgt, &img));
    /* Row 0 is the top: top-right is blue clear colour, bottom-left is red. */
    const uint8_t *tr = img.px + (size_t)(0 * 64 + 60) * 4;
    const uint8_t *bl = img.px + (size_t)(31 * 64 + 2) * 4;
    CHECK(tr[0] < 10 && tr[2] > 245);
    CHECK(bl[0] > 245 && bl[2] < 10);
    /* The diagonal is antialiased by the 4x MSAA resolve: some mixed pixel. */
    int mixed = 0;
    for (int i = 0; i < 64 * 32; i++) mixed += img.px[i * 4] > 40 && img.px[i * 4] < 215;
    CHECK(mixed > 0);
    int translucent = 0;
    for (int i = 0; i < 64 * 32; i++) translucent += img.px[i * 4 + 3] != 255;
    CHECK_MSG(translucent == 0, "%d pixels read back with alpha below 255", translucent);
    core_image_free(&img);

    /* Nearest depth sample per pixel (61 x 37, so the edge crosses pixels
     * at many offsets): the triangle, upside down (glClipControl), at window
     * depth 0.5 over a cleared depth of 1. A pixel reads 0.5 when any of its
     * samples (at GL_SAMPLE_POSITION) lies inside the triangle (x + y < 0 in
     * NDC, y flipped), else 1; pixels with a sample within 1e-3 of the edge
     * are left out. The check discriminates: on some pixels sample 0 is
     * outside and another sample inside, where one sample's depth would read
     * 1. */
    enum { DW = 61, DH = 37 };
    gfx_target_t dt = gfx_target_make(&(gfx_target_desc_t){.w = DW, .h = DH, .samples = 4, .label = "smoke.depth"});
    gfx_target_bind(&dt);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glClipControl(GL_UPPER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glUseProgram(prog.id);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_DEPTH_TEST);
    float nearest[DW * DH], pos[4][2];
    CHECK(gfx_target_read_depth_nearest(&dt, nearest));
    for (int k = 0; k < 4; k++) glGetMultisamplefv(GL_SAMPLE_POSITION, (GLuint)k, pos[k]);
    int wrong = 0, checked = 0, not_sample0 = 0;
    for (int y = 0; y < DH; y++)
        for (int x = 0; x < DW; x++) {
            int gy = DH - 1 - y; /* row 0 of the read is the top */
            bool inside[4], any = false, near_edge = false;
            for (int k = 0; k < 4; k++) {
                float nx = ((float)x + pos[k][0]) / DW * 2.0f - 1.0f, ny = 1.0f - ((float)gy + pos[k][1]) / DH * 2.0f;
                inside[k] = nx + ny < 0.0f;
                any = any || inside[k];
                near_edge = near_edge || fabsf(nx + ny) < 1e-3f;
            }
            if (near_edge) continue;
            checked++;
            wrong += fabsf(nearest[y * DW + x] - (any ? 0.5f : 1.0f)) > 1e-6f;
            not_sample0 += any && !inside[0];
        }
    printf("nearest depth: %d of %d pixels wrong; %d pixels covered only off sample 0\n", wrong, checked, not_sample0);
    CHECK(checked > DW * DH * 9 / 10 && wrong == 0);
    CHECK(not_sample0 > 0);
    gfx_target_destroy(&dt);

    gfx_timer_flush();
    CHECK(gfx_timer_count() == 1);
    CHECK(strcmp(gfx_timer_name(0), "test") == 0);
    CHECK(gfx_timer_avg_ms(0) > 0.0);

    /* Buffer round trip. */
    float data[4] = {1, 2, 3, 4}, back[4] = {0};
    gfx_buffer_t buf = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof data, .data = data, .dynamic = true,
                                                            .label = "smoke.buf"});
    CHECK(buf.id != 0);
    gfx_buffer_read(buf, 0, sizeof back, back);
    CHECK(memcmp(data, back, sizeof data) == 0);

    /* Readback ring: one fenced copy per frame; poll takes the oldest
     * completed, latest the newest (dropping the rest); busy while the slot
     * about to be written is unread. */
    gfx_readback_t rb = gfx_readback_make(sizeof(uint32_t), 3, "smoke.readback");
    CHECK(rb.depth == 3);
    for (uint32_t v = 1; v <= 3; v++) {
        gfx_buffer_update(buf, 0, sizeof v, &v);
        gfx_readback_copy(&rb, buf, 0, 0, sizeof v);
        CHECK(gfx_readback_fence(&rb) == (int)v - 1);
    }
    CHECK(gfx_readback_busy(&rb));
    uint32_t got = 0;
    int slot = gfx_readback_poll(&rb, true);
    CHECK(slot == 0);
    gfx_readback_read(&rb, slot, 0, sizeof got, &got);
    CHECK(got == 1);
    CHECK(!gfx_readback_busy(&rb));
    slot = gfx_readback_latest(&rb, true);
    CHECK(slot == 2);
    gfx_readback_read(&rb, slot, 0, sizeof got, &got);
    CHECK(got == 3);
    CHECK(gfx_readback_poll(&rb, false) == -1 && gfx_readback_latest(&rb, true) == -1);
    gfx_readback_copy(&rb, buf, 0, 0, sizeof got);
    CHECK(gfx_readback_fence(&rb) == 0);
    glFinish();
    CHECK(gfx_readback_poll(&rb, false) == 0);
    gfx_readback_destroy(&rb);
    CHECK(rb.depth == 0 && rb.buf[0].id == 0);

    CHECK(gfx_live_objects() > 0);
    gfx_buffer_destroy(&buf);
    gfx_vertex_array_destroy(&vao);
    gfx_target_destroy(&tgt);
    gfx_program_destroy(&prog);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

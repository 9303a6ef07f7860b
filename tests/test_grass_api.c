/* test_grass_api: the library's face (grass.h) as a host uses it, on
 * scenes/tiny.json at 96x64, a ball rolling through the grass:
 *   a) two grass_t in one context, stepped and drawn each into its own
 *      framebuffer frame by frame, give the images each gives alone; so
 *      do two in two GL contexts of one process, switched between every
 *      frame, and a field drawn in two parts (grass_draw_part);
 *   b) two views drawn in one frame (the same eye, a second direction)
 *      give the images each view gives when it is the only one;
 *   c) the GL state the header lists is the same before and after
 *      grass_draw, from a host state unlike grass's own; the comparison
 *      finds a binding the test changes itself (it can fail);
 *   d) GRASS_MAX_COLLIDERS colliders step without a word through io.log;
 *      two more give one warning naming the count and the limit, not
 *      repeated while the count stays, again when it changes.
 * The host's framebuffers are the test kit's gfx targets. */
#include "grass/grass.h"
#include "test.h"
#include "test_gl.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cglm/cglm.h>
#include <math.h>
#include <stddef.h>
#include <string.h>

#define W 96
#define H 64
#define FRAMES 4
#define DT (1.0f / 30.0f)

static const test_image_cmp_t SAME = {.pixel_threshold = 1, .mean_threshold = 0.01, .fail_budget = 0.0};

static void view_at(grass_view_t *v, const float eye[3], const float at[3], float t)
{
    mat4 view, proj;
    glm_lookat((float *)eye, (float *)at, (vec3){0, 1, 0}, view);
    glm_perspective(glm_rad(60.0f), (float)W / (float)H, 0.1f, 100.0f, proj);
    grass_view_make(v, (const float *)view, (const float *)proj, W, H, t);
}

static grass_target_t host_of(const gfx_target_t *t)
{
    return (grass_target_t){.fbo = t->fbo, .color_texture = t->color.id, .depth_texture = t->depth.id,
                            .width = t->w, .height = t->h, .samples = t->samples};
}

/* The ball of tiny.json's path at time t. */
static grass_collider_t ball_at(float t)
{
    float x = -3.0f + 12.0f * fmodf(t, 0.5f);
    return (grass_collider_t){.shape = GRASS_SHAPE_SPHERE, .position = {x, 0.4f, 0.0f}, .radius = 0.4f};
}

typedef struct run_t {
    grass_desc_t desc;
    float eye[2][3], at[2][3];
    int views;       /* views drawn per frame: 1 or 2 */
    int only;        /* with views 1: which of the two */
    bool split;      /* grass_draw_part: the ground, then the grass */
    gfx_target_t target[2];
} run_t;

static grass_t *start(run_t *r)
{
    grass_t *g = grass_make(&r->desc);
    CHECK(g != NULL);
    for (int i = 0; i < 2; i++)
        r->target[i] = gfx_target_make(&(gfx_target_desc_t){.w = W, .h = H, .samples = 1, .label = "test.host"});
    return g;
}

/* One frame of r: a step, then its views into its targets. */
static void frame(run_t *r, grass_t *g, int f)
{
    float t = (float)(f + 1) * DT;
    grass_collider_t ball = ball_at(t);
    grass_update(g, &ball, 1, t, DT);
    for (int k = 0; k < r->views; k++) {
        int which = r->views == 2 ? k : r->only;
        grass_view_t v;
        view_at(&v, r->eye[which], r->at[which], t);
        gfx_target_bind(&r->target[which]);
        glClearColor(0, 0, 0, 1);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        grass_target_t ht = host_of(&r->target[which]);
        if (r->split) {
            grass_draw_part(g, &v, &ht, GRASS_PART_GROUND);
            grass_draw_part(g, &v, &ht, GRASS_PART_GRASS);
        } else {
            grass_draw(g, &v, &ht);
        }
    }
}

static void finish(run_t *r, grass_t *g, core_image_t out[2])
{
    for (int i = 0; i < 2; i++) {
        if (out) CHECK(gfx_target_read(&r->target[i], &out[i]));
        gfx_target_destroy(&r->target[i]);
    }
    grass_destroy(g);
}

static void expect_same(const core_image_t *a, const core_image_t *b, const char *what)
{
    test_image_result_t d = test_image_diff(a, b, &SAME, NULL);
    if (!d.pass) fprintf(stderr, "%s: mean diff %.4f, max %d\n", what, d.mean_diff, d.max_diff);
    CHECK(d.pass);
    double rgb[3];
    CHECK(test_grass_pixels(a, rgb) > 0.05); /* grass in view: the comparison sees it */
}

static run_t run_of(grass_mode_t mode, uint32_t seed)
{
    return (run_t){.desc = {.scene = "scenes/tiny.json", .mode = mode, .seed = seed},
                   .eye = {{0, 2.5f, 5}, {0, 2.5f, 5}},
                   .at = {{0, 0, 0}, {-3, 0, -1}},
                   .views = 1};
}

/* A GL context of the process and its surfaces (EGL). */
typedef struct gl_context_t {
    EGLDisplay dpy;
    EGLContext ctx;
    EGLSurface draw, read;
} gl_context_t;

static gl_context_t gl_current(void)
{
    return (gl_context_t){eglGetCurrentDisplay(), eglGetCurrentContext(), eglGetCurrentSurface(EGL_DRAW),
                          eglGetCurrentSurface(EGL_READ)};
}

static bool gl_bind(gl_context_t c) { return eglMakeCurrent(c.dpy, c.draw, c.read, c.ctx); }

/* A second GL 4.5 context on the first's display, sharing nothing with it. */
static gl_context_t gl_second(gl_context_t first)
{
    EGLint id = 0, n = 0;
    EGLConfig cfg = EGL_NO_CONFIG_KHR;
    eglQueryContext(first.dpy, first.ctx, EGL_CONFIG_ID, &id);
    EGLint pick[] = {EGL_CONFIG_ID, id, EGL_NONE};
    if (id && (!eglChooseConfig(first.dpy, pick, &cfg, 1, &n) || n < 1)) cfg = EGL_NO_CONFIG_KHR;
    EGLint attr[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5, EGL_CONTEXT_OPENGL_PROFILE_MASK,
                     EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    return (gl_context_t){first.dpy, eglCreateContext(first.dpy, cfg, EGL_NO_CONTEXT, attr), EGL_NO_SURFACE,
                          EGL_NO_SURFACE};
}

/* The hybrid of run_of(GRASS_MODE_HYBRID, 0) in this context and in a
 * second one, a frame in each by turns: both equal `alone`. The second's
 * host targets live in a gfx context of its own. */
static void check_two_contexts(const core_image_t *alone)
{
    gl_context_t one = gl_current(), two = gl_second(one);
    CHECK(one.ctx != EGL_NO_CONTEXT && two.ctx != EGL_NO_CONTEXT);
    if (two.ctx == EGL_NO_CONTEXT) return;
    run_t r[2] = {run_of(GRASS_MODE_HYBRID, 0), run_of(GRASS_MODE_HYBRID, 0)};
    grass_t *g[2];
    gfx_ctx_t *host_two = NULL;
    core_image_t img[2][2];
    for (int step = 0; step < FRAMES + 2; step++)
        for (int k = 0; k < 2; k++) {
            CHECK(gl_bind(k ? two : one));
            if (k && !host_two) host_two = gfx_ctx_make(NULL);
            gfx_ctx_bind(k ? host_two : NULL);
            if (step == 0) g[k] = start(&r[k]);
            else if (step <= FRAMES) frame(&r[k], g[k], step - 1);
            else finish(&r[k], g[k], img[k]);
        }
    gfx_ctx_destroy(host_two, true);
    gfx_ctx_bind(NULL);
    CHECK(gl_bind(one));
    eglDestroyContext(two.dpy, two.ctx);
    expect_same(alone, &img[0][0], "the hybrid in the first of two GL contexts");
    expect_same(alone, &img[1][0], "the hybrid in the second of two GL contexts");
    for (int k = 0; k < 2; k++) {
        core_image_free(&img[k][0]);
        core_image_free(&img[k][1]);
    }
}

/* a) two fields, alone and side by side. */
static void check_two_fields(void)
{
    core_image_t alone[2][2], both[2][2];
    run_t r[2] = {run_of(GRASS_MODE_HYBRID, 0), run_of(GRASS_MODE_BLADE, 11)};
    for (int i = 0; i < 2; i++) {
        grass_t *g = start(&r[i]);
        for (int f = 0; f < FRAMES; f++) frame(&r[i], g, f);
        finish(&r[i], g, alone[i]);
    }
    grass_t *g[2] = {start(&r[0]), start(&r[1])};
    for (int f = 0; f < FRAMES; f++)
        for (int i = 0; i < 2; i++) frame(&r[i], g[i], f);
    for (int i = 0; i < 2; i++) finish(&r[i], g[i], both[i]);
    expect_same(&alone[0][0], &both[0][0], "the hybrid beside a second field");
    expect_same(&alone[1][0], &both[1][0], "blade mode beside a second field");
    check_two_contexts(&alone[0][0]);
    /* The same frames drawn in two parts, the ground and then the grass. */
    core_image_t split[2];
    run_t rs = run_of(GRASS_MODE_HYBRID, 0);
    rs.split = true;
    grass_t *gs = start(&rs);
    for (int f = 0; f < FRAMES; f++) frame(&rs, gs, f);
    finish(&rs, gs, split);
    expect_same(&alone[0][0], &split[0], "grass_draw_part: the ground, then the grass");
    core_image_free(&split[0]);
    core_image_free(&split[1]);
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 2; k++) {
            core_image_free(&alone[i][k]);
            core_image_free(&both[i][k]);
        }
}

/* b) two views a frame against each alone. */
static void check_two_views(void)
{
    core_image_t alone[2][2], both[2];
    for (int k = 0; k < 2; k++) {
        run_t r = run_of(GRASS_MODE_HYBRID, 0);
        r.only = k;
        grass_t *g = start(&r);
        for (int f = 0; f < FRAMES; f++) frame(&r, g, f);
        finish(&r, g, alone[k]);
    }
    run_t r = run_of(GRASS_MODE_HYBRID, 0);
    r.views = 2;
    grass_t *g = start(&r);
    for (int f = 0; f < FRAMES; f++) frame(&r, g, f);
    finish(&r, g, both);
    expect_same(&alone[0][0], &both[0], "the first of two views");
    expect_same(&alone[1][1], &both[1], "the second of two views");
    test_image_result_t d = test_image_diff(&both[0], &both[1], &SAME, NULL);
    CHECK(!d.pass); /* the two views differ: b) compares two pictures, not one */
    for (int k = 0; k < 2; k++) {
        core_image_free(&alone[k][0]);
        core_image_free(&alone[k][1]);
        core_image_free(&both[k]);
    }
}

/* ---- c) the GL state of the header's contract, read independently ---- */
enum { UNITS = 16, NTEX = 5, NBUF = 9, NEN = 10, NINT = 12 };
typedef struct snapshot_t {
    GLint ints[NINT], viewport[4], polygon[2], tex[UNITS][NTEX], buf[NBUF];
    GLboolean en[NEN], masks[5]; /* depth write, colour write */
} snapshot_t;

static void snapshot(snapshot_t *s)
{
    static const GLenum ints[NINT] = {GL_CURRENT_PROGRAM,   GL_VERTEX_ARRAY_BINDING, GL_DRAW_FRAMEBUFFER_BINDING,
                                      GL_READ_FRAMEBUFFER_BINDING, GL_DEPTH_FUNC,   GL_BLEND_SRC_RGB,
                                      GL_BLEND_SRC_ALPHA,   GL_BLEND_DST_RGB,        GL_BLEND_DST_ALPHA,
                                      GL_BLEND_EQUATION_RGB, GL_BLEND_EQUATION_ALPHA, GL_ACTIVE_TEXTURE};
    static const GLenum tex[NTEX] = {GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_2D_ARRAY, GL_TEXTURE_BINDING_3D,
                                     GL_TEXTURE_BINDING_CUBE_MAP, GL_TEXTURE_BINDING_2D_MULTISAMPLE};
    static const GLenum buf[NBUF] = {GL_ARRAY_BUFFER_BINDING,        GL_DRAW_INDIRECT_BUFFER_BINDING,
                                     GL_DISPATCH_INDIRECT_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_BINDING,
                                     GL_UNIFORM_BUFFER_BINDING,      GL_ATOMIC_COUNTER_BUFFER_BINDING,
                                     GL_PIXEL_PACK_BUFFER_BINDING,   GL_PIXEL_UNPACK_BUFFER_BINDING,
                                     GL_COPY_READ_BUFFER_BINDING};
    static const GLenum en[NEN] = {GL_DEPTH_TEST,   GL_BLEND,          GL_CULL_FACE,      GL_SAMPLE_ALPHA_TO_COVERAGE,
                                   GL_SCISSOR_TEST, GL_STENCIL_TEST,   GL_POLYGON_OFFSET_FILL, GL_MULTISAMPLE,
                                   GL_RASTERIZER_DISCARD, GL_PROGRAM_POINT_SIZE};
    memset(s, 0, sizeof *s);
    for (int i = 0; i < NINT; i++) glGetIntegerv(ints[i], &s->ints[i]);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    glGetIntegerv(GL_POLYGON_MODE, s->polygon);
    for (int u = 0; u < UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (int k = 0; k < NTEX; k++) glGetIntegerv(tex[k], &s->tex[u][k]);
    }
    glActiveTexture((GLenum)s->ints[NINT - 1]);
    for (int i = 0; i < NBUF; i++) glGetIntegerv(buf[i], &s->buf[i]);
    for (int i = 0; i < NEN; i++) s->en[i] = glIsEnabled(en[i]);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s->masks[0]);
    glGetBooleanv(GL_COLOR_WRITEMASK, &s->masks[1]);
}

/* Entries that differ (printed with `what`). */
static int differences(const snapshot_t *a, const snapshot_t *b, const char *what, bool print)
{
    int n = 0;
    const GLint *x = (const GLint *)a, *y = (const GLint *)b;
    size_t ints = offsetof(snapshot_t, en) / sizeof(GLint);
    for (size_t i = 0; i < ints; i++)
        if (x[i] != y[i] && ++n && print) fprintf(stderr, "%s: state word %zu was %d, is %d\n", what, i, x[i], y[i]);
    for (int i = 0; i < NEN; i++)
        if (a->en[i] != b->en[i] && ++n && print) fprintf(stderr, "%s: enable %d changed\n", what, i);
    for (int i = 0; i < 5; i++)
        if (a->masks[i] != b->masks[i] && ++n && print) fprintf(stderr, "%s: mask %d changed\n", what, i);
    return n;
}

static void check_gl_state(void)
{
    run_t r = run_of(GRASS_MODE_HYBRID, 0);
    grass_t *g = start(&r);
    gfx_buffer_t b = gfx_buffer_make(&(gfx_buffer_desc_t){.size = 64, .label = "test.host_buffer"});
    gfx_texture_t tx = gfx_texture_make(&(gfx_texture_desc_t){.w = 4, .h = 4, .format = GL_RGBA8, .label = "test.host_texture"});
    GLuint vao = gfx_vertex_array_make("test.host_vao");
    grass_view_t v;
    view_at(&v, r.eye[0], r.at[0], DT);
    grass_target_t ht = host_of(&r.target[0]);
    grass_collider_t ball = ball_at(DT);
    grass_update(g, &ball, 1, DT, DT);
    /* A host state unlike grass's: its own buffer, texture, vertex array and blending. */
    gfx_target_bind(&r.target[1]);
    glViewport(3, 5, 40, 30);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, b.id);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, b.id);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, tx.id);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_FALSE);
    glEnable(GL_CULL_FACE);
    snapshot_t before, after;
    snapshot(&before);
    grass_draw(g, &v, &ht);
    snapshot(&after);
    CHECK(differences(&before, &after, "grass_draw", true) == 0);
    /* The comparison can fail: a binding changed by hand is found. */
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    snapshot(&after);
    CHECK(differences(&before, &after, "a binding changed by the test", false) == 1);
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    gfx_vertex_array_destroy(&vao);
    gfx_texture_destroy(&tx);
    gfx_buffer_destroy(&b);
    finish(&r, g, NULL);
}

/* io.log's warnings from grass_update, the last one kept. */
typedef struct heard_t {
    int warnings;
    char last[512];
} heard_t;

static void hear(int level, const char *line, void *user)
{
    heard_t *h = user;
    if (level != 1 || strncmp(line, "grass_update:", 13)) return;
    h->warnings++;
    snprintf(h->last, sizeof h->last, "%s", line);
}

static void check_collider_limit(void)
{
    heard_t heard = {0};
    run_t r = run_of(GRASS_MODE_HYBRID, 0);
    r.desc.io = (grass_io_t){.log = hear, .user = &heard};
    grass_t *g = start(&r);
    grass_collider_t c[GRASS_MAX_COLLIDERS + 3];
    for (int i = 0; i < GRASS_MAX_COLLIDERS + 3; i++)
        c[i] = (grass_collider_t){.shape = GRASS_SHAPE_SPHERE,
                                  .position = {-3.5f + 0.5f * (float)(i % 15), 0.1f, -3.5f + 0.5f * (float)(i / 15)},
                                  .radius = 0.1f};
    const int counts[] = {GRASS_MAX_COLLIDERS, GRASS_MAX_COLLIDERS + 2, GRASS_MAX_COLLIDERS + 2,
                          GRASS_MAX_COLLIDERS + 3, GRASS_MAX_COLLIDERS};
    const int heard_after[] = {0, 1, 1, 2, 2};
    for (int s = 0; s < 5; s++) {
        grass_update(g, c, counts[s], (float)(s + 1) * DT, DT);
        CHECK_MSG(heard.warnings == heard_after[s], "step %d, %d colliders: %d warnings, expected %d", s, counts[s],
                  heard.warnings, heard_after[s]);
        if (s == 1)
            CHECK_MSG(strstr(heard.last, "130 colliders given, the collide set holds 128") &&
                          strstr(heard.last, "colliders 129..130 bend blades only"),
                      "warning: %s", heard.last);
    }
    finish(&r, g, NULL);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    check_two_fields();
    check_two_views();
    check_gl_state();
    check_collider_limit();
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

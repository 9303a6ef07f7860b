/* gfx: object registry with debug labels, buffers, textures, render targets
 * with MSAA resolve, vertex arrays, queries and screenshots. */
#include "gfx/gfx_local.h"

/* This file's state in the current context (gfx_local.h). */
#define G (gfx_cur->registry)
#define U (gfx_cur->upload)

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* A desc field's value: the field, else the environment variable when
 * set and not empty, else NULL. */
static const char *desc_or_env(const char *field, const char *var)
{
    const char *env = getenv(var);
    return field && *field ? field : env && *env ? env : NULL;
}

gfx_desc_t gfx_desc_defaults(const gfx_desc_t *desc)
{
    gfx_desc_t d = desc ? *desc : (gfx_desc_t){0};
    d.shader_dir = desc_or_env(d.shader_dir, "MEADOW_SHADER_DIR");
    d.shader_cache = desc_or_env(d.shader_cache, "MEADOW_SHADER_CACHE");
    const char *poison = getenv("MEADOW_GFX_POISON");
    d.poison = d.poison || (poison && *poison && strcmp(poison, "0") != 0);
    return d;
}

bool gfx_init_desc(const gfx_desc_t *desc)
{
    memset(&G, 0, sizeof G);
    gfx_uniforms_forget(0);
    gfx_desc_t d = gfx_desc_defaults(desc);
    G.poison = d.poison;
    gfx_shader_setup(&d);
    return true;
}

bool gfx_init(void) { return gfx_init_desc(NULL); }

/* ---- contexts ---- */
static gfx_ctx_t default_ctx = GFX_CTX_INITIAL;
gfx_ctx_t *gfx_cur = &default_ctx;

gfx_ctx_t *gfx_ctx_current(void) { return gfx_cur; }
void gfx_ctx_bind(gfx_ctx_t *c) { gfx_cur = c ? c : &default_ctx; }

gfx_ctx_t *gfx_ctx_make(const gfx_desc_t *desc)
{
    gfx_ctx_t *c = malloc(sizeof *c);
    if (!c) return NULL;
    *c = (gfx_ctx_t)GFX_CTX_INITIAL;
    gfx_ctx_t *prev = gfx_cur;
    gfx_cur = c;
    gfx_init_desc(desc);
    gfx_cur = prev;
    return c;
}

void gfx_ctx_destroy(gfx_ctx_t *c, bool report_leaks)
{
    if (!c || c == &default_ctx) return;
    gfx_ctx_t *prev = gfx_cur == c ? &default_ctx : gfx_cur;
    gfx_cur = c;
    gfx_shutdown(report_leaks);
    gfx_cur = prev;
    free(c);
}

void gfx_track(GLenum kind, GLuint id, const char *label)
{
    if (!id) return;
    if (G.count == G.cap) {
        int cap = G.cap ? G.cap * 2 : 256;
        gfx_obj_t *grown = realloc(G.objs, (size_t)cap * sizeof *grown);
        if (!grown) abort();
        G.objs = grown;
        G.cap = cap;
    }
    gfx_obj_t *o = &G.objs[G.count++];
    G.made++;
    o->kind = kind;
    o->id = id;
    o->bytes = 0;
    snprintf(o->label, sizeof o->label, "%s", label ? label : "?");
    glObjectLabel(kind, id, -1, o->label);
}

void gfx_untrack(GLenum kind, GLuint id)
{
    for (int i = G.count - 1; i >= 0; i--) {
        if (G.objs[i].kind == kind && G.objs[i].id == id) {
            G.objs[i] = G.objs[--G.count];
            return;
        }
    }
}

void gfx_delete_object(GLenum kind, GLuint id)
{
    switch (kind) {
    case GL_BUFFER: glDeleteBuffers(1, &id); break;
    case GL_TEXTURE: glDeleteTextures(1, &id); break;
    case GL_PROGRAM:
        gfx_uniforms_forget(id);
        glDeleteProgram(id);
        break;
    case GL_FRAMEBUFFER: glDeleteFramebuffers(1, &id); break;
    case GL_VERTEX_ARRAY: glDeleteVertexArrays(1, &id); break;
    case GL_QUERY: glDeleteQueries(1, &id); break;
    case GL_TRANSFORM_FEEDBACK: glDeleteTransformFeedbacks(1, &id); break;
    default: break;
    }
}

static void release(GLenum kind, GLuint id)
{
    if (!id) return;
    gfx_untrack(kind, id);
    gfx_delete_object(kind, id);
}

static bool upload_ring_alive(void);
int gfx_live_objects(void) { return G.count - (upload_ring_alive() ? 1 : 0); }
long gfx_objects_made(void) { return G.made; }

static void set_bytes(GLenum kind, GLuint id, size_t bytes)
{
    for (int i = G.count - 1; i >= 0; i--)
        if (G.objs[i].kind == kind && G.objs[i].id == id) {
            G.objs[i].bytes = bytes;
            return;
        }
}

size_t gfx_memory_bytes(void)
{
    size_t total = 0;
    for (int i = 0; i < G.count; i++) total += G.objs[i].bytes;
    return total;
}

static size_t format_bytes(GLenum f)
{
    switch (f) {
    case GL_RGBA32F: return 16;
    case GL_RGBA16F: case GL_RG32F: return 8;
    case GL_R8: return 1;
    case GL_RG8: case GL_R16F: return 2;
    case GL_RGB8: return 3;
    default: return 4;
    }
}

static void upload_shutdown(void);

void gfx_shutdown(bool report_leaks)
{
    upload_shutdown();
    gfx_text_shutdown();
    gfx_depth_shutdown();
    gfx_timer_shutdown();
    gfx_count_shutdown();
    int unused = gfx_programs_prefetch_drop();
    /* built ahead for a path the run did not take (raster auto chose the
     * other): news, not a fault */
    if (report_leaks && unused) core_log_info("gfx: %d prefetched programs never made", unused);
    if (report_leaks && G.count)
        for (int i = 0; i < G.count; i++) core_log_warn("gfx: '%s' still alive at shutdown", G.objs[i].label);
    while (G.count) {
        gfx_obj_t o = G.objs[--G.count];
        gfx_delete_object(o.kind, o.id);
    }
    free(G.objs);
    memset(&G, 0, sizeof G);
    gfx_uniforms_forget(0);
}

int gfx_check_errors(const char *where)
{
    int n = 0;
    for (GLenum e; (e = glGetError()) != GL_NO_ERROR && n < 64; n++)
        core_log_error("%s: GL error 0x%04x", where, (unsigned)e);
    return n;
}

/* ---- buffers ---------------------------------------------------------------- */

gfx_buffer_t gfx_buffer_make(const gfx_buffer_desc_t *desc)
{
    gfx_buffer_t b = {0};
    while (glGetError() != GL_NO_ERROR) {}
    /* Persistent: mapped for writing, or for reading when readable. */
    GLbitfield map = 0;
    if (desc->persistent)
        map = (desc->readable ? GL_MAP_READ_BIT : GL_MAP_WRITE_BIT) | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    GLbitfield flags = map;
    if (desc->dynamic) flags |= GL_DYNAMIC_STORAGE_BIT;
    if (desc->readable) flags |= GL_MAP_READ_BIT;
    glCreateBuffers(1, &b.id);
    glNamedBufferStorage(b.id, (GLsizeiptr)desc->size, desc->data, flags);
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        core_log_error("gfx: cannot allocate buffer '%s' of %.1f MB: %s", desc->label,
                       (double)desc->size / (1024.0 * 1024.0), e == GL_OUT_OF_MEMORY ? "GL_OUT_OF_MEMORY" : "GL error");
        glDeleteBuffers(1, &b.id);
        return (gfx_buffer_t){0};
    }
    /* Without data the store starts as zeros, not as whatever memory the
     * driver recycled (a new world in a process that freed another one). */
    if (!desc->data && !desc->uninitialized && desc->size > 0) {
        static const uint8_t zero = 0;
        glClearNamedBufferData(b.id, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
    }
    if (!desc->data && desc->uninitialized && G.poison && desc->size > 0) {
        static const uint8_t ones = 0xff;
        glClearNamedBufferData(b.id, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &ones);
    }
    b.size = desc->size;
    b.readable = desc->readable;
    if (desc->persistent) b.mapped = glMapNamedBufferRange(b.id, 0, (GLsizeiptr)desc->size, map);
    gfx_track(GL_BUFFER, b.id, desc->label);
    set_bytes(GL_BUFFER, b.id, desc->size);
    return b;
}

void gfx_buffer_destroy(gfx_buffer_t *buf)
{
    if (buf->mapped) glUnmapNamedBuffer(buf->id);
    release(GL_BUFFER, buf->id);
    memset(buf, 0, sizeof *buf);
}

/* ---- uploads ----------------------------------------------------------------
 * Every CPU -> buffer update goes through one persistently mapped ring: the
 * bytes are written to a part of the ring that no queued command still
 * reads, then copied on the GPU (glCopyNamedBufferSubData), in order with
 * the commands around it. On the H100, glNamedBufferSubData into a buffer
 * that queued compute work had yet to read reached that work: the hybrid
 * tiles' init list of one frame was read by the previous frame's dispatch,
 * which initialised the wrong slot (test_hybrid_trail, test_gfx_upload;
 * docs/PERFORMANCE.md "GPU correctness"). The ring is split into segments;
 * a segment is fenced when the ring leaves it and waited for (rarely: the GPU
 * must be a whole ring of uploads behind) before it is written again, so
 * callers need not pace their frames. */
#define UPLOAD_RING_BYTES ((size_t)8 << 20)
#define UPLOAD_SEGMENT (UPLOAD_RING_BYTES / GFX_UPLOAD_SEGMENTS)
#define UPLOAD_ALIGN 256

static bool upload_ring_ready(void)
{
    if (U.id || U.failed) return U.id != 0;
    const GLbitfield flags = GL_MAP_WRITE_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glCreateBuffers(1, &U.id);
    glNamedBufferStorage(U.id, (GLsizeiptr)UPLOAD_RING_BYTES, NULL, flags);
    U.map = glMapNamedBufferRange(U.id, 0, (GLsizeiptr)UPLOAD_RING_BYTES, flags);
    if (!U.map) {
        core_log_warn("gfx: cannot map the upload ring; buffer updates use glNamedBufferSubData");
        glDeleteBuffers(1, &U.id);
        U.id = 0;
        U.failed = true;
        return false;
    }
    gfx_track(GL_BUFFER, U.id, "gfx.upload_ring");
    set_bytes(GL_BUFFER, U.id, UPLOAD_RING_BYTES);
    return true;
}

/* Fences the segment being left and opens the next, waiting for its last
 * copies when the GPU has not done them yet. */
static void upload_next_segment(void)
{
    U.fence[U.seg] = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    U.seg = (U.seg + 1) % GFX_UPLOAD_SEGMENTS;
    GLsync f = U.fence[U.seg];
    if (f) {
        GLenum r = glClientWaitSync(f, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
        if (r == GL_TIMEOUT_EXPIRED) {
            U.waits++;
            for (int tries = 0; r == GL_TIMEOUT_EXPIRED && tries < 6; tries++)
                r = glClientWaitSync(f, GL_SYNC_FLUSH_COMMANDS_BIT, 10000000000ull);
        }
        if (r == GL_TIMEOUT_EXPIRED || r == GL_WAIT_FAILED) {
            core_log_error("gfx: the GPU has not finished an upload after 60 s; waiting for it");
            glFinish();
        }
        glDeleteSync(f);
        U.fence[U.seg] = 0;
    }
    U.head = (size_t)U.seg * UPLOAD_SEGMENT;
}

void gfx_upload_raw(GLuint dst, size_t offset, size_t size, const void *data)
{
    if (!upload_ring_ready()) {
        glNamedBufferSubData(dst, (GLintptr)offset, (GLsizeiptr)size, data);
        return;
    }
    const uint8_t *src = data;
    while (size > 0) {
        size_t n = size < UPLOAD_SEGMENT ? size : UPLOAD_SEGMENT;
        if (U.head + n > (size_t)(U.seg + 1) * UPLOAD_SEGMENT) upload_next_segment();
        memcpy(U.map + U.head, src, n);
        glCopyNamedBufferSubData(U.id, dst, (GLintptr)U.head, (GLintptr)offset, (GLsizeiptr)n);
        U.head += (n + UPLOAD_ALIGN - 1) & ~(size_t)(UPLOAD_ALIGN - 1);
        src += n;
        offset += n;
        size -= n;
    }
}

static void upload_shutdown(void)
{
    for (int i = 0; i < GFX_UPLOAD_SEGMENTS; i++)
        if (U.fence[i]) glDeleteSync(U.fence[i]);
    if (U.id) {
        glUnmapNamedBuffer(U.id);
        release(GL_BUFFER, U.id);
    }
    memset(&U, 0, sizeof U);
}

static bool upload_ring_alive(void) { return U.id != 0; }
long gfx_upload_waits(void) { return U.waits; }

void gfx_buffer_update(gfx_buffer_t buf, size_t offset, size_t size, const void *data)
{
    if (buf.mapped && !buf.readable)
        memcpy((char *)buf.mapped + offset, data, size);
    else
        gfx_upload_raw(buf.id, offset, size, data);
}

bool gfx_buffer_read(gfx_buffer_t buf, size_t offset, size_t size, void *out)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    if (buf.readable) {
        glGetNamedBufferSubData(buf.id, (GLintptr)offset, (GLsizeiptr)size, out);
        return true;
    }
    enum { STAGE = 4 << 20 };
    size_t stage = size < STAGE ? size : STAGE;
    if (stage == 0) return true;
    gfx_buffer_t tmp = gfx_buffer_make(&(gfx_buffer_desc_t){.size = stage, .readable = true, .label = "gfx.staging"});
    if (!tmp.id) return false;
    for (size_t done = 0; done < size; done += stage) {
        size_t n = size - done < stage ? size - done : stage;
        glCopyNamedBufferSubData(buf.id, tmp.id, (GLintptr)(offset + done), 0, (GLsizeiptr)n);
        glGetNamedBufferSubData(tmp.id, 0, (GLsizeiptr)n, (char *)out + done);
    }
    gfx_buffer_destroy(&tmp);
    return true;
}

/* ---- textures ----------------------------------------------------------------- */

static int mip_count(int w, int h)
{
    int n = 1;
    while ((w | h) >> n) n++;
    return n;
}

gfx_texture_t gfx_texture_make(const gfx_texture_desc_t *d)
{
    gfx_texture_t t = {0};
    t.target = d->target ? d->target : GL_TEXTURE_2D;
    t.w = d->w;
    t.h = d->h;
    t.layers = d->layers > 0 ? d->layers : 1;
    t.samples = d->samples > 0 ? d->samples : 4;
    t.format = d->format ? d->format : GL_RGBA8;
    int mips = d->mip_levels < 0 ? mip_count(d->w, d->h) : (d->mip_levels ? d->mip_levels : 1);
    while (glGetError() != GL_NO_ERROR) {}
    glCreateTextures(t.target, 1, &t.id);
    switch (t.target) {
    case GL_TEXTURE_2D_MULTISAMPLE:
        glTextureStorage2DMultisample(t.id, t.samples, t.format, t.w, t.h, GL_TRUE);
        break;
    case GL_TEXTURE_2D_ARRAY:
    case GL_TEXTURE_3D:
        glTextureStorage3D(t.id, mips, t.format, t.w, t.h, t.layers);
        break;
    default:
        glTextureStorage2D(t.id, mips, t.format, t.w, t.h);
        break;
    }
    if (t.target != GL_TEXTURE_2D_MULTISAMPLE) {
        GLenum filter = d->filter ? d->filter : GL_LINEAR;
        GLenum wrap = d->wrap ? d->wrap : GL_CLAMP_TO_EDGE;
        glTextureParameteri(t.id, GL_TEXTURE_MIN_FILTER,
                            mips > 1 && filter == GL_LINEAR ? GL_LINEAR_MIPMAP_LINEAR : (GLint)filter);
        glTextureParameteri(t.id, GL_TEXTURE_MAG_FILTER, (GLint)filter);
        glTextureParameteri(t.id, GL_TEXTURE_WRAP_S, (GLint)wrap);
        glTextureParameteri(t.id, GL_TEXTURE_WRAP_T, (GLint)wrap);
        if (t.target == GL_TEXTURE_3D) glTextureParameteri(t.id, GL_TEXTURE_WRAP_R, (GLint)wrap);
        if (d->data) {
            GLenum fmt = d->upload_format ? d->upload_format : GL_RGBA;
            GLenum type = d->upload_type ? d->upload_type : GL_UNSIGNED_BYTE;
            glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
            if (t.target == GL_TEXTURE_2D_ARRAY || t.target == GL_TEXTURE_3D)
                glTextureSubImage3D(t.id, 0, 0, 0, 0, t.w, t.h, t.layers, fmt, type, d->data);
            else
                glTextureSubImage2D(t.id, 0, 0, 0, t.w, t.h, fmt, type, d->data);
            if (mips > 1) glGenerateTextureMipmap(t.id);
        }
    }
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        core_log_error("gfx: cannot create texture '%s' (%dx%dx%d): GL error 0x%04x%s", d->label, t.w, t.h, t.layers,
                       (unsigned)e, e == GL_OUT_OF_MEMORY ? " (GL_OUT_OF_MEMORY)" : "");
        glDeleteTextures(1, &t.id);
        return (gfx_texture_t){0};
    }
    gfx_track(GL_TEXTURE, t.id, d->label);
    size_t texels = (size_t)t.w * (size_t)t.h * (size_t)t.layers *
                    (t.target == GL_TEXTURE_2D_MULTISAMPLE ? (size_t)t.samples : 1);
    set_bytes(GL_TEXTURE, t.id, texels * format_bytes(t.format) * (mips > 1 ? 4 : 3) / 3);
    return t;
}

void gfx_texture_destroy(gfx_texture_t *tex)
{
    release(GL_TEXTURE, tex->id);
    memset(tex, 0, sizeof *tex);
}

/* ---- render targets --------------------------------------------------------------- */

static GLuint make_fbo(const char *label, const char *suffix, GLuint color, GLuint depth)
{
    char name[96];
    snprintf(name, sizeof name, "%s.%s", label, suffix);
    GLuint fbo;
    glCreateFramebuffers(1, &fbo);
    if (color) glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color, 0);
    if (depth) glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, depth, 0);
    GLenum st = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        core_log_error("gfx: framebuffer '%s' incomplete (0x%04x)", name, (unsigned)st);
        glDeleteFramebuffers(1, &fbo);
        return 0;
    }
    gfx_track(GL_FRAMEBUFFER, fbo, name);
    return fbo;
}

gfx_limits_t gfx_limits(void)
{
    gfx_limits_t l = {0};
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &l.max_texture_size);
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &l.max_renderbuffer_size);
    glGetIntegerv(GL_MAX_GEOMETRY_OUTPUT_VERTICES, &l.max_gs_vertices);
    glGetIntegerv(GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS, &l.max_gs_components);
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &l.max_compute_groups);
    GLint kb[4] = {0};
    if (epoxy_has_gl_extension("GL_NVX_gpu_memory_info")) {
        glGetIntegerv(0x9049 /* GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX */, kb);
        l.gpu_bytes = (double)kb[0] * 1024.0;
    } else if (epoxy_has_gl_extension("GL_ATI_meminfo")) {
        glGetIntegerv(0x87FC /* GL_TEXTURE_FREE_MEMORY_ATI */, kb);
        l.gpu_bytes = (double)kb[0] * 1024.0;
    }
    return l;
}

int gfx_target_samples(int requested)
{
    int samples = requested > 0 ? requested : 4;
    if (G.max_samples == 0) {
        GLint max_samples = 1;
        glGetIntegerv(GL_MAX_SAMPLES, &max_samples);
        G.max_samples = max_samples > 0 ? max_samples : 1;
    }
    return samples < G.max_samples ? samples : G.max_samples;
}

gfx_target_t gfx_target_make(const gfx_target_desc_t *d)
{
    gfx_target_t t = {0};
    t.w = d->w;
    t.h = d->h;
    int asked = d->samples > 0 ? d->samples : 4;
    t.samples = gfx_target_samples(asked);
    if (t.samples < asked)
        core_log_warn("gfx: target '%s' asks for %dx MSAA, this GL offers at most %dx: using %dx", d->label, asked,
                      t.samples, t.samples);
    GLenum cf = d->color_format ? d->color_format : GL_RGBA8;
    GLenum df = d->depth_format ? d->depth_format : GL_DEPTH_COMPONENT24;
    char name[96];
    bool ms = t.samples > 1;
    GLenum target = ms ? GL_TEXTURE_2D_MULTISAMPLE : GL_TEXTURE_2D;
    snprintf(name, sizeof name, "%s.color", d->label);
    t.color = gfx_texture_make(&(gfx_texture_desc_t){.target = target, .w = t.w, .h = t.h, .samples = t.samples,
                                                     .format = cf, .label = name});
    if (!d->no_depth) {
        snprintf(name, sizeof name, "%s.depth", d->label);
        t.depth = gfx_texture_make(&(gfx_texture_desc_t){.target = target, .w = t.w, .h = t.h,
                                                         .samples = t.samples, .format = df,
                                                         .filter = GL_NEAREST, .label = name});
    }
    /* poisoned: a frame that leaves a pixel undrawn shows magenta */
    static const float magenta[4] = {1.0f, 0.0f, 1.0f, 1.0f};
    if (G.poison && t.color.id) glClearTexImage(t.color.id, 0, GL_RGBA, GL_FLOAT, magenta);
    t.fbo = make_fbo(d->label, "fbo", t.color.id, t.depth.id);
    if (ms) {
        snprintf(name, sizeof name, "%s.resolve_color", d->label);
        t.resolve_color = gfx_texture_make(&(gfx_texture_desc_t){.w = t.w, .h = t.h, .format = cf, .label = name});
        if (!d->no_depth) {
            snprintf(name, sizeof name, "%s.resolve_depth", d->label);
            t.resolve_depth = gfx_texture_make(&(gfx_texture_desc_t){
                .w = t.w, .h = t.h, .format = df, .filter = GL_NEAREST, .label = name});
        }
        t.resolve_fbo = make_fbo(d->label, "resolve", t.resolve_color.id, t.resolve_depth.id);
    } else {
        t.resolve_color = t.color;
        t.resolve_depth = t.depth;
        t.resolve_fbo = t.fbo;
    }
    if (!t.fbo || !t.resolve_fbo || !t.color.id) {
        gfx_target_destroy(&t);
        return (gfx_target_t){0};
    }
    return t;
}

void gfx_target_destroy(gfx_target_t *t)
{
    if (t->resolve_fbo != t->fbo) {
        release(GL_FRAMEBUFFER, t->resolve_fbo);
        release(GL_TEXTURE, t->resolve_color.id);
        release(GL_TEXTURE, t->resolve_depth.id);
    }
    release(GL_FRAMEBUFFER, t->fbo);
    release(GL_TEXTURE, t->color.id);
    release(GL_TEXTURE, t->depth.id);
    memset(t, 0, sizeof *t);
}

gfx_layered_target_t gfx_layered_target_make(gfx_texture_t color, const char *label)
{
    gfx_layered_target_t t = {0};
    char name[96];
    snprintf(name, sizeof name, "%s.depth", label);
    t.depth = gfx_texture_make(&(gfx_texture_desc_t){.target = GL_TEXTURE_2D_ARRAY, .w = color.w, .h = color.h,
                                                     .layers = color.layers, .format = GL_DEPTH_COMPONENT32F,
                                                     .filter = GL_NEAREST, .label = name});
    if (t.depth.id) t.fbo = make_fbo(label, "fbo", color.id, t.depth.id);
    if (!t.fbo) gfx_layered_target_destroy(&t);
    return t;
}

void gfx_layered_target_destroy(gfx_layered_target_t *t)
{
    release(GL_FRAMEBUFFER, t->fbo);
    release(GL_TEXTURE, t->depth.id);
    memset(t, 0, sizeof *t);
}

void gfx_target_bind(const gfx_target_t *t)
{
    glBindFramebuffer(GL_FRAMEBUFFER, t->fbo);
    glViewport(0, 0, t->w, t->h);
}

void gfx_target_resolve_depth(const gfx_target_t *t)
{
    /* (a target without depth: the GL ignores the depth bit) */
    if (t->resolve_fbo == t->fbo) return;
    glBlitNamedFramebuffer(t->fbo, t->resolve_fbo, 0, 0, t->w, t->h, 0, 0, t->w, t->h, GL_DEPTH_BUFFER_BIT,
                           GL_NEAREST);
}

void gfx_target_resolve(const gfx_target_t *t)
{
    if (t->resolve_fbo == t->fbo) return;
    glBlitNamedFramebuffer(t->fbo, t->resolve_fbo, 0, 0, t->w, t->h, 0, 0, t->w, t->h, GL_COLOR_BUFFER_BIT,
                           GL_NEAREST);
    gfx_target_resolve_depth(t);
}

bool gfx_target_read(const gfx_target_t *t, core_image_t *out)
{
    gfx_target_resolve(t);
    if (!core_image_alloc(out, t->w, t->h, 4)) return false;
    size_t row = (size_t)t->w * 4;
    uint8_t *tmp = malloc(row * (size_t)t->h);
    if (!tmp) {
        core_image_free(out);
        return false;
    }
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t->resolve_fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glReadPixels(0, 0, t->w, t->h, GL_RGBA, GL_UNSIGNED_BYTE, tmp);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    for (int y = 0; y < t->h; y++) memcpy(out->px + (size_t)y * row, tmp + (size_t)(t->h - 1 - y) * row, row);
    free(tmp);
    /* The frame is opaque: alpha-to-coverage leaves fragment alpha in the
     * target, which image viewers would blend with their background. */
    for (size_t i = 3; i < row * (size_t)t->h; i += 4) out->px[i] = 255;
    return true;
}

bool gfx_target_read_depth(const gfx_target_t *t, float *out)
{
    if (!t->depth.id) return false;
    gfx_target_resolve_depth(t);
    size_t row = (size_t)t->w;
    float *tmp = malloc(sizeof(float) * row * (size_t)t->h);
    if (!tmp) return false;
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, t->resolve_fbo);
    glReadPixels(0, 0, t->w, t->h, GL_DEPTH_COMPONENT, GL_FLOAT, tmp);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    for (int y = 0; y < t->h; y++) memcpy(out + (size_t)y * row, tmp + (size_t)(t->h - 1 - y) * row, sizeof(float) * row);
    free(tmp);
    return true;
}

bool gfx_target_screenshot(const gfx_target_t *t, const char *path)
{
    core_image_t img;
    if (!gfx_target_read(t, &img)) return false;
    bool ok = core_image_write_png(&img, path);
    core_image_free(&img);
    return ok;
}

void gfx_target_present(const gfx_target_t *t, int win_w, int win_h)
{
    gfx_target_resolve(t);
    glBlitNamedFramebuffer(t->resolve_fbo, 0, 0, 0, t->w, t->h, 0, 0, win_w, win_h, GL_COLOR_BUFFER_BIT, GL_LINEAR);
}

/* ---- vertex arrays, queries, transform feedback --------------------------------------- */

GLuint gfx_vertex_array_make(const char *label)
{
    GLuint id;
    glCreateVertexArrays(1, &id);
    gfx_track(GL_VERTEX_ARRAY, id, label);
    return id;
}

void gfx_vertex_array_destroy(GLuint *vao)
{
    release(GL_VERTEX_ARRAY, *vao);
    *vao = 0;
}

GLuint gfx_query_make(GLenum target, const char *label)
{
    GLuint id;
    glCreateQueries(target, 1, &id);
    gfx_track(GL_QUERY, id, label);
    return id;
}

void gfx_query_destroy(GLuint *q)
{
    release(GL_QUERY, *q);
    *q = 0;
}

GLuint gfx_transform_feedback_make(const char *label)
{
    GLuint id;
    glCreateTransformFeedbacks(1, &id);
    gfx_track(GL_TRANSFORM_FEEDBACK, id, label);
    return id;
}

void gfx_transform_feedback_destroy(GLuint *tf)
{
    release(GL_TRANSFORM_FEEDBACK, *tf);
    *tf = 0;
}

void gfx_world_height_uniforms(gfx_program_t p, const uint32_t *keys, int layers, float height)
{
    glProgramUniform1uiv(p.id, gfx_uniform(p, "u_world_keys"), layers, keys);
    glProgramUniform1f(p.id, gfx_uniform(p, "u_world_height"), height);
}

/* raster: the compute rasterizer's visibility buffer, its start from the
 * opaque depth, the dispatch of the grass modules' raster shaders (per
 * primitive, then the queued medium and large triangles) and the
 * composite. See
 * raster.h; the shader side is shaders/raster/raster.glsl. */
#include "raster/raster.h"

#include <math.h>

#include <stdio.h>
#include <string.h>

#include "common/bindings_raster.glsl"

#define RASTER_BIG_THREADS 64   /* raster.glsl */
#define RASTER_PRIM_THREADS 64  /* local size of the per-primitive variants */
#define QUEUE_HEADER 16         /* large count, overflow, medium count, overflow */

bool raster_has_atomic64(void)
{
    return epoxy_has_gl_extension("GL_NV_shader_atomic_int64") && epoxy_has_gl_extension("GL_ARB_gpu_shader_int64");
}

bool raster_desc_resolve(const raster_desc_t *in, raster_desc_t *out)
{
    raster_desc_t d = *in;
    if (!d.samples) d.samples = 4;
    if (!d.small_samples) d.small_samples = 64;
    if (!d.medium_samples) d.medium_samples = 4096;
    /* Derived from the target: RASTER_QUEUE_LAYERS layers of the smallest
     * queued triangles over every sample, at least 1 << 20. */
    if (!d.queue_capacity && d.w > 0 && d.h > 0 && d.small_samples > 0) {
        double fill = (double)d.w * d.h * (d.samples ? d.samples : 4) * RASTER_QUEUE_LAYERS / d.small_samples;
        d.queue_capacity = fill > (double)(1 << 20) ? (int)fmin(fill, (double)(1 << 26)) : 1 << 20;
    }
    if (!d.label) d.label = "raster";
    if (d.w <= 0 || d.h <= 0 || (d.samples != 1 && d.samples != 4) || d.small_samples < 1 ||
        d.medium_samples < d.small_samples || d.queue_capacity < 1) {
        core_log_error("raster: bad desc (size %dx%d, samples %d: 1 or 4, small %d, medium %d >= small, queue %d)",
                       d.w, d.h, d.samples, d.small_samples, d.medium_samples, d.queue_capacity);
        return false;
    }
    *out = d;
    return true;
}

/* The one-pass 64-bit buffer, unless desc asks for the 32-bit one or the
 * GL lacks its atomics. */
static bool wants_atomic64(const raster_desc_t *desc) { return !desc->no_atomic64 && raster_has_atomic64(); }

bool raster_make(raster_t *r, const raster_desc_t *desc)
{
    memset(r, 0, sizeof *r);
    if (!raster_desc_resolve(desc, &r->desc)) return false;
    const raster_desc_t *d = &r->desc;
    r->atomic64 = wants_atomic64(d);
    size_t samples = (size_t)d->w * (size_t)d->h * (size_t)d->samples;
    char label[128];
    snprintf(label, sizeof label, "%s.visibility", d->label);
    r->vis = gfx_buffer_make(&(gfx_buffer_desc_t){.size = samples * 8, .label = label});
    snprintf(label, sizeof label, "%s.queue", d->label);
    r->queue = gfx_buffer_make(&(gfx_buffer_desc_t){
        .size = QUEUE_HEADER + 2 * (size_t)d->queue_capacity * 8, .label = label});
    snprintf(label, sizeof label, "%s.args", d->label);
    r->args = gfx_buffer_make(&(gfx_buffer_desc_t){.size = 32, .label = label});
    snprintf(label, sizeof label, "%s.opaque_depth", d->label);
    r->opaque_depth = gfx_texture_make(&(gfx_texture_desc_t){
        .w = d->w, .h = d->h, .format = GL_R32F, .filter = GL_NEAREST, .label = label});
    gfx_program_t progs[6];
    gfx_programs_make(6,
                      (gfx_program_desc_t[6]){
                          {.cs = "raster/raster_init.comp", .label = "raster.init"},
                          {.cs = "raster/raster_init.comp", .defines = "#define RASTER_DEPTH_MS 1\n",
                           .label = "raster.init_ms"},
                          {.cs = "raster/raster_args.comp", .label = "raster.args"},
                          {.vs = "raster/raster_composite.vert", .fs = "raster/raster_composite.frag",
                           .label = "raster.composite"},
                          {.cs = "raster/raster_composite.comp", .label = "raster.composite_cs"},
                          {.cs = "raster/raster_composite.comp", .defines = "#define RASTER_TARGET_MS 1\n",
                           .label = "raster.composite_cs_ms"}},
                      progs);
    r->init = progs[0];
    r->init_ms = progs[1];
    r->args_prog = progs[2];
    r->composite = progs[3];
    r->composite_cs = progs[4];
    r->composite_cs_ms = progs[5];
    glGetIntegerv(GL_MAX_IMAGE_SAMPLES, &r->image_samples);
    r->empty_vao = gfx_vertex_array_make("raster.empty");
    if (!r->vis.id || !r->queue.id || !r->args.id || !r->opaque_depth.id || !r->init.id || !r->init_ms.id ||
        !r->args_prog.id || !r->composite.id || !r->composite_cs.id || !r->composite_cs_ms.id) {
        raster_destroy(r);
        return false;
    }
    core_log_info("raster: %dx%d, %d samples per pixel, %s visibility buffer (%.1f MB)", d->w, d->h,
                  d->samples, r->atomic64 ? "64-bit atomic" : "two-pass 32-bit",
                  (double)(samples * 8) / (1024.0 * 1024.0));
    return true;
}

void raster_destroy(raster_t *r)
{
    gfx_buffer_destroy(&r->vis);
    gfx_buffer_destroy(&r->queue);
    gfx_buffer_destroy(&r->args);
    gfx_texture_destroy(&r->opaque_depth);
    gfx_program_destroy(&r->init);
    gfx_program_destroy(&r->init_ms);
    gfx_program_destroy(&r->args_prog);
    gfx_program_destroy(&r->composite);
    gfx_program_destroy(&r->composite_cs);
    gfx_program_destroy(&r->composite_cs_ms);
    gfx_vertex_array_destroy(&r->empty_vao);
}

/* A raster program's two descs (the primitive's pass and the big list's)
 * for the atomic64 variant or the two-pass one; false when the defines do
 * not fit (logged). */
typedef struct program_descs_t {
    char defs[2048], big_defs[2048 + 32], big_label[160];
    gfx_program_desc_t d[2];
} program_descs_t;

static bool program_descs(program_descs_t *pd, bool atomic64, const char *cs, const char *defines, const char *label)
{
    static const char ext64[] = "#extension GL_ARB_gpu_shader_int64 : require\n"
                                "#extension GL_NV_shader_atomic_int64 : require\n"
                                "#define RASTER_ATOMIC64 1\n";
    int n = snprintf(pd->defs, sizeof pd->defs, "%s%s", atomic64 ? ext64 : "", defines ? defines : "");
    if (n < 0 || (size_t)n >= sizeof pd->defs) {
        core_log_error("raster: defines of %s too long", cs);
        return false;
    }
    snprintf(pd->big_defs, sizeof pd->big_defs, "%s#define RASTER_BIG 1\n", pd->defs);
    snprintf(pd->big_label, sizeof pd->big_label, "%s.big", label);
    pd->d[0] = (gfx_program_desc_t){.cs = cs, .defines = pd->defs, .label = label};
    pd->d[1] = (gfx_program_desc_t){.cs = cs, .defines = pd->big_defs, .label = pd->big_label};
    return true;
}

raster_program_t raster_program_make(const raster_t *r, const char *cs, const char *defines, const char *label)
{
    raster_program_t p = {.atomic64 = r->atomic64};
    program_descs_t pd;
    if (!program_descs(&pd, r->atomic64, cs, defines, label)) return p;
    gfx_program_t progs[2];
    bool ok = gfx_programs_make(2, pd.d, progs);
    p.prim = progs[0];
    p.big = progs[1];
    if (!ok) raster_program_destroy(&p);
    return p;
}

void raster_program_prefetch(const raster_desc_t *desc, const char *cs, const char *defines)
{
    program_descs_t pd;
    if (program_descs(&pd, wants_atomic64(desc), cs, defines, cs))
        gfx_programs_prefetch(2, pd.d);
}

void raster_program_destroy(raster_program_t *p)
{
    gfx_program_destroy(&p->prim);
    gfx_program_destroy(&p->big);
}

bool raster_program_ensure(const raster_t *r, raster_program_t *p, const char *cs, const char *defines,
                           const char *label)
{
    /* remade when the defines change */
    uint32_t h = (uint32_t)core_hash_bytes(defines ? defines : "", defines ? strlen(defines) : 0, 0);
    if (p->prim.id && (p->atomic64 != r->atomic64 || p->defines != h)) raster_program_destroy(p);
    if (!p->prim.id) {
        *p = raster_program_make(r, cs, defines, label);
        p->defines = h;
    }
    return p->prim.id != 0;
}

static void set_frame_uniforms(const raster_t *r, gfx_program_t p)
{
    glUniform2i(gfx_uniform(p, "u_raster_pixels"), r->desc.w, r->desc.h);
    glUniform1i(gfx_uniform(p, "u_raster_samples"), r->desc.samples);
}

void raster_begin(raster_t *r, const gfx_target_t *target)
{
    gfx_timer_begin(GFX_PASS_RASTER_INIT);
    bool ms = target->samples > 1;
    gfx_program_t p = ms ? r->init_ms : r->init;
    glUseProgram(p.id);
    set_frame_uniforms(r, p);
    if (ms) glUniform1i(gfx_uniform(p, "u_target_samples"), target->samples);
    glBindTextureUnit(RASTER_TEX_DEPTH, target->depth.id);
    glBindImageTexture(RASTER_IMG_OPAQUE, r->opaque_depth.id, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, RASTER_BIND_VIS, r->vis.id);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    glDispatchCompute((GLuint)(r->desc.w + 15) / 16, (GLuint)(r->desc.h + 15) / 16, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glBindTextureUnit(RASTER_TEX_DEPTH, 0);
    glBindImageTexture(RASTER_IMG_OPAQUE, 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
    gfx_timer_end();
}

/* Dispatch arguments from a GPU count into args slot `slot`. */
static void write_args(raster_t *r, gfx_buffer_t src, uint32_t index, uint32_t max, uint32_t group, int slot)
{
    gfx_program_t p = r->args_prog;
    glUseProgram(p.id);
    glUniform1i(gfx_uniform(p, "u_queue"), src.id == r->queue.id);
    glUniform1ui(gfx_uniform(p, "u_src_index"), index);
    glUniform1ui(gfx_uniform(p, "u_max"), max);
    glUniform1ui(gfx_uniform(p, "u_group"), group);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, RASTER_BIND_ARGS_SRC, src.id);
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, RASTER_BIND_ARGS, r->args.id, (GLintptr)slot * 16, 12);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

static void use_raster_program(const raster_t *r, gfx_program_t p, int pass, const raster_items_t *items,
                               raster_bind_fn bind, void *user)
{
    glUseProgram(p.id);
    set_frame_uniforms(r, p);
    glUniform1i(gfx_uniform(p, "u_raster_pass"), pass);
    GLuint small = items->small_samples ? items->small_samples : (GLuint)r->desc.small_samples;
    GLuint medium = items->medium_samples ? items->medium_samples : (GLuint)r->desc.medium_samples;
    glUniform1ui(gfx_uniform(p, "u_raster_small_samples"), small);
    glUniform1ui(gfx_uniform(p, "u_raster_medium_samples"), medium > small ? medium : small);
    glUniform1ui(gfx_uniform(p, "u_raster_queue_capacity"), (GLuint)r->desc.queue_capacity);
    bind(p, user);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, RASTER_BIND_VIS, r->vis.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, RASTER_BIND_QUEUE, r->queue.id);
}

void raster_draw(raster_t *r, const raster_program_t *p, const raster_items_t *items, raster_bind_fn bind,
                 void *user)
{
    if (!items->count_buffer.id && items->count == 0) return;
    static const uint32_t zero = 0;
    int passes = r->atomic64 ? 1 : 2;
    for (int pass = 0; pass < passes; pass++) {
        glClearNamedBufferSubData(r->queue.id, GL_R32UI, 0, QUEUE_HEADER, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        if (items->count_buffer.id)
            write_args(r, items->count_buffer, items->count_index, items->count_max, RASTER_PRIM_THREADS, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        use_raster_program(r, p->prim, pass, items, bind, user);
        if (items->count_buffer.id) {
            glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, r->args.id);
            glDispatchComputeIndirect(0);
        } else {
            glDispatchCompute((items->count + RASTER_PRIM_THREADS - 1) / RASTER_PRIM_THREADS, 1, 1);
        }
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        write_args(r, r->queue, 0, (uint32_t)r->desc.queue_capacity, RASTER_BIG_THREADS, 1);
        use_raster_program(r, p->big, pass, items, bind, user);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, r->args.id);
        glDispatchComputeIndirect(16);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    }
}

void raster_end(raster_t *r, const gfx_target_t *target)
{
    gfx_timer_begin(GFX_PASS_RASTER_COMPOSITE);
    glBindFramebuffer(GL_FRAMEBUFFER, target->fbo);
    glViewport(0, 0, target->w, target->h);
    glUseProgram(r->composite.id);
    set_frame_uniforms(r, r->composite);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, RASTER_BIND_VIS, r->vis.id);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glBindVertexArray(r->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glDepthFunc(GL_LESS);
    gfx_timer_end();
}

void raster_end_color(raster_t *r, const gfx_target_t *target)
{
    bool ms = target->color.samples > 1;
    gfx_program_t p = ms ? r->composite_cs_ms : r->composite_cs;
    if (target->color.format != GL_RGBA8 || !p.id || (ms && target->color.samples > r->image_samples)) {
        raster_end(r, target);
        return;
    }
    gfx_timer_begin(GFX_PASS_RASTER_COMPOSITE);
    glUseProgram(p.id);
    set_frame_uniforms(r, p);
    if (ms) glUniform1i(gfx_uniform(p, "u_target_samples"), target->color.samples);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, RASTER_BIND_VIS, r->vis.id);
    glBindImageTexture(RASTER_IMG_TARGET, target->color.id, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glDispatchCompute((GLuint)(r->desc.w + 7) / 8, (GLuint)(r->desc.h + 7) / 8, 1);
    /* what comes after reads the colour as a framebuffer or a texture */
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindImageTexture(RASTER_IMG_TARGET, 0, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA8);
    gfx_timer_end();
}

void raster_read_stats(raster_t *r, raster_stats_t *out)
{
    uint32_t hdr[4];
    gfx_buffer_read(r->queue, 0, sizeof hdr, hdr);
    r->stats.large = hdr[0];
    r->stats.medium = hdr[2];
    r->stats.overflow = hdr[1] + hdr[3];
    if (r->stats.overflow && !r->warned_overflow) {
        core_log_warn("raster: %u queued triangles past the lists' %d (sized for %d layers of them over the "
                      "target) were not drawn",
                      r->stats.overflow, r->desc.queue_capacity, RASTER_QUEUE_LAYERS);
        r->warned_overflow = true;
    }
    *out = r->stats;
}

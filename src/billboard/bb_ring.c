/* bb_ring: the billboard field on a world terrain (docs/WORLD.md,
 * "Streaming: the billboard ring"): instead of the octree's field made
 * once over a heightfield, a window of W x W ring cells (bb_ring.h) that
 * follows the camera. Slot s of the window owns points [s K^2, (s+1) K^2)
 * of the field's one points buffer; a cell that enters the window is
 * generated on the GPU into its slot by bb_ring.geom with transform
 * feedback (one draw of (K / tile)^2 tiles per cell, the root on the
 * world's height function, the extent map of the field's layout), over
 * the cell that left. Every candidate writes one point (dead ones have
 * size 0), so no count comes back and the slot's range is always whole.
 * Drawn by the hardware path per cell in view (a CPU loop over the W^2
 * slots) or by the compute rasterizer over the whole buffer (bb_draw.c).
 * Nothing collides with the ring yet (bb_field_update only keeps the time). */
#include "billboard/bb_local.h"

#include <math.h>
#include <stdlib.h>

#include "scene/terrain_world.h"

bool bb_ring_make(bb_field_t *f, int tile)
{
    const bb_field_desc_t *d = &f->desc;
    const terrain_mesh_t *t = d->terrain;
    int cand = bb_ring_cand(d->ring_cell, f->gen.spacing, tile);
    int side = bb_ring_side(d->ring_reach, (float)cand * f->gen.spacing);
    double cap = (double)side * side * cand * cand;
    if (cap > (double)(1u << 26)) {
        core_log_error("bb_field_make: a ring of %d x %d cells of %d x %d candidates exceeds the limit of %u "
                       "billboards; lower grass.billboard_density", side, side, cand, cand, 1u << 26);
        return false;
    }
    f->capacity = (int)cap;
    f->ring_tile = tile;
    for (int a = 0; a < 2; a++) {
        f->ring_cells[a] = (int)ceilf((t->aabb_max[2 * a] - t->aabb_min[2 * a]) / f->gen.spacing);
        f->ring_max[a] = t->aabb_max[2 * a];
    }
    f->ring_y[0] = t->aabb_min[1];
    f->ring_y[1] = t->aabb_max[1] + 1.4f * d->size[1] + 0.6f * d->size[0] + d->wind.strength;
    size_t slots = (size_t)side * (size_t)side;
    f->ring_slots = malloc(sizeof *f->ring_slots * slots);
    f->ring_coords = malloc(sizeof *f->ring_coords * slots);
    f->firsts = malloc(sizeof *f->firsts * slots);
    f->counts_gl = malloc(sizeof *f->counts_gl * slots);
    if (!f->ring_slots || !f->ring_coords || !f->firsts || !f->counts_gl ||
        !bb_ring_window_make(&f->ring, side, cand, f->gen.spacing, f->gen.origin)) {
        core_log_error("out of memory for the billboard ring");
        return false;
    }
    char world[256], defines[sizeof f->defines + sizeof world];
    if (terrain_world_defines(&t->world, world, sizeof world) < 0) return false;
    snprintf(defines, sizeof defines, "%s%s", f->defines, world);
    f->gen_prog = gfx_program_make(&(gfx_program_desc_t){.vs = "billboard/bb_ring.vert", .gs = "billboard/bb_ring.geom",
                                                         .defines = defines, .tf_varyings = bb_tf_varyings,
                                                         .label = "bb.ring.generate"});
    core_log_info("bb: ring of %d x %d cells of %d x %d candidates (%.2f m), %d billboards, %.1f MiB", side, side,
                  cand, cand, (double)((float)cand * f->gen.spacing), f->capacity,
                  cap * (double)sizeof(bb_point_t) / 1048576.0);
    return f->gen_prog.id != 0;
}

void bb_ring_destroy(bb_field_t *f)
{
    bb_ring_window_free(&f->ring);
    free(f->ring_slots);
    free(f->ring_coords);
}

static void ring_uniforms(const bb_field_t *f)
{
    gfx_program_t p = f->gen_prog;
    bb_set_gen(f);
    glUniform1i(gfx_uniform(p, "u_cand"), f->ring.cand);
    glUniform2i(gfx_uniform(p, "u_cells"), f->ring_cells[0], f->ring_cells[1]);
    glUniform2f(gfx_uniform(p, "u_field_max"), f->ring_max[0], f->ring_max[1]);
}

void bb_ring_follow(bb_field_t *f, const float camera[3])
{
    int n = bb_ring_window_plan(&f->ring, camera, f->ring_slots, f->ring_coords);
    if (n == 0) return;
    gfx_timer_begin("bb.ring");
    ring_uniforms(f);
    GLint cell0 = gfx_uniform(f->gen_prog, "u_cell0");
    int k = f->ring.cand, tiles = (k / f->ring_tile) * (k / f->ring_tile);
    GLsizeiptr bytes = (GLsizeiptr)k * k * (GLsizeiptr)sizeof(bb_point_t);
    GLint fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, f->cube_target.fbo); /* draws need a complete framebuffer */
    glBindVertexArray(f->empty_vao);
    glEnable(GL_RASTERIZER_DISCARD);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, f->tf);
    for (int q = 0; q < n; q++) {
        glUniform2i(cell0, f->ring_coords[q][0] * k, f->ring_coords[q][1] * k);
        glBindBufferRange(GL_TRANSFORM_FEEDBACK_BUFFER, 0, f->points.id, (GLintptr)f->ring_slots[q] * bytes, bytes);
        glBeginTransformFeedback(GL_POINTS);
        glDrawArrays(GL_POINTS, 0, tiles);
        glEndTransformFeedback();
    }
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
    glDisable(GL_RASTERIZER_DISCARD);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    f->ring_generated += n;
    gfx_count_add("bb.ring_cells", n);
    gfx_timer_end();
}

/* Whether slot s's cell box can show a billboard in dd's view: inside the
 * world square, the frustum, nearer than far_end and not all nearer than
 * fade_start (less a metre). */
static bool cell_drawn(const bb_field_t *f, int s, const bb_draw_desc_t *dd)
{
    const int32_t *c = f->ring.held[s];
    if (c[0] == BB_RING_NONE) return false;
    float cell = (float)f->ring.cand * f->ring.spacing;
    float lo[3] = {f->ring.origin[0] + (float)c[0] * cell, f->ring_y[0], f->ring.origin[1] + (float)c[1] * cell};
    float hi[3] = {lo[0] + cell, f->ring_y[1], lo[2] + cell};
    if (hi[0] <= f->ring.origin[0] || hi[2] <= f->ring.origin[1] || lo[0] >= f->ring_max[0] || lo[2] >= f->ring_max[1])
        return false;
    for (int p = 0; p < 6; p++) {
        const float *pl = dd->planes[p];
        float far = pl[3];
        for (int a = 0; a < 3; a++) far += pl[a] * (pl[a] >= 0.0f ? hi[a] : lo[a]);
        if (far < 0.0f) return false;
    }
    float near2 = 0.0f, far2 = 0.0f;
    for (int a = 0; a < 3; a++) {
        float e = dd->camera[a], dn = e < lo[a] ? lo[a] - e : (e > hi[a] ? e - hi[a] : 0.0f);
        float df = fmaxf(fabsf(e - lo[a]), fabsf(e - hi[a]));
        near2 += dn * dn, far2 += df * df;
    }
    if (dd->far_end > 0.0f && near2 > dd->far_end * dd->far_end) return false;
    float fade = dd->fade_start - 1.0f;
    return !(fade > 0.0f && far2 < fade * fade);
}

int bb_ring_ranges(bb_field_t *f, const bb_draw_desc_t *dd)
{
    int n = 0, per = f->ring.cand * f->ring.cand;
    for (int s = 0; s < f->ring.side * f->ring.side; s++) {
        if (!cell_drawn(f, s, dd)) continue;
        if (n > 0 && f->firsts[n - 1] + f->counts_gl[n - 1] == s * per) {
            f->counts_gl[n - 1] += per;
            continue;
        }
        f->firsts[n] = s * per;
        f->counts_gl[n++] = per;
    }
    return n;
}

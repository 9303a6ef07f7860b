/* bb_ring: the billboard field on a world terrain (docs/WORLD.md,
 * "Streaming: the billboard ring"): instead of the octree's field made
 * once over a heightfield, a window of W x W ring cells (bb_ring.h) that
 * follows the camera. Slot s of the window owns points [s K^2, (s+1) K^2)
 * of the field's one points buffer; a cell that enters the window is
 * generated on the GPU into its slot by bb_ring_gen.comp (one dispatch of
 * K^2 threads per cell, the root on the world's height function, the
 * extent map of the field's layout), over the cell that left. Every
 * candidate writes one point (dead ones have size 0), so no count comes
 * back and the slot's range is always whole.
 * Drawn by the hardware path per cell in view (a CPU loop over the W^2
 * slots) or by the compute rasterizer over the whole buffer (bb_draw.c).
 * Collision (bb_update.c) takes the slots as the octree's leaves: a slot's
 * state follows bb_ring_window_touch, its range goes through the same
 * collide and recover passes (the collide pass's ground is the world
 * function), at most BB_RING_COLLIDE_SLOTS slots per pass; a cell that
 * leaves deformed gives its meshes back to the pool (bb_ring_release.comp)
 * and its state is dropped. */
#include "billboard/bb_local.h"

#include <math.h>
#include <stdlib.h>

#include "terrain/terrain_world.h"

/* Slots one collide pass takes at most (the collide scratch holds their
 * points): 32 cells of 8 m, 16 walkers touching two cells each. */
#define BB_RING_COLLIDE_SLOTS 32

bool bb_ring_defines(const char *field_defines, char *buf, size_t size)
{
    int n = snprintf(buf, size, "%s#define BB_GROUND_WORLD 1\n", field_defines);
    return n > 0 && (size_t)n < size;
}

/* The ring's generation and release programs for a field's defines;
 * defines gets the generation's (bb_ring_defines). */
static bool ring_programs(const char *field_defines, char *defines, size_t size, gfx_program_desc_t out[2])
{
    if (!bb_ring_defines(field_defines, defines, size)) return false;
    out[0] = (gfx_program_desc_t){.cs = "billboard/bb_ring_gen.comp", .defines = defines, .label = "bb.ring.generate"};
    out[1] = (gfx_program_desc_t){.cs = "billboard/bb_ring_release.comp", .defines = field_defines,
                                  .label = "bb.ring.release"};
    return true;
}

void bb_ring_prefetch(const char *field_defines)
{
    char defines[sizeof((bb_field_t *)0)->defines + 32];
    gfx_program_desc_t pds[2];
    if (ring_programs(field_defines, defines, sizeof defines, pds)) gfx_programs_prefetch(2, pds);
}

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
    for (int a = 0; a < 2; a++) {
        f->ring_cells[a] = (int)ceilf((t->aabb_max[2 * a] - t->aabb_min[2 * a]) / f->gen.spacing);
        f->ring_max[a] = t->aabb_max[2 * a];
    }
    f->ring_y[0] = t->aabb_min[1];
    f->ring_y[1] = t->aabb_max[1] + 1.4f * d->size[1] + 0.6f * d->size[0] + d->wind.strength;
    /* the largest bounding sphere a billboard can have (bb_read_spheres'
     * radius at the rule's largest width and height) */
    float wmax = 1.2f * d->size[0], hmax = 1.4f * d->size[1];
    f->sphere_max = 0.5f * sqrtf(wmax * wmax + hmax * hmax) + d->wind.strength;
    size_t slots = (size_t)side * (size_t)side;
    f->ring_collide_slots = (int)slots < BB_RING_COLLIDE_SLOTS ? (int)slots : BB_RING_COLLIDE_SLOTS;
    f->ring_slots = malloc(sizeof *f->ring_slots * slots);
    f->ring_coords = malloc(sizeof *f->ring_coords * slots);
    f->ring_dropped = malloc(sizeof *f->ring_dropped * slots);
    f->firsts = malloc(sizeof *f->firsts * slots);
    f->counts_gl = malloc(sizeof *f->counts_gl * slots);
    f->ranges = malloc(sizeof *f->ranges * slots);
    f->recover_ranges = malloc(sizeof *f->recover_ranges * 4 * slots);
    if (!f->ring_slots || !f->ring_coords || !f->ring_dropped || !f->firsts || !f->counts_gl || !f->ranges ||
        !f->recover_ranges || !bb_ring_window_make(&f->ring, side, cand, f->gen.spacing, f->gen.origin)) {
        core_log_error("out of memory for the billboard ring");
        return false;
    }
    float margin = 1.4f * d->size[1] + 0.6f * d->size[0] + d->wind.strength + 0.05f; /* the octree's (bb.c) */
    f->ring.margin = margin > 1.0f ? margin : 1.0f;
    f->ring.y[0] = f->ring_y[0], f->ring.y[1] = f->ring_y[1];
    char defines[sizeof f->defines + 32];
    gfx_program_desc_t pds[2];
    if (!ring_programs(f->defines, defines, sizeof defines, pds)) return false;
    gfx_program_t progs[2];
    gfx_programs_make(2, pds, progs);
    f->gen_prog = progs[0];
    f->release_prog = progs[1];
    terrain_world_gpu_t w = terrain_world_gpu(&f->desc.terrain->world);
    if (f->gen_prog.id) gfx_world_height_uniforms(f->gen_prog, w.keys, TERRAIN_WORLD_LAYERS, w.height);
    core_log_info("bb: ring of %d x %d cells of %d x %d candidates (%.2f m), %d billboards, %.1f MiB", side, side,
                  cand, cand, (double)((float)cand * f->gen.spacing), f->capacity,
                  cap * (double)sizeof(bb_point_t) / 1048576.0);
    return f->gen_prog.id && f->release_prog.id;
}

void bb_ring_destroy(bb_field_t *f)
{
    bb_ring_window_free(&f->ring);
    free(f->ring_slots);
    free(f->ring_coords);
    free(f->ring_dropped);
    gfx_program_destroy(&f->release_prog);
}

/* Gives the deformed meshes of slot s's points back to the pool. */
static void release_slot(bb_field_t *f, int s)
{
    GLuint per = (GLuint)(f->ring.cand * f->ring.cand);
    gfx_program_t p = f->release_prog;
    glUseProgram(p.id);
    glUniform1ui(gfx_uniform(p, "u_first"), (GLuint)s * per);
    glUniform1ui(gfx_uniform(p, "u_count"), per);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POOL, f->pool.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_MESHES, f->meshes.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POINTS, f->points.id);
    glDispatchCompute((per + 63u) / 64u, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_TRANSFORM_FEEDBACK_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    f->ring_released++;
}

int bb_ring_collect(bb_field_t *f, uint32_t state_mask)
{
    int n = 0, per = f->ring.cand * f->ring.cand, skipped = 0;
    bool colliding = state_mask == BB_NODE_MASK(BB_NODE_COLLIDING);
    for (int s = 0; s < f->ring.side * f->ring.side; s++) {
        if (f->ring.held[s][0] == BB_RING_NONE || !(BB_NODE_MASK(f->ring.state[s]) & state_mask)) continue;
        if (colliding && n == f->ring_collide_slots) {
            skipped++;
            continue;
        }
        f->ranges[n++] = (bb_range_t){.first = (uint32_t)(s * per), .count = (uint32_t)per, .leaf = (uint32_t)s,
                                      .state = f->ring.state[s], .recover_left = f->ring.timer[s]};
    }
    if (skipped > 0 && f->ring_skipped == 0)
        core_log_warn("bb: %d billboard ring cells collide at once, a pass takes %d: the rest wait (warned once)",
                      n + skipped, f->ring_collide_slots);
    f->ring_skipped += skipped;
    return n;
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
    int n = bb_ring_window_plan(&f->ring, camera, f->ring_slots, f->ring_coords, f->ring_dropped);
    if (n == 0) return;
    gfx_timer_begin(GFX_PASS_BB_RING);
    for (int q = 0; q < n; q++)
        if (f->ring_dropped[q]) release_slot(f, f->ring_slots[q]);
    ring_uniforms(f);
    gfx_program_t p = f->gen_prog;
    GLint cell0 = gfx_uniform(p, "u_cell0"), first = gfx_uniform(p, "u_first");
    GLuint per = (GLuint)(f->ring.cand * f->ring.cand);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POINTS, f->points.id);
    for (int q = 0; q < n; q++) {
        glUniform2i(cell0, f->ring_coords[q][0] * f->ring.cand, f->ring_coords[q][1] * f->ring.cand);
        glUniform1ui(first, (GLuint)f->ring_slots[q] * per);
        glDispatchCompute((per + 63u) / 64u, 1, 1);
    }
    /* read next as storage (collide, raster), vertices (the hardware
     * path's pulled quads and bb_point.vert) and by transform feedback's
     * copies (bb_update) */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
                    GL_TRANSFORM_FEEDBACK_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    f->ring_generated += n;
    gfx_count_add("bb.ring_cells", n);
    gfx_timer_end();
}

/* Whether slot s's cell box can show a billboard in dd's view: inside the
 * world square, the frustum, nearer than far_end and not all nearer than
 * fade_start (less a metre). */
static bool cell_drawn(const bb_field_t *f, int s, const bb_draw_desc_t *dd)
{
    float lo[3], hi[3];
    if (!bb_ring_slot_box(&f->ring, s, lo, hi)) return false;
    if (hi[0] <= f->ring.origin[0] || hi[2] <= f->ring.origin[1] || lo[0] >= f->ring_max[0] || lo[2] >= f->ring_max[1])
        return false;
    for (int p = 0; p < 6; p++) {
        const float *pl = dd->view.planes[p];
        float far = pl[3];
        for (int a = 0; a < 3; a++) far += pl[a] * (pl[a] >= 0.0f ? hi[a] : lo[a]);
        if (far < 0.0f) return false;
    }
    float near2 = 0.0f, far2 = 0.0f;
    for (int a = 0; a < 3; a++) {
        float e = dd->view.camera[a], dn = e < lo[a] ? lo[a] - e : (e > hi[a] ? e - hi[a] : 0.0f);
        float df = fmaxf(fabsf(e - lo[a]), fabsf(e - hi[a]));
        near2 += dn * dn, far2 += df * df;
    }
    if (dd->far_end > 0.0f && near2 > dd->far_end * dd->far_end) return false;
    float fade = dd->fade_start - 1.0f;
    return !(fade > 0.0f && far2 < fade * fade);
}

int bb_ring_ranges(bb_field_t *f, const bb_draw_desc_t *dd, uint32_t state_mask)
{
    int n = 0, per = f->ring.cand * f->ring.cand;
    for (int s = 0; s < f->ring.side * f->ring.side; s++) {
        if (!(BB_NODE_MASK(f->ring.state[s]) & state_mask) || !cell_drawn(f, s, dd)) continue;
        if (n > 0 && f->firsts[n - 1] + f->counts_gl[n - 1] == s * per) {
            f->counts_gl[n - 1] += per;
            continue;
        }
        f->firsts[n] = s * per;
        f->counts_gl[n++] = per;
    }
    return n;
}

/* bb_occlude.c: occlusion culling of billboard batches (Orthmann et al.
 * 2009 sec. 6), hardware path. Each octree leaf is a batch: after the
 * billboards are drawn, the margin-grown box of every leaf that was in the
 * frustum is drawn with colour and depth writes off inside its own
 * GL_ANY_SAMPLES_PASSED_CONSERVATIVE query (bb_occlude.vert). A later draw
 * reads a query only once its result is available (never waiting) and
 * skips a leaf whose latest result passed no sample; a skipped leaf is
 * queried again every frame, so it comes back one or two frames after it
 * shows. A leaf whose box holds the camera is always drawn and never
 * queried (its box's faces would be clipped away). */
#include "billboard/bb_local.h"

#include <stdlib.h>
#include <string.h>

#include "core/core.h"

/* Metres around a leaf's box within which the camera counts as inside. */
#define BB_OCCLUDE_NEAR 1.0f

bool bb_occlusion_make(bb_field_t *f)
{
    int n = f->tree.leaf_count;
    f->occ_query = calloc((size_t)n, sizeof *f->occ_query);
    f->occ_state = calloc((size_t)n, sizeof *f->occ_state);
    f->occ_frame = calloc((size_t)n, sizeof *f->occ_frame);
    f->occ_tested = malloc(sizeof *f->occ_tested * (size_t)n);
    f->occlude_prog = gfx_program_make(&(gfx_program_desc_t){.vs = "billboard/bb_occlude.vert",
                                                             .fs = "billboard/bb_occlude.frag",
                                                             .label = "bb.occlude"});
    if (!f->occ_query || !f->occ_state || !f->occ_frame || !f->occ_tested || !f->occlude_prog.id) {
        core_log_error("bb: occlusion culling cannot be set up");
        return false;
    }
    return true;
}

void bb_occlusion_destroy(bb_field_t *f)
{
    if (f->occ_query)
        for (int i = 0; i < f->tree.leaf_count; i++) gfx_query_destroy(&f->occ_query[i]);
    free(f->occ_query);
    free(f->occ_state);
    free(f->occ_frame);
    free(f->occ_tested);
    gfx_program_destroy(&f->occlude_prog);
    f->occ_query = NULL;
    f->occ_state = NULL;
    f->occ_frame = NULL;
    f->occ_tested = NULL;
}

/* Leaf `leaf`'s box grown by the octree margin (and by `extra`). */
static void leaf_box(const bb_field_t *f, uint32_t leaf, float extra, float lo[3], float hi[3])
{
    int node = bb_octree_leaf_node(&f->tree, leaf);
    float m = f->tree.desc.margin + extra;
    for (int k = 0; k < 3; k++) {
        lo[k] = f->tree.lo[node][k] - m;
        hi[k] = f->tree.hi[node][k] + m;
    }
}

static bool holds_camera(const bb_field_t *f, uint32_t leaf, const float camera[3])
{
    float lo[3], hi[3];
    leaf_box(f, leaf, BB_OCCLUDE_NEAR, lo, hi);
    for (int k = 0; k < 3; k++)
        if (camera[k] < lo[k] || camera[k] > hi[k]) return false;
    return true;
}

int bb_occlusion_filter(bb_field_t *f, bb_range_t *ranges, int n, const float camera[3])
{
    int kept = 0;
    for (int i = 0; i < n; i++) {
        uint32_t leaf = ranges[i].leaf;
        uint8_t *st = &f->occ_state[leaf];
        if (*st & BB_OCC_PENDING) {
            GLuint ready = 0, passed = 1;
            glGetQueryObjectuiv(f->occ_query[leaf], GL_QUERY_RESULT_AVAILABLE, &ready);
            if (ready) {
                glGetQueryObjectuiv(f->occ_query[leaf], GL_QUERY_RESULT, &passed);
                *st = passed ? 0 : BB_OCC_HIDDEN;
            }
        }
        /* A result older than the last two draws is stale: the leaf left
         * the frustum (or held the camera) in between. */
        bool inside = holds_camera(f, leaf, camera);
        if (inside || f->occ_draws - f->occ_frame[leaf] > 2u) *st &= (uint8_t)~BB_OCC_HIDDEN;
        if (!inside) f->occ_tested[f->occ_tested_count++] = leaf;
        if (*st & BB_OCC_HIDDEN) {
            f->occ_skipped++;
            continue;
        }
        ranges[kept++] = ranges[i];
    }
    return kept;
}

void bb_occlusion_query(bb_field_t *f, const bb_draw_desc_t *dd)
{
    if (f->occ_tested_count == 0) return;
    gfx_program_t p = f->occlude_prog;
    glUseProgram(p.id);
    glUniformMatrix4fv(gfx_uniform(p, "u_viewproj"), 1, GL_FALSE, dd->view.viewproj);
    glBindVertexArray(f->empty_vao);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glDepthMask(GL_FALSE);
    int issued = 0;
    for (int i = 0; i < f->occ_tested_count; i++) {
        uint32_t leaf = f->occ_tested[i];
        if (f->occ_state[leaf] & BB_OCC_PENDING) continue;
        if (!f->occ_query[leaf])
            f->occ_query[leaf] = gfx_query_make(GL_ANY_SAMPLES_PASSED_CONSERVATIVE, "bb.occlusion");
        float lo[3], hi[3];
        leaf_box(f, leaf, 0.0f, lo, hi);
        glUniform3fv(gfx_uniform(p, "u_lo"), 1, lo);
        glUniform3fv(gfx_uniform(p, "u_hi"), 1, hi);
        glBeginQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE, f->occ_query[leaf]);
        glDrawArrays(GL_TRIANGLES, 0, 36);
        glEndQuery(GL_ANY_SAMPLES_PASSED_CONSERVATIVE);
        f->occ_state[leaf] |= BB_OCC_PENDING;
        f->occ_frame[leaf] = f->occ_draws;
        issued++;
    }
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glBindVertexArray(0);
    gfx_count_add("bb.occlusion_queries", issued);
    gfx_count_add("bb.occluded_leaves", f->occ_skipped);
    f->occluded_last = f->occ_skipped;
    f->occ_tested_count = 0;
    f->occ_skipped = 0;
    f->occ_draws++;
}

int bb_occlusion_hidden(const bb_field_t *f)
{
    int n = 0;
    if (f->occ_state)
        for (int i = 0; i < f->tree.leaf_count; i++) n += f->occ_state[i] & BB_OCC_HIDDEN ? 1 : 0;
    return n;
}

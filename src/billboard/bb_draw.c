/* bb_draw: drawing the billboard field: the hardware path (idle leaves'
 * plain quads by vertex pulling, colliding and recovering leaves through
 * bb_render.geom, frustum-culled leaves nearest first, occlusion culling
 * with bb_occlude.c), the compute rasterizer's path (bb_raster.comp), and
 * the deformed billboards' tilts handed to the blades (bb_slope.comp). */
#include "billboard/bb_local.h"

/* The view-dependent cards' uniforms (shaders/billboard/bb_view.glsl). */
static void set_views(const bb_field_t *f, GLuint prog)
{
    gfx_program_t gp = {.id = prog};
    glProgramUniform2i(prog, gfx_uniform(gp, "u_views"), f->views.elevations, f->views.azimuths);
    glProgramUniform1f(prog, gfx_uniform(gp, "u_view_elevation_max"), f->views.elevation_max);
    glProgramUniform1i(prog, gfx_uniform(gp, "u_view_layers"), (GLint)f->gen.layers);
    glProgramUniform2f(prog, gfx_uniform(gp, "u_view_wind"), f->desc.wind.dir[0], f->desc.wind.dir[1]);
    glProgramUniform1i(prog, gfx_uniform(gp, "u_view_lit"), f->views.on);
}

void bb_render_uniforms(const bb_field_t *f, gfx_program_t p, const bb_draw_desc_t *dd)
{
    glUseProgram(p.id);
    glUniformMatrix4fv(gfx_uniform(p, "u_viewproj"), 1, GL_FALSE, dd->view.viewproj);
    glUniform3fv(gfx_uniform(p, "u_camera"), 1, dd->view.camera);
    glUniform3fv(gfx_uniform(p, "u_sun"), 1, dd->view.sun);
    glUniform1f(gfx_uniform(p, "u_time"), dd->view.time);
    glUniform1f(gfx_uniform(p, "u_fade_start"), dd->fade_start);
    glUniform1f(gfx_uniform(p, "u_fade_end"), dd->fade_end);
    glUniform1f(gfx_uniform(p, "u_far_start"), dd->far_start);
    glUniform1f(gfx_uniform(p, "u_far_end"), dd->far_end);
    glUniform1i(gfx_uniform(p, "u_overlay"), dd->overlay);
    bb_set_wind(p.id, &f->desc.wind);
    set_views(f, p.id);
    const hybrid_slope_grid_t *g = &dd->slope_grid;
    glUniform1i(gfx_uniform(p, "u_slope_on"), dd->slope_map.id != 0);
    glUniform1f(gfx_uniform(p, "u_slope_time"), dd->view.time);
    glUniform1f(gfx_uniform(p, "u_slope_recover"), dd->slope_recover > 0.0f ? dd->slope_recover : f->desc.recover_time);
    glUniform2fv(gfx_uniform(p, "u_slope_origin"), 1, g->origin);
    glUniform1f(gfx_uniform(p, "u_slope_cell"), g->cell);
    glUniform2i(gfx_uniform(p, "u_slope_dims"), g->nx, g->nz);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HYBRID_BIND_SLOPE_MAP, dd->slope_map.id);
    gi_set_uniforms(p.id, f->desc.gi ? &dd->gi : NULL); /* without BB_GI no vertex carries it */
    blade_lod_t lod = bb_lod_rule(dd->lod);
    blade_lod_uniforms(p, &lod, dd->focal_px, BB_LOD_CULL);
}

void bb_field_add_slopes(bb_field_t *f, const hybrid_slope_grid_t *g, gfx_buffer_t sums)
{
    if (f->billboards == 0) return;
    gfx_program_t p = f->slope_prog;
    glUseProgram(p.id);
    glUniform1ui(gfx_uniform(p, "u_count"), (GLuint)f->billboards);
    glUniform1f(gfx_uniform(p, "u_time"), f->time);
    glUniform2fv(gfx_uniform(p, "u_slope_origin"), 1, g->origin);
    glUniform1f(gfx_uniform(p, "u_slope_cell"), g->cell);
    glUniform2i(gfx_uniform(p, "u_slope_dims"), g->nx, g->nz);
    bb_set_wind(p.id, &f->desc.wind);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_MESHES, f->meshes.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POINTS, f->points.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, HYBRID_BIND_SLOPE_SUMS, sums.id);
    glDispatchCompute(((GLuint)f->billboards + 255u) / 256u, 1, 1);
    gfx_count_add("bb.slope_read", f->billboards);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* The leaves in state_mask that this draw shows (in the frustum, their
 * boxes grown by the widest card the thinning draws, nearer than far_end
 * when set, not occluded), nearest first, merged into draw
 * ranges f->firsts / f->counts_gl; returns how many. */
static int drawn_ranges(bb_field_t *f, uint32_t state_mask, const bb_draw_desc_t *dd)
{
    const float(*planes)[4] = (const float (*)[4])dd->view.planes;
    blade_lod_t lod = bb_lod_rule(dd->lod);
    int n = bb_octree_collect(&f->tree, state_mask, planes, bb_lod_reach(&lod, f->desc.size[0]), f->ranges,
                              f->tree.leaf_count);
    if (dd->far_end > 0.0f) n = bb_octree_keep_near(&f->tree, dd->view.camera, dd->far_end, f->ranges, n);
    if (f->desc.occlusion) n = bb_occlusion_filter(f, f->ranges, n, dd->view.camera);
    if (n <= 0) return 0;
    bb_octree_sort_near_first(&f->tree, dd->view.camera, f->ranges, n, f->sort_keys);
    return bb_merge_ranges(f, n);
}

/* The hardware path's programs, made by its first draw: a field drawn by
 * the compute rasterizer alone never compiles them (with the tiles' draw
 * programs, the world hybrid's start-up with a cold shader cache on the
 * H100 went 6.9 -> 6.6 s). False (logged) when they do not build; the draw
 * then shows nothing. */
static bool draw_programs(bb_field_t *f)
{
    if (f->quad_prog.id) return true;
    if (f->programs_failed) return false;
    gfx_program_t progs[2];
    bool ok = gfx_programs_make(
        2,
        (gfx_program_desc_t[2]){{.vs = "billboard/bb_point.vert", .gs = "billboard/bb_render.geom",
                                 .fs = "billboard/bb_render.frag", .defines = f->defines, .label = "bb.render"},
                                {.vs = "billboard/bb_quad.vert", .fs = "billboard/bb_render.frag",
                                 .defines = f->defines, .label = "bb.quad"}},
        progs);
    f->render_prog = progs[0];
    f->quad_prog = progs[1];
    if (ok) return true;
    gfx_program_destroy(&f->render_prog);
    gfx_program_destroy(&f->quad_prog);
    f->programs_failed = true;
    return false;
}

/* Idle leaves (only plain quads) are drawn by vertex pulling, six vertices
 * per billboard, with no geometry shader; colliding and recovering leaves,
 * which hold deformed meshes, go through bb_render.geom. Both share
 * bb_render.frag. Leaves go nearest first (bb_octree_sort_near_first), so
 * the coarse depth test rejects more of the far layers that nearer ones
 * already cover (docs/PERFORMANCE.md). */
void bb_field_draw(bb_field_t *f, const bb_draw_desc_t *dd)
{
    bb_field_follow(f, dd->view.camera);
    if (!draw_programs(f)) return;
    glBindTextureUnit(BB_TEX_CLUMPS, f->clumps.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POOL, f->pool.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_MESHES, f->meshes.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POINTS, f->points.id);
    glBindVertexArray(f->points_vao);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    gfx_timer_begin(GFX_PASS_BB_RENDER);
    int nr = f->ring_on ? bb_ring_ranges(f, dd, BB_NODE_MASK(BB_NODE_IDLE))
                        : drawn_ranges(f, BB_NODE_MASK(BB_NODE_IDLE), dd);
    if (nr > 0) {
        gfx_count_add("bb.drawn_quads", bb_range_total(f->counts_gl, nr));
        for (int i = 0; i < nr; i++) {
            f->firsts[i] *= 6;
            f->counts_gl[i] *= 6;
        }
        bb_render_uniforms(f, f->quad_prog, dd);
        glMultiDrawArrays(GL_TRIANGLES, f->firsts, f->counts_gl, nr);
    }
    uint32_t deformed = BB_NODE_MASK(BB_NODE_COLLIDING) | BB_NODE_MASK(BB_NODE_RECOVERING);
    nr = f->ring_on ? bb_ring_ranges(f, dd, deformed) : drawn_ranges(f, deformed, dd);
    if (nr > 0) {
        gfx_count_add("bb.drawn_meshes", bb_range_total(f->counts_gl, nr));
        bb_render_uniforms(f, f->render_prog, dd);
        glMultiDrawArrays(GL_POINTS, f->firsts, f->counts_gl, nr);
    }
    gfx_timer_end();
    if (f->desc.occlusion) {
        gfx_timer_begin(GFX_PASS_BB_OCCLUSION);
        bb_occlusion_query(f, dd);
        gfx_timer_end();
    }
    glBindVertexArray(0);
}

typedef struct raster_bind_t {
    const bb_field_t *f;
    const bb_draw_desc_t *dd;
} raster_bind_t;

static void bind_raster(gfx_program_t p, void *user)
{
    const raster_bind_t *b = user;
    bb_render_uniforms(b->f, p, b->dd);
    glUniform4fv(gfx_uniform(p, "u_planes"), 6, &b->dd->view.planes[0][0]);
    glUniform1ui(gfx_uniform(p, "u_count"), (GLuint)b->f->billboards);
    glBindTextureUnit(BB_TEX_CLUMPS, b->f->clumps.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POOL, b->f->pool.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_MESHES, b->f->meshes.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_POINTS, b->f->points.id);
}

bool bb_field_raster(bb_field_t *f, raster_t *r, const bb_draw_desc_t *dd)
{
    bb_field_follow(f, dd->view.camera);
    gfx_timer_begin(GFX_PASS_BB_RASTER);
    raster_program_t *prog = &f->raster_prog;
    bool ok = raster_program_ensure(r, prog, "billboard/bb_raster.comp", f->defines, "bb.raster");
    if (ok && f->billboards > 0) {
        raster_bind_t b = {.f = f, .dd = dd};
        /* No medium list (bb_raster.comp: RASTER_NO_MEDIUM): on the H100 one
         * thread per medium billboard triangle (a texel fetch per pixel) cost
         * meadow_large 4.65 -> 6.59 ms and meadow.json 0.62 -> 3.16 ms against
         * work groups from 256 samples. */
        raster_items_t items = {.count = (uint32_t)f->billboards, .small_samples = 256};
        raster_draw(r, prog, &items, bind_raster, &b);
    }
    glBindTextureUnit(BB_TEX_CLUMPS, 0);
    gfx_timer_end();
    return ok;
}

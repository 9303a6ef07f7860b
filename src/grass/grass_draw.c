/* grass_draw: the composition of one draw. grass_pass_list's passes in
 * order (the ground, the compute rasterizer's start, the blades or their
 * tiles, the billboards, the composite) with the bands they share: the
 * switch fade, the canopy's band, the frame's thinning and the
 * grass-shaded ground under it. grass_draw wraps the host's framebuffer
 * and keeps grass.h's GL state contract. */
#include "grass/grass_local.h"

#include <math.h>
#include <string.h>

/* The visibility buffer at the target's size (made or remade here). */
static raster_t *frame_raster(grass_t *gr, const gfx_target_t *target)
{
    raster_t *r = &gr->raster;
    if (r->vis.id && r->desc.w == target->w && r->desc.h == target->h) return r;
    raster_destroy(r);
    if (!raster_make(r, &(raster_desc_t){.w = target->w, .h = target->h, .samples = gr->raster_samples})) {
        core_log_warn("compute rasterizer unavailable; drawing grass with the hardware path");
        gr->raster_compute = false;
        return NULL;
    }
    return r;
}

/* One draw's state shared by its passes (grass_draw_target). */
typedef struct frame_draw_t {
    const grass_view_t *v;
    const gfx_target_t *target;
    raster_t *raster;       /* NULL: the hardware path */
    bool tiles;             /* the frame draws tiles (and the canopy beyond) */
    float fade_lo, fade_hi; /* the blades' fade band (hybrid) */
    float far_lo, far_hi;   /* the canopy's fade band */
    /* The frame's thinning (frame_lod), shared by the blades, the tiles and
     * the ground under them: grass.lod, the focal length of the target,
     * and the distance where the blades end. */
    blade_lod_t lod;
    float focal, cull;
    bool raster_ok;
} frame_draw_t;

/* Where the switch band's dithered fade ends the blades (the tiles, the
 * hybrid's whole field) they end at its far edge with no end fade of
 * their own; blade mode's field ends at grass.blade_distance (default:
 * the field's edge or the far plane). */
static void frame_lod(const grass_t *gr, frame_draw_t *f)
{
    const grass_view_t *v = f->v;
    bool switch_ends = f->tiles || gr->mode == SCENE_MODE_HYBRID;
    f->lod = gr->reference ? (blade_lod_t){.rule = BLADE_LOD_OFF} : gr->scene->grass.lod;
    f->lod.no_fade = f->lod.no_fade || switch_ends;
    f->focal = blade_lod_focal(f->v->viewproj, f->target->h);
    f->cull = switch_ends ? f->fade_hi
                          : scene_blade_distance(&gr->scene->grass, f->v->camera, v->far, gr->terrain->aabb_min,
                                                 gr->terrain->aabb_max);
}

/* The target's depth resolved for the hardware path's occlusion tests; a
 * single-sampled target has nothing to resolve, and no pass is timed. */
static void resolve_depth(const gfx_target_t *target)
{
    if (target->resolve_fbo == target->fbo) return;
    gfx_timer_begin(GFX_PASS_DEPTH_RESOLVE);
    gfx_target_resolve_depth(target);
    gfx_timer_end();
}

static void draw_tiles(grass_t *gr, frame_draw_t *f)
{
    const grass_view_t *v = f->v;
    blade_draw_desc_t dd = {.view = *f->v, .focal_px = f->focal, .fade_start = f->fade_lo, .fade_end = f->fade_hi,
                            .gi = gr->gi_bind};
    blade_tiles_set_overlay(gr->tiles, v->overlay);
    blade_tiles_set_lod(gr->tiles, &f->lod, f->focal);
    /* Occlusion culling reads the opaque depth, as blade mode's below. */
    if (f->raster) {
        f->raster_ok = blade_tiles_raster(gr->tiles, f->raster, &dd, f->raster->opaque_depth.id) && f->raster_ok;
    } else {
        resolve_depth(f->target);
        blade_tiles_draw(gr->tiles, &dd, f->target->resolve_depth.id);
    }
}

static void draw_blades(grass_t *gr, frame_draw_t *f)
{
    const gfx_target_t *target = f->target;
    /* Occlusion culling reads the resolved depth of the opaque pass (the
     * compute path: the farthest opaque sample, from raster_begin). */
    if (!f->raster) resolve_depth(target);
    /* Thinned by the scene's grass.lod to the frame's cull distance
     * (frame_lod, docs/BLADES.md). */
    bool hybrid = gr->mode == SCENE_MODE_HYBRID;
    blade_cull_desc_t cd = {.view = *f->v,
                            .max_distance = f->cull,
                            .disable = gr->reference ? 0xffu : gr->tuning.cull_disable,
                            .lod = f->lod,
                            .focal_px = f->focal};
    GLuint depth = f->raster ? f->raster->opaque_depth.id : target->resolve_depth.id;
    blade_gpu_cull(gr->blades, &cd, gr->reference ? 0 : depth);
    glBindFramebuffer(GL_FRAMEBUFFER, target->fbo);
    glViewport(0, 0, target->w, target->h);
    blade_draw_desc_t dd = {.view = *f->v, .focal_px = cd.focal_px, .gi = gr->gi_bind};
    if (hybrid && !gr->reference) {
        dd.fade_start = f->fade_lo;
        dd.fade_end = f->fade_hi;
    }
    if (f->raster) f->raster_ok = blade_gpu_raster(gr->blades, f->raster, &dd) && f->raster_ok;
    else blade_gpu_draw(gr->blades, &dd);
}

static void draw_billboards(grass_t *gr, frame_draw_t *f)
{
    const grass_view_t *v = f->v;
    const scene_grass_desc_t *g = &gr->scene->grass;
    blade_lod_t lod = g->lod; /* the cards' rule: grass.lod's, its width_px grass.bb_lod_width_px's */
    if (g->bb_lod_width_px > 0.0f) lod.width_px = g->bb_lod_width_px;
    bb_draw_desc_t d = {.view = *f->v,
                        .overlay = v->overlay == 1,
                        .gi = gr->gi_bind,
                        .lod = g->bb_lod ? &lod : NULL,
                        .focal_px = f->focal};
    if (gr->mode == SCENE_MODE_HYBRID) {
        d.fade_start = f->fade_lo;
        d.fade_end = f->fade_hi;
    }
    if (f->tiles || (grass_ground_of(gr) == GRASS_GROUND_WORLD)) { /* a world's ring ends at the canopy in every mode */
        d.far_start = f->far_lo;
        d.far_end = f->far_hi;
    }
    if (f->tiles) blade_tiles_slope(gr->tiles, &d.slope_map, &d.slope_grid, &d.slope_recover);
    if (f->raster) f->raster_ok = bb_field_raster(gr->bb, f->raster, &d) && f->raster_ok;
    else bb_field_draw(gr->bb, &d);
}

static void run_pass(grass_t *gr, frame_draw_t *f, grass_pass_kind_t kind)
{
    switch (kind) {
    case GRASS_PASS_GROUND:
        gfx_timer_begin(GFX_PASS_TERRAIN);
        ground_draw(gr->ground, f->v, f->v->inv_viewproj);
        gfx_timer_end();
        break;
    /* raster_begin takes the opaque depth (also read by occlusion culling). */
    case GRASS_PASS_RASTER_BEGIN: raster_begin(f->raster, f->target); break;
    case GRASS_PASS_TILES: draw_tiles(gr, f); break;
    case GRASS_PASS_BLADES: draw_blades(gr, f); break;
    case GRASS_PASS_BILLBOARDS: draw_billboards(gr, f); break;
    case GRASS_PASS_RASTER_END:
        if (gr->grass_depth) raster_end(f->raster, f->target);
        else raster_end_color(f->raster, f->target);
        break;
    case GRASS_PASS_KINDS: break;
    }
}

/* The canopy match (ground_match) after the grass of a hybrid frame's own
 * draw whose blades end in the canopy (no billboards between; blade mode on
 * a world ends in the canopy too, but its match ran into a segmentation
 * fault inside llvmpipe's compiled code under the sanitizers, not found:
 * docs/journal/2026-11-29-canopy-match.md), over the opaque
 * depth they were drawn on: the compute path's, or the hardware path's
 * resolve (a single-sample target keeps no copy of it: no match). */
static void match_canopy(grass_t *gr, const frame_draw_t *f, bool ring)
{
    if (!gr->match_frame || !f->tiles || ring || gr->reference || gr->mode != SCENE_MODE_HYBRID ||
        gr->scene->grass.canopy_match != SCENE_CANOPY_MATCH_ON)
        return;
    const gfx_target_t *t = f->target;
    GLuint depth = f->raster ? f->raster->opaque_depth.id : (t->resolve_fbo != t->fbo ? t->resolve_depth.id : 0);
    gfx_timer_begin(GFX_PASS_CANOPY_MATCH);
    ground_match(gr->ground, f->v, t, depth, grass_tiles_distance(gr), GRASS_SWITCH_FADE);
    gfx_timer_end();
}

/* The grass-shaded ground under the frame's thinned blades: the tiles' (to
 * their switch; with billboards beyond, nearer than them) or blade mode's
 * whole field (to its cull distance); none under billboards alone. */
static void set_ground_lod(grass_t *gr, const frame_draw_t *f, bool ring, bool field)
{
    if (!f->tiles && !field) {
        ground_set_lod(gr->ground, NULL, 0.0f, 0.0f, 0.0f, 0.0f);
        return;
    }
    blade_population_t pop = blade_population_defaults(&gr->scene->grass.population);
    float width = 0.5f * (pop.width[0] + pop.width[1]);
    ground_set_lod(gr->ground, &f->lod, width, f->focal, f->cull, ring ? f->fade_lo : INFINITY);
}

/* The passes of grass_pass_list that belong to `parts` (grass_part_t; 0:
 * all), in order, into the bound target. */
static void draw_passes(grass_t *gr, const grass_view_t *v, const gfx_target_t *target, scene_mode_t mode,
                        bool grass, unsigned parts)
{
    if (gr->views++ == 0) memcpy(gr->view_camera, v->camera, sizeof gr->view_camera);
    memcpy(gr->camera, v->camera, sizeof gr->camera);
    gr->drawn = true;
    frame_draw_t f = {.v = v, .target = target, .raster_ok = true};
    /* The compute path composites into the target's colour texture. */
    bool compute = gr->raster_compute && !v->wireframe && v->overlay == 0 && target->color.id && target->depth.id;
    f.raster = compute ? frame_raster(gr, target) : NULL;
    glPolygonMode(GL_FRONT_AND_BACK, v->wireframe ? GL_LINE : GL_FILL);
    scene_mode_t keep = gr->mode;
    gr->mode = mode;
    grass_pass_t passes[GRASS_PASS_KINDS];
    int n = grass_pass_list(&(grass_pass_desc_t){.mode = mode, .ground = grass_ground_of(gr),
                                                 .compute = f.raster != NULL, .reference = gr->reference,
                                                 .have_tiles = grass && gr->have_tiles,
                                                 .have_blades = grass && gr->have_blades,
                                                 .have_billboards = grass && gr->bb != NULL,
                                                 .billboards = gr->scene->grass.billboards},
                            passes);
    f.tiles = grass_pass_has(passes, n, GRASS_PASS_TILES); /* the hybrid's near blades, and its canopy */
    float reach = gr->tiles_reach > 0.0f ? gr->tiles_reach : grass_tiles_distance(gr);
    f.fade_lo = reach - GRASS_SWITCH_FADE;
    f.fade_hi = reach + GRASS_SWITCH_FADE;
    /* The canopy fades in beyond the billboards of the hybrid (or of a
     * world), or, without them (grass.billboards none, blade mode on a
     * world), where the blades fade out. */
    bool world = grass_ground_of(gr) == GRASS_GROUND_WORLD;
    bool ring = (f.tiles || world) && grass_pass_has(passes, n, GRASS_PASS_BILLBOARDS);
    f.far_lo = !ring ? f.fade_lo : gr->scene->grass.canopy_distance - GRASS_CANOPY_FADE;
    f.far_hi = !ring ? f.fade_hi : gr->scene->grass.canopy_distance + GRASS_CANOPY_FADE;
    ground_set_canopy_fade(gr->ground, f.tiles || ring ? f.far_lo : 0.0f, f.tiles || ring ? f.far_hi : 0.0f,
                           f.tiles && !ring);
    frame_lod(gr, &f);
    set_ground_lod(gr, &f, ring, grass_pass_has(passes, n, GRASS_PASS_BLADES) && !gr->reference);
    if (gr->canopy_all) ground_set_canopy_fade(gr->ground, 0.0f, 1e-3f, false);
    unsigned want = parts ? parts : GRASS_PART_GROUND | GRASS_PART_GRASS;
    for (int i = 0; i < n; i++)
        if (want & (passes[i].kind == GRASS_PASS_GROUND ? GRASS_PART_GROUND : GRASS_PART_GRASS))
            run_pass(gr, &f, passes[i].kind);
    if (want & GRASS_PART_GRASS) match_canopy(gr, &f, ring);
    gr->mode = keep;
    if (!f.raster_ok) {
        core_log_warn("compute rasterizer shaders unavailable (see above); drawing grass with the hardware path");
        gr->raster_compute = false;
    }
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
}

void grass_draw_target(grass_t *gr, const grass_view_t *v, const gfx_target_t *t, const grass_draw_as_t *as)
{
    if (!as) {
        gr->match_frame = true;
        draw_passes(gr, v, t, gr->mode, true, 0);
        gr->match_frame = false;
        return;
    }
    gr->canopy_all = as->canopy_all;
    gr->grass_depth = as->depth;
    gr->match_frame = !as->depth && !as->canopy_all && !as->no_grass && as->mode == gr->mode;
    gr->tiles_reach = as->tiles_distance;
    draw_passes(gr, v, t, as->mode, !as->no_grass, as->parts);
    gr->canopy_all = gr->grass_depth = gr->match_frame = false;
    gr->tiles_reach = 0.0f;
}

/* ---- the host's framebuffer and its GL state (grass.h's contract) ---- */
enum { STATE_UNITS = 16, STATE_TEXTURE_TARGETS = 5, STATE_BUFFERS = 9, STATE_ENABLES = 10 };
static const GLenum texture_targets[STATE_TEXTURE_TARGETS][2] = {
    {GL_TEXTURE_2D, GL_TEXTURE_BINDING_2D},
    {GL_TEXTURE_2D_ARRAY, GL_TEXTURE_BINDING_2D_ARRAY},
    {GL_TEXTURE_3D, GL_TEXTURE_BINDING_3D},
    {GL_TEXTURE_CUBE_MAP, GL_TEXTURE_BINDING_CUBE_MAP},
    {GL_TEXTURE_2D_MULTISAMPLE, GL_TEXTURE_BINDING_2D_MULTISAMPLE}};
static const GLenum buffer_targets[STATE_BUFFERS][2] = {
    {GL_ARRAY_BUFFER, GL_ARRAY_BUFFER_BINDING},
    {GL_DRAW_INDIRECT_BUFFER, GL_DRAW_INDIRECT_BUFFER_BINDING},
    {GL_DISPATCH_INDIRECT_BUFFER, GL_DISPATCH_INDIRECT_BUFFER_BINDING},
    {GL_SHADER_STORAGE_BUFFER, GL_SHADER_STORAGE_BUFFER_BINDING},
    {GL_UNIFORM_BUFFER, GL_UNIFORM_BUFFER_BINDING},
    {GL_ATOMIC_COUNTER_BUFFER, GL_ATOMIC_COUNTER_BUFFER_BINDING},
    {GL_PIXEL_PACK_BUFFER, GL_PIXEL_PACK_BUFFER_BINDING},
    {GL_PIXEL_UNPACK_BUFFER, GL_PIXEL_UNPACK_BUFFER_BINDING},
    {GL_COPY_READ_BUFFER, GL_COPY_READ_BUFFER_BINDING}};
static const GLenum state_enables[STATE_ENABLES] = {
    GL_DEPTH_TEST,   GL_BLEND,           GL_CULL_FACE,       GL_SAMPLE_ALPHA_TO_COVERAGE, GL_SCISSOR_TEST,
    GL_STENCIL_TEST, GL_POLYGON_OFFSET_FILL, GL_MULTISAMPLE, GL_RASTERIZER_DISCARD,      GL_PROGRAM_POINT_SIZE};

typedef struct gl_state_t {
    GLint program, vao, draw_fbo, read_fbo, viewport[4], depth_func, blend_src[2], blend_dst[2], blend_eq[2],
        polygon_mode[2], active_texture;
    GLint buffers[STATE_BUFFERS], textures[STATE_UNITS][STATE_TEXTURE_TARGETS];
    GLboolean depth_mask, color_mask[4], enables[STATE_ENABLES];
} gl_state_t;

static void state_save(gl_state_t *s)
{
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vao);
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s->draw_fbo);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s->read_fbo);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    glGetIntegerv(GL_DEPTH_FUNC, &s->depth_func);
    glGetIntegerv(GL_BLEND_SRC_RGB, &s->blend_src[0]);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &s->blend_src[1]);
    glGetIntegerv(GL_BLEND_DST_RGB, &s->blend_dst[0]);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &s->blend_dst[1]);
    glGetIntegerv(GL_BLEND_EQUATION_RGB, &s->blend_eq[0]);
    glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &s->blend_eq[1]);
    glGetIntegerv(GL_POLYGON_MODE, s->polygon_mode);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active_texture);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    glGetBooleanv(GL_COLOR_WRITEMASK, s->color_mask);
    for (int i = 0; i < STATE_ENABLES; i++) s->enables[i] = glIsEnabled(state_enables[i]);
    for (int i = 0; i < STATE_BUFFERS; i++) glGetIntegerv(buffer_targets[i][1], &s->buffers[i]);
    for (int u = 0; u < STATE_UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (int k = 0; k < STATE_TEXTURE_TARGETS; k++) glGetIntegerv(texture_targets[k][1], &s->textures[u][k]);
    }
}

static void state_restore(const gl_state_t *s)
{
    glUseProgram((GLuint)s->program);
    glBindVertexArray((GLuint)s->vao);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, (GLuint)s->draw_fbo);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, (GLuint)s->read_fbo);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glDepthFunc((GLenum)s->depth_func);
    glBlendFuncSeparate((GLenum)s->blend_src[0], (GLenum)s->blend_dst[0], (GLenum)s->blend_src[1],
                        (GLenum)s->blend_dst[1]);
    glBlendEquationSeparate((GLenum)s->blend_eq[0], (GLenum)s->blend_eq[1]);
    glPolygonMode(GL_FRONT_AND_BACK, (GLenum)s->polygon_mode[0]);
    glDepthMask(s->depth_mask);
    glColorMask(s->color_mask[0], s->color_mask[1], s->color_mask[2], s->color_mask[3]);
    for (int i = 0; i < STATE_ENABLES; i++) (s->enables[i] ? glEnable : glDisable)(state_enables[i]);
    for (int i = 0; i < STATE_BUFFERS; i++) glBindBuffer(buffer_targets[i][0], (GLuint)s->buffers[i]);
    for (int u = 0; u < STATE_UNITS; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)u);
        for (int k = 0; k < STATE_TEXTURE_TARGETS; k++) glBindTexture(texture_targets[k][0], (GLuint)s->textures[u][k]);
    }
    glActiveTexture((GLenum)s->active_texture);
}

/* The host's framebuffer as a gfx target: its depth texture when it is a
 * single-sample one, else a resolve copy grass keeps at its size (made
 * after the ground is drawn, for the occlusion tests). */
static bool host_target(grass_t *gr, const grass_target_t *t, gfx_target_t *out)
{
    int samples = t->samples > 1 ? t->samples : 1;
    *out = (gfx_target_t){.w = t->width, .h = t->height, .samples = samples, .fbo = t->fbo, .resolve_fbo = t->fbo,
                          .color = {.id = t->color_texture, .samples = samples},
                          .depth = {.id = t->depth_texture, .samples = samples}};
    out->resolve_depth = out->depth;
    if (t->depth_texture && samples == 1) return true;
    gfx_target_t *d = &gr->host_depth;
    if (!d->fbo || d->w != t->width || d->h != t->height) {
        gfx_target_destroy(d);
        *d = gfx_target_make(&(gfx_target_desc_t){.w = t->width, .h = t->height, .samples = 1,
                                                  .label = "grass.host_depth"});
        if (!d->fbo) return false;
    }
    out->resolve_fbo = d->fbo;
    out->resolve_depth = d->depth;
    return true;
}

void grass_draw(grass_t *gr, const grass_view_t *v, const grass_target_t *t)
{
    grass_draw_part(gr, v, t, GRASS_PART_ALL);
}

void grass_draw_part(grass_t *gr, const grass_view_t *v, const grass_target_t *t, grass_part_t part)
{
    gfx_ctx_t *prev = grass_enter(gr);
    gl_state_t saved;
    state_save(&saved);
    gfx_target_t target;
    if (!host_target(gr, t, &target)) {
        core_log_error("grass_draw: cannot make a %dx%d depth copy of the host's framebuffer", t->width, t->height);
        grass_leave(prev);
        return;
    }
    gfx_target_bind(&target);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    gr->match_frame = true;
    draw_passes(gr, v, &target, gr->mode, true, part);
    gr->match_frame = false;
    state_restore(&saved);
    grass_leave(prev);
}

/* bb: the billboard field's life (Orthmann, Rezk-Salama & Kolb 2009): the
 * desc's defaults and limits, bb_field_make in its stages (layout, octree,
 * programs, buffers, generation: bb_generate.c), bb_field_destroy, and the
 * read APIs (info, read, stats). The per-update passes are in
 * bb_update.c and bb_batch.c, drawing in bb_draw.c (bb_local.h lists the
 * files); bb.h has the overview. */
#include "billboard/bb_local.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

const char *const bb_tf_varyings[] = {"o_pos_angle", "o_growth_mess", "o_size", "o_layer_state",
                                             "o_recover",   "o_seed",        "o_pad",  NULL};

static int pass_objects(const bb_field_desc_t *d)
{
    return d->max_objects < BB_PASS_OBJECTS ? d->max_objects : BB_PASS_OBJECTS;
}

int bb_pass_objects(const bb_field_t *f) { return pass_objects(&f->desc); }

bb_field_desc_t bb_field_desc_defaults(const bb_field_desc_t *desc)
{
    bb_field_desc_t d = desc ? *desc : (bb_field_desc_t){0};
    if (d.density <= 0) d.density = BB_DEFAULT_DENSITY;
    if (d.size[0] <= 0) d.size[0] = BB_DEFAULT_WIDTH;
    if (d.size[1] <= 0) d.size[1] = BB_DEFAULT_HEIGHT;
    if (d.subdiv[0] <= 0) d.subdiv[0] = BB_DEFAULT_SUBDIV;
    if (d.subdiv[1] <= 0) d.subdiv[1] = BB_DEFAULT_SUBDIV;
    if (d.iterations <= 0) d.iterations = BB_DEFAULT_SPRING_ITERATIONS;
    if (d.r1 <= 0) d.r1 = 1.0f;
    if (d.r2 <= 0) d.r2 = 0.5f;
    if (d.cube_res <= 0) d.cube_res = BB_DEFAULT_CUBE_RESOLUTION;
    if (d.recover_time <= 0) d.recover_time = BB_DEFAULT_RECOVER_TIME;
    if (d.max_objects <= 0) d.max_objects = 8;
    if (d.max_deformed <= 0) d.max_deformed = 4096;
    if (d.octree_depth <= 0) d.octree_depth = 4;
    if (d.ring_reach <= 0) d.ring_reach = BB_RING_REACH_DEFAULT;
    if (d.ring_cell <= 0) d.ring_cell = BB_RING_CELL_DEFAULT;
    d.wind = bb_wind_desc_defaults(&d.wind);
    d.layout.seed = d.seed;
    if (d.layout.clump.size[0] <= 0.0f) d.layout.clump.size[0] = d.size[0];
    if (d.layout.clump.size[1] <= 0.0f) d.layout.clump.size[1] = d.size[1];
    if (d.layout.clump.depth <= 0.0f) d.layout.clump.depth = 1.5707963f / (d.layout.clump.size[0] * d.density);
    d.layout = bb_layout_desc_defaults(&d.layout);
    return d;
}

void bb_point_frame(const bb_point_t *p, vec3 right, vec3 up)
{
    glm_vec3_copy((float *)p->growth, up);
    vec3 t = {cosf(p->angle), 0.0f, sinf(p->angle)};
    float d = glm_vec3_dot(t, up);
    for (int k = 0; k < 3; k++) right[k] = t[k] - up[k] * d;
    if (glm_vec3_dot(right, right) < 1e-6f) {
        glm_vec3_copy((vec3){-sinf(p->angle), 0.0f, cosf(p->angle)}, t);
        d = glm_vec3_dot(t, up);
        for (int k = 0; k < 3; k++) right[k] = t[k] - up[k] * d;
    }
    glm_vec3_scale(right, 1.0f / sqrtf(glm_vec3_dot(right, right)), right);
}

void bb_set_wind(GLuint prog, const bb_wind_desc_t *w)
{
    gfx_program_t gp = {.id = prog};
    glProgramUniform2f(prog, gfx_uniform(gp, "u_wind.dir"), w->dir[0], w->dir[1]);
    glProgramUniform1f(prog, gfx_uniform(gp, "u_wind.strength"), w->strength);
    glProgramUniform1f(prog, gfx_uniform(gp, "u_wind.omega"), w->omega);
    glProgramUniform1f(prog, gfx_uniform(gp, "u_wind.wavenumber"), w->wavenumber);
}

static void setup_points_vao(GLuint vao, GLuint buffer)
{
    glVertexArrayVertexBuffer(vao, 0, buffer, 0, sizeof(bb_point_t));
    static const struct { int n; GLenum type; bool integer; GLuint offset; } at[7] = {
        {4, GL_FLOAT, false, 0}, {4, GL_FLOAT, false, 16}, {2, GL_FLOAT, false, 32}, {2, GL_UNSIGNED_INT, true, 40},
        {1, GL_FLOAT, false, 48}, {1, GL_UNSIGNED_INT, true, 52}, {2, GL_UNSIGNED_INT, true, 56}};
    for (GLuint k = 0; k < 7; k++) {
        glEnableVertexArrayAttrib(vao, k);
        if (at[k].integer) glVertexArrayAttribIFormat(vao, k, at[k].n, at[k].type, at[k].offset);
        else glVertexArrayAttribFormat(vao, k, at[k].n, at[k].type, GL_FALSE, at[k].offset);
        glVertexArrayAttribBinding(vao, k, 0);
    }
}

static double wall_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

const char *bb_make_stage_name(int stage)
{
    static const char *const names[BB_MAKE_STAGES] = {"layout", "programs", "generate", "spheres"};
    assert(stage >= 0 && stage < BB_MAKE_STAGES);
    return names[stage];
}

/* Adds the wall time since *mark to stage `stage` and moves the mark. */
static void stage_done(bb_field_t *f, int stage, double *mark)
{
    double now = wall_ms();
    f->make_stage_ms[stage] += (float)(now - *mark);
    *mark = now;
}

/* The desc's ranges and the GPU's geometry-shader limits (false, logged,
 * when the field cannot be made). *tile: generation tiles of tile x tile
 * candidate cells; *render_verts: bb_render.geom's output vertices. */
static bool check_limits(const bb_field_desc_t *d, int *tile, int *render_verts, bool quiet)
{
    if (d->max_objects > BB_MAX_OBJECTS || d->subdiv[0] < BB_SUBDIV_MIN || d->subdiv[0] > BB_SUBDIV_MAX ||
        d->subdiv[1] < BB_SUBDIV_MIN || d->subdiv[1] > BB_SUBDIV_MAX || d->octree_depth > BB_OCTREE_MAX_DEPTH) {
        if (!quiet)
            core_log_error("bb_field_make: max_objects %d (at most %d), subdiv %dx%d (%d..%d), octree depth %d "
                           "(at most %d) out of range", d->max_objects, BB_MAX_OBJECTS, d->subdiv[0], d->subdiv[1],
                           BB_SUBDIV_MIN, BB_SUBDIV_MAX, d->octree_depth, BB_OCTREE_MAX_DEPTH);
        return false;
    }
    int n = d->subdiv[0], m = d->subdiv[1];
    GLint max_verts = 0, max_comps = 0;
    glGetIntegerv(GL_MAX_GEOMETRY_OUTPUT_VERTICES, &max_verts);
    glGetIntegerv(GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS, &max_comps);
    *render_verts = (m - 1) * 2 * n > 4 ? (m - 1) * 2 * n : 4;
    /* bb_render.geom's vertex: g_world, g_normal, g_uvl (3 each), g_tint,
     * g_card, g_overlay (1 each) and gl_Position (4) = 16 components; with
     * BB_GI g_amb_front and g_amb_back (3 each) too. */
    int comps = *render_verts * (d->gi ? 22 : 16);
    if (*render_verts > max_verts || comps > max_comps) {
        if (!quiet)
            core_log_error("bb_field_make: a %dx%d mesh needs %d geometry-shader vertices (%d components%s); "
                           "this GPU allows %d (%d)", n, m, *render_verts, comps, d->gi ? " with grass.gi" : "",
                           max_verts, max_comps);
        return false;
    }
    /* Generation tiles of 2 x 2 candidate cells: at most 4 points (64
     * components) per geometry-shader invocation. The GPU's limit allowed
     * 8 x 8 (1,024 components), which ran at a fraction of the rate on the
     * H100: meadow_large generation 423 ms at 8 x 8, 139 ms at 4 x 4, 69 ms
     * at 2 x 2, the same 384,670 billboards. (llvmpipe goes the other way,
     * 48 -> 102 ms on meadow.json: more invocations.) */
    int tile_points = max_comps / 16 < max_verts ? max_comps / 16 : max_verts;
    *tile = (int)floorf(sqrtf((float)tile_points));
    *tile = *tile > 2 ? 2 : *tile;
    return true;
}

/* The points buffer's capacity: the candidate cells of a heightfield, or
 * of the seeding triangles of a mesh terrain (*tris, their frames). */
static bool count_candidates(bb_field_t *f, const terrain_mesh_t *t, bb_gen_tri_t **tris)
{
    double cap;
    if (t->grid_res > 0) {
        float ext_x = t->aabb_max[0] - t->aabb_min[0], ext_z = t->aabb_max[2] - t->aabb_min[2];
        f->cells[0] = (int)ceilf(ext_x / f->gen.spacing);
        f->cells[1] = (int)ceilf(ext_z / f->gen.spacing);
        cap = (double)f->cells[0] * (double)f->cells[1];
    } else if (!(*tris = bb_mesh_tris(t, f->gen.spacing, &f->triangles, &cap))) {
        return false;
    }
    if (cap > (double)(1u << 26)) {
        core_log_error("bb_field_make: %.0f candidate billboards exceed the limit of %u; lower grass.billboard_density",
                       cap, 1u << 26);
        return false;
    }
    f->capacity = (int)cap > 0 ? (int)cap : 1;
    return true;
}

/* The octree over the terrain's box and the per-leaf scratch arrays. */
static bool make_tree(bb_field_t *f, const terrain_mesh_t *t)
{
    const bb_field_desc_t *d = &f->desc;
    float ymin = t->aabb_min[1], ymax = t->aabb_max[1];
    float pad = 0.01f + 1e-3f * (ymax - ymin);
    float margin = 1.4f * d->size[1] + 0.6f * d->size[0] + d->wind.strength + 0.05f;
    bb_octree_desc_t od = {.min = {t->aabb_min[0], ymin - pad, t->aabb_min[2]},
                           .max = {t->aabb_max[0], ymax + pad, t->aabb_max[2]},
                           .max_depth = d->octree_depth,
                           .margin = margin > 1.0f ? margin : 1.0f};
    if (!bb_octree_build(&f->tree, &od)) return false;
    f->ranges = malloc(sizeof *f->ranges * (size_t)f->tree.leaf_count);
    f->sort_keys = malloc(sizeof *f->sort_keys * (size_t)f->tree.leaf_count);
    f->firsts = malloc(sizeof *f->firsts * (size_t)f->tree.leaf_count);
    f->counts_gl = malloc(sizeof *f->counts_gl * (size_t)f->tree.leaf_count);
    f->recover_ranges = malloc(sizeof *f->recover_ranges * 4 * (size_t)f->tree.leaf_count);
    if (!f->ranges || !f->sort_keys || !f->firsts || !f->counts_gl || !f->recover_ranges) {
        core_log_error("out of memory");
        return false;
    }
    return true;
}

/* The programs of a field of desc d (resolved): the defines of its mesh
 * size and limits, and the descs of what make_programs builds (the ring's
 * generation program is bb_ring_make's: n is 4 on world terrains, 5 with
 * the generation program; triangles: generation per triangle, on mesh
 * terrains). */
typedef struct field_programs_t {
    char defines[sizeof((bb_field_t *)0)->defines];
    char gen_defines[sizeof((bb_field_t *)0)->defines + 32];
    char collide_defines[sizeof((bb_field_t *)0)->defines + 32];
    gfx_program_desc_t d[5];
    int n;
} field_programs_t;

static bool field_programs(const bb_field_desc_t *d, int tile, int render_verts, field_programs_t *p)
{
    bool ring_on = d->terrain->type == TERRAIN_WORLD, triangles = !ring_on && d->terrain->grid_res <= 0;
    snprintf(p->defines, sizeof p->defines,
             "#define BB_N %d\n#define BB_M %d\n#define BB_MAX_CUBES %d\n#define BB_TILE %d\n"
             "#define BB_TILE_POINTS %d\n#define BB_RENDER_VERTS %d\n%s%s",
             d->subdiv[0], d->subdiv[1], pass_objects(d), tile, tile * tile, render_verts,
             /* the view cards' code only where they are on: compiled in, unused, it
              * cost bb.raster 22 % on the H100 (meadow_large billboard mode) */
             d->layout.views.on ? "#define BB_VIEW_CARDS 1\n" : "", d->gi ? "#define BB_GI 1\n" : "");
    snprintf(p->gen_defines, sizeof p->gen_defines, "%s%s", p->defines, triangles ? "#define BB_GEN_TRIANGLES\n" : "");
    /* the ring's collide pass stands billboards on the world's function */
    if (!ring_on) snprintf(p->collide_defines, sizeof p->collide_defines, "%s", p->defines);
    else if (!bb_ring_defines(p->defines, p->collide_defines, sizeof p->collide_defines)) return false;
    const char *defines = p->defines;
    gfx_program_desc_t pds[5] = {
        {.vs = "billboard/bb_point.vert", .gs = "billboard/bb_collide.geom", .defines = p->collide_defines,
         .tf_varyings = bb_tf_varyings, .label = "bb.collide"},
        {.cs = "billboard/bb_recover.comp", .defines = defines, .label = "bb.recover"},
        {.vs = "billboard/bb_cube.vert", .fs = "billboard/bb_cube.frag", .defines = defines, .label = "bb.cube"},
        {.cs = "billboard/bb_slope.comp", .defines = defines, .label = "bb.slope"},
        {.vs = "billboard/bb_tile.vert", .gs = "billboard/bb_generate.geom", .defines = p->gen_defines,
         .tf_varyings = bb_tf_varyings, .label = "bb.generate"}};
    memcpy(p->d, pds, sizeof pds);
    p->n = ring_on ? 4 : 5;
    return true;
}

/* The programs (and occlusion culling's), built side by side, with the
 * defines of field_programs in f->defines. */
static bool make_programs(bb_field_t *f, int tile, int render_verts)
{
    const bb_field_desc_t *d = &f->desc;
    field_programs_t p;
    if (!field_programs(d, tile, render_verts, &p)) return false;
    snprintf(f->defines, sizeof f->defines, "%s", p.defines);
    gfx_program_t progs[5] = {{0}};
    if (!gfx_programs_make(p.n, p.d, progs)) {
        for (int k = 0; k < 5; k++) gfx_program_destroy(&progs[k]);
        return false;
    }
    f->collide_prog = progs[0];
    f->recover_prog = progs[1];
    f->cube_prog = progs[2];
    f->slope_prog = progs[3];
    if (!f->ring_on) f->gen_prog = progs[4];
    if (f->ring_on) {
        terrain_world_gpu_t w = terrain_world_gpu(&d->terrain->world);
        gfx_world_height_uniforms(f->collide_prog, w.keys, TERRAIN_WORLD_LAYERS, w.height);
    }
    return !d->occlusion || bb_occlusion_make(f);
}

void bb_field_prefetch(const bb_field_desc_t *desc, const raster_desc_t *raster)
{
    bb_field_desc_t d = bb_field_desc_defaults(desc);
    int tile = 0, render_verts = 0;
    field_programs_t p;
    if (!d.terrain || !check_limits(&d, &tile, &render_verts, true) || !field_programs(&d, tile, render_verts, &p))
        return;
    gfx_programs_prefetch(p.n, p.d);
    if (d.terrain->type == TERRAIN_WORLD) bb_ring_prefetch(p.defines);
    if (raster) raster_program_prefetch(raster, "billboard/bb_raster.comp", p.defines);
}

/* The pool with every slot free, the points buffers, the objects uniform
 * buffer, the cube-map array and its target, vertex arrays, transform
 * feedback and the pool readback. */
static bool make_buffers(bb_field_t *f)
{
    const bb_field_desc_t *d = &f->desc;
    size_t pool_words = 4 + (size_t)d->max_deformed;
    uint32_t *pool = calloc(pool_words, sizeof *pool);
    if (!pool) return false;
    pool[0] = (uint32_t)d->max_deformed;
    for (int s = 0; s < d->max_deformed; s++) pool[4 + s] = (uint32_t)(d->max_deformed - 1 - s);
    f->pool = gfx_buffer_make(&(gfx_buffer_desc_t){.size = pool_words * 4, .data = pool, .label = "bb.pool"});
    size_t ranges = f->ring_on ? (size_t)f->ring.side * (size_t)f->ring.side : (size_t)f->tree.leaf_count;
    f->recover_range_buf = gfx_buffer_make(&(gfx_buffer_desc_t){.size = ranges * 16, .dynamic = true,
                                                                .label = "bb.recover_ranges"});
    free(pool);
    f->meshes = gfx_buffer_make(&(gfx_buffer_desc_t){
        .size = (size_t)d->max_deformed * (size_t)(d->subdiv[0] * d->subdiv[1]) * 16, .label = "bb.meshes"});
    f->points = gfx_buffer_make(&(gfx_buffer_desc_t){.size = (size_t)f->capacity * sizeof(bb_point_t),
                                                     .label = "bb.points"});
    /* The ring's collide pass takes at most ring_collide_slots slots (bb_ring.c). */
    size_t scratch = f->ring_on ? (size_t)f->ring_collide_slots * (size_t)(f->ring.cand * f->ring.cand)
                                : (size_t)f->capacity;
    f->scratch = gfx_buffer_make(&(gfx_buffer_desc_t){.size = scratch * sizeof(bb_point_t),
                                                      .label = "bb.points_scratch"});
    GLint align = 256;
    glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &align);
    align = align > 0 ? align : 256;
    f->objects_stride = sizeof(bb_object_gpu_t) * (size_t)bb_pass_objects(f);
    f->objects_stride = (f->objects_stride + (size_t)align - 1) / (size_t)align * (size_t)align;
    f->objects_size = 4 * f->objects_stride;
    f->objects = gfx_buffer_make(&(gfx_buffer_desc_t){.size = f->objects_size, .dynamic = true,
                                                      .label = "bb.objects"});
    f->cubes = gfx_texture_make(&(gfx_texture_desc_t){.target = GL_TEXTURE_2D_ARRAY, .w = d->cube_res,
                                                      .h = d->cube_res, .layers = 6 * d->max_objects,
                                                      .format = GL_RGBA32F, .filter = GL_NEAREST,
                                                      .label = "bb.cubes"});
    if (f->cubes.id) f->cube_target = gfx_layered_target_make(f->cubes, "bb.cube_target");
    f->points_vao = gfx_vertex_array_make("bb.points_vao");
    f->empty_vao = gfx_vertex_array_make("bb.empty_vao");
    f->tf = gfx_transform_feedback_make("bb.tf");
    if (!f->pool.id || !f->recover_range_buf.id || !f->meshes.id || !f->points.id || !f->scratch.id || !f->objects.id || !f->cubes.id ||
        !f->cube_target.fbo)
        return false;
    f->readback = gfx_readback_make(16, BB_READBACK_SLOTS, "bb.pool_readback");
    if (!f->readback.depth) return false;
    setup_points_vao(f->points_vao, f->points.id);
    return true;
}

bb_field_t *bb_field_make(const bb_field_desc_t *desc)
{
    double t_start = wall_ms(), mark = t_start;
    bb_field_t *f = calloc(1, sizeof *f);
    if (!f) {
        core_log_error("out of memory for a billboard field");
        return NULL;
    }
    bb_gen_tri_t *tris = NULL; /* mesh terrains: generation per triangle */
    f->desc = bb_field_desc_defaults(desc);
    const bb_field_desc_t *d = &f->desc;
    const terrain_mesh_t *t = d->terrain;
    f->ring_on = t && t->type == TERRAIN_WORLD;
    assert(t && (f->ring_on || (t->positions && t->index_count >= 3)));
    f->desc.occlusion = f->desc.occlusion && !f->ring_on; /* the ring's cells are culled as boxes */
    int tile = 0, render_verts = 0;
    if (!check_limits(d, &tile, &render_verts, false)) goto fail;
    f->gen = bb_gen_desc_defaults(&(bb_gen_desc_t){
        .spacing = 1.0f / sqrtf(d->density), .origin = {t->aabb_min[0], t->aabb_min[2]}, .width = d->size[0],
        .height = d->size[1], .seed = d->placement_seed ? d->placement_seed : d->seed});
    if (!bb_upload_layout(f)) goto fail;
    stage_done(f, BB_MAKE_LAYOUT, &mark);
    if (f->ring_on) { /* world terrains: cells are generated as the camera follows (bb_ring.c) */
        if (!make_programs(f, tile, render_verts) || !bb_ring_make(f, tile) || !make_buffers(f)) goto fail;
        f->billboards = f->capacity;
        stage_done(f, BB_MAKE_PROGRAMS, &mark);
        f->make_ms = (float)(wall_ms() - t_start);
        return f;
    }
    if (!count_candidates(f, t, &tris) || !make_tree(f, t) || !bb_upload_heights(f, t) ||
        !make_programs(f, tile, render_verts))
        goto fail;
    stage_done(f, BB_MAKE_PROGRAMS, &mark);
    if (!make_buffers(f) || !bb_generate(f, t, tris, tile)) goto fail;
    free(tris);
    tris = NULL;
    stage_done(f, BB_MAKE_GENERATE, &mark);
    if (!bb_read_spheres(f)) goto fail;
    stage_done(f, BB_MAKE_SPHERES, &mark);
    f->make_ms = (float)(wall_ms() - t_start);
    return f;
fail:
    free(tris);
    bb_field_destroy(f);
    return NULL;
}

void bb_field_destroy(bb_field_t *f)
{
    if (!f) return;
    gfx_texture_destroy(&f->extent);
    gfx_texture_destroy(&f->direction);
    gfx_texture_destroy(&f->messiness);
    gfx_texture_destroy(&f->clumps);
    gfx_texture_destroy(&f->heights);
    gfx_texture_destroy(&f->cubes);
    if (f->cube_target.fbo) gfx_layered_target_destroy(&f->cube_target);
    gfx_buffer_destroy(&f->points);
    gfx_buffer_destroy(&f->scratch);
    gfx_buffer_destroy(&f->pool);
    gfx_buffer_destroy(&f->meshes);
    gfx_buffer_destroy(&f->objects);
    gfx_buffer_destroy(&f->counts);
    gfx_readback_destroy(&f->readback);
    gfx_vertex_array_destroy(&f->points_vao);
    gfx_vertex_array_destroy(&f->empty_vao);
    gfx_transform_feedback_destroy(&f->tf);
    gfx_program_destroy(&f->gen_prog);
    gfx_program_destroy(&f->collide_prog);
    gfx_program_destroy(&f->recover_prog);
    gfx_program_destroy(&f->render_prog);
    raster_program_destroy(&f->raster_prog);
    gfx_program_destroy(&f->quad_prog);
    gfx_program_destroy(&f->cube_prog);
    gfx_program_destroy(&f->slope_prog);
    bb_occlusion_destroy(f);
    bb_ring_destroy(f);
    bb_octree_free(&f->tree);
    free(f->ranges);
    free(f->sort_keys);
    free(f->recover_ranges);
    gfx_buffer_destroy(&f->recover_range_buf);
    free(f->firsts);
    free(f->counts_gl);
    free(f->spheres);
    bb_batch_plan_t *pl = &f->plan;
    free(pl->range_start), free(pl->obj_count), free(pl->obj), free(pl->first), free(pl->size);
    free(f);
}

double bb_range_total(const GLsizei *size, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++) s += (double)size[i];
    return s;
}

int bb_merge_ranges(bb_field_t *f, int count)
{
    int k = 0;
    for (int i = 0; i < count; i++) {
        const bb_range_t *r = &f->ranges[i];
        if (k > 0 && (uint32_t)(f->firsts[k - 1] + f->counts_gl[k - 1]) == r->first) {
            f->counts_gl[k - 1] += (GLsizei)r->count;
        } else {
            f->firsts[k] = (GLint)r->first;
            f->counts_gl[k] = (GLsizei)r->count;
            k++;
        }
    }
    return k;
}


void bb_field_follow(bb_field_t *f, const float camera[3])
{
    if (f->ring_on) bb_ring_follow(f, camera);
}

int bb_field_ring_slot(const bb_field_t *f, const int32_t cell[2])
{
    return f->ring_on ? bb_ring_window_find(&f->ring, cell) : -1;
}

void bb_field_stats(const bb_field_t *f, bool wait, bb_stats_t *out)
{
    memset(out, 0, sizeof *out);
    out->billboards = f->billboards;
    out->occluded = f->occluded_last;
    const bb_octree_t *t = &f->tree;
    for (int k = 0; k < t->leaf_count; k++) {
        int node = bb_octree_leaf_node(t, (uint32_t)k);
        if (t->count[node]) out->leaves[t->state[node]]++;
    }
    for (int s = 0; f->ring_on && s < f->ring.side * f->ring.side; s++)
        if (f->ring.held[s][0] != BB_RING_NONE) out->leaves[f->ring.state[s]]++;
    out->pool_capacity = f->desc.max_deformed;
    out->generate_ms = f->generate_ms;
    out->make_ms = f->make_ms;
    memcpy(out->make_stage_ms, f->make_stage_ms, sizeof out->make_stage_ms);
    out->batches = f->batches_last;
    out->objects_dropped = f->dropped;
    out->objects_hidden = f->hidden_last;
    out->occlusion_hidden = bb_occlusion_hidden(f);
    if (!wait) {
        out->deformed = f->deformed_last;
        out->pool_exhausted = f->exhausted_last;
    } else {
        uint32_t hdr[2];
        gfx_buffer_read(f->pool, 0, sizeof hdr, hdr);
        out->deformed = f->desc.max_deformed - (int32_t)hdr[0];
        out->pool_exhausted = (int)hdr[1];
    }
    long mesh = 2L * (f->desc.subdiv[0] - 1) * (f->desc.subdiv[1] - 1);
    out->triangles = (long)(out->billboards - out->deformed) * 2 + (long)out->deformed * mesh;
}


void bb_field_info(const bb_field_t *f, bb_field_info_t *out)
{
    *out = (bb_field_info_t){.desc = f->desc,
                             .gen = f->gen,
                             .billboards = f->billboards,
                             .capacity = f->capacity,
                             .cells = {f->cells[0], f->cells[1]},
                             .triangles = f->triangles,
                             .mesh_vertices = f->desc.subdiv[0] * f->desc.subdiv[1],
                             .sphere_max = f->sphere_max,
                             .ring_side = f->ring.side,
                             .ring_cand = f->ring.cand,
                             .ring_generated = f->ring_generated,
                             .extent_texture = f->extent.id,
                             .time = f->time,
                             .tree = &f->tree};
}

bool bb_field_read(const bb_field_t *f, bb_data_t what, size_t first, size_t count, void *out)
{
    const bb_field_desc_t *d = &f->desc;
    size_t res = (size_t)d->cube_res, limit = 0, bytes = 0;
    gfx_buffer_t buf = {0};
    switch (what) {
    case BB_DATA_POINTS: buf = f->points, limit = (size_t)f->billboards, bytes = sizeof(bb_point_t); break;
    case BB_DATA_MESHES:
        buf = f->meshes, limit = (size_t)d->max_deformed, bytes = 16 * (size_t)(d->subdiv[0] * d->subdiv[1]);
        break;
    case BB_DATA_POOL: buf = f->pool, limit = 4 + (size_t)d->max_deformed, bytes = 4; break;
    case BB_DATA_CUBES: limit = 6 * (size_t)d->max_objects, bytes = 16 * res * res; break;
    }
    if (first > limit || count > limit - first) return false;
    if (count == 0) return true;
    if (what != BB_DATA_CUBES) return gfx_buffer_read(buf, first * bytes, count * bytes, out);
    glGetTextureSubImage(f->cubes.id, 0, 0, 0, (GLint)first, (GLsizei)res, (GLsizei)res, (GLsizei)count, GL_RGBA,
                         GL_FLOAT, (GLsizei)(count * bytes), out);
    return true;
}

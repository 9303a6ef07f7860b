/* ground: uploads a terrain mesh and draws it (lit soil-and-grass ground),
 * and draws the sky gradient behind everything (ground.h). A world terrain
 * (no vertices) is drawn as a clipmap (terrain/terrain_clipmap.h): one vertex
 * grid of integer coordinates, five index ranges, a draw per level of
 * terrain_world.vert, displaced by world_height; the same terrain.frag. */
#include "ground/ground.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ground/ground_match.h"

#include "blade/blade.h"
#include "common/bindings_ground.glsl"
#include "terrain/terrain_clipmap.h"

/* The terrain, and in the hybrid the ground canopy it is shaded as beyond
 * the billboards. */
struct ground_t {
    gfx_buffer_t vbo, ibo;
    GLuint vao, empty_vao;
    int index_count;
    float edge; /* m, the mesh's longest triangle edge (the canopy's frustum margin) */
    /* World terrains (TERRAIN_WORLD): the clipmap's levels and index ranges
     * (its arrays freed once uploaded: vbo holds the grid, ibo the ranges);
     * prog is terrain_world.vert with the world's uniforms (terrain_world_gpu). */
    bool world;
    terrain_clipmap_t clipmap;
    gfx_program_t prog, sky;
    gfx_texture_t noise; /* terrain.frag's value noise lattice (make_noise) */
    /* Ground canopy: its table (blade_canopy_pack's texture, its rows,
     * poses, first sun elevation, top and largest wind), the winds that
     * pick its poses, the extent map that thins it (borrowed), and this
     * frame's fade (start, end; end 0: none) and whether it continues the
     * tiles' blades under their overhang. */
    gfx_texture_t canopy;
    int canopy_rows, canopy_poses;
    float canopy_sun0, canopy_top, canopy_wind, canopy_gravity;
    blade_wind_t winds[BLADE_MAX_WINDS];
    int wind_count;
    GLuint extent;
    float extent_origin[2], extent_spacing;
    float canopy_fade[2];
    bool canopy_overhang;
    /* Grass-shaded ground under thinned blades (ground_set_lod): on, the
     * rule, its frame values and where it ends. */
    bool lod_on;
    blade_lod_t lod;
    float lod_width, lod_focal, lod_cull, lod_far;
    gi_bind_t gi;
    /* The canopy match (ground_match): its buffer (gain, then the frame's
     * and the canopy's sums: canopy_match.comp's layout) and programs (made
     * by the first ground_match: measure on single- and multisampled
     * targets, step). */
    gfx_buffer_t match, match_gain; /* the state; a copy of its gain the terrain reads */
    gfx_program_t match_measure[2], match_step;
    /* The terrain's normals for the match: a heightfield's vertex normals
     * and heights (the tiles' ground texture, borrowed: ground_set_grid;
     * its cells a side, the field's half side), or the world's height
     * function. */
    GLuint grid;
    int grid_res;
    float grid_half;
    terrain_world_gpu_t world_fn;
    bool match_tried;
};

/* The match buffer at rest: gains 1, no sums. */
static const ground_match_state_t match_rest = {.gain = {1.0f, 1.0f, 1.0f, 1.0f}};

/* The lattice of terrain.frag's value noise: at integer point (i, j) the
 * hash it hashed there per fragment before (core_hash_float of i 73856093
 * xor j 19349663), for i, j in [0, GROUND_NOISE_SIZE), repeating. */
static bool make_noise(ground_t *t)
{
    enum { N = GROUND_NOISE_SIZE };
    float *lattice = malloc(sizeof(float) * N * N);
    if (!lattice) return false;
    for (uint32_t j = 0; j < N; j++)
        for (uint32_t i = 0; i < N; i++) lattice[j * N + i] = core_hash_float(i * 73856093u ^ j * 19349663u);
    t->noise = gfx_texture_make(&(gfx_texture_desc_t){.w = N, .h = N, .format = GL_R32F, .wrap = GL_REPEAT,
                                                      .data = lattice, .upload_format = GL_RED,
                                                      .upload_type = GL_FLOAT, .label = "terrain.noise"});
    free(lattice);
    return t->noise.id != 0;
}

/* The terrain's program (desc) and the sky's, built side by side. */
static bool make_programs(ground_t *t, const gfx_program_desc_t *terrain)
{
    gfx_program_t progs[2];
    bool ok = gfx_programs_make(
        2, (gfx_program_desc_t[2]){*terrain, {.vs = "ground/sky.vert", .fs = "ground/sky.frag", .label = "sky.program"}},
        progs);
    t->prog = progs[0];
    t->sky = progs[1];
    t->empty_vao = gfx_vertex_array_make("sky.vao");
    return ok;
}

/* The clipmap's grid and index ranges on the GPU and the world program. */
static bool make_world(ground_t *t, const terrain_mesh_t *mesh)
{
    t->world = true;
    terrain_clipmap_t *c = &t->clipmap;
    if (!terrain_clipmap_make(c, &(terrain_clipmap_desc_t){0})) return false;
    t->vbo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof(uint16_t) * 2 * c->vertex_count, .data = c->grid,
                                                  .label = "terrain.clipmap.grid"});
    t->ibo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof(uint32_t) * c->index_count, .data = c->indices,
                                                  .label = "terrain.clipmap.indices"});
    free(c->grid);
    free(c->indices);
    c->grid = NULL;
    c->indices = NULL;
    t->vao = gfx_vertex_array_make("terrain.clipmap.vao");
    glVertexArrayVertexBuffer(t->vao, 0, t->vbo.id, 0, 2 * sizeof(uint16_t));
    glVertexArrayElementBuffer(t->vao, t->ibo.id);
    glEnableVertexArrayAttrib(t->vao, 0);
    glVertexArrayAttribIFormat(t->vao, 0, 2, GL_UNSIGNED_SHORT, 0);
    glVertexArrayAttribBinding(t->vao, 0, 0);
    bool ok = make_programs(t, &(gfx_program_desc_t){.vs = "ground/terrain_world.vert", .fs = "ground/terrain.frag",
                                                      .label = "terrain.world.program"});
    t->world_fn = terrain_world_gpu(&mesh->world);
    if (t->prog.id) gfx_world_height_uniforms(t->prog, t->world_fn.keys, TERRAIN_WORLD_LAYERS, t->world_fn.height);
    return ok && t->vbo.id && t->ibo.id;
}

/* A terrain mesh's interleaved vertices, indices and program. */
static bool make_mesh(ground_t *t, const terrain_mesh_t *mesh)
{
    size_t nv = mesh->vertex_count;
    float *interleaved = malloc(nv * 8 * sizeof(float));
    if (!interleaved) return false;
    for (size_t i = 0; i < nv; i++) {
        memcpy(interleaved + i * 8, mesh->positions + i * 3, 3 * sizeof(float));
        memcpy(interleaved + i * 8 + 3, mesh->normals + i * 3, 3 * sizeof(float));
        memcpy(interleaved + i * 8 + 6, mesh->uvs + i * 2, 2 * sizeof(float));
    }
    t->vbo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = nv * 8 * sizeof(float), .data = interleaved,
                                                  .label = "terrain.vertices"});
    free(interleaved);
    t->ibo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = mesh->index_count * sizeof(uint32_t),
                                                  .data = mesh->indices, .label = "terrain.indices"});
    t->index_count = (int)mesh->index_count;
    for (uint32_t i = 0; i < mesh->index_count; i++) {
        const float *a = mesh->positions + 3 * mesh->indices[i];
        const float *b = mesh->positions + 3 * mesh->indices[i % 3 == 2 ? i - 2 : i + 1];
        float d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
        t->edge = fmaxf(t->edge, sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
    }
    t->vao = gfx_vertex_array_make("terrain.vao");
    glVertexArrayVertexBuffer(t->vao, 0, t->vbo.id, 0, 8 * sizeof(float));
    glVertexArrayElementBuffer(t->vao, t->ibo.id);
    for (int a = 0; a < 3; a++) {
        static const int sizes[3] = {3, 3, 2}, offsets[3] = {0, 3, 6};
        glEnableVertexArrayAttrib(t->vao, (GLuint)a);
        glVertexArrayAttribFormat(t->vao, (GLuint)a, sizes[a], GL_FLOAT, GL_FALSE,
                                  (GLuint)(offsets[a] * sizeof(float)));
        glVertexArrayAttribBinding(t->vao, (GLuint)a, 0);
    }
    bool ok = make_programs(t, &(gfx_program_desc_t){.vs = "ground/terrain.vert", .fs = "ground/terrain.frag",
                                                      .label = "terrain.program"});
    return ok && t->vbo.id && t->ibo.id;
}

ground_t *ground_make(const terrain_mesh_t *mesh)
{
    ground_t *t = calloc(1, sizeof *t);
    if (!t) return NULL;
    t->match = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof match_rest, .data = &match_rest, .dynamic = true,
                                                    .label = "terrain.canopy.match"});
    t->match_gain = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof match_rest.gain, .data = match_rest.gain,
                                                         .dynamic = true, .label = "terrain.canopy.match_gain"});
    bool made = mesh->type == TERRAIN_WORLD ? make_world(t, mesh) : make_mesh(t, mesh);
    if (made && make_noise(t) && t->match.id && t->match_gain.id) return t;
    ground_destroy(t);
    return NULL;
}

void ground_set_canopy(ground_t *t, const blade_canopy_t *c, GLuint extent, const float origin[2], float spacing)
{
    blade_canopy_texture_t *tex = malloc(sizeof *tex);
    gfx_texture_destroy(&t->canopy);
    t->canopy_rows = 0;
    if (tex) {
        blade_canopy_pack(c, tex);
        t->canopy = gfx_texture_make(&(gfx_texture_desc_t){.w = BLADE_CANOPY_TEXELS,
                                                           .h = tex->rows * BLADE_CANOPY_LEVELS * tex->poses,
                                                           .format = GL_RGBA32F, .filter = GL_NEAREST,
                                                           .data = tex->texel, .upload_type = GL_FLOAT,
                                                           .label = "terrain.canopy.table"});
        t->canopy_rows = t->canopy.id ? tex->rows : 0;
        t->canopy_poses = tex->poses;
        t->canopy_sun0 = tex->sun0;
        t->canopy_top = tex->top;
        t->canopy_wind = tex->wind;
        t->canopy_gravity = tex->gravity;
        free(tex);
    } else {
        core_log_error("ground: no memory for the canopy table; the ground is drawn without it");
    }
    t->extent = extent;
    memcpy(t->extent_origin, origin, sizeof t->extent_origin);
    t->extent_spacing = spacing;
}

bool ground_has_canopy(const ground_t *t) { return t->canopy_rows > 1; }

void ground_set_winds(ground_t *t, const blade_wind_t *winds, int count)
{
    t->wind_count = count < BLADE_MAX_WINDS ? (count > 0 ? count : 0) : BLADE_MAX_WINDS;
    if (t->wind_count) memcpy(t->winds, winds, sizeof *winds * (size_t)t->wind_count);
}

void ground_set_canopy_fade(ground_t *t, float start, float end, bool overhang)
{
    t->canopy_fade[0] = start;
    t->canopy_fade[1] = end;
    t->canopy_overhang = overhang;
}

void ground_set_gi(ground_t *t, gi_bind_t gi) { t->gi = gi; }

void ground_set_lod(ground_t *t, const blade_lod_t *lod, float width, float focal_px, float cull, float far)
{
    t->lod_on = lod && !lod->no_ground;
    if (!t->lod_on) return;
    t->lod = *lod; /* resolved by blade_lod_uniforms */
    t->lod_width = width;
    t->lod_focal = focal_px;
    t->lod_cull = cull;
    t->lod_far = far;
}

void ground_destroy(ground_t *t)
{
    if (!t) return;
    gfx_buffer_destroy(&t->vbo);
    gfx_buffer_destroy(&t->ibo);
    gfx_vertex_array_destroy(&t->vao);
    gfx_vertex_array_destroy(&t->empty_vao);
    gfx_program_destroy(&t->prog);
    gfx_program_destroy(&t->sky);
    gfx_texture_destroy(&t->noise);
    gfx_texture_destroy(&t->canopy);
    gfx_buffer_destroy(&t->match);
    gfx_buffer_destroy(&t->match_gain);
    for (int k = 0; k < 2; k++) gfx_program_destroy(&t->match_measure[k]);
    gfx_program_destroy(&t->match_step);
    terrain_clipmap_free(&t->clipmap);
    free(t);
}

/* A clipmap triangle's longest edge in cells: a morphed cell's diagonal
 * (up to 2 sqrt 2) at a slope of up to 2 (63 degrees), times sqrt 5. */
#define GROUND_WORLD_EDGE 6.4f

/* One draw per clipmap level around the camera. */
static void draw_world(const ground_t *t, const grass_view_t *v)
{
    const terrain_clipmap_t *c = &t->clipmap;
    GLint origin = gfx_uniform(t->prog, "u_origin"), cell = gfx_uniform(t->prog, "u_cell"),
          morph = gfx_uniform(t->prog, "u_morph"), margin = gfx_uniform(t->prog, "u_canopy_margin");
    double tris = 0.0;
    for (int l = 0; l < c->desc.levels; l++) {
        terrain_clipmap_level_t lv = terrain_clipmap_place(c, l, v->camera[0], v->camera[2]);
        glUniform2fv(origin, 1, lv.origin);
        glUniform1f(cell, lv.cell);
        glUniform1f(margin, GROUND_WORLD_EDGE * lv.cell);
        glUniform2fv(morph, 1, lv.morph);
        glDrawElements(GL_TRIANGLES, (GLsizei)c->count[lv.range], GL_UNSIGNED_INT,
                       (const void *)(sizeof(uint32_t) * c->first[lv.range]));
        tris += c->count[lv.range] / 3.0;
    }
    gfx_count_add("terrain.clipmap.triangles", tris);
}

/* The canopy table's uniforms and textures (ground/terrain_canopy.glsl,
 * the extent map of terrain_ground.glsl) for view v in p. */
static void canopy_uniforms(const ground_t *t, gfx_program_t p, const grass_view_t *v)
{
    static const float root[3] = BLADE_DEFAULT_ALBEDO_ROOT, tip[3] = BLADE_DEFAULT_ALBEDO_TIP;
    glUniform1i(gfx_uniform(p, "u_canopy_rows"), t->canopy_rows);
    glUniform1f(gfx_uniform(p, "u_canopy_sun0"), t->canopy_sun0);
    glUniform1f(gfx_uniform(p, "u_canopy_top"), t->canopy_top);
    glUniform1i(gfx_uniform(p, "u_canopy_poses"), t->canopy_poses);
    glUniform1f(gfx_uniform(p, "u_canopy_wind"), t->canopy_wind);
    glUniform1f(gfx_uniform(p, "u_canopy_gravity"), t->canopy_gravity);
    glUniform1i(gfx_uniform(p, "u_wind_count"), t->wind_count);
    if (t->wind_count) glUniform4fv(gfx_uniform(p, "u_winds"), 2 * t->wind_count, t->winds[0].a);
    glUniform1f(gfx_uniform(p, "u_time"), v->time);
    glUniform4fv(gfx_uniform(p, "u_frustum"), 6, v->planes[0]);
    glUniform1f(gfx_uniform(p, "u_canopy_margin"), t->edge);
    glBindTextureUnit(GROUND_TEX_CANOPY, t->canopy.id);
    glUniform3fv(gfx_uniform(p, "u_canopy_albedo_root"), 1, root);
    glUniform3fv(gfx_uniform(p, "u_canopy_albedo_tip"), 1, tip);
    glUniform1i(gfx_uniform(p, "u_extent_on"), t->extent != 0);
    glUniform2fv(gfx_uniform(p, "u_extent_origin"), 1, t->extent_origin);
    glUniform1f(gfx_uniform(p, "u_extent_spacing"), t->extent_spacing);
    glBindTextureUnit(GROUND_TEX_EXTENT, t->extent);
}

/* What terrain_shade (ground/terrain_ground.glsl) reads for view v, in p
 * (the terrain's program or the match's): the frame's canopy band, the
 * thinning under the blades and the canopy's table. */
static void terrain_uniforms(const ground_t *t, gfx_program_t p, const grass_view_t *v)
{
    glUniform3fv(gfx_uniform(p, "u_camera"), 1, v->camera);
    glUniform3fv(gfx_uniform(p, "u_sun"), 1, v->sun);
    gi_set_uniforms(p.id, &t->gi);
    bool lod = t->canopy_rows > 1 && t->lod_on;
    bool canopy = t->canopy_rows > 1 && (t->canopy_fade[1] > 0.0f || lod);
    glUniform1i(gfx_uniform(p, "u_lod_on"), lod);
    if (lod) {
        blade_lod_uniforms(p, &t->lod, t->lod_focal, t->lod_cull);
        glUniform2f(gfx_uniform(p, "u_lod_ground"), t->lod_width, t->lod_far);
    }
    glUniform2f(gfx_uniform(p, "u_canopy_fade"), canopy ? t->canopy_fade[0] : 0.0f, canopy ? t->canopy_fade[1] : 0.0f);
    glUniform1i(gfx_uniform(p, "u_canopy_on"), canopy);
    bool overhang = canopy && t->canopy_overhang && t->canopy_fade[1] > 0.0f;
    glUniform2f(gfx_uniform(p, "u_canopy_switch"), overhang ? 0.5f * (t->canopy_fade[0] + t->canopy_fade[1]) : 0.0f,
                overhang ? 0.5f * (t->canopy_fade[1] - t->canopy_fade[0]) : 0.0f);
    if (canopy) canopy_uniforms(t, p, v);
    glBindTextureUnit(GROUND_TEX_NOISE, t->noise.id);
    glBindBufferBase(GL_UNIFORM_BUFFER, GROUND_UBO_MATCH, t->match_gain.id);
}

void ground_draw(const ground_t *t, const grass_view_t *v, const float inv_viewproj[16])
{
    glUseProgram(t->prog.id);
    glUniformMatrix4fv(gfx_uniform(t->prog, "u_viewproj"), 1, GL_FALSE, v->viewproj);
    terrain_uniforms(t, t->prog, v);
    glBindVertexArray(t->vao);
    if (t->world) draw_world(t, v);
    else glDrawElements(GL_TRIANGLES, t->index_count, GL_UNSIGNED_INT, NULL);

    /* Sky after the ground, at the far plane with LEQUAL and no depth write:
     * only pixels the terrain left empty run the sky shader. */
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_FALSE);
    glUseProgram(t->sky.id);
    glUniformMatrix4fv(gfx_uniform(t->sky, "u_inv_viewproj"), 1, GL_FALSE, inv_viewproj);
    glBindVertexArray(t->empty_vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glBindVertexArray(0);
}

void ground_set_grid(ground_t *t, GLuint grid, int res, float half)
{
    t->grid = grid;
    t->grid_res = grid ? res : 0;
    t->grid_half = half;
}

/* The match's programs (measure on single- and multisampled targets, step)
 * for t's terrain; false without terrain normals (a heightfield whose grid
 * was not set, an imported mesh). */
static bool match_descs(const ground_t *t, char ms[64], gfx_program_desc_t out[3])
{
    if (!t->world && t->grid_res <= 0) return false;
    const char *world = t->world ? "#define MATCH_WORLD 1\n" : "";
    snprintf(ms, 64, "%s#define MATCH_MS 1\n", world);
    out[0] = (gfx_program_desc_t){.cs = "ground/canopy_match.comp", .defines = world, .label = "terrain.canopy.match"};
    out[1] = (gfx_program_desc_t){.cs = "ground/canopy_match.comp", .defines = ms, .label = "terrain.canopy.match_ms"};
    out[2] = (gfx_program_desc_t){.cs = "ground/canopy_match_update.comp", .label = "terrain.canopy.match_step"};
    return true;
}

void ground_match_prefetch(const ground_t *t)
{
    char ms[64];
    gfx_program_desc_t descs[3];
    if (match_descs(t, ms, descs)) gfx_programs_prefetch(3, descs);
}

/* The match's programs, made by its first call (a failure is logged once
 * and the match stays off). */
static bool match_programs(ground_t *t)
{
    if (t->match_tried) return t->match_step.id != 0;
    t->match_tried = true;
    char ms[64];
    gfx_program_desc_t descs[3];
    gfx_program_t progs[3];
    if (!match_descs(t, ms, descs)) return false;
    if (!gfx_programs_make(3, descs, progs)) {
        for (int k = 0; k < 3; k++) gfx_program_destroy(&progs[k]);
        core_log_warn("ground: the canopy match's programs failed; the canopy is drawn unmatched");
        return false;
    }
    t->match_measure[0] = progs[0];
    t->match_measure[1] = progs[1];
    t->match_step = progs[2];
    for (int k = 0; k < 2 && t->world; k++)
        gfx_world_height_uniforms(t->match_measure[k], t->world_fn.keys, TERRAIN_WORLD_LAYERS, t->world_fn.height);
    return true;
}

void ground_match(ground_t *t, const grass_view_t *v, const gfx_target_t *target, GLuint opaque_depth,
                  float switch_distance, float fade)
{
    if (t->canopy_rows <= 1 || t->canopy_fade[1] <= 0.0f || !target->color.id || !opaque_depth || !match_programs(t))
        return;
    gfx_program_t p = t->match_measure[target->color.samples > 1];
    float window[2];
    ground_match_window(switch_distance, fade, window);
    glUseProgram(p.id);
    terrain_uniforms(t, p, v);
    int stride = target->h > GROUND_MATCH_ROWS ? target->h / GROUND_MATCH_ROWS : 1;
    glUniform1i(gfx_uniform(p, "u_samples"), target->color.samples > 1 ? target->color.samples : 1);
    glUniform1i(gfx_uniform(p, "u_stride"), stride);
    glUniformMatrix4fv(gfx_uniform(p, "u_inv_viewproj"), 1, GL_FALSE, v->inv_viewproj);
    glUniform2fv(gfx_uniform(p, "u_window"), 1, window);
    glBindTextureUnit(GROUND_TEX_MATCH_COLOR, target->color.id);
    glBindTextureUnit(GROUND_TEX_MATCH_DEPTH, opaque_depth);
    if (!t->world) {
        glBindTextureUnit(GROUND_TEX_MATCH_GRID, t->grid);
        glUniform1i(gfx_uniform(p, "u_grid_res"), t->grid_res);
        glUniform1f(gfx_uniform(p, "u_grid_half"), t->grid_half);
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, GROUND_BIND_MATCH, t->match.id);
    glDispatchCompute((GLuint)((target->w + stride - 1) / stride + 7) / 8,
                      (GLuint)((target->h + stride - 1) / stride + 7) / 8, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(t->match_step.id);
    glUniform1ui(gfx_uniform(t->match_step, "u_min_pixels"), GROUND_MATCH_MIN_PIXELS);
    glUniform1f(gfx_uniform(t->match_step, "u_rate"), GROUND_MATCH_RATE);
    glUniform2f(gfx_uniform(t->match_step, "u_range"), GROUND_MATCH_GAIN_MIN, GROUND_MATCH_GAIN_MAX);
    glDispatchCompute(1, 1, 1);
    /* The terrain reads a copy: read as a uniform block while the shaders
     * store to it, the state cost meadow_large's terrain pass 0.07 ms (H200) */
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    glCopyNamedBufferSubData(t->match.id, t->match_gain.id, 0, 0, sizeof match_rest.gain);
    /* the target's textures unbound: drawn into while bound, they cost the
     * next frame's passes */
    for (GLuint u = GROUND_TEX_MATCH_COLOR; u <= GROUND_TEX_MATCH_GRID; u++) glBindTextureUnit(u, 0);
}

void ground_match_reset(ground_t *t)
{
    glNamedBufferSubData(t->match.id, 0, sizeof match_rest, &match_rest);
    glNamedBufferSubData(t->match_gain.id, 0, sizeof match_rest.gain, match_rest.gain);
}

void ground_match_state(const ground_t *t, ground_match_state_t *out)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glGetNamedBufferSubData(t->match.id, 0, sizeof *out, out);
}

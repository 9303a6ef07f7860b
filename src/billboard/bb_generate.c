/* bb_generate: bb_field_make's GPU data (Orthmann et al. 2009 sec. 4): the
 * layout textures and clump array (bb_layout), the height grid, the
 * generation entries (per octree leaf on heightfields, per leaf and
 * triangle on mesh terrains), the one generation draw that captures every
 * billboard into the leaf-ordered points buffer (bb_generate.geom with
 * transform feedback), and each billboard's bounding sphere read back for
 * the collide batches. */
#include "billboard/bb_local.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

bool bb_upload_layout(bb_field_t *f)
{
    bb_layout_t lay;
    if (!bb_layout_generate(&lay, &f->desc.layout)) return false;
    int s = lay.extent.w;
    f->extent = gfx_texture_make(&(gfx_texture_desc_t){.w = s, .h = s, .format = GL_R8, .filter = GL_NEAREST,
                                                       .wrap = GL_REPEAT, .data = lay.extent.px,
                                                       .upload_format = GL_RED, .label = "bb.extent"});
    f->direction = gfx_texture_make(&(gfx_texture_desc_t){.w = s, .h = s, .format = GL_RGB8, .filter = GL_NEAREST,
                                                          .wrap = GL_REPEAT, .data = lay.direction.px,
                                                          .upload_format = GL_RGB, .label = "bb.direction"});
    f->messiness = gfx_texture_make(&(gfx_texture_desc_t){.w = s, .h = s, .format = GL_R8, .filter = GL_NEAREST,
                                                          .wrap = GL_REPEAT, .data = lay.messiness.px,
                                                          .upload_format = GL_RED, .label = "bb.messiness"});
    int cs = lay.clumps[0].w, layers = lay.clump_layers, lo = lay.clump_stats[0].blades, hi = lo;
    int images = layers * lay.views.elevations * lay.views.azimuths;
    for (int k = 1; k < images; k++) {
        lo = lay.clump_stats[k].blades < lo ? lay.clump_stats[k].blades : lo;
        hi = lay.clump_stats[k].blades > hi ? lay.clump_stats[k].blades : hi;
    }
    /* The array: the V L albedo images, then (views on) their V L light
     * images. */
    int array_layers = lay.views.on ? 2 * images : images;
    size_t layer_bytes = (size_t)cs * (size_t)cs * 4;
    f->clump_bytes = layer_bytes * (size_t)array_layers * 4 / 3;
    char views[96] = "one view, Orthmann's cards";
    if (lay.views.on)
        snprintf(views, sizeof views, "view cards: %d elevations up to %.0f deg x %d wind azimuths",
                 lay.views.elevations, lay.views.elevation_max * 57.29578f, lay.views.azimuths);
    core_log_info("billboards: %d clump layers (%s) of %d-%d blades (%d for the field's density, more for its "
                  "coverage), clump array %.2f MiB with mipmaps",
                  layers, views, lo, hi, f->desc.layout.blades, (double)f->clump_bytes / 1048576.0);
    f->views = lay.views;
    uint8_t *all = malloc(layer_bytes * (size_t)array_layers);
    if (all) {
        for (int k = 0; k < images; k++) {
            memcpy(all + layer_bytes * (size_t)k, lay.clumps[k].px, layer_bytes);
            if (lay.views.on) memcpy(all + layer_bytes * (size_t)(images + k), lay.clump_light[k].px, layer_bytes);
        }
        f->clumps = gfx_texture_make(&(gfx_texture_desc_t){.target = GL_TEXTURE_2D_ARRAY, .w = cs, .h = cs,
                                                           .layers = array_layers, .mip_levels = -1, .data = all,
                                                           .label = "bb.clumps"});
    } else {
        core_log_error("out of memory for %d clump images", array_layers);
    }
    free(all);
    f->gen.layers = (uint32_t)layers;
    bb_layout_free(&lay);
    return f->extent.id && f->direction.id && f->messiness.id && f->clumps.id;
}

/* Height grid on the GPU: the heightfield's own vertices, or a mesh terrain
 * resampled with terrain_height_at at the candidate spacing (-1e30 where no
 * ground lies under a grid vertex); read by generation and collision
 * (shaders/billboard/bb_ground.glsl). */
void bb_set_heights(const bb_field_t *f, gfx_program_t p)
{
    glBindTextureUnit(BB_TEX_HEIGHTS, f->heights.id);
    glUniform2f(gfx_uniform(p, "u_hmin"), f->hgrid[0], f->hgrid[1]);
    glUniform2f(gfx_uniform(p, "u_hmax"), f->hgrid[2], f->hgrid[3]);
    glUniform1f(gfx_uniform(p, "u_hcell"), f->hgrid[4]);
}

bool bb_upload_heights(bb_field_t *f, const terrain_mesh_t *t)
{
    float *hgrid = f->hgrid;
    int nx, nz;
    float *h;
    if (t->grid_res > 0) {
        nx = nz = t->grid_res;
        float half = t->grid_size * 0.5f, cell = t->grid_size / (float)t->grid_res;
        h = malloc(sizeof *h * (size_t)(nx + 1) * (size_t)(nz + 1));
        if (!h) return false;
        for (uint32_t k = 0; k < (uint32_t)((nx + 1) * (nz + 1)); k++) h[k] = t->positions[3 * k + 1];
        hgrid[0] = -half, hgrid[1] = -half, hgrid[2] = half, hgrid[3] = half, hgrid[4] = cell;
    } else {
        float cell = f->gen.spacing;
        nx = (int)ceilf((t->aabb_max[0] - t->aabb_min[0]) / cell);
        nz = (int)ceilf((t->aabb_max[2] - t->aabb_min[2]) / cell);
        nx = nx < 1 ? 1 : nx;
        nz = nz < 1 ? 1 : nz;
        h = malloc(sizeof *h * (size_t)(nx + 1) * (size_t)(nz + 1));
        if (!h) return false;
        for (int j = 0; j <= nz; j++) {
            for (int i = 0; i <= nx; i++) {
                float y = terrain_height_at(t, t->aabb_min[0] + (float)i * cell, t->aabb_min[2] + (float)j * cell, NULL);
                h[j * (nx + 1) + i] = y < -1e30f ? -1e30f : y;
            }
        }
        hgrid[0] = t->aabb_min[0], hgrid[1] = t->aabb_min[2];
        hgrid[2] = t->aabb_min[0] + (float)nx * cell, hgrid[3] = t->aabb_min[2] + (float)nz * cell;
        hgrid[4] = cell;
    }
    f->heights = gfx_texture_make(&(gfx_texture_desc_t){.w = nx + 1, .h = nz + 1, .format = GL_R32F,
                                                        .filter = GL_NEAREST, .data = h, .upload_format = GL_RED,
                                                        .upload_type = GL_FLOAT, .label = "bb.heights"});
    free(h);
    return f->heights.id != 0;
}

/* Terrain height range under each column of leaves (side x side, x-major),
 * from the triangles whose xz bounds overlap the column. */
static void column_ranges(const bb_field_t *f, const terrain_mesh_t *t, float *lo, float *hi)
{
    int side = f->tree.side;
    for (int k = 0; k < side * side; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    const float *mn = f->tree.desc.min, *mx = f->tree.desc.max;
    for (uint32_t tri = 0; tri < t->index_count / 3; tri++) {
        float bmin[3] = {INFINITY, INFINITY, INFINITY}, bmax[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int v = 0; v < 3; v++) {
            const float *p = &t->positions[3 * t->indices[3 * tri + (uint32_t)v]];
            for (int a = 0; a < 3; a++) bmin[a] = fminf(bmin[a], p[a]), bmax[a] = fmaxf(bmax[a], p[a]);
        }
        int c0[2], c1[2];
        for (int q = 0; q < 2; q++) {
            int a = q * 2;
            float s = (float)side / (mx[a] - mn[a]);
            c0[q] = (int)floorf((bmin[a] - mn[a]) * s) - 1;
            c1[q] = (int)floorf((bmax[a] - mn[a]) * s) + 1;
            c0[q] = c0[q] < 0 ? 0 : c0[q];
            c1[q] = c1[q] > side - 1 ? side - 1 : c1[q];
        }
        for (int z = c0[1]; z <= c1[1]; z++) {
            for (int x = c0[0]; x <= c1[0]; x++) {
                lo[z * side + x] = fminf(lo[z * side + x], bmin[1]);
                hi[z * side + x] = fmaxf(hi[z * side + x], bmax[1]);
            }
        }
    }
}

/* std430 twin of struct bb_gen_entry in bb_gen_leaves.glsl. */
typedef struct bb_gen_entry_t {
    int32_t cells[4];
    int32_t tiles_x;
    uint32_t leaf, first, tri;
} bb_gen_entry_t;

/* The leaves whose footprint and terrain height range can hold billboards,
 * in Morton order, each with its tiles of candidate cells and the first
 * vertex of those tiles in the one generation draw. Returns the count; the
 * total number of tiles goes to *vertices. */
static int gen_entries(const bb_field_t *f, const float *clo, const float *chi, int tile, bb_gen_entry_t *out,
                       uint32_t *vertices)
{
    const bb_octree_t *tr = &f->tree;
    const bb_gen_desc_t *g = &f->gen;
    int n = 0;
    uint32_t first = 0;
    for (int leaf = 0; leaf < tr->leaf_count; leaf++) {
        int node = bb_octree_leaf_node(tr, (uint32_t)leaf);
        int lc[3];
        bb_octree_leaf_coords((uint32_t)leaf, lc);
        float ylo = clo[lc[2] * tr->side + lc[0]], yhi = chi[lc[2] * tr->side + lc[0]];
        float eps = 1e-3f * (tr->desc.max[1] - tr->desc.min[1]);
        if (yhi < tr->lo[node][1] - eps || ylo > tr->hi[node][1] + eps) continue;
        int c[4];
        for (int q = 0; q < 2; q++) {
            int a = q * 2;
            c[q] = (int)floorf((tr->lo[node][a] - g->origin[q]) / g->spacing) - 1;
            c[q + 2] = (int)floorf((tr->hi[node][a] - g->origin[q]) / g->spacing) + 2;
            c[q] = c[q] < 0 ? 0 : c[q];
            c[q + 2] = c[q + 2] > f->cells[q] ? f->cells[q] : c[q + 2];
        }
        int tx = (c[2] - c[0] + tile - 1) / tile, tz = (c[3] - c[1] + tile - 1) / tile;
        if (tx <= 0 || tz <= 0) continue;
        out[n++] = (bb_gen_entry_t){.cells = {c[0], c[1], c[2], c[3]}, .tiles_x = tx, .leaf = (uint32_t)leaf,
                                    .first = first};
        first += (uint32_t)(tx * tz);
    }
    *vertices = first;
    return n;
}

/* Mesh terrains: the frame of every triangle (bb_gen_tri_make, zeroed
 * where it seeds nothing), the count of those that seed (*seeding) and the
 * candidates they hold (*cells, an upper bound on the billboards). NULL
 * when out of memory (logged). */
bb_gen_tri_t *bb_mesh_tris(const terrain_mesh_t *t, float spacing, int *seeding, double *cells)
{
    uint32_t n = t->index_count / 3;
    bb_gen_tri_t *tris = malloc(sizeof *tris * (size_t)n);
    if (!tris) {
        core_log_error("out of memory for %u terrain triangles", n);
        return NULL;
    }
    *seeding = 0, *cells = 0.0;
    for (uint32_t k = 0; k < n; k++) {
        const float *v[3];
        for (int c = 0; c < 3; c++) v[c] = &t->positions[3 * t->indices[3 * k + (uint32_t)c]];
        if (!bb_gen_tri_make(v[0], v[1], v[2], spacing, &tris[k])) continue;
        (*seeding)++;
        *cells += (double)tris[k].cells[0] * (double)tris[k].cells[1];
    }
    return tris;
}

/* Leaf coordinates [out[0], out[1]] along axis a that [p0, p1], grown by
 * 1e-4 of the tree's extent (roots computed on the GPU may round across),
 * overlaps. */
static void leaf_span(const bb_octree_t *tr, int a, float p0, float p1, int out[2])
{
    float mn = tr->desc.min[a], ext = tr->desc.max[a] - mn, s = (float)tr->side / ext;
    int c[2] = {(int)floorf((p0 - 1e-4f * ext - mn) * s), (int)floorf((p1 + 1e-4f * ext - mn) * s)};
    for (int q = 0; q < 2; q++) out[q] = c[q] < 0 ? 0 : (c[q] > tr->side - 1 ? tr->side - 1 : c[q]);
}

/* Candidate cells [c[0], c[2]) x [c[1], c[3]) of triangle tri whose roots
 * can lie in leaf box [lo, hi]: the box's corners projected on the
 * triangle's frame, grown by 1e-3 cell. False when empty. */
static bool tri_cells_in_box(const bb_gen_tri_t *tri, float spacing, const float lo[3], const float hi[3], int c[4])
{
    for (int q = 0; q < 2; q++) {
        const float *axis = q ? tri->v : tri->u;
        float dmin = 0.0f, dmax = 0.0f;
        for (int k = 0; k < 3; k++) {
            float d0 = (lo[k] - tri->a[k]) * axis[k], d1 = (hi[k] - tri->a[k]) * axis[k];
            dmin += fminf(d0, d1), dmax += fmaxf(d0, d1);
        }
        int c0 = (int)floorf(dmin / spacing - 1e-3f), c1 = (int)floorf(dmax / spacing + 1e-3f) + 1;
        c[q] = c0 < 0 ? 0 : c0;
        c[q + 2] = c1 > tri->cells[q] ? tri->cells[q] : c1;
        if (c[q + 2] <= c[q]) return false;
    }
    return true;
}

/* Mesh terrains: one entry per (leaf, seeding triangle) pair whose boxes
 * overlap, with the triangle's candidate cells that can reach the leaf, in
 * Morton order of the leaves (triangle order within a leaf); tiles and
 * first vertices as gen_entries. Returns the entries (malloc, *count of
 * them), NULL when out of memory. */
static bb_gen_entry_t *tri_entries(const bb_field_t *f, const terrain_mesh_t *t, const bb_gen_tri_t *tris,
                                   int tile, int *count, uint32_t *vertices)
{
    const bb_octree_t *tr = &f->tree;
    size_t n = 0, cap = 0;
    bb_gen_entry_t *tmp = NULL, *out = NULL;
    uint32_t *per_leaf = calloc((size_t)tr->leaf_count + 1, sizeof *per_leaf);
    bool ok = per_leaf != NULL;
    *count = 0, *vertices = 0;
    for (uint32_t k = 0; ok && k < t->index_count / 3; k++) {
        if (tris[k].cells[0] == 0) continue;
        float bmin[3] = {INFINITY, INFINITY, INFINITY}, bmax[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (int v = 0; v < 3; v++) {
            const float *p = &t->positions[3 * t->indices[3 * k + (uint32_t)v]];
            for (int a = 0; a < 3; a++) bmin[a] = fminf(bmin[a], p[a]), bmax[a] = fmaxf(bmax[a], p[a]);
        }
        int span[3][2];
        for (int a = 0; a < 3; a++) leaf_span(tr, a, bmin[a], bmax[a], span[a]);
        for (int z = span[2][0]; ok && z <= span[2][1]; z++) {
            for (int y = span[1][0]; ok && y <= span[1][1]; y++) {
                for (int x = span[0][0]; ok && x <= span[0][1]; x++) {
                    uint32_t leaf = bb_octree_leaf_at((const int[3]){x, y, z});
                    int node = bb_octree_leaf_node(tr, leaf), c[4];
                    if (!tri_cells_in_box(&tris[k], f->gen.spacing, tr->lo[node], tr->hi[node], c)) continue;
                    if (n == cap) {
                        cap = cap ? 2 * cap : 1024;
                        bb_gen_entry_t *grown = realloc(tmp, sizeof *tmp * cap);
                        if (!grown) {
                            ok = false;
                            break;
                        }
                        tmp = grown;
                    }
                    int tx = (c[2] - c[0] + tile - 1) / tile, tz = (c[3] - c[1] + tile - 1) / tile;
                    tmp[n++] = (bb_gen_entry_t){.cells = {c[0], c[1], c[2], c[3]}, .tiles_x = tx, .leaf = leaf,
                                                .first = (uint32_t)(tx * tz), .tri = k};
                    per_leaf[leaf + 1]++;
                }
            }
        }
    }
    if (ok) out = malloc(sizeof *out * (n ? n : 1));
    if (out) {
        /* Counting sort by leaf (stable: triangle order within a leaf), then
         * .first from tile counts to first vertices. */
        for (int l = 0; l < tr->leaf_count; l++) per_leaf[l + 1] += per_leaf[l];
        for (size_t q = 0; q < n; q++) out[per_leaf[tmp[q].leaf]++] = tmp[q];
        uint32_t first = 0;
        for (size_t q = 0; q < n; q++) {
            uint32_t tiles = out[q].first;
            out[q].first = first;
            first += tiles;
        }
        *count = (int)n, *vertices = first;
    }
    free(tmp), free(per_leaf);
    return out;
}

/* Heightfields: gen_entries over the terrain's column height ranges
 * (malloc, *count of them), NULL when out of memory. */
static bb_gen_entry_t *grid_entries(const bb_field_t *f, const terrain_mesh_t *t, int tile, int *count,
                                    uint32_t *vertices)
{
    int side = f->tree.side;
    float *clo = malloc(sizeof *clo * (size_t)(side * side)), *chi = malloc(sizeof *chi * (size_t)(side * side));
    bb_gen_entry_t *entries = malloc(sizeof *entries * (size_t)f->tree.leaf_count);
    if (clo && chi && entries) {
        column_ranges(f, t, clo, chi);
        *count = gen_entries(f, clo, chi, tile, entries, vertices);
    } else {
        free(entries);
        entries = NULL;
    }
    free(clo), free(chi);
    return entries;
}

void bb_set_gen(const bb_field_t *f)
{
    gfx_program_t p = f->gen_prog;
    glUseProgram(p.id);
    glBindTextureUnit(BB_TEX_EXTENT, f->extent.id);
    glBindTextureUnit(BB_TEX_DIRECTION, f->direction.id);
    glBindTextureUnit(BB_TEX_MESSINESS, f->messiness.id);
    const bb_gen_desc_t *g = &f->gen;
    glUniform1f(gfx_uniform(p, "u_gen.spacing"), g->spacing);
    glUniform2f(gfx_uniform(p, "u_gen.origin"), g->origin[0], g->origin[1]);
    glUniform1i(gfx_uniform(p, "u_gen.cells_per_texel"), g->cells_per_texel);
    glUniform1f(gfx_uniform(p, "u_gen.width"), g->width);
    glUniform1f(gfx_uniform(p, "u_gen.height"), g->height);
    glUniform1ui(gfx_uniform(p, "u_gen.seed"), g->seed);
    glUniform1ui(gfx_uniform(p, "u_gen.layers"), g->layers);
}

/* The generation program's uniforms and textures (the layout maps and the
 * heights, on their bindings_billboard.glsl units). */
static void gen_uniforms(const bb_field_t *f, int nentries)
{
    const bb_octree_t *tr = &f->tree;
    gfx_program_t p = f->gen_prog;
    bb_set_gen(f);
    bb_set_heights(f, p);
    glUniform3fv(gfx_uniform(p, "u_tree_min"), 1, tr->desc.min);
    glUniform3fv(gfx_uniform(p, "u_tree_max"), 1, tr->desc.max);
    glUniform1i(gfx_uniform(p, "u_side"), tr->side);
    glUniform1i(gfx_uniform(p, "u_entry_count"), nentries);
}

/* Node ranges of the generated order (counts[k] billboards in leaf k, total
 * in all): bb_octree_assign on each leaf's cell centre, repeated count
 * times, gives the same prefix sums the GPU order has. False when out of
 * memory (logged). */
static bool node_ranges(bb_octree_t *tr, const uint32_t *counts, uint64_t total)
{
    float (*pos)[3] = malloc(sizeof *pos * (size_t)(total ? total : 1));
    uint32_t *order = malloc(sizeof *order * (size_t)(total ? total : 1));
    bool ok = pos && order;
    if (ok) {
        size_t s = 0;
        for (int k = 0; k < tr->leaf_count; k++) {
            int node = bb_octree_leaf_node(tr, (uint32_t)k);
            for (uint32_t q = 0; q < counts[k]; q++, s++)
                for (int a = 0; a < 3; a++) pos[s][a] = 0.5f * (tr->lo[node][a] + tr->hi[node][a]);
        }
        bb_octree_assign(tr, (const float (*)[3])pos, (int)total, order);
        for (size_t q = 0; q < total; q++) assert(order[q] == q);
    } else {
        core_log_error("out of memory for %llu billboard ranges", (unsigned long long)total);
    }
    free(pos), free(order);
    return ok;
}

bool bb_generate(bb_field_t *f, const terrain_mesh_t *t, const bb_gen_tri_t *tris, int tile)
{
    bb_octree_t *tr = &f->tree;
    uint32_t *counts = calloc((size_t)tr->leaf_count, sizeof *counts);
    uint32_t vertices = 0;
    int nentries = 0;
    bb_gen_entry_t *entries = tris ? tri_entries(f, t, tris, tile, &nentries, &vertices)
                                   : grid_entries(f, t, tile, &nentries, &vertices);
    if (!counts || !entries) {
        free(counts), free(entries);
        core_log_error("out of memory for generation");
        return false;
    }
    gfx_buffer_t tri_buf = {0};
    if (tris)
        tri_buf = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof *tris * (size_t)(t->index_count / 3),
                                                       .data = tris, .label = "bb.generate.triangles"});
    gfx_buffer_t entry_buf = gfx_buffer_make(&(gfx_buffer_desc_t){
        .size = sizeof *entries * (size_t)(nentries > 0 ? nentries : 1), .data = entries,
        .label = "bb.generate.leaves"});
    free(entries);
    f->counts = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof *counts * (size_t)tr->leaf_count,
                                                     .data = counts, .label = "bb.leaf_counts"});
    GLuint query = gfx_query_make(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, "bb.generate.written");
    /* Timed with two timestamps rather than gfx_timer: the pass runs once,
     * outside any frame, and llvmpipe's GL_TIME_ELAPSED around it returned
     * ~3e6 ms. */
    GLint stamp_bits = 0;
    glGetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &stamp_bits);
    GLuint stamps[2] = {gfx_query_make(GL_TIMESTAMP, "bb.generate.t0"), gfx_query_make(GL_TIMESTAMP, "bb.generate.t1")};
    gen_uniforms(f, nentries);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_LEAF_COUNTS, f->counts.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_GEN_ENTRIES, entry_buf.id);
    if (tris) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BB_BIND_GEN_TRIS, tri_buf.id);
    glBindVertexArray(f->empty_vao);
    GLint fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, f->cube_target.fbo); /* draws need a complete framebuffer */
    glQueryCounter(stamps[0], GL_TIMESTAMP);
    glEnable(GL_RASTERIZER_DISCARD);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, f->tf);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, f->points.id);
    glBeginQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN, query);
    glBeginTransformFeedback(GL_POINTS);
    if (vertices > 0) glDrawArrays(GL_POINTS, 0, (GLsizei)vertices);
    glEndTransformFeedback();
    glEndQuery(GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN);
    glDisable(GL_RASTERIZER_DISCARD);
    glQueryCounter(stamps[1], GL_TIMESTAMP);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    GLuint written = 0;
    glGetQueryObjectuiv(query, GL_QUERY_RESULT, &written);
    gfx_query_destroy(&query);
    gfx_buffer_destroy(&entry_buf);
    if (tris) gfx_buffer_destroy(&tri_buf);
    f->generate_ms = -1.0f;
    if (stamp_bits > 0) {
        GLuint64 t0 = 0, t1 = 0;
        glGetQueryObjectui64v(stamps[0], GL_QUERY_RESULT, &t0);
        glGetQueryObjectui64v(stamps[1], GL_QUERY_RESULT, &t1);
        f->generate_ms = t1 >= t0 ? (float)((double)(t1 - t0) * 1e-6) : -1.0f;
    }
    gfx_query_destroy(&stamps[0]);
    gfx_query_destroy(&stamps[1]);
    gfx_buffer_read(f->counts, 0, sizeof *counts * (size_t)tr->leaf_count, counts);
    uint64_t total = 0;
    for (int k = 0; k < tr->leaf_count; k++) total += counts[k];
    bool ok = true;
    if (total != written || total > (uint64_t)f->capacity) {
        core_log_error("billboard generation overflow: %llu billboards counted, %u captured, "
                       "buffer holds %d", (unsigned long long)total, written, f->capacity);
        ok = false;
    }
    f->billboards = (int)written;
    ok = ok && node_ranges(tr, counts, total);
    if (tris)
        core_log_info("bb: generated %u billboards on %d terrain triangles in %d (leaf, triangle) entries "
                      "(one draw)", written, f->triangles, nentries);
    else
        core_log_info("bb: generated %u billboards from %d x %d candidates in %d leaves (one draw)", written,
                      f->cells[0], f->cells[1], nentries);
    free(counts);
    return ok;
}

/* Each billboard's bounding sphere as bb_collide.geom computes it (centre
 * half way up the growth direction, radius half the diagonal plus the wind
 * strength), read back once in chunks (through a staging copy: gfx.h). */
bool bb_read_spheres(bb_field_t *f)
{
    enum { CHUNK = 16384 };
    f->spheres = malloc(sizeof *f->spheres * (size_t)(f->billboards ? f->billboards : 1));
    bb_point_t *pts = malloc(sizeof *pts * CHUNK);
    if (!f->spheres || !pts) {
        free(pts);
        core_log_error("out of memory for %d billboard spheres", f->billboards);
        return false;
    }
    for (int i0 = 0; i0 < f->billboards; i0 += CHUNK) {
        int n = f->billboards - i0 < CHUNK ? f->billboards - i0 : CHUNK;
        if (!gfx_buffer_read(f->points, sizeof *pts * (size_t)i0, sizeof *pts * (size_t)n, pts)) {
            free(pts);
            return false;
        }
        for (int i = 0; i < n; i++) {
            const bb_point_t *p = &pts[i];
            vec3 right, up;
            bb_point_frame(p, right, up);
            for (int a = 0; a < 3; a++) f->spheres[i0 + i][a] = p->position[a] + up[a] * (0.5f * p->size[1]);
            f->spheres[i0 + i][3] = 0.5f * sqrtf(p->size[0] * p->size[0] + p->size[1] * p->size[1]) +
                                    f->desc.wind.strength;
            f->sphere_max = fmaxf(f->sphere_max, f->spheres[i0 + i][3]);
        }
    }
    free(pts);
    return true;
}

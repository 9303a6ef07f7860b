/* bb: GL driver of the responsive billboard grass of Orthmann, Rezk-Salama &
 * Kolb 2009: GPU generation from layout textures into one leaf-ordered
 * buffer, the CPU octree broad phase, depth cube maps, the collision pass
 * (eq. 1-7) as a geometry shader with transform feedback, the recovery
 * pass (eq. 8) as a compute shader, and rendering. See bb.h for the
 * overview. */
#include "billboard/bb.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

/* The octree keeps a leaf RECOVERING this much longer than a billboard's own
 * recovery (bb_recover.comp), so float drift in the two timers can never
 * leave a billboard deformed in a leaf that already went IDLE. */
#define BB_LEAF_RECOVER_SLACK 0.25f

static const char *const bb_tf_varyings[] = {"o_pos_angle", "o_growth_mess", "o_size", "o_layer_state",
                                             "o_recover",   "o_seed",        "o_pad",  NULL};

/* std140 twin of struct bb_object in bb_collide.geom. */
typedef struct bb_object_gpu_t {
    float w2c[16];
    float c2w[16];
    float cube[4];
    float sphere[4];
    int32_t layer[4]; /* first cube-array layer (6 * object index), 3 pad */
    float sweep[4];   /* previous - current world position (swept collision), 0 pad */
} bb_object_gpu_t;

/* Objects one collide pass tests: the shader's BB_MAX_CUBES. */
static int pass_objects(const bb_field_t *f)
{
    return f->desc.max_objects < BB_PASS_OBJECTS ? f->desc.max_objects : BB_PASS_OBJECTS;
}

bb_field_desc_t bb_field_desc_defaults(const bb_field_desc_t *desc)
{
    bb_field_desc_t d = desc ? *desc : (bb_field_desc_t){0};
    if (d.density <= 0) d.density = SCENE_DEFAULT_BILLBOARD_DENSITY;
    if (d.size[0] <= 0) d.size[0] = SCENE_DEFAULT_BILLBOARD_WIDTH;
    if (d.size[1] <= 0) d.size[1] = SCENE_DEFAULT_BILLBOARD_HEIGHT;
    if (d.subdiv[0] <= 0) d.subdiv[0] = SCENE_DEFAULT_SUBDIV;
    if (d.subdiv[1] <= 0) d.subdiv[1] = SCENE_DEFAULT_SUBDIV;
    if (d.iterations <= 0) d.iterations = SCENE_DEFAULT_SPRING_ITERATIONS;
    if (d.r1 <= 0) d.r1 = 1.0f;
    if (d.r2 <= 0) d.r2 = 0.5f;
    if (d.cube_res <= 0) d.cube_res = SCENE_DEFAULT_CUBE_RESOLUTION;
    if (d.recover_time <= 0) d.recover_time = SCENE_DEFAULT_RECOVER_TIME;
    if (d.max_objects <= 0) d.max_objects = 8;
    if (d.max_deformed <= 0) d.max_deformed = 4096;
    if (d.octree_depth <= 0) d.octree_depth = 4;
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

static void set_wind(GLuint prog, const bb_wind_desc_t *w)
{
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_wind.dir"), w->dir[0], w->dir[1]);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_wind.strength"), w->strength);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_wind.omega"), w->omega);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_wind.wavenumber"), w->wavenumber);
}

/* The view-dependent cards' uniforms (shaders/billboard/bb_view.glsl). */
static void set_views(const bb_field_t *f, GLuint prog)
{
    glProgramUniform2i(prog, glGetUniformLocation(prog, "u_views"), f->views.elevations, f->views.azimuths);
    glProgramUniform1f(prog, glGetUniformLocation(prog, "u_view_elevation_max"), f->views.elevation_max);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_view_layers"), (GLint)f->gen.layers);
    glProgramUniform2f(prog, glGetUniformLocation(prog, "u_view_wind"), f->desc.wind.dir[0], f->desc.wind.dir[1]);
    glProgramUniform1i(prog, glGetUniformLocation(prog, "u_view_lit"), f->views.on);
}

static GLint loc(gfx_program_t p, const char *name) { return glGetUniformLocation(p.id, name); }

/* ---- make ------------------------------------------------------------------ */

static bool upload_layout(bb_field_t *f)
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
static void set_heights(const bb_field_t *f, gfx_program_t p, int unit)
{
    glBindTextureUnit((GLuint)unit, f->heights.id);
    glUniform1i(loc(p, "u_heights"), unit);
    glUniform2f(loc(p, "u_hmin"), f->hgrid[0], f->hgrid[1]);
    glUniform2f(loc(p, "u_hmax"), f->hgrid[2], f->hgrid[3]);
    glUniform1f(loc(p, "u_hcell"), f->hgrid[4]);
}

static bool upload_heights(bb_field_t *f, const terrain_mesh_t *t, float hgrid[5])
{
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
static bb_gen_tri_t *mesh_tris(const terrain_mesh_t *t, float spacing, int *seeding, double *cells)
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

static bool generate(bb_field_t *f, const terrain_mesh_t *t, const bb_gen_tri_t *tris, int tile)
{
    bb_octree_t *tr = &f->tree;
    int side = tr->side;
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
    gfx_program_t p = f->gen_prog;
    glUseProgram(p.id);
    glBindTextureUnit(0, f->extent.id);
    glBindTextureUnit(1, f->direction.id);
    glBindTextureUnit(2, f->messiness.id);
    glUniform1i(loc(p, "u_extent"), 0);
    glUniform1i(loc(p, "u_direction"), 1);
    glUniform1i(loc(p, "u_messiness"), 2);
    set_heights(f, p, 3);
    const bb_gen_desc_t *g = &f->gen;
    glUniform1f(loc(p, "u_gen.spacing"), g->spacing);
    glUniform2f(loc(p, "u_gen.origin"), g->origin[0], g->origin[1]);
    glUniform1i(loc(p, "u_gen.cells_per_texel"), g->cells_per_texel);
    glUniform1f(loc(p, "u_gen.width"), g->width);
    glUniform1f(loc(p, "u_gen.height"), g->height);
    glUniform1ui(loc(p, "u_gen.seed"), g->seed);
    glUniform1ui(loc(p, "u_gen.layers"), g->layers);
    glUniform3fv(loc(p, "u_tree_min"), 1, tr->desc.min);
    glUniform3fv(loc(p, "u_tree_max"), 1, tr->desc.max);
    glUniform1i(loc(p, "u_side"), side);
    glUniform1i(loc(p, "u_entry_count"), nentries);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, f->counts.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, entry_buf.id);
    if (tris) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, tri_buf.id);
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
    /* Node ranges: bb_octree_assign on each leaf's cell centre, repeated
     * count times, gives the same prefix sums the GPU order has. */
    float (*pos)[3] = malloc(sizeof *pos * (size_t)(total ? total : 1));
    uint32_t *order = malloc(sizeof *order * (size_t)(total ? total : 1));
    if (ok && pos && order) {
        size_t s = 0;
        for (int k = 0; k < tr->leaf_count; k++) {
            int node = bb_octree_leaf_node(tr, (uint32_t)k);
            for (uint32_t q = 0; q < counts[k]; q++, s++)
                for (int a = 0; a < 3; a++) pos[s][a] = 0.5f * (tr->lo[node][a] + tr->hi[node][a]);
        }
        bb_octree_assign(tr, (const float (*)[3])pos, (int)total, order);
        for (size_t q = 0; q < total; q++) assert(order[q] == q);
    } else if (ok) {
        core_log_error("out of memory for %llu billboard ranges", (unsigned long long)total);
        ok = false;
    }
    if (tris)
        core_log_info("bb: generated %u billboards on %d terrain triangles in %d (leaf, triangle) entries "
                      "(one draw)", written, f->triangles, nentries);
    else
        core_log_info("bb: generated %u billboards from %d x %d candidates in %d leaves (one draw)", written,
                      f->cells[0], f->cells[1], nentries);
    free(pos), free(order), free(counts);
    return ok;
}

/* Each billboard's bounding sphere as bb_collide.geom computes it (centre
 * half way up the growth direction, radius half the diagonal plus the wind
 * strength), read back once in chunks (through a staging copy: gfx.h). */
static bool read_spheres(bb_field_t *f)
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

bool bb_field_make(bb_field_t *f, const bb_field_desc_t *desc)
{
    double t_start = wall_ms(), mark = t_start;
    bb_gen_tri_t *tris = NULL; /* mesh terrains: generation per triangle */
    memset(f, 0, sizeof *f);
    f->desc = bb_field_desc_defaults(desc);
    bb_field_desc_t *d = &f->desc;
    const terrain_mesh_t *t = d->terrain;
    assert(t && t->positions && t->index_count >= 3);
    if (d->max_objects > BB_MAX_OBJECTS || d->subdiv[0] < SCENE_SUBDIV_MIN || d->subdiv[0] > SCENE_SUBDIV_MAX ||
        d->subdiv[1] < SCENE_SUBDIV_MIN || d->subdiv[1] > SCENE_SUBDIV_MAX || d->octree_depth > BB_OCTREE_MAX_DEPTH) {
        core_log_error("bb_field_make: max_objects %d (at most %d), subdiv %dx%d (%d..%d), octree depth %d "
                       "(at most %d) out of range", d->max_objects, BB_MAX_OBJECTS,
                       d->subdiv[0], d->subdiv[1], SCENE_SUBDIV_MIN, SCENE_SUBDIV_MAX, d->octree_depth, BB_OCTREE_MAX_DEPTH);
        return false;
    }
    int n = d->subdiv[0], m = d->subdiv[1];
    GLint max_verts = 0, max_comps = 0;
    glGetIntegerv(GL_MAX_GEOMETRY_OUTPUT_VERTICES, &max_verts);
    glGetIntegerv(GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS, &max_comps);
    int render_verts = (m - 1) * 2 * n > 4 ? (m - 1) * 2 * n : 4;
    /* bb_render.geom's vertex: g_world, g_normal, g_uvl (3 each), g_tint,
     * g_card, g_overlay (1 each) and gl_Position (4) = 16 components; with
     * BB_GI g_amb_front and g_amb_back (3 each) too. */
    int comps = render_verts * (d->gi ? 22 : 16);
    if (render_verts > max_verts || comps > max_comps) {
        core_log_error("bb_field_make: a %dx%d mesh needs %d geometry-shader vertices (%d components%s); "
                       "this GPU allows %d (%d)", n, m, render_verts, comps,
                       d->gi ? " with grass.gi" : "", max_verts, max_comps);
        return false;
    }
    /* Generation tiles of 2 x 2 candidate cells: at most 4 points (64
     * components) per geometry-shader invocation. The GPU's limit allowed
     * 8 x 8 (1,024 components), which ran at a fraction of the rate on the
     * H100: meadow_large generation 423 ms at 8 x 8, 139 ms at 4 x 4, 69 ms
     * at 2 x 2, the same 384,670 billboards. (llvmpipe goes the other way,
     * 48 -> 102 ms on meadow.json: more invocations.) */
    int tile_points = max_comps / 16 < max_verts ? max_comps / 16 : max_verts;
    int tile = (int)floorf(sqrtf((float)tile_points));
    tile = tile > 2 ? 2 : tile;

    f->gen = bb_gen_desc_defaults(&(bb_gen_desc_t){
        .spacing = 1.0f / sqrtf(d->density), .origin = {t->aabb_min[0], t->aabb_min[2]}, .width = d->size[0],
        .height = d->size[1], .seed = d->placement_seed ? d->placement_seed : d->seed});
    if (!upload_layout(f)) goto fail;
    stage_done(f, BB_MAKE_LAYOUT, &mark);
    double cap;
    if (t->grid_res > 0) {
        float ext_x = t->aabb_max[0] - t->aabb_min[0], ext_z = t->aabb_max[2] - t->aabb_min[2];
        f->cells[0] = (int)ceilf(ext_x / f->gen.spacing);
        f->cells[1] = (int)ceilf(ext_z / f->gen.spacing);
        cap = (double)f->cells[0] * (double)f->cells[1];
    } else if (!(tris = mesh_tris(t, f->gen.spacing, &f->triangles, &cap))) {
        goto fail;
    }
    if (cap > (double)(1u << 26)) {
        core_log_error("bb_field_make: %.0f candidate billboards exceed the limit of %u; lower grass.billboard_density",
                       cap, 1u << 26);
        goto fail;
    }
    f->capacity = (int)cap > 0 ? (int)cap : 1;

    float ymin = t->aabb_min[1], ymax = t->aabb_max[1];
    float pad = 0.01f + 1e-3f * (ymax - ymin);
    float margin = 1.4f * d->size[1] + 0.6f * d->size[0] + d->wind.strength + 0.05f;
    bb_octree_desc_t od = {.min = {t->aabb_min[0], ymin - pad, t->aabb_min[2]},
                           .max = {t->aabb_max[0], ymax + pad, t->aabb_max[2]},
                           .max_depth = d->octree_depth,
                           .margin = margin > 1.0f ? margin : 1.0f};
    if (!bb_octree_build(&f->tree, &od)) goto fail;
    f->ranges = malloc(sizeof *f->ranges * (size_t)f->tree.leaf_count);
    f->sort_keys = malloc(sizeof *f->sort_keys * (size_t)f->tree.leaf_count);
    f->firsts = malloc(sizeof *f->firsts * (size_t)f->tree.leaf_count);
    f->counts_gl = malloc(sizeof *f->counts_gl * (size_t)f->tree.leaf_count);
    f->recover_ranges = malloc(sizeof *f->recover_ranges * 4 * (size_t)f->tree.leaf_count);
    if (!f->ranges || !f->sort_keys || !f->firsts || !f->counts_gl || !f->recover_ranges) {
        core_log_error("out of memory");
        goto fail;
    }

    if (!upload_heights(f, t, f->hgrid)) goto fail;

    char *defines = f->defines;
    snprintf(f->defines, sizeof f->defines,
             "#define BB_N %d\n#define BB_M %d\n#define BB_MAX_CUBES %d\n#define BB_TILE %d\n"
             "#define BB_TILE_POINTS %d\n#define BB_RENDER_VERTS %d\n%s%s",
             n, m, pass_objects(f), tile, tile * tile, render_verts,
             /* the view cards' code only where they are on: compiled in, unused, it
              * cost bb.raster 22 % on the H100 (meadow_large billboard mode) */
             f->views.on ? "#define BB_VIEW_CARDS 1\n" : "", d->gi ? "#define BB_GI 1\n" : "");
    char gen_defines[sizeof f->defines + 32];
    snprintf(gen_defines, sizeof gen_defines, "%s%s", defines, tris ? "#define BB_GEN_TRIANGLES\n" : "");
    f->gen_prog = gfx_program_make(&(gfx_program_desc_t){.vs = "billboard/bb_tile.vert",
                                                         .gs = "billboard/bb_generate.geom", .defines = gen_defines,
                                                         .tf_varyings = bb_tf_varyings, .label = "bb.generate"});
    f->collide_prog = gfx_program_make(&(gfx_program_desc_t){.vs = "billboard/bb_point.vert",
                                                             .gs = "billboard/bb_collide.geom", .defines = defines,
                                                             .tf_varyings = bb_tf_varyings, .label = "bb.collide"});
    f->recover_prog = gfx_program_make(&(gfx_program_desc_t){.cs = "billboard/bb_recover.comp", .defines = defines,
                                                             .label = "bb.recover"});
    f->render_prog = gfx_program_make(&(gfx_program_desc_t){.vs = "billboard/bb_point.vert",
                                                            .gs = "billboard/bb_render.geom",
                                                            .fs = "billboard/bb_render.frag", .defines = defines,
                                                            .label = "bb.render"});
    f->quad_prog = gfx_program_make(&(gfx_program_desc_t){.vs = "billboard/bb_quad.vert",
                                                          .fs = "billboard/bb_render.frag", .defines = defines,
                                                          .label = "bb.quad"});
    f->cube_prog = gfx_program_make(&(gfx_program_desc_t){.vs = "billboard/bb_cube.vert",
                                                          .fs = "billboard/bb_cube.frag", .defines = defines,
                                                          .label = "bb.cube"});
    f->slope_prog = gfx_program_make(&(gfx_program_desc_t){.cs = "billboard/bb_slope.comp", .defines = defines,
                                                           .label = "bb.slope"});
    if (!f->gen_prog.id || !f->collide_prog.id || !f->recover_prog.id || !f->render_prog.id || !f->cube_prog.id ||
        !f->quad_prog.id || !f->slope_prog.id)
        goto fail;
    if (d->occlusion && !bb_occlusion_make(f)) goto fail;
    stage_done(f, BB_MAKE_PROGRAMS, &mark);

    size_t pool_words = 4 + (size_t)d->max_deformed;
    uint32_t *pool = calloc(pool_words, sizeof *pool);
    if (!pool) goto fail;
    pool[0] = (uint32_t)d->max_deformed;
    for (int s = 0; s < d->max_deformed; s++) pool[4 + s] = (uint32_t)(d->max_deformed - 1 - s);
    f->pool = gfx_buffer_make(&(gfx_buffer_desc_t){.size = pool_words * 4, .data = pool, .label = "bb.pool"});
    f->recover_range_buf = gfx_buffer_make(&(gfx_buffer_desc_t){.size = (size_t)f->tree.leaf_count * 16, .dynamic = true,
                                                                .label = "bb.recover_ranges"});
    free(pool);
    f->meshes = gfx_buffer_make(&(gfx_buffer_desc_t){.size = (size_t)d->max_deformed * (size_t)(n * m) * 16,
                                                     .label = "bb.meshes"});
    f->points = gfx_buffer_make(&(gfx_buffer_desc_t){.size = (size_t)f->capacity * sizeof(bb_point_t),
                                                     .label = "bb.points"});
    f->scratch = gfx_buffer_make(&(gfx_buffer_desc_t){.size = (size_t)f->capacity * sizeof(bb_point_t),
                                                      .label = "bb.points_scratch"});
    GLint align = 256;
    glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &align);
    align = align > 0 ? align : 256;
    f->objects_stride = sizeof(bb_object_gpu_t) * (size_t)pass_objects(f);
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
        goto fail;
    f->readback = gfx_readback_make(16, BB_READBACK_SLOTS, "bb.pool_readback");
    if (!f->readback.depth) goto fail;
    setup_points_vao(f->points_vao, f->points.id);
    if (!generate(f, t, tris, tile)) goto fail;
    free(tris);
    tris = NULL;
    stage_done(f, BB_MAKE_GENERATE, &mark);
    if (!read_spheres(f)) goto fail;
    stage_done(f, BB_MAKE_SPHERES, &mark);
    f->make_ms = (float)(wall_ms() - t_start);
    return true;
fail:
    free(tris);
    bb_field_destroy(f);
    return false;
}

void bb_field_destroy(bb_field_t *f)
{
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
    memset(f, 0, sizeof *f);
}

/* ---- update ---------------------------------------------------------------- */

void bb_field_set_cube(bb_field_t *f, int object, const collide_cubemap_t *cube)
{
    assert(object >= 0 && object < f->desc.max_objects && cube->res == f->desc.cube_res);
    glTextureSubImage3D(f->cubes.id, 0, 0, 0, 6 * object, cube->res, cube->res, 6, GL_RGBA, GL_FLOAT, cube->texels);
    glm_vec3_copy((float *)cube->centre, f->cube_centre[object]);
    f->cube_half[object] = cube->half;
}

void bb_field_lend_cubes(const bb_field_t *f, collide_set_t *colliders)
{
    int count = colliders->object_count < f->desc.max_objects ? colliders->object_count : f->desc.max_objects;
    /* Proxy k reads layers 6k .. 6k+5: an object without a rendered map
     * keeps its index with a skipped proxy (sphere radius 0) rather than
     * shifting the later objects onto its layers. */
    for (int k = 0; k < count && colliders->cube_count < COLLIDE_MAX_CUBES; k++) {
        collide_cube_proxy_t *out = &colliders->cubes[colliders->cube_count++];
        float half = f->cube_half[k];
        if (half > 0.0f) collide_make_cube_proxy(colliders->objects[k].model, f->cube_centre[k], half, out);
        else memset(out, 0, sizeof *out);
    }
    colliders->cube_texture = f->cubes.id;
    colliders->cube_res = f->desc.cube_res;
}

/* Billboards in draw ranges (work counters). */
static double range_total(const GLsizei *size, int n)
{
    double s = 0.0;
    for (int i = 0; i < n; i++) s += (double)size[i];
    return s;
}

/* Merges leaf ranges that are adjacent in the buffer into draw ranges. */
static int merge_ranges(bb_field_t *f, int count)
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

/* Object k's six faces into layers 6k .. 6k+5 of f->cubes: the faces'
 * backgrounds, then its mesh, each one instanced draw (instance = face; the
 * layered target's depth was cleared to 1 and the depth test is LEQUAL). */
static void render_cube(bb_field_t *f, const collide_object_t *o, int k)
{
    gfx_program_t p = f->cube_prog;
    glUniform3fv(loc(p, "u_centre"), 1, o->centre);
    glUniform1f(loc(p, "u_half"), o->radius);
    glUniform1i(loc(p, "u_layer"), 6 * k);
    glUniform1i(loc(p, "u_background"), 1);
    glBindVertexArray(f->empty_vao);
    glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, 6);
    glUniform1i(loc(p, "u_background"), 0);
    glBindVertexArray(o->vao);
    glDrawElementsInstanced(GL_TRIANGLES, o->index_count, o->index_type, NULL, 6);
    glm_vec3_copy((float *)o->centre, f->cube_centre[k]);
    f->cube_half[k] = o->radius;
}

/* ---- collide batches ------------------------------------------------------ */

static bool plan_reserve(bb_batch_plan_t *pl, int batches, int ranges)
{
    if (batches > pl->cap) {
        int cap = batches > 2 * pl->cap ? batches : 2 * pl->cap;
        int *rs = realloc(pl->range_start, sizeof *rs * (size_t)(cap + 1));
        if (rs) pl->range_start = rs;
        int *oc = realloc(pl->obj_count, sizeof *oc * (size_t)cap);
        if (oc) pl->obj_count = oc;
        int(*ob)[BB_PASS_OBJECTS] = realloc(pl->obj, sizeof *ob * (size_t)cap);
        if (ob) pl->obj = ob;
        if (!rs || !oc || !ob) return false;
        pl->cap = cap;
    }
    if (ranges > pl->range_cap) {
        int cap = ranges > 2 * pl->range_cap ? ranges : 2 * pl->range_cap;
        GLint *fi = realloc(pl->first, sizeof *fi * (size_t)cap);
        if (fi) pl->first = fi;
        GLsizei *sz = realloc(pl->size, sizeof *sz * (size_t)cap);
        if (sz) pl->size = sz;
        if (!fi || !sz) return false;
        pl->range_cap = cap;
    }
    return true;
}

/* Adds billboards [first, first+count) that must be tested against objs
 * (n <= limit, ascending) to the open batch when the union of the two
 * object lists stays within limit, else opens a new batch. Ranges adjacent
 * in the buffer and in the same batch are merged. */
static bool plan_add(bb_batch_plan_t *pl, int limit, GLint first, GLsizei count, const int *objs, int n)
{
    int b = pl->count - 1, merged[BB_PASS_OBJECTS], m = 0;
    bool fits = b >= 0;
    if (fits) {
        const int *a = pl->obj[b];
        int na = pl->obj_count[b], i = 0, j = 0;
        while ((i < na || j < n) && fits) {
            int v;
            if (j == n || (i < na && a[i] < objs[j])) v = a[i++];
            else if (i == na || objs[j] < a[i]) v = objs[j++];
            else v = a[i++], j++;
            fits = m < limit;
            if (fits) merged[m++] = v;
        }
    }
    if (!plan_reserve(pl, pl->count + 1, pl->range_count + 1)) return false;
    if (!fits) {
        b = pl->count++;
        pl->range_start[b] = pl->range_count;
        memcpy(pl->obj[b], objs, sizeof *objs * (size_t)n);
        pl->obj_count[b] = n;
    } else {
        memcpy(pl->obj[b], merged, sizeof *merged * (size_t)m);
        pl->obj_count[b] = m;
    }
    int r = pl->range_count - 1;
    if (r >= pl->range_start[b] && pl->first[r] + pl->size[r] == first) {
        pl->size[r] += count;
    } else {
        pl->first[++r] = first;
        pl->size[r] = count;
        pl->range_count++;
    }
    pl->range_start[pl->count] = pl->range_count;
    return true;
}

static int cmp_int(const void *a, const void *b) { return *(const int *)a - *(const int *)b; }

/* A leaf whose box meets more than `limit` objects: each billboard's own
 * objects (bounding spheres closer than the sum of the radii, 1 mm of slack
 * over the shader's float test) join the plan one billboard at a time, so
 * runs of billboards share batches; billboards that touch nothing are left
 * out. More than `limit` objects on one billboard: the nearest (surface
 * distance) are kept and the rest counted in f->dropped. */
/* Distance from p to an object's bound (negative inside a sphere, 0 inside
 * a box: a swept object's capsule boxed). */
static float bound_distance(const bb_bound_t *b, const float p[3])
{
    if (b->kind == BB_BOUND_SPHERE) return sqrtf(glm_vec3_distance2((float *)p, (float *)b->centre)) - b->radius;
    float d2 = 0.0f;
    for (int a = 0; a < 3; a++) {
        float e = fmaxf(fabsf(p[a] - b->centre[a]) - b->half[a], 0.0f);
        d2 += e * e;
    }
    return sqrtf(d2);
}

static bool plan_split_leaf(bb_field_t *f, int limit, const bb_range_t *r, const bb_bound_t *bounds,
                            const int *objs, int n)
{
    for (uint32_t i = r->first; i < r->first + r->count; i++) {
        const float *sp = f->spheres[i];
        float dist[BB_MAX_OBJECTS];
        int hit[BB_MAX_OBJECTS], h = 0;
        for (int q = 0; q < n; q++) {
            float dd = bound_distance(&bounds[objs[q]], sp) - sp[3];
            if (dd < 1e-3f) dist[h] = dd, hit[h++] = objs[q];
        }
        if (h == 0) continue;
        if (h > limit) {
            for (int a = 1; a < h; a++) /* insertion sort by distance, ties by index */
                for (int c = a; c > 0 && dist[c] < dist[c - 1]; c--) {
                    float td = dist[c];
                    dist[c] = dist[c - 1], dist[c - 1] = td;
                    int ti = hit[c];
                    hit[c] = hit[c - 1], hit[c - 1] = ti;
                }
            f->dropped += h - limit;
            h = limit;
            qsort(hit, (size_t)h, sizeof *hit, cmp_int);
        }
        if (!plan_add(&f->plan, limit, (GLint)i, 1, hit, h)) return false;
    }
    return true;
}

/* Groups the colliding leaf ranges f->ranges[0..ncol) into batches of at
 * most pass_objects(f) objects; need[k] is set for every object in a batch. */
static bool plan_batches(bb_field_t *f, int ncol, const bb_bound_t *bounds, int count, bool *need)
{
    bb_batch_plan_t *pl = &f->plan;
    pl->count = pl->range_count = 0;
    int limit = pass_objects(f);
    int dropped_before = f->dropped;
    for (int i = 0; i < ncol; i++) {
        const bb_range_t *r = &f->ranges[i];
        int node = bb_octree_leaf_node(&f->tree, r->leaf), objs[BB_MAX_OBJECTS], n = 0;
        for (int k = 0; k < count; k++)
            if (bb_bound_overlaps_box(&bounds[k], f->tree.lo[node], f->tree.hi[node], f->tree.desc.margin))
                objs[n++] = k;
        bool ok = n <= limit ? n == 0 || plan_add(pl, limit, (GLint)r->first, (GLsizei)r->count, objs, n)
                             : plan_split_leaf(f, limit, r, bounds, objs, n);
        if (!ok) {
            core_log_error("out of memory for %d collide batches", pl->count);
            return false;
        }
    }
    for (int b = 0; b < pl->count; b++)
        for (int j = 0; j < pl->obj_count[b]; j++) need[pl->obj[b][j]] = true;
    if (f->dropped > dropped_before && f->dropped_logged == 0) {
        core_log_warn("bb: a billboard's bounding sphere meets more than %d objects; it collides with the nearest "
                      "%d (%d object hits left out so far, see bb_stats_t.objects_dropped)",
                      limit, limit, f->dropped);
        f->dropped_logged = f->dropped;
    }
    return true;
}

/* Runs one transform-feedback pass of `prog` over the ranges first/size:
 * points -> scratch (appended in draw order), then copied back in place.
 * With a plan (collide), batch b binds its region of the objects buffer,
 * sets u_count and draws its own ranges, all inside the one transform
 * feedback. */
static void tf_pass(bb_field_t *f, gfx_program_t prog, const GLint *first, const GLsizei *size, int nranges,
                    const bb_batch_plan_t *pl)
{
    glUseProgram(prog.id);
    glBindVertexArray(f->points_vao);
    GLint fbo = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, f->cube_target.fbo); /* draws need a complete framebuffer */
    glEnable(GL_RASTERIZER_DISCARD);
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, f->tf);
    glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, f->scratch.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, f->pool.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, f->meshes.id);
    glBeginTransformFeedback(GL_POINTS);
    if (!pl) {
        glMultiDrawArrays(GL_POINTS, first, size, nranges);
    } else {
        GLint count_loc = loc(prog, "u_count");
        for (int b = 0; b < pl->count; b++) {
            glBindBufferRange(GL_UNIFORM_BUFFER, 0, f->objects.id, (GLintptr)(f->objects_stride * (size_t)b),
                              (GLsizeiptr)f->objects_stride);
            glUniform1i(count_loc, pl->obj_count[b]);
            int r0 = pl->range_start[b];
            glMultiDrawArrays(GL_POINTS, first + r0, size + r0, pl->range_start[b + 1] - r0);
        }
    }
    glEndTransformFeedback();
    glBindTransformFeedback(GL_TRANSFORM_FEEDBACK, 0);
    glDisable(GL_RASTERIZER_DISCARD);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
    size_t off = 0;
    for (int i = 0; i < nranges; i++) {
        size_t bytes = (size_t)size[i] * sizeof(bb_point_t);
        glCopyNamedBufferSubData(f->scratch.id, f->points.id, (GLintptr)off,
                                 (GLintptr)((size_t)first[i] * sizeof(bb_point_t)), (GLsizeiptr)bytes);
        off += bytes;
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* Uploads every batch's object entries (one aligned region per batch, all
 * in a single update before the pass, so no batch waits on another's
 * upload) and runs the collide pass over the batches. */
static bool collide_batches(bb_field_t *f, const bb_object_gpu_t *gpu)
{
    bb_batch_plan_t *pl = &f->plan;
    size_t need = f->objects_stride * (size_t)pl->count;
    if (need > f->objects_size) {
        size_t size = need > 2 * f->objects_size ? need : 2 * f->objects_size;
        gfx_buffer_destroy(&f->objects);
        f->objects = gfx_buffer_make(&(gfx_buffer_desc_t){.size = size, .dynamic = true, .label = "bb.objects"});
        f->objects_size = f->objects.id ? size : 0;
        if (!f->objects.id) return false;
    }
    uint8_t *staging = calloc(need, 1);
    if (!staging) {
        core_log_error("out of memory for %d collide batches", pl->count);
        return false;
    }
    for (int b = 0; b < pl->count; b++) {
        bb_object_gpu_t *dst = (bb_object_gpu_t *)(staging + f->objects_stride * (size_t)b);
        for (int j = 0; j < pl->obj_count[b]; j++) dst[j] = gpu[pl->obj[b][j]];
    }
    gfx_buffer_update(f->objects, 0, need, staging);
    free(staging);

    tf_pass(f, f->collide_prog, f->plan.first, f->plan.size, f->plan.range_count, &f->plan);
    gfx_count_add("bb.collided", range_total(f->plan.size, f->plan.range_count));
    gfx_count_add("bb.collide_batches", pl->count);
    return true;
}

static float max_scale(const float *m)
{
    float s = 0.0f;
    for (int c = 0; c < 3; c++) s = fmaxf(s, sqrtf(m[4 * c] * m[4 * c] + m[4 * c + 1] * m[4 * c + 1] + m[4 * c + 2] * m[4 * c + 2]));
    return s;
}

/* Reads every readback slot whose fence has passed (the copy has completed,
 * so the read does not wait), oldest first, and logs pool exhaustion the
 * first time and whenever the refused count has doubled since the last
 * warning (no per-frame spam). */
static void poll_readbacks(bb_field_t *f)
{
    int slot;
    while ((slot = gfx_readback_poll(&f->readback, false)) >= 0) {
        uint32_t hdr[2];
        gfx_readback_read(&f->readback, slot, 0, sizeof hdr, hdr);
        f->deformed_last = f->desc.max_deformed - (int32_t)hdr[0];
        f->exhausted_last = (int)hdr[1] > f->exhausted_last ? (int)hdr[1] : f->exhausted_last;
        if (f->exhausted_last > 0 && f->exhausted_last >= 2 * f->exhausted_logged) {
            core_log_warn("bb: deformed-mesh pool of %d slots exhausted: %d collisions left undeformed so far "
                          "(raise grass.deformed_pool)", f->desc.max_deformed, f->exhausted_last);
            f->exhausted_logged = f->exhausted_last;
        }
    }
}

/* Queues a fenced copy of the pool header. When every slot is still in
 * flight the copy is skipped (a later one reports the same running
 * counters). */
static void queue_readback(bb_field_t *f)
{
    if (gfx_readback_busy(&f->readback)) return;
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_readback_copy(&f->readback, f->pool, 0, 0, 16);
    gfx_readback_fence(&f->readback);
}

void bb_field_set_hidden(bb_field_t *f, const float camera[3], float fade_start)
{
    for (int a = 0; a < 3; a++) f->hidden[a] = camera[a];
    f->hidden[3] = fade_start > 0.0f ? fade_start : 0.0f;
}

/* True when bound b cannot reach a drawn billboard (bb_field_set_hidden).
 * A drawn billboard's root is at least fade_start - r from the camera
 * (bb_fade_dropped: r = half its diagonal, at most its bounding sphere's
 * radius), its sphere's centre at most r above the root and its geometry
 * within the sphere, so all of it lies beyond fade_start - 3 r. */
static bool bound_hidden(const bb_field_t *f, const bb_bound_t *b)
{
    if (f->hidden[3] <= 0.0f) return false;
    float reach = b->radius;
    if (b->kind == BB_BOUND_AABB) reach = glm_vec3_norm((float *)b->half);
    return glm_vec3_distance((float *)f->hidden, (float *)b->centre) + reach < f->hidden[3] - 3.0f * f->sphere_max;
}

void bb_field_update(bb_field_t *f, const collide_set_t *colliders, float time, float dt)
{
    const collide_object_t *objs = colliders ? colliders->objects : NULL;
    int count = colliders ? colliders->object_count : 0;
    assert(count >= 0 && count <= f->desc.max_objects);
    const bb_field_desc_t *d = &f->desc;
    f->time = time;
    f->batches_last = 0;
    poll_readbacks(f);
    bool gpu_work = false;
    bb_bound_t bounds[BB_MAX_OBJECTS];
    bb_object_gpu_t gpu[BB_MAX_OBJECTS];
    int hidden = 0;
    for (int k = 0; k < count; k++) {
        mat4 model, inv;
        memcpy(model, objs[k].model, sizeof model);
        glm_mat4_inv(model, inv);
        vec3 c;
        glm_mat4_mulv3(model, (float *)objs[k].centre, 1.0f, c);
        float radius = objs[k].radius * max_scale(objs[k].model);
        vec3 sweep;
        glm_vec3_sub((float *)objs[k].prev_position, (float *)objs[k].position, sweep);
        bounds[k] = (bb_bound_t){.kind = BB_BOUND_SPHERE, .centre = {c[0], c[1], c[2]}, .radius = radius};
        if (glm_vec3_norm2(sweep) > 0.0f) {
            /* the step's capsule, boxed (broad phase only) */
            bounds[k].kind = BB_BOUND_AABB;
            for (int a = 0; a < 3; a++) {
                bounds[k].centre[a] = c[a] + 0.5f * sweep[a];
                bounds[k].half[a] = 0.5f * fabsf(sweep[a]) + radius;
            }
        }
        if (bound_hidden(f, &bounds[k])) {
            bounds[k].kind = BB_BOUND_NONE;
            hidden++;
        }
        memcpy(gpu[k].sweep, sweep, sizeof sweep);
        gpu[k].sweep[3] = 0.0f;
        memcpy(gpu[k].w2c, inv, sizeof inv);
        memcpy(gpu[k].c2w, model, sizeof model);
        memcpy(gpu[k].sphere, c, sizeof c);
        gpu[k].sphere[3] = -1.0f;
        gpu[k].layer[0] = 6 * k;
        gpu[k].layer[1] = gpu[k].layer[2] = gpu[k].layer[3] = 0;
    }
    f->hidden_last = hidden;
    bb_octree_update(&f->tree, bounds, count, dt, d->recover_time + BB_LEAF_RECOVER_SLACK);
    int ncol = bb_octree_collect(&f->tree, BB_NODE_MASK(BB_NODE_COLLIDING), NULL, f->ranges, f->tree.leaf_count);
    if (ncol > 0) {
        /* Cube maps only for objects in a collide batch. */
        bool need[BB_MAX_OBJECTS] = {0};
        bool planned = plan_batches(f, ncol, bounds, count, need);
        int nneed = 0;
        for (int k = 0; k < count; k++) nneed += need[k] && objs[k].vao;
        if (nneed > 0) {
            GLint fbo = 0, vp[4];
            glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &fbo);
            glGetIntegerv(GL_VIEWPORT, vp);
            gfx_timer_begin("bb.cubemaps");
            glBindFramebuffer(GL_FRAMEBUFFER, f->cube_target.fbo);
            glEnable(GL_DEPTH_TEST);
            glDepthFunc(GL_LEQUAL);
            glDepthMask(GL_TRUE);
            glDisable(GL_CULL_FACE);
            glDisable(GL_BLEND);
            glViewport(0, 0, d->cube_res, d->cube_res);
            float one = 1.0f;
            glClearBufferfv(GL_DEPTH, 0, &one); /* every layer */
            glUseProgram(f->cube_prog.id);
            for (int k = 0; k < count; k++)
                if (need[k] && objs[k].vao) render_cube(f, &objs[k], k);
            glDepthFunc(GL_LESS);
            gfx_timer_end();
            glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)fbo);
            glViewport(vp[0], vp[1], vp[2], vp[3]);
        }
        for (int k = 0; k < count; k++) {
            if (!need[k]) continue;
            glm_vec3_copy(f->cube_centre[k], gpu[k].cube);
            gpu[k].cube[3] = f->cube_half[k];
            gpu[k].sphere[3] = bounds[k].radius;
        }
        gfx_program_t p = f->collide_prog;
        glUseProgram(p.id);
        glBindTextureUnit(0, f->cubes.id);
        glUniform1i(loc(p, "u_cubes"), 0);
        set_heights(f, p, 1);
        glUniform1i(loc(p, "u_res"), d->cube_res);
        glUniform1f(loc(p, "u_time"), time);
        glUniform1f(loc(p, "u_recover"), d->recover_time);
        glUniform1f(loc(p, "u_r1"), d->r1);
        glUniform1f(loc(p, "u_r2"), d->r2);
        glUniform1i(loc(p, "u_iterations"), d->iterations);
        glUniform1i(loc(p, "u_paper"), d->paper ? 1 : 0);
        set_wind(p.id, &d->wind);
        f->batches_last = planned ? f->plan.count : 0;
        if (f->batches_last > 0) {
            gfx_timer_begin("bb.collide");
            gpu_work = collide_batches(f, gpu);
            gfx_timer_end();
        }
    }
    int nrec = bb_octree_collect(&f->tree, BB_NODE_MASK(BB_NODE_COLLIDING) | BB_NODE_MASK(BB_NODE_RECOVERING), NULL,
                                 f->ranges, f->tree.leaf_count);
    if (nrec > 0) {
        int nr = merge_ranges(f, nrec);
        uint32_t threads = 0;
        for (int i = 0; i < nr; i++) {
            f->recover_ranges[4 * i + 0] = (uint32_t)f->firsts[i];
            f->recover_ranges[4 * i + 1] = (uint32_t)f->counts_gl[i];
            f->recover_ranges[4 * i + 2] = threads;
            threads += (uint32_t)f->counts_gl[i];
        }
        gfx_program_t p = f->recover_prog;
        glUseProgram(p.id);
        glUniform1f(loc(p, "u_time"), time);
        glUniform1f(loc(p, "u_dt"), dt);
        glUniform1i(loc(p, "u_range_count"), nr);
        glUniform1ui(loc(p, "u_threads"), threads);
        set_wind(p.id, &d->wind);
        gfx_timer_begin("bb.recover");
        gfx_buffer_update(f->recover_range_buf, 0, (size_t)nr * 16, f->recover_ranges);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, f->pool.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, f->meshes.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, f->points.id);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, f->recover_range_buf.id);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
        glDispatchCompute((threads + 63u) / 64u, 1, 1);
        glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT |
                        GL_BUFFER_UPDATE_BARRIER_BIT);
        gfx_timer_end();
        gfx_count_add("bb.recovered", range_total(f->counts_gl, nr));
        gpu_work = true;
    }
    if (gpu_work) queue_readback(f);
}

/* ---- draw ------------------------------------------------------------------ */

static void render_uniforms(const bb_field_t *f, gfx_program_t p, const bb_draw_desc_t *dd)
{
    glUseProgram(p.id);
    glUniformMatrix4fv(loc(p, "u_viewproj"), 1, GL_FALSE, dd->viewproj);
    glUniform3fv(loc(p, "u_camera"), 1, dd->camera);
    glUniform3fv(loc(p, "u_sun"), 1, dd->sun_dir);
    glUniform1f(loc(p, "u_time"), dd->time);
    glUniform1f(loc(p, "u_fade_start"), dd->fade_start);
    glUniform1f(loc(p, "u_fade_end"), dd->fade_end);
    glUniform1f(loc(p, "u_far_start"), dd->far_start);
    glUniform1f(loc(p, "u_far_end"), dd->far_end);
    glUniform1i(loc(p, "u_clumps"), 0);
    glUniform1i(loc(p, "u_overlay"), dd->overlay);
    set_wind(p.id, &f->desc.wind);
    set_views(f, p.id);
    const hybrid_slope_grid_t *g = &dd->slope_grid;
    glUniform1i(loc(p, "u_slope_on"), dd->slope_map.id != 0);
    glUniform1f(loc(p, "u_slope_time"), dd->time);
    glUniform1f(loc(p, "u_slope_recover"), dd->slope_recover > 0.0f ? dd->slope_recover : f->desc.recover_time);
    glUniform2fv(loc(p, "u_slope_origin"), 1, g->origin);
    glUniform1f(loc(p, "u_slope_cell"), g->cell);
    glUniform2i(loc(p, "u_slope_dims"), g->nx, g->nz);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 13, dd->slope_map.id);
    gi_set_uniforms(p.id, f->desc.gi ? &dd->gi : NULL); /* without BB_GI no vertex carries it */
}

void bb_field_add_slopes(bb_field_t *f, const hybrid_slope_grid_t *g, gfx_buffer_t sums)
{
    if (f->billboards == 0) return;
    gfx_program_t p = f->slope_prog;
    glUseProgram(p.id);
    glUniform1ui(loc(p, "u_count"), (GLuint)f->billboards);
    glUniform1f(loc(p, "u_time"), f->time);
    glUniform2fv(loc(p, "u_slope_origin"), 1, g->origin);
    glUniform1f(loc(p, "u_slope_cell"), g->cell);
    glUniform2i(loc(p, "u_slope_dims"), g->nx, g->nz);
    set_wind(p.id, &f->desc.wind);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, f->meshes.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, f->points.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 14, sums.id);
    glDispatchCompute(((GLuint)f->billboards + 255u) / 256u, 1, 1);
    gfx_count_add("bb.slope_read", f->billboards);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* Idle leaves (only plain quads) are drawn by vertex pulling, six vertices
 * per billboard, with no geometry shader; colliding and recovering leaves,
 * which hold deformed meshes, go through bb_render.geom. Both share
 * bb_render.frag. Leaves go nearest first (bb_octree_sort_near_first), so
 * the coarse depth test rejects more of the far layers that nearer ones
 * already cover (docs/PERFORMANCE.md). */
void bb_field_draw(bb_field_t *f, const bb_draw_desc_t *dd)
{
    glBindTextureUnit(0, f->clumps.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, f->pool.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, f->meshes.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, f->points.id);
    glBindVertexArray(f->points_vao);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    gfx_timer_begin("bb.render");
    const float(*planes)[4] = (const float (*)[4])dd->planes;
    int n = bb_octree_collect(&f->tree, BB_NODE_MASK(BB_NODE_IDLE), planes, f->ranges, f->tree.leaf_count);
    if (dd->far_end > 0.0f) n = bb_octree_keep_near(&f->tree, dd->camera, dd->far_end, f->ranges, n);
    if (f->desc.occlusion) n = bb_occlusion_filter(f, f->ranges, n, dd->camera);
    if (n > 0) {
        bb_octree_sort_near_first(&f->tree, dd->camera, f->ranges, n, f->sort_keys);
        int nr = merge_ranges(f, n);
        gfx_count_add("bb.drawn_quads", range_total(f->counts_gl, nr));
        for (int i = 0; i < nr; i++) {
            f->firsts[i] *= 6;
            f->counts_gl[i] *= 6;
        }
        render_uniforms(f, f->quad_prog, dd);
        glMultiDrawArrays(GL_TRIANGLES, f->firsts, f->counts_gl, nr);
    }
    n = bb_octree_collect(&f->tree, BB_NODE_MASK(BB_NODE_COLLIDING) | BB_NODE_MASK(BB_NODE_RECOVERING), planes,
                          f->ranges, f->tree.leaf_count);
    if (dd->far_end > 0.0f) n = bb_octree_keep_near(&f->tree, dd->camera, dd->far_end, f->ranges, n);
    if (f->desc.occlusion) n = bb_occlusion_filter(f, f->ranges, n, dd->camera);
    if (n > 0) {
        bb_octree_sort_near_first(&f->tree, dd->camera, f->ranges, n, f->sort_keys);
        int nr = merge_ranges(f, n);
        gfx_count_add("bb.drawn_meshes", range_total(f->counts_gl, nr));
        render_uniforms(f, f->render_prog, dd);
        glMultiDrawArrays(GL_POINTS, f->firsts, f->counts_gl, nr);
    }
    gfx_timer_end();
    if (f->desc.occlusion) {
        gfx_timer_begin("bb.occlusion");
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
    render_uniforms(b->f, p, b->dd);
    glUniform4fv(loc(p, "u_planes"), 6, &b->dd->planes[0][0]);
    glUniform1ui(loc(p, "u_count"), (GLuint)b->f->billboards);
    glBindTextureUnit(0, b->f->clumps.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, b->f->pool.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, b->f->meshes.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, b->f->points.id);
}

bool bb_field_raster(bb_field_t *f, raster_t *r, const bb_draw_desc_t *dd)
{
    gfx_timer_begin("bb.raster");
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
    glBindTextureUnit(0, 0);
    gfx_timer_end();
    return ok;
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
    out->pool_capacity = f->desc.max_deformed;
    out->generate_ms = f->generate_ms;
    out->make_ms = f->make_ms;
    memcpy(out->make_stage_ms, f->make_stage_ms, sizeof out->make_stage_ms);
    out->batches = f->batches_last;
    out->objects_dropped = f->dropped;
    out->objects_hidden = f->hidden_last;
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

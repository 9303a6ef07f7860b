/* terrain: procedural value-noise fBm heightfield, assimp mesh loading, and
 * ground-height queries (barycentric on the grid, vertical ray casts through a
 * uniform 2D triangle grid for meshes). See terrain.h. */
#include "terrain/terrain.h"
#include "mesh/mesh_import.h"

#include <assert.h>
#include <assimp/cimport.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/core.h"

#define TERRAIN_OCTAVES 4
#define TERRAIN_BASE_WAVELENGTH 16.0f
#define TERRAIN_GRID_MAX_CELLS 512
#define TERRAIN_GRID_TRIS_PER_CELL 4.0

/* Unit normal, or +y for a degenerate (zero) one. */
static void normalize_or_up(float *n)
{
    float len = glm_vec3_norm(n);
    if (len > 0) {
        glm_vec3_scale(n, 1.0f / len, n);
    } else {
        n[0] = 0;
        n[1] = 1;
        n[2] = 0;
    }
}

terrain_desc_t terrain_desc_defaults(const terrain_desc_t *d)
{
    terrain_desc_t r = *d;
    if (r.size <= 0) r.size = TERRAIN_DEFAULT_SIZE;
    if (r.resolution <= 0) r.resolution = TERRAIN_DEFAULT_RESOLUTION;
    if (r.height <= 0) r.height = TERRAIN_DEFAULT_HEIGHT;
    if (r.scale <= 0) r.scale = TERRAIN_DEFAULT_SCALE;
    return r;
}

/* Lattice value in [-1, 1) at integer (ix, iz) of one octave. */
static float lattice(int32_t ix, int32_t iz, uint32_t octave, uint64_t seed)
{
    uint32_t h = core_hash_u32((uint32_t)seed ^ core_hash_u32((uint32_t)(seed >> 32) ^ octave));
    h = core_hash_u32(h ^ (uint32_t)ix);
    h = core_hash_u32(h ^ (uint32_t)iz);
    return core_hash_float(h) * 2.0f - 1.0f;
}

static float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

/* fBm of value noise, normalised to [-1, 1]. */
static float fbm(float x, float z, uint64_t seed)
{
    float sum = 0, norm = 0, amp = 1, freq = 1.0f / TERRAIN_BASE_WAVELENGTH;
    for (uint32_t o = 0; o < TERRAIN_OCTAVES; o++) {
        float fx = x * freq, fz = z * freq;
        float x0 = floorf(fx), z0 = floorf(fz);
        int32_t ix = (int32_t)x0, iz = (int32_t)z0;
        float u = fade(fx - x0), v = fade(fz - z0);
        float a = lattice(ix, iz, o, seed), b = lattice(ix + 1, iz, o, seed);
        float c = lattice(ix, iz + 1, o, seed), d = lattice(ix + 1, iz + 1, o, seed);
        float n = (a + (b - a) * u) + ((c + (d - c) * u) - (a + (b - a) * u)) * v;
        sum += amp * n;
        norm += amp;
        amp *= 0.5f;
        freq *= 2.0f;
    }
    return sum / norm;
}

static bool alloc_mesh(terrain_mesh_t *m, uint32_t nv, uint32_t ni)
{
    m->positions = malloc(sizeof(float) * 3 * nv);
    m->normals = calloc((size_t)nv * 3, sizeof(float));
    m->uvs = malloc(sizeof(float) * 2 * nv);
    m->indices = malloc(sizeof(uint32_t) * ni);
    m->vertex_count = nv;
    m->index_count = ni;
    if (m->positions && m->normals && m->uvs && m->indices) return true;
    terrain_free(m);
    return false;
}

static void compute_aabb(terrain_mesh_t *m)
{
    glm_vec3_fill(m->aabb_min, FLT_MAX);
    glm_vec3_fill(m->aabb_max, -FLT_MAX);
    for (uint32_t i = 0; i < m->vertex_count; i++) {
        glm_vec3_minv(m->aabb_min, &m->positions[3 * i], m->aabb_min);
        glm_vec3_maxv(m->aabb_max, &m->positions[3 * i], m->aabb_max);
    }
}

/* Area-weighted vertex normals from the faces. */
static void compute_normals(terrain_mesh_t *m)
{
    memset(m->normals, 0, sizeof(float) * 3 * m->vertex_count);
    for (uint32_t t = 0; t + 2 < m->index_count; t += 3) {
        const uint32_t *ix = &m->indices[t];
        vec3 e1, e2, n;
        glm_vec3_sub(&m->positions[3 * ix[1]], &m->positions[3 * ix[0]], e1);
        glm_vec3_sub(&m->positions[3 * ix[2]], &m->positions[3 * ix[0]], e2);
        glm_vec3_cross(e1, e2, n);
        for (int k = 0; k < 3; k++) glm_vec3_add(&m->normals[3 * ix[k]], n, &m->normals[3 * ix[k]]);
    }
    for (uint32_t i = 0; i < m->vertex_count; i++) {
        float *n = &m->normals[3 * i];
        normalize_or_up(n);
    }
}

bool terrain_make_world(terrain_mesh_t *mesh, const terrain_desc_t *desc, uint64_t seed)
{
    memset(mesh, 0, sizeof *mesh);
    terrain_world_t w = terrain_world_make(desc, seed);
    if (!(w.size <= TERRAIN_WORLD_SIZE_MAX)) {
        core_log_error("terrain: world size %g m exceeds the maximum %g (TERRAIN_WORLD_SIZE_MAX)", (double)w.size,
                       (double)TERRAIN_WORLD_SIZE_MAX);
        return false;
    }
    mesh->type = TERRAIN_WORLD;
    mesh->world = w;
    float half = w.size * 0.5f;
    glm_vec3_copy((vec3){-half, -w.height, -half}, mesh->aabb_min);
    glm_vec3_copy((vec3){half, w.height, half}, mesh->aabb_max);
    return true;
}

bool terrain_make_heightfield(terrain_mesh_t *mesh, const terrain_desc_t *desc, uint64_t seed)
{
    if (desc->type == TERRAIN_WORLD) return terrain_make_world(mesh, desc, seed);
    memset(mesh, 0, sizeof *mesh);
    terrain_desc_t d = terrain_desc_defaults(desc);
    if (d.resolution > TERRAIN_RESOLUTION_MAX) {
        core_log_error("terrain: resolution %d exceeds the maximum %d (TERRAIN_RESOLUTION_MAX)", d.resolution,
                       TERRAIN_RESOLUTION_MAX);
        return false;
    }
    uint32_t res = (uint32_t)d.resolution, side = res + 1;
    if (!alloc_mesh(mesh, side * side, res * res * 6)) {
        core_log_error("terrain: out of memory for a %u x %u heightfield", res, res);
        return false;
    }
    float half = d.size * 0.5f, cell = d.size / (float)res;
    for (uint32_t j = 0; j < side; j++) {
        for (uint32_t i = 0; i < side; i++) {
            uint32_t v = j * side + i;
            float x = -half + (float)i * cell, z = -half + (float)j * cell;
            mesh->positions[3 * v + 0] = x;
            mesh->positions[3 * v + 1] = d.height * fbm(x, z, seed);
            mesh->positions[3 * v + 2] = z;
            mesh->uvs[2 * v + 0] = (float)i / (float)res;
            mesh->uvs[2 * v + 1] = (float)j / (float)res;
        }
    }
    uint32_t *ix = mesh->indices;
    for (uint32_t j = 0; j < res; j++) {
        for (uint32_t i = 0; i < res; i++) {
            uint32_t v00 = j * side + i, v10 = v00 + 1, v01 = v00 + side, v11 = v01 + 1;
            /* Diagonal v00-v11; both triangles counter-clockwise seen from +y. */
            *ix++ = v00;
            *ix++ = v01;
            *ix++ = v11;
            *ix++ = v00;
            *ix++ = v11;
            *ix++ = v10;
        }
    }
    compute_normals(mesh);
    compute_aabb(mesh);
    mesh->grid_res = d.resolution;
    mesh->grid_size = d.size;
    return true;
}

/* After SortByPType a mesh holds one primitive type; newer assimp also sets
 * flag bits (e.g. NGON encoding), so mask to the primitive kinds. */
static bool is_triangle_mesh(const struct aiMesh *am)
{
    unsigned kinds = aiPrimitiveType_POINT | aiPrimitiveType_LINE | aiPrimitiveType_TRIANGLE |
                     aiPrimitiveType_POLYGON;
    return (am->mPrimitiveTypes & kinds) == aiPrimitiveType_TRIANGLE;
}

static bool finite3(const float *v) { return isfinite(v[0]) && isfinite(v[1]) && isfinite(v[2]); }

bool terrain_load_mesh(terrain_mesh_t *mesh, const char *path, float scale, char *err,
                       size_t err_size)
{
    memset(mesh, 0, sizeof *mesh);
    if (scale <= 0) scale = 1.0f;
    char full[4096];
    if (path[0] == '/') {
        snprintf(full, sizeof full, "%s", path);
    } else if (!core_fs_resolve(path, full, sizeof full)) {
        snprintf(err, err_size, "%s: cannot read: %s", path, strerror(ENOENT));
        return false;
    }
    if (access(full, R_OK) != 0) {
        snprintf(err, err_size, "%s: cannot read: %s", path, strerror(errno));
        return false;
    }
    char why[512];
    const struct aiScene *sc =
        mesh_import(full, aiProcess_Triangulate | aiProcess_GenSmoothNormals | aiProcess_JoinIdenticalVertices |
                              aiProcess_PreTransformVertices | aiProcess_SortByPType,
                    why, sizeof why);
    if (!sc) {
        snprintf(err, err_size, "%s: %s", path, why);
        return false;
    }
    uint64_t nv = 0, ni = 0;
    for (unsigned m = 0; m < sc->mNumMeshes; m++) {
        const struct aiMesh *am = sc->mMeshes[m];
        if (!is_triangle_mesh(am)) continue;
        nv += am->mNumVertices;
        ni += (uint64_t)am->mNumFaces * 3;
    }
    if (nv == 0 || ni == 0) {
        snprintf(err, err_size, "%s: no triangles (%llu vertices in %u meshes)", path,
                 (unsigned long long)nv, sc->mNumMeshes);
        aiReleaseImport(sc);
        return false;
    }
    if (nv > UINT32_MAX || ni > UINT32_MAX || !alloc_mesh(mesh, (uint32_t)nv, (uint32_t)ni)) {
        snprintf(err, err_size, "%s: out of memory (%llu vertices)", path, (unsigned long long)nv);
        aiReleaseImport(sc);
        return false;
    }
    uint32_t base = 0, *ix = mesh->indices;
    bool has_uv = true;
    for (unsigned m = 0; m < sc->mNumMeshes; m++) {
        const struct aiMesh *am = sc->mMeshes[m];
        if (!is_triangle_mesh(am)) continue;
        if (!am->mTextureCoords[0]) has_uv = false;
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            float *p = &mesh->positions[3 * (base + v)], *n = &mesh->normals[3 * (base + v)];
            p[0] = am->mVertices[v].x * scale;
            p[1] = am->mVertices[v].y * scale;
            p[2] = am->mVertices[v].z * scale;
            if (am->mNormals) {
                n[0] = am->mNormals[v].x;
                n[1] = am->mNormals[v].y;
                n[2] = am->mNormals[v].z;
            }
            if (am->mTextureCoords[0]) {
                mesh->uvs[2 * (base + v) + 0] = am->mTextureCoords[0][v].x;
                mesh->uvs[2 * (base + v) + 1] = am->mTextureCoords[0][v].y;
            }
            if (!finite3(p) || !finite3(n) ||
                (am->mTextureCoords[0] && !(isfinite(mesh->uvs[2 * (base + v)]) &&
                                            isfinite(mesh->uvs[2 * (base + v) + 1])))) {
                snprintf(err, err_size, "%s: mesh %u vertex %u has NaN or infinite data", path, m, v);
                aiReleaseImport(sc);
                terrain_free(mesh);
                return false;
            }
            normalize_or_up(n);
        }
        for (unsigned f = 0; f < am->mNumFaces; f++)
            for (int k = 0; k < 3; k++) *ix++ = base + am->mFaces[f].mIndices[k];
        base += am->mNumVertices;
    }
    aiReleaseImport(sc);
    mesh->type = TERRAIN_MESH;
    compute_aabb(mesh);
    if (!has_uv) {
        float wx = fmaxf(mesh->aabb_max[0] - mesh->aabb_min[0], 1e-6f);
        float wz = fmaxf(mesh->aabb_max[2] - mesh->aabb_min[2], 1e-6f);
        for (uint32_t v = 0; v < mesh->vertex_count; v++) {
            mesh->uvs[2 * v + 0] = (mesh->positions[3 * v + 0] - mesh->aabb_min[0]) / wx;
            mesh->uvs[2 * v + 1] = (mesh->positions[3 * v + 2] - mesh->aabb_min[2]) / wz;
        }
    }
    if (!terrain_build_grid(mesh)) {
        snprintf(err, err_size, "%s: out of memory building the triangle grid", path);
        terrain_free(mesh);
        return false;
    }
    return true;
}

static void cell_of(const terrain_mesh_t *m, float x, float z, int *cx, int *cz)
{
    int i = (int)floorf((x - m->aabb_min[0]) / m->cell_w);
    int j = (int)floorf((z - m->aabb_min[2]) / m->cell_d);
    *cx = i < 0 ? 0 : i >= m->cells_x ? m->cells_x - 1 : i;
    *cz = j < 0 ? 0 : j >= m->cells_z ? m->cells_z - 1 : j;
}

bool terrain_build_grid(terrain_mesh_t *m)
{
    free(m->cell_start);
    free(m->cell_tris);
    m->cell_start = m->cell_tris = NULL;
    uint32_t ntri = m->index_count / 3;
    float wx = fmaxf(m->aabb_max[0] - m->aabb_min[0], 1e-3f);
    float wz = fmaxf(m->aabb_max[2] - m->aabb_min[2], 1e-3f);
    double cells = fmax(1.0, ntri / TERRAIN_GRID_TRIS_PER_CELL);
    double nx = round(sqrt(cells * wx / wz)), nz = round(sqrt(cells * wz / wx));
    m->cells_x = (int)fmin(fmax(nx, 1.0), TERRAIN_GRID_MAX_CELLS);
    m->cells_z = (int)fmin(fmax(nz, 1.0), TERRAIN_GRID_MAX_CELLS);
    m->cell_w = wx / (float)m->cells_x;
    m->cell_d = wz / (float)m->cells_z;
    size_t ncell = (size_t)m->cells_x * (size_t)m->cells_z;
    m->cell_start = calloc(ncell + 1, sizeof(uint32_t));
    if (!m->cell_start) return false;
    /* Two passes over the triangles' xz bounding boxes: count, then fill. */
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t t = 0; t < ntri; t++) {
            const uint32_t *ix = &m->indices[3 * t];
            float x0 = FLT_MAX, x1 = -FLT_MAX, z0 = FLT_MAX, z1 = -FLT_MAX;
            for (int k = 0; k < 3; k++) {
                const float *p = &m->positions[3 * ix[k]];
                x0 = fminf(x0, p[0]);
                x1 = fmaxf(x1, p[0]);
                z0 = fminf(z0, p[2]);
                z1 = fmaxf(z1, p[2]);
            }
            int i0, j0, i1, j1;
            cell_of(m, x0, z0, &i0, &j0);
            cell_of(m, x1, z1, &i1, &j1);
            for (int j = j0; j <= j1; j++) {
                for (int i = i0; i <= i1; i++) {
                    size_t c = (size_t)j * (size_t)m->cells_x + (size_t)i;
                    if (pass == 0) m->cell_start[c + 1]++;
                    else m->cell_tris[m->cell_start[c]++] = t;
                }
            }
        }
        if (pass == 0) {
            for (size_t c = 0; c < ncell; c++) m->cell_start[c + 1] += m->cell_start[c];
            m->cell_tris = malloc(sizeof(uint32_t) * (m->cell_start[ncell] ? m->cell_start[ncell] : 1));
            if (!m->cell_tris) {
                free(m->cell_start);
                m->cell_start = NULL;
                return false;
            }
        }
    }
    /* The fill pass advanced every start to the next cell's start; shift back. */
    memmove(m->cell_start + 1, m->cell_start, sizeof(uint32_t) * ncell);
    m->cell_start[0] = 0;
    return true;
}

static void face_normal(const float *a, const float *b, const float *c, vec3 out)
{
    vec3 e1, e2;
    glm_vec3_sub((float *)b, (float *)a, e1);
    glm_vec3_sub((float *)c, (float *)a, e2);
    glm_vec3_cross(e1, e2, out);
    glm_vec3_normalize(out);
}

static float grid_height(const terrain_mesh_t *m, float x, float z, vec3 normal_out)
{
    int res = m->grid_res, side = res + 1;
    float half = m->grid_size * 0.5f, cell = m->grid_size / (float)res;
    float fx = (glm_clamp(x, -half, half) + half) / cell;
    float fz = (glm_clamp(z, -half, half) + half) / cell;
    int i = (int)floorf(fx), j = (int)floorf(fz);
    i = i < 0 ? 0 : i > res - 1 ? res - 1 : i;
    j = j < 0 ? 0 : j > res - 1 ? res - 1 : j;
    float u = fx - (float)i, v = fz - (float)j;
    const float *p00 = &m->positions[3 * (j * side + i)], *p10 = p00 + 3;
    const float *p01 = p00 + 3 * side, *p11 = p01 + 3;
    float h;
    if (v >= u) {
        h = p00[1] + u * (p11[1] - p01[1]) + v * (p01[1] - p00[1]);
        if (normal_out) face_normal(p00, p01, p11, normal_out);
    } else {
        h = p00[1] + u * (p10[1] - p00[1]) + v * (p11[1] - p10[1]);
        if (normal_out) face_normal(p00, p11, p10, normal_out);
    }
    return h;
}

float terrain_height_at(const terrain_mesh_t *m, float x, float z, vec3 normal_out)
{
    if (m->type == TERRAIN_WORLD) return terrain_world_height(&m->world, x, z, normal_out);
    if (m->grid_res > 0) return grid_height(m, x, z, normal_out);
    assert(m->cell_start && "terrain_build_grid not called");
    float best = -FLT_MAX;
    int best_tri = -1;
    const float eps = 1e-4f;
    if (x >= m->aabb_min[0] - eps && x <= m->aabb_max[0] + eps && z >= m->aabb_min[2] - eps &&
        z <= m->aabb_max[2] + eps) {
        int ci, cj;
        cell_of(m, x, z, &ci, &cj);
        size_t c = (size_t)cj * (size_t)m->cells_x + (size_t)ci;
        for (uint32_t k = m->cell_start[c]; k < m->cell_start[c + 1]; k++) {
            uint32_t t = m->cell_tris[k];
            const uint32_t *ix = &m->indices[3 * t];
            const float *a = &m->positions[3 * ix[0]], *b = &m->positions[3 * ix[1]],
                        *cc = &m->positions[3 * ix[2]];
            float den = (b[0] - a[0]) * (cc[2] - a[2]) - (cc[0] - a[0]) * (b[2] - a[2]);
            if (fabsf(den) < 1e-12f) continue; /* vertical triangle: a ray cannot hit its face */
            float w1 = ((x - a[0]) * (cc[2] - a[2]) - (cc[0] - a[0]) * (z - a[2])) / den;
            float w2 = ((b[0] - a[0]) * (z - a[2]) - (x - a[0]) * (b[2] - a[2])) / den;
            float w0 = 1.0f - w1 - w2;
            const float tol = -1e-6f;
            if (w0 < tol || w1 < tol || w2 < tol) continue;
            float y = w0 * a[1] + w1 * b[1] + w2 * cc[1];
            if (y > best) {
                best = y;
                best_tri = (int)t;
            }
        }
    }
    if (normal_out) {
        if (best_tri >= 0) {
            const uint32_t *ix = &m->indices[3 * best_tri];
            face_normal(&m->positions[3 * ix[0]], &m->positions[3 * ix[1]], &m->positions[3 * ix[2]],
                        normal_out);
        } else {
            normal_out[0] = 0;
            normal_out[1] = 1;
            normal_out[2] = 0;
        }
    }
    return best;
}

uint64_t terrain_hash(const terrain_mesh_t *m)
{
    uint64_t h = core_hash_bytes(m->positions, sizeof(float) * 3 * m->vertex_count, 0);
    h = core_hash_bytes(&m->type, sizeof m->type, h);
    h = core_hash_bytes(&m->world, sizeof m->world, h);
    h = core_hash_bytes(m->normals, sizeof(float) * 3 * m->vertex_count, h);
    h = core_hash_bytes(m->uvs, sizeof(float) * 2 * m->vertex_count, h);
    return core_hash_bytes(m->indices, sizeof(uint32_t) * m->index_count, h);
}

void terrain_free(terrain_mesh_t *m)
{
    free(m->positions);
    free(m->normals);
    free(m->uvs);
    free(m->indices);
    free(m->cell_start);
    free(m->cell_tris);
    memset(m, 0, sizeof *m);
}

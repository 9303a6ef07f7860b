/* bb_gpu_test_util: helpers shared by the billboard GPU tests (Orthmann et
 * al. 2009): an uploaded collider mesh, the CPU twin of one billboard's
 * refined mesh (bb_mesh_init_quad + wind pose) and the readback of a
 * field's points and deformed meshes. */
#ifndef MEADOW_BB_GPU_TEST_UTIL_H
#define MEADOW_BB_GPU_TEST_UTIL_H

#include "billboard/bb.h"
#include "collide/collide_shape.h"

#include <stdlib.h>
#include <string.h>

typedef struct test_mesh_t {
    collide_mesh_t shape;
    gfx_buffer_t pos, nrm, idx;
    GLuint vao;
} test_mesh_t;

static inline void test_mesh_make(test_mesh_t *m, const collide_shape_t *c)
{
    collide_make_mesh(&m->shape, c);
    m->pos = gfx_buffer_make(&(gfx_buffer_desc_t){.size = 12 * (size_t)m->shape.vertex_count,
                                                  .data = m->shape.positions, .label = "test.pos"});
    m->nrm = gfx_buffer_make(&(gfx_buffer_desc_t){.size = 12 * (size_t)m->shape.vertex_count,
                                                  .data = m->shape.normals, .label = "test.nrm"});
    m->idx = gfx_buffer_make(&(gfx_buffer_desc_t){.size = 4 * (size_t)m->shape.index_count,
                                                  .data = m->shape.indices, .label = "test.idx"});
    m->vao = gfx_vertex_array_make("test.vao");
    glVertexArrayVertexBuffer(m->vao, 0, m->pos.id, 0, 12);
    glVertexArrayVertexBuffer(m->vao, 1, m->nrm.id, 0, 12);
    glVertexArrayElementBuffer(m->vao, m->idx.id);
    for (GLuint a = 0; a < 2; a++) {
        glEnableVertexArrayAttrib(m->vao, a);
        glVertexArrayAttribFormat(m->vao, a, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribBinding(m->vao, a, a);
    }
}

static inline void test_mesh_destroy(test_mesh_t *m)
{
    gfx_vertex_array_destroy(&m->vao);
    gfx_buffer_destroy(&m->pos);
    gfx_buffer_destroy(&m->nrm);
    gfx_buffer_destroy(&m->idx);
    collide_free_mesh(&m->shape);
}

static inline collide_object_t test_object(const test_mesh_t *m, const float centre[3], float radius)
{
    collide_object_t o = {.vao = m ? m->vao : 0, .index_count = m ? (GLsizei)m->shape.index_count : 0,
                     .index_type = GL_UNSIGNED_INT, .radius = radius};
    mat4 model;
    glm_translate_make(model, (float *)centre);
    memcpy(o.model, model, sizeof model);
    return o;
}

/* The collide set of objs[0..n) (one static set, rebuilt by every call). */
static inline const collide_set_t *test_set(const collide_object_t *objs, int n)
{
    static collide_set_t set;
    collide_begin_set(&set);
    for (int k = 0; k < n; k++) collide_add_object(&set, &objs[k], 0.0f);
    return &set;
}

/* The collision tests' field: an 8 m heightfield (seed 3) and 36
 * billboards/m^2 of 0.5 x 0.4 m (the tolerances in metres were set for these;
 * the program's default billboard is 1.0 x 0.6 m) in an octree of depth 3,
 * small layout textures; the rest at the program's defaults. */
static inline bb_field_desc_t test_field_desc(terrain_mesh_t *terrain, int cube_res, int max_objects)
{
    CHECK(terrain_make_heightfield(terrain, &(terrain_desc_t){.size = 8, .resolution = 8, .height = 0.3f}, 3));
    return (bb_field_desc_t){.terrain = terrain, .seed = 99, .density = 36, .octree_depth = 3, .size = {0.5f, 0.4f},
                             .cube_res = cube_res, .max_objects = max_objects,
                             .layout = {.size = 32, .clump_size = 32}};
}

/* What field f holds (bb_field_info). */
static inline bb_field_info_t test_info(const bb_field_t *f)
{
    bb_field_info_t info;
    bb_field_info(f, &info);
    return info;
}

/* CPU twin of a billboard's mesh of a field of resolved desc d as the
 * collision pass starts it: the rest quad, moved to the wind pose at
 * `time`. */
static inline void test_cpu_mesh(const bb_field_desc_t *d, const bb_point_t *p, float time, bb_mesh_t *mesh)
{
    vec3 right, up;
    bb_point_frame(p, right, up);
    bb_mesh_init_quad(mesh, p->position, right, up, p->size[0], p->size[1], d->subdiv[0], d->subdiv[1]);
    bb_ref_wind_pose(mesh, &d->wind, time, mesh->pos);
}

/* A field's points and deformed meshes read back (test_readback_*). */
typedef struct test_readback_t {
    bb_field_info_t info;
    bb_point_t *pts;   /* info.billboards */
    float *meshes;     /* desc.max_deformed slots of info.mesh_vertices x 4 floats */
} test_readback_t;

/* Room for field f's points and meshes (read nothing yet). */
static inline test_readback_t test_readback_make(const bb_field_t *f)
{
    test_readback_t r = {.info = test_info(f)};
    r.pts = malloc(sizeof *r.pts * (size_t)r.info.billboards);
    r.meshes = malloc(sizeof(float) * 4 * (size_t)r.info.mesh_vertices * (size_t)r.info.desc.max_deformed);
    CHECK(r.pts && r.meshes);
    return r;
}

/* Reads f's points and, with meshes, its deformed meshes into r. */
static inline void test_readback_read(const bb_field_t *f, test_readback_t *r, bool meshes)
{
    CHECK(bb_field_read(f, BB_DATA_POINTS, 0, (size_t)r->info.billboards, r->pts));
    if (meshes) CHECK(bb_field_read(f, BB_DATA_MESHES, 0, (size_t)r->info.desc.max_deformed, r->meshes));
}

/* The deformed mesh of pool slot `slot` (mesh_vertices x 4 floats). */
static inline const float *test_readback_mesh(const test_readback_t *r, uint32_t slot)
{
    return &r->meshes[(size_t)slot * (size_t)r->info.mesh_vertices * 4];
}

static inline void test_readback_free(test_readback_t *r)
{
    free(r->pts);
    free(r->meshes);
}

static inline float test_ground_at(const void *terrain, float x, float z)
{
    return terrain_height_at(terrain, x, z, NULL);
}

/* The CPU twin of the collision pass of a field of resolved desc d (its
 * bb_field_info): its springs and its terrain as the ground
 * (bb_collide_desc_t.ground). */
static inline bb_collide_desc_t test_collide_desc(const bb_field_desc_t *d)
{
    return (bb_collide_desc_t){.r1 = d->r1, .r2 = d->r2, .iterations = d->iterations,
                               .ground = test_ground_at, .ground_user = d->terrain, .paper = d->paper};
}

/* Whether world point p lies on the terrain of desc d (within 0.1 mm
 * above it) or under it (below counts it, more than 0.1 mm under). */
static inline bool test_on_ground(const bb_field_desc_t *d, const float *p, int *below)
{
    float g = terrain_height_at(d->terrain, p[0], p[2], NULL);
    if (p[1] < g - 1e-4f) (*below)++;
    return p[1] <= g + 1e-4f;
}

/* The small field of the render tests: an 8 m heightfield of 0.2 m hills
 * (seed 11) into terrain, and its billboards' desc (64 per m^2 of 0.5 m,
 * octree depth 3, a 32-texel layout of 64-texel clumps). */
static inline bool test_small_field(terrain_mesh_t *terrain, bb_field_desc_t *desc)
{
    *desc = (bb_field_desc_t){.terrain = terrain, .seed = 11, .density = 64, .octree_depth = 3,
                              .size = {0.5f, 0.5f}, .layout = {.size = 32, .clump_size = 64}};
    return terrain_make_heightfield(terrain, &(terrain_desc_t){.size = 8, .resolution = 8, .height = 0.2f}, 11);
}

/* The view-projection of the 192 x 128 test views: from eye towards the
 * origin, 50 degrees, near 0.1, far 50. */
static inline void test_view(const vec3 eye, mat4 vp)
{
    mat4 view, proj;
    glm_lookat((float *)eye, (vec3){0, 0, 0}, (vec3){0, 1, 0}, view);
    glm_perspective(glm_rad(50.0f), 192.0f / 128.0f, 0.1f, 50.0f, proj);
    glm_mat4_mul(proj, view, vp);
}

/* A draw desc for view-projection vp from eye at time t under the tests'
 * sun, with vp's frustum planes. */
static inline bb_draw_desc_t test_draw_desc(const mat4 vp, const vec3 eye, float time)
{
    bb_draw_desc_t d = {.view = {.time = time, .sun = {0.4f, 0.8f, 0.3f}}};
    memcpy(d.view.viewproj, vp, sizeof d.view.viewproj);
    memcpy(d.view.camera, eye, sizeof d.view.camera);
    glm_vec3_normalize(d.view.sun);
    vec4 planes[6];
    glm_frustum_planes((vec4 *)vp, planes);
    memcpy(d.view.planes, planes, sizeof d.view.planes);
    return d;
}

/* Field f drawn with d into tgt cleared to the soil colour: by the
 * compute rasterizer r, or the hardware path when r is NULL. */
static inline void test_draw_path(bb_field_t *f, const gfx_target_t *tgt, raster_t *r, const bb_draw_desc_t *d)
{
    gfx_target_bind(tgt);
    glClearColor(0.33f, 0.27f, 0.2f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (r) {
        raster_begin(r, tgt);
        CHECK(bb_field_raster(f, r, d));
        raster_end(r, tgt);
    } else {
        bb_field_draw(f, d);
    }
}

#endif

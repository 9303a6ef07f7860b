/* collide_shape: analytic collider meshes, signed distances, bounding
 * spheres, CPU cube maps and sphere proxies (see collide_shape.h). */
#include "collide/collide_shape.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI_F 3.14159265358979f

static bool alloc_mesh(collide_mesh_t *m, uint32_t nv, uint32_t ni)
{
    memset(m, 0, sizeof *m);
    m->positions = calloc(nv * 3, sizeof(float));
    m->normals = calloc(nv * 3, sizeof(float));
    m->indices = calloc(ni, sizeof(uint32_t));
    m->vertex_count = nv;
    m->index_count = ni;
    if (!m->positions || !m->normals || !m->indices) {
        collide_free_mesh(m);
        return false;
    }
    return true;
}

/* UV sphere of radius r whose upper half is lifted by +h and lower half by
 * -h: a sphere for h = 0, a vertical capsule of segment length 2h else. */
static bool make_round(collide_mesh_t *m, float r, float h)
{
    const uint32_t slices = 24, stacks = 16;
    uint32_t nv = (slices + 1) * (stacks + 1), ni = slices * stacks * 6;
    if (!alloc_mesh(m, nv, ni)) return false;
    uint32_t v = 0, k = 0;
    for (uint32_t j = 0; j <= stacks; j++) {
        float phi = PI_F * (float)j / (float)stacks;
        for (uint32_t i = 0; i <= slices; i++, v++) {
            float th = 2.0f * PI_F * (float)i / (float)slices;
            float n[3] = {sinf(phi) * cosf(th), cosf(phi), sinf(phi) * sinf(th)};
            memcpy(m->normals + v * 3, n, sizeof n);
            m->positions[v * 3 + 0] = r * n[0];
            m->positions[v * 3 + 1] = r * n[1] + (j <= stacks / 2 ? h : -h);
            m->positions[v * 3 + 2] = r * n[2];
        }
    }
    for (uint32_t j = 0; j < stacks; j++)
        for (uint32_t i = 0; i < slices; i++) {
            uint32_t a = j * (slices + 1) + i, b = a + slices + 1;
            uint32_t tri[6] = {a, a + 1, b, a + 1, b + 1, b};
            memcpy(m->indices + k, tri, sizeof tri);
            k += 6;
        }
    return true;
}

static bool make_box(collide_mesh_t *m, const float he[3])
{
    if (!alloc_mesh(m, 24, 36)) return false;
    for (int f = 0; f < 6; f++) {
        int axis = f / 2;
        float s = (f % 2) ? -1.0f : 1.0f;
        int u = (axis + 1) % 3, w = (axis + 2) % 3;
        static const float cu[4] = {-1, 1, 1, -1}, cw[4] = {-1, -1, 1, 1};
        for (int c = 0; c < 4; c++) {
            float *p = m->positions + (f * 4 + c) * 3, *n = m->normals + (f * 4 + c) * 3;
            p[axis] = s * he[axis];
            p[u] = cu[c] * he[u] * s;
            p[w] = cw[c] * he[w];
            n[axis] = s;
        }
        uint32_t b = (uint32_t)f * 4;
        uint32_t tri[6] = {b, b + 1, b + 2, b, b + 2, b + 3};
        memcpy(m->indices + f * 6, tri, sizeof tri);
    }
    return true;
}

bool collide_make_mesh(collide_mesh_t *m, const collide_shape_t *c)
{
    switch (c->type) {
    case COLLIDE_SHAPE_CAPSULE: return make_round(m, c->radius, c->length * 0.5f);
    case COLLIDE_SHAPE_BOX: return make_box(m, c->half_extents);
    default: return make_round(m, c->radius, 0.0f);
    }
}

void collide_free_mesh(collide_mesh_t *m)
{
    free(m->positions);
    free(m->normals);
    free(m->indices);
    memset(m, 0, sizeof *m);
}

float collide_signed_distance(const collide_shape_t *c, const float p[3])
{
    switch (c->type) {
    case COLLIDE_SHAPE_CAPSULE: {
        float h = c->length * 0.5f;
        float y = p[1] > h ? p[1] - h : (p[1] < -h ? p[1] + h : 0.0f);
        return sqrtf(p[0] * p[0] + y * y + p[2] * p[2]) - c->radius;
    }
    case COLLIDE_SHAPE_BOX: {
        float q[3], out = 0.0f, in = -INFINITY;
        for (int i = 0; i < 3; i++) {
            q[i] = fabsf(p[i]) - c->half_extents[i];
            out += q[i] > 0 ? q[i] * q[i] : 0.0f;
            if (q[i] > in) in = q[i];
        }
        return sqrtf(out) + (in < 0 ? in : 0.0f);
    }
    default: return sqrtf(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - c->radius;
    }
}

float collide_bounding_radius(const collide_shape_t *c)
{
    switch (c->type) {
    case COLLIDE_SHAPE_CAPSULE: return c->radius + c->length * 0.5f;
    case COLLIDE_SHAPE_BOX:
        return sqrtf(c->half_extents[0] * c->half_extents[0] + c->half_extents[1] * c->half_extents[1] +
                     c->half_extents[2] * c->half_extents[2]);
    default: return c->radius;
    }
}

void collide_render_shape(collide_cubemap_t *cube, const collide_shape_t *c)
{
    switch (c->type) {
    case COLLIDE_SHAPE_CAPSULE:
        collide_render_capsule(cube, (vec3){0, -0.5f * c->length, 0}, (vec3){0, 0.5f * c->length, 0}, c->radius);
        break;
    case COLLIDE_SHAPE_BOX: collide_render_box(cube, (vec3){0, 0, 0}, (float *)c->half_extents); break;
    default: collide_render_sphere(cube, (vec3){0, 0, 0}, c->radius); break;
    }
}

int collide_pack_spheres(const collide_shape_t *c, const float position[3], float (*out)[4], int max)
{
    int k = 1;
    float r = collide_bounding_radius(c), step = 0;
    if (c->type == COLLIDE_SHAPE_CAPSULE && c->length > 0.0f) {
        r = c->radius;
        /* a radius far below the length (0 included) needs more than any
         * set holds: the count saturates */
        float q = r > 0.0f ? c->length / r : INFINITY;
        k = 1 + (q < (float)COLLIDE_PACK_SATURATED ? (int)ceilf(q) : COLLIDE_PACK_SATURATED);
        step = c->length / (float)(k - 1);
    }
    for (int j = 0; j < k && j < max; j++) {
        float y = k > 1 ? -0.5f * c->length + step * (float)j : 0.0f;
        out[j][0] = position[0];
        out[j][1] = position[1] + y;
        out[j][2] = position[2];
        out[j][3] = r;
    }
    return k;
}

/* blade_seed_plan: the stratified, index-addressed seeding of
 * blade_seed_plan.h (the plan on the CPU, every blade as a function of its
 * index) and the whole field on the CPU as the GPU seeding's reference. */
#include "blade/blade_seed_plan.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"

#define PLAN_GOLDEN 0x9e3779b9u
#define PLAN_EXTENT_SALT 0x5bd1e995u

static const float *corner(const blade_mesh_t *m, size_t tri, int k)
{
    return m->positions + 3 * (size_t)m->indices[3 * tri + (size_t)k];
}

static double tri_area(const blade_mesh_t *m, size_t tri)
{
    const float *a = corner(m, tri, 0), *b = corner(m, tri, 1), *c = corner(m, tri, 2);
    double e1[3], e2[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = (double)b[k] - a[k];
        e2[k] = (double)c[k] - a[k];
    }
    double x = e1[1] * e2[2] - e1[2] * e2[1], y = e1[2] * e2[0] - e1[0] * e2[2], z = e1[0] * e2[1] - e1[1] * e2[0];
    return 0.5 * sqrt(x * x + y * y + z * z);
}

static bool plan_fail(blade_seed_plan_t *out, const char *msg, size_t a, size_t b)
{
    blade_seed_plan_free(out);
    core_log_error("blade_seed_plan_make: %s (%zu, %zu)", msg, a, b);
    return false;
}

bool blade_seed_plan_make(const blade_mesh_t *mesh, const blade_seed_desc_t *desc, blade_seed_plan_t *out)
{
    memset(out, 0, sizeof *out);
    blade_seed_desc_t d = blade_seed_desc_defaults(desc);
    out->desc = d;
    out->patch_size = d.patch_size;
    out->key = core_hash_u32((uint32_t)d.seed ^ core_hash_u32((uint32_t)(d.seed >> 32) ^ 0x626c6164u));
    if (!mesh->positions || !mesh->indices || mesh->index_count % 3 != 0)
        return plan_fail(out, "mesh needs positions and a multiple of 3 indices", mesh->index_count, 0);
    if (d.patch_size <= 0 || d.population.density < 0.0f)
        return plan_fail(out, "bad patch_size or density", (size_t)d.patch_size, 0);
    if (mesh->index_count / 3 > UINT32_MAX - 1)
        return plan_fail(out, "too many triangles", mesh->index_count / 3, (size_t)UINT32_MAX - 1);
    for (size_t i = 0; i < mesh->index_count; i++)
        if (mesh->indices[i] >= mesh->vertex_count)
            return plan_fail(out, "index out of range (index, vertex_count)", mesh->indices[i], mesh->vertex_count);
    size_t nt = mesh->index_count / 3;
    out->tri_count = nt;
    if (nt == 0) return true;

    blade_field_t frame;
    blade_seed_frame(mesh, &frame);
    memcpy(out->morton_origin, frame.morton_origin, sizeof out->morton_origin);
    out->morton_scale = frame.morton_scale;

    blade_seed_key_t *keys = malloc(2 * nt * sizeof *keys);
    out->order = malloc(nt * sizeof *out->order);
    out->offsets = malloc((nt + 1) * sizeof *out->offsets);
    if (!keys || !out->order || !out->offsets) {
        free(keys);
        return plan_fail(out, "out of memory (triangles)", nt, 0);
    }
    for (size_t t = 0; t < nt; t++) {
        float c[3];
        for (int k = 0; k < 3; k++) c[k] = (corner(mesh, t, 0)[k] + corner(mesh, t, 1)[k] + corner(mesh, t, 2)[k]) / 3.0f;
        keys[t] = (blade_seed_key_t){blade_seed_morton(&frame, c), (uint32_t)t};
    }
    blade_seed_sort(keys, keys + nt, nt);
    double area = 0.0, density = (double)d.population.density;
    out->offsets[0] = 0;
    for (size_t k = 0; k < nt; k++) {
        out->order[k] = keys[k].index;
        area += tri_area(mesh, keys[k].index);
        double n = floor(density * area + 0.5);
        if (n > (double)d.max_blades) {
            free(keys);
            return plan_fail(out, "blade count exceeds max_blades", (size_t)(density * area), d.max_blades);
        }
        out->offsets[k + 1] = (uint32_t)n;
    }
    free(keys);
    size_t ps = (size_t)d.patch_size;
    out->blade_count = out->offsets[nt];
    out->patch_count = (out->blade_count + ps - 1) / ps;
    out->padded_count = out->patch_count * ps;
    return true;
}

void blade_seed_plan_free(blade_seed_plan_t *plan)
{
    free(plan->order);
    free(plan->offsets);
    memset(plan, 0, sizeof *plan);
}

/* The ordered triangle that holds blade i: the last k with offsets[k] <= i. */
static size_t plan_triangle(const blade_seed_plan_t *p, uint32_t i)
{
    size_t lo = 0, hi = p->tri_count - 1;
    while (lo < hi) {
        size_t mid = lo + (hi - lo + 1) / 2;
        if (p->offsets[mid] <= i) lo = mid;
        else hi = mid - 1;
    }
    return lo;
}

static float plan_draw(uint32_t s, uint32_t n) { return core_hash_float(s + n * PLAN_GOLDEN); }

void blade_seed_plan_blade(const blade_seed_plan_t *p, const blade_mesh_t *mesh, size_t index, blade_t *out)
{
    uint32_t last = (uint32_t)p->blade_count - 1u;
    uint32_t i = index < p->blade_count ? (uint32_t)index : last;
    size_t k = plan_triangle(p, i);
    uint32_t t = p->order[k], j = i - p->offsets[k];
    uint32_t s = core_hash_u32(core_hash_u32(p->key ^ core_hash_u32(t)) + j);
    float r = sqrtf(plan_draw(s, 0)), u1 = plan_draw(s, 1);
    float bary[3] = {1.0f - r, r * (1.0f - u1), r * u1};
    float v0[3], up[3];
    blade_seed_point(mesh, t, bary, v0);
    blade_seed_normal(mesh, t, bary, up);
    const blade_population_t *pop = &p->desc.population;
    float h = pop->height[0] + (pop->height[1] - pop->height[0]) * plan_draw(s, 2);
    float w = pop->width[0] + (pop->width[1] - pop->width[0]) * plan_draw(s, 3);
    float st = pop->stiffness[0] + (pop->stiffness[1] - pop->stiffness[0]) * plan_draw(s, 4);
    float an = p->desc.angle_min + (p->desc.angle_max - p->desc.angle_min) * plan_draw(s, 5);
    if (index >= p->blade_count) h = w = 0.0f;
    blade_seed_rest(out, v0, up, h, w, st, an);
}

bool blade_seed_extent_keeps(const blade_seed_extent_t *e, uint32_t i, const float v0[3])
{
    if (!e || !e->px) return true;
    int cx = (int)floorf((v0[0] - e->origin[0]) / e->spacing);
    int cz = (int)floorf((v0[2] - e->origin[1]) / e->spacing);
    int tx = ((cx % e->w) + e->w) % e->w, tz = ((cz % e->h) + e->h) % e->h;
    uint32_t texel = e->px[(size_t)tz * (size_t)e->w + (size_t)tx];
    return core_hash_u32(i ^ core_hash_u32(e->key ^ PLAN_EXTENT_SALT)) % 255u < texel;
}

bool blade_seed_plan_field(const blade_seed_plan_t *p, const blade_mesh_t *mesh,
                           const blade_seed_extent_t *extent, blade_field_t *out, size_t *thinned)
{
    memset(out, 0, sizeof *out);
    if (thinned) *thinned = 0;
    out->patch_size = p->patch_size;
    memcpy(out->morton_origin, p->morton_origin, sizeof out->morton_origin);
    out->morton_scale = p->morton_scale;
    if (p->blade_count == 0) return true;
    out->blades = malloc(p->padded_count * sizeof *out->blades);
    out->eta = calloc(p->padded_count, sizeof *out->eta);
    out->patch_aabbs = malloc(p->patch_count * sizeof *out->patch_aabbs);
    if (!out->blades || !out->eta || !out->patch_aabbs) {
        blade_field_free(out);
        core_log_error("blade_seed_plan_field: out of memory (%zu blades)", p->padded_count);
        return false;
    }
    out->blade_count = p->blade_count;
    out->padded_count = p->padded_count;
    out->patch_count = p->patch_count;
    for (size_t i = 0; i < p->padded_count; i++) {
        blade_t *b = &out->blades[i];
        blade_seed_plan_blade(p, mesh, i, b);
        if (i < p->blade_count && !blade_seed_extent_keeps(extent, (uint32_t)i, b->v0)) {
            memcpy(b->v1, b->v0, 3 * sizeof(float));
            memcpy(b->v2, b->v0, 3 * sizeof(float));
            b->v1[3] = 0.0f;
            b->v2[3] = 0.0f;
            if (thinned) (*thinned)++;
        }
    }
    blade_seed_patch_boxes(out);
    return true;
}

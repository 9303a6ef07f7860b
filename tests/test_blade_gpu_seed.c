/* test_blade_gpu_seed: blade mode's field seeded on the GPU
 * (blade_seed.comp, blade_seed_boxes.comp) against its CPU twin
 * (blade_seed_plan_field) on a bumpy 8 x 8 m heightfield with one
 * degenerate triangle, thinned by an 8 x 8 extent map:
 *   a) the plan: the field holds round(density * area) blades, every
 *      triangle its area's share to within one, triangles in Morton order;
 *   b) every GPU blade equals the CPU twin's (1e-5 m, 1e-5 rad), the same
 *      blades thinned, the same thinned count, every eta 0 (the buffers
 *      start poisoned with 0xff: gfx_desc_t.poison);
 *   c) the patch boxes and their real-blade counts equal the twin's, and
 *      every real blade lies in its patch's box;
 *   d) invariants: no NaN, unit up, heights and widths in their ranges,
 *      roots on the mesh, the kept fraction near the map's mean;
 *   e) with vertex normals and without (face normals). */
#include "blade/blade.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define N 16           /* quads per side */
#define SIDE 8.0f      /* metres */
#define DENSITY 60.0f  /* blades per m^2 */
#define EXTENT 8       /* texels per side */

static float height_at(float x, float z) { return 0.3f * sinf(0.9f * x) * cosf(0.7f * z); }

typedef struct grid_mesh_t {
    float pos[3 * (N + 1) * (N + 1)], nrm[3 * (N + 1) * (N + 1)];
    uint32_t idx[6 * N * N + 3];
} grid_mesh_t;

static blade_mesh_t make_grid(grid_mesh_t *g, bool normals)
{
    for (int z = 0; z <= N; z++)
        for (int x = 0; x <= N; x++) {
            float px = SIDE * (float)x / N, pz = SIDE * (float)z / N;
            float *p = &g->pos[3 * (z * (N + 1) + x)], *n = &g->nrm[3 * (z * (N + 1) + x)];
            p[0] = px;
            p[1] = height_at(px, pz);
            p[2] = pz;
            float dx = 0.27f * cosf(0.9f * px) * cosf(0.7f * pz), dz = -0.21f * sinf(0.9f * px) * sinf(0.7f * pz);
            float l = sqrtf(dx * dx + 1.0f + dz * dz);
            n[0] = -dx / l;
            n[1] = 1.0f / l;
            n[2] = -dz / l;
        }
    size_t k = 0;
    for (int z = 0; z < N; z++)
        for (int x = 0; x < N; x++) {
            uint32_t a = (uint32_t)(z * (N + 1) + x), b = a + 1, c = a + N + 1, d = c + 1;
            uint32_t q[6] = {a, c, b, b, c, d};
            memcpy(&g->idx[k], q, sizeof q);
            k += 6;
        }
    g->idx[k++] = 0; /* a degenerate triangle: no blades */
    g->idx[k++] = 1;
    g->idx[k++] = 1;
    return (blade_mesh_t){g->pos, normals ? g->nrm : NULL, (N + 1) * (N + 1), g->idx, k};
}

/* Heron's formula: independent of the plan's cross product. */
static double area_of(const blade_mesh_t *m, uint32_t t)
{
    double l[3];
    for (int e = 0; e < 3; e++) {
        const float *p = &m->positions[3 * m->indices[3 * t + (uint32_t)e]];
        const float *q = &m->positions[3 * m->indices[3 * t + (uint32_t)(e + 1) % 3]];
        l[e] = sqrt(((double)p[0] - q[0]) * ((double)p[0] - q[0]) + ((double)p[1] - q[1]) * ((double)p[1] - q[1]) +
                    ((double)p[2] - q[2]) * ((double)p[2] - q[2]));
    }
    double s = 0.5 * (l[0] + l[1] + l[2]), h = s * (s - l[0]) * (s - l[1]) * (s - l[2]);
    return h > 0.0 ? sqrt(h) : 0.0;
}

static int blade_differs(const blade_t *a, const blade_t *b)
{
    const float *x = &a->v0[0], *y = &b->v0[0];
    for (int k = 0; k < 16; k++)
        if (!(fabsf(x[k] - y[k]) <= 1e-5f)) return 1;
    return 0;
}

static void run(bool normals)
{
    printf("-- %s\n", normals ? "vertex normals" : "face normals");
    grid_mesh_t grid;
    blade_mesh_t mesh = make_grid(&grid, normals);
    blade_seed_desc_t sd = {.seed = 0x1234567890abULL, .population = {.density = DENSITY}};
    blade_seed_plan_t plan;
    CHECK(blade_seed_plan_make(&mesh, &sd, &plan));

    /* a) the plan */
    double area = 0.0;
    int off_share = 0, unordered = 0;
    blade_field_t frame = {.morton_scale = plan.morton_scale};
    memcpy(frame.morton_origin, plan.morton_origin, sizeof frame.morton_origin);
    uint64_t prev_code = 0;
    for (size_t k = 0; k < plan.tri_count; k++) {
        double at = area_of(&mesh, plan.order[k]);
        area += at;
        double n = (double)(plan.offsets[k + 1] - plan.offsets[k]);
        off_share += fabs(n - DENSITY * at) >= 1.0;
        const uint32_t *ix = &mesh.indices[3 * plan.order[k]];
        float c[3];
        for (int q = 0; q < 3; q++)
            c[q] = (mesh.positions[3 * ix[0] + q] + mesh.positions[3 * ix[1] + q] + mesh.positions[3 * ix[2] + q]) / 3.0f;
        uint64_t code = blade_seed_morton(&frame, c);
        unordered += k > 0 && code < prev_code;
        prev_code = code;
    }
    printf("a) %zu blades (density x area %.1f) in %zu patches; %d triangles off their share, %d out of order\n",
           plan.blade_count, DENSITY * area, plan.patch_count, off_share, unordered);
    CHECK((double)plan.blade_count == floor(DENSITY * area + 0.5));
    CHECK(plan.blade_count > 3000 && off_share == 0 && unordered == 0);

    uint8_t px[EXTENT * EXTENT];
    double mean = 0.0;
    for (int i = 0; i < EXTENT * EXTENT; i++) {
        px[i] = (uint8_t)(i % 5 == 0 ? 0 : i % 3 == 0 ? 255 : (37 * i) % 256);
        mean += px[i] / 255.0 / (EXTENT * EXTENT);
    }
    blade_seed_extent_t ex = {px, EXTENT, EXTENT, {0.0f, 0.0f}, SIDE / EXTENT, 77u};
    blade_field_t ref;
    size_t thinned_ref = 0;
    CHECK(blade_seed_plan_field(&plan, &mesh, &ex, &ref, &thinned_ref));

    gfx_texture_t tex = gfx_texture_make(&(gfx_texture_desc_t){.w = EXTENT, .h = EXTENT, .format = GL_R8,
                                                               .filter = GL_NEAREST, .data = px,
                                                               .upload_format = GL_RED, .label = "seed_test.extent"});
    CHECK(tex.id);
    blade_gpu_seed_t seed = {.plan = &plan, .mesh = &mesh, .extent_texture = tex.id,
                             .extent_origin = {0.0f, 0.0f}, .extent_spacing = SIDE / EXTENT, .extent_key = 77u};
    blade_gpu_t *g = blade_gpu_make(&(blade_gpu_desc_t){.seed = &seed, .label = "seed_test"});
    CHECK(g);
    blade_gpu_info_t info = blade_gpu_info(g);
    CHECK(info.blade_count == plan.blade_count && info.padded_count == plan.padded_count);

    /* b) blades */
    blade_t *got = malloc(plan.padded_count * sizeof *got);
    float *eta = malloc(plan.padded_count * sizeof *eta);
    blade_gpu_read_blades(g, got, eta);
    int differ = 0, thin_differ = 0, eta_set = 0;
    for (size_t i = 0; i < plan.padded_count; i++) {
        differ += blade_differs(&got[i], &ref.blades[i]);
        thin_differ += (got[i].v1[3] > 0.0f) != (ref.blades[i].v1[3] > 0.0f);
        eta_set += eta[i] != 0.0f;
    }
    printf("b) %d blades differ, %d thinned differently; thinned GPU %u, CPU %zu; %d eta not 0\n", differ,
           thin_differ, info.thinned, thinned_ref, eta_set);
    CHECK(differ == 0 && thin_differ == 0 && eta_set == 0);
    CHECK(info.thinned == thinned_ref);

    /* c) patch boxes */
    float(*boxes)[8] = malloc(plan.patch_count * sizeof *boxes);
    blade_gpu_read_patch_boxes(g, boxes);
    int box_differ = 0, real_differ = 0, outside = 0;
    for (size_t p = 0; p < plan.patch_count; p++) {
        uint32_t real, want = 0;
        memcpy(&real, &boxes[p][3], sizeof real);
        for (size_t i = p * plan.patch_size; i < (p + 1) * (size_t)plan.patch_size; i++) {
            const blade_t *b = &ref.blades[i];
            want += b->v1[3] > 0.0f;
            for (int k = 0; k < 3 && b->v1[3] > 0.0f; k++)
                outside += b->v0[k] < boxes[p][k] || b->v0[k] > boxes[p][4 + k] ||
                           b->v2[k] < boxes[p][k] || b->v2[k] > boxes[p][4 + k];
        }
        real_differ += real != want;
        for (int k = 0; k < 3; k++)
            box_differ += !(fabsf(boxes[p][k] - ref.patch_aabbs[p].min[k]) <= 1e-5f) ||
                          !(fabsf(boxes[p][4 + k] - ref.patch_aabbs[p].max[k]) <= 1e-5f);
    }
    printf("c) %zu patches: %d box coordinates differ, %d real counts differ, %d blade points outside\n",
           plan.patch_count, box_differ, real_differ, outside);
    CHECK(box_differ == 0 && real_differ == 0 && outside == 0);

    /* d) invariants */
    const blade_population_t pop = blade_population_defaults(&sd.population);
    int bad = 0, off_mesh = 0;
    size_t kept = 0;
    for (size_t i = 0; i < plan.blade_count; i++) {
        const blade_t *b = &got[i];
        const float *x = &b->v0[0];
        for (int k = 0; k < 16; k++) bad += !isfinite(x[k]);
        float ul = sqrtf(b->up[0] * b->up[0] + b->up[1] * b->up[1] + b->up[2] * b->up[2]);
        bad += fabsf(ul - 1.0f) > 1e-5f || b->up[1] <= 0.0f;
        bad += b->up[3] < pop.stiffness[0] || b->up[3] > pop.stiffness[1];
        blade_t full;
        blade_seed_plan_blade(&plan, &mesh, i, &full);
        bad += full.v1[3] < pop.height[0] || full.v1[3] > pop.height[1] || full.v2[3] < pop.width[0] ||
               full.v2[3] > pop.width[1];
        bool inside = b->v0[0] >= 0.0f && b->v0[0] <= SIDE && b->v0[2] >= 0.0f && b->v0[2] <= SIDE;
        /* a root on a flat facet of the grid: within the facet's chord of the surface */
        off_mesh += !inside || fabsf(b->v0[1] - height_at(b->v0[0], b->v0[2])) > 0.02f;
        kept += b->v1[3] > 0.0f;
    }
    double frac = (double)kept / (double)plan.blade_count;
    printf("d) %d invariants broken, %d roots off the mesh; kept %.3f of the blades (map mean %.3f)\n", bad, off_mesh,
           frac, mean);
    CHECK(bad == 0 && off_mesh == 0);
    CHECK(fabs(frac - mean) < 0.05);

    free(boxes);
    free(got);
    free(eta);
    blade_gpu_destroy(g);
    gfx_texture_destroy(&tex);
    blade_field_free(&ref);
    blade_seed_plan_free(&plan);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    run(true);
    run(false);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

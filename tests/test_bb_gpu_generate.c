/* test_bb_gpu_generate: the billboard generation geometry shader of
 * Orthmann et al. 2009 (bb_generate.geom) read back from its transform
 * feedback buffer equals the CPU rule bb_layout_sample + terrain_height_at on
 * every candidate cell (same accepted set, fields within tolerance), and the
 * buffer is ordered by octree leaf with the ranges bb_octree holds. On a
 * mesh terrain with a vertical face and an overhang (test_mesh_wall) it
 * equals the triangle rule bb_layout_sample_tri on every triangle, every
 * root lies on a triangle facing up or sideways, and the vertical face holds
 * roots per m^2 as the floor does (the height-grid generation before gave
 * it none). */
#include "test.h"
#include "test_gl.h"

#include "billboard/bb.h"

#include <string.h>
#include <time.h>

static int find_seed(const bb_point_t *pts, int n, uint32_t seed)
{
    for (int i = 0; i < n; i++)
        if (pts[i].seed == seed) return i;
    return -1;
}

/* Largest |difference| of the float fields of matched billboards, and the
 * count of unmatched ones or of integer fields that differ. */
static void compare_points(const bb_point_t *gpu, int ngpu, const bb_point_t *cpu, int ncpu, double tol_y)
{
    double max_xz = 0, max_y = 0, max_size = 0, max_growth = 0, max_mess = 0;
    int unmatched = 0, bad_int = 0;
    for (int i = 0; i < ngpu; i++) {
        const bb_point_t *g = &gpu[i];
        int j = find_seed(cpu, ncpu, g->seed);
        if (j < 0) {
            unmatched++;
            continue;
        }
        const bb_point_t *c = &cpu[j];
        max_xz = fmax(max_xz, fmax(fabs(g->position[0] - c->position[0]), fabs(g->position[2] - c->position[2])));
        max_y = fmax(max_y, fabs(g->position[1] - c->position[1]));
        max_size = fmax(max_size, fmax(fabs(g->size[0] - c->size[0]), fabs(g->size[1] - c->size[1])));
        max_size = fmax(max_size, fabs(g->angle - c->angle));
        for (int k = 0; k < 3; k++) max_growth = fmax(max_growth, fabs(g->growth[k] - c->growth[k]));
        max_mess = fmax(max_mess, fabs(g->messiness - c->messiness));
        bad_int += g->layer != c->layer || g->state != BB_STATE_IDLE || g->pad[0] != BB_NO_SLOT;
    }
    printf("max |dxz| %.3g, |dy| %.3g, |dsize/angle| %.3g, |dgrowth| %.3g, |dmessiness| %.3g, unmatched %d, bad "
           "ints %d\n",
           max_xz, max_y, max_size, max_growth, max_mess, unmatched, bad_int);
    CHECK(unmatched == 0);
    CHECK(bad_int == 0);
    CHECK(max_xz < 1e-5);
    CHECK(max_y < tol_y);
    CHECK(max_size < 1e-5);
    CHECK(max_growth < 1e-5);
    CHECK(max_mess < 1e-5);
}

/* Leaf order: every leaf's range holds exactly its billboards. */
static void check_leaf_order(const bb_field_info_t *fi, const bb_point_t *gpu)
{
    const bb_octree_t *tree = fi->tree;
    int wrong_leaf = 0;
    uint32_t covered = 0;
    for (int k = 0; k < tree->leaf_count; k++) {
        int node = bb_octree_leaf_node(tree, (uint32_t)k);
        covered += tree->count[node];
        for (uint32_t s = tree->first[node]; s < tree->first[node] + tree->count[node]; s++)
            wrong_leaf += bb_octree_leaf_of(tree, gpu[s].position) != (uint32_t)k;
    }
    printf("billboards in the wrong leaf range: %d\n", wrong_leaf);
    CHECK(wrong_leaf == 0);
    CHECK(covered == (uint32_t)fi->billboards);
    CHECK(tree->count[0] == (uint32_t)fi->billboards);
}

/* Distance from p to triangle (a, b, c): the plane distance when p
 * projects inside, else the distance to the nearest edge. */
static double tri_distance(const float *a, const float *b, const float *c, const float *p)
{
    const float *v[3] = {a, b, c};
    double e1[3], e2[3], n[3], ap[3];
    for (int k = 0; k < 3; k++) e1[k] = b[k] - a[k], e2[k] = c[k] - a[k], ap[k] = p[k] - a[k];
    n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    bool inside = true;
    for (int q = 0; q < 3; q++) {
        const float *s = v[q], *t = v[(q + 1) % 3];
        double st[3], sp[3];
        for (int k = 0; k < 3; k++) st[k] = t[k] - s[k], sp[k] = p[k] - s[k];
        double cx = st[1] * sp[2] - st[2] * sp[1], cy = st[2] * sp[0] - st[0] * sp[2];
        double cz = st[0] * sp[1] - st[1] * sp[0];
        inside = inside && cx * n[0] + cy * n[1] + cz * n[2] >= 0.0;
    }
    if (inside) return fabs(ap[0] * n[0] + ap[1] * n[1] + ap[2] * n[2]) / nl;
    double best = INFINITY;
    for (int q = 0; q < 3; q++) {
        const float *s = v[q], *t = v[(q + 1) % 3];
        double st[3], sp[3], ll = 0, d = 0;
        for (int k = 0; k < 3; k++) st[k] = t[k] - s[k], sp[k] = p[k] - s[k], ll += st[k] * st[k], d += st[k] * sp[k];
        double u = fmin(fmax(d / ll, 0.0), 1.0), dd = 0;
        for (int k = 0; k < 3; k++) dd += (sp[k] - u * st[k]) * (sp[k] - u * st[k]);
        best = fmin(best, sqrt(dd));
    }
    return best;
}

/* A mesh terrain: floor y = 0 (x in [-4, 0]), a vertical face at x = 0 up
 * to y = 3 facing -x, a slope rising from there to y = 5 at x = 4, all 8 m
 * deep, and the underside of a ledge at y = 1.5 (x in [-1, 0]) facing
 * down. */
static void wall_terrain(terrain_mesh_t *t)
{
    static const float quads[4][4][3] = {
        {{-4, 0, 4}, {0, 0, 4}, {0, 0, -4}, {-4, 0, -4}},
        {{0, 0, 4}, {0, 3, 4}, {0, 3, -4}, {0, 0, -4}},
        {{0, 3, 4}, {4, 5, 4}, {4, 5, -4}, {0, 3, -4}},
        {{-1, 1.5f, 4}, {-1, 1.5f, -4}, {0, 1.5f, -4}, {0, 1.5f, 4}},
    };
    memset(t, 0, sizeof *t);
    t->vertex_count = 16, t->index_count = 24;
    t->positions = malloc(sizeof(float) * 3 * 16);
    t->normals = calloc(3 * 16, sizeof(float));
    t->indices = malloc(sizeof(uint32_t) * 24);
    for (int q = 0; q < 4; q++) {
        for (int k = 0; k < 4; k++) memcpy(&t->positions[3 * (4 * q + k)], quads[q][k], sizeof quads[q][k]);
        static const uint32_t tri[6] = {0, 1, 2, 0, 2, 3};
        for (int k = 0; k < 6; k++) t->indices[6 * q + k] = 4 * (uint32_t)q + tri[k];
    }
    glm_vec3_copy((vec3){-4, 0, -4}, t->aabb_min);
    glm_vec3_copy((vec3){4, 5, 4}, t->aabb_max);
    CHECK(terrain_build_grid(t));
}

static void test_mesh_wall(void)
{
    terrain_mesh_t terrain;
    wall_terrain(&terrain);
    bb_field_t *f = bb_field_make(&(bb_field_desc_t){.terrain = &terrain, .seed = 99, .octree_depth = 3,
                                                     .density = 25, .layout = {.size = 64, .clump_size = 32}});
    CHECK(f);
    if (!f) return;
    bb_field_info_t fi;
    bb_field_info(f, &fi);
    CHECK(fi.triangles == 6);
    bb_layout_t lay;
    CHECK(bb_layout_generate(&lay, &fi.desc.layout));
    bb_point_t *cpu = malloc(sizeof *cpu * (size_t)fi.capacity);
    int ncpu = 0, faces_down = 0;
    for (uint32_t k = 0; k < terrain.index_count / 3; k++) {
        const float *v[3];
        for (int c = 0; c < 3; c++) v[c] = &terrain.positions[3 * terrain.indices[3 * k + (uint32_t)c]];
        bb_gen_tri_t tri;
        if (!bb_gen_tri_make(v[0], v[1], v[2], fi.gen.spacing, &tri)) {
            faces_down++;
            continue;
        }
        for (int j = 0; j < tri.cells[1]; j++)
            for (int i = 0; i < tri.cells[0]; i++)
                if (bb_layout_sample_tri(&lay, &fi.gen, &tri, k, i, j, &cpu[ncpu])) ncpu++;
    }
    CHECK(faces_down == 2);
    bb_point_t *gpu = malloc(sizeof *gpu * (size_t)(fi.billboards + 1));
    CHECK(bb_field_read(f, BB_DATA_POINTS, 0, (size_t)fi.billboards, gpu));
    printf("mesh: gpu %d, cpu %d billboards (capacity %d)\n", fi.billboards, ncpu, fi.capacity);
    CHECK(fi.billboards == ncpu && ncpu > 500 && ncpu <= fi.capacity);
    compare_points(gpu, fi.billboards, cpu, ncpu, 1e-5);
    check_leaf_order(&fi, gpu);

    /* Every root on a triangle that seeds (not the ledge's underside);
     * roots per m^2 of the face (x = 0, 0.1 < y < 2.9) over those of the
     * floor (y = 0). */
    double worst = 0.0;
    int face = 0, floor = 0, ledge = 0;
    for (int i = 0; i < fi.billboards; i++) {
        const float *p = gpu[i].position;
        double best = INFINITY;
        for (uint32_t k = 0; k < 18 / 3; k++) {
            const uint32_t *ix = &terrain.indices[3 * k];
            best = fmin(best, tri_distance(&terrain.positions[3 * ix[0]], &terrain.positions[3 * ix[1]],
                                           &terrain.positions[3 * ix[2]], p));
        }
        worst = fmax(worst, best);
        face += fabsf(p[0]) < 1e-4f && p[1] > 0.1f && p[1] < 2.9f;
        floor += fabsf(p[1]) < 1e-4f && p[0] < -1e-4f;
        ledge += fabsf(p[1] - 1.5f) < 1e-4f && p[0] < -1e-4f;
    }
    double ratio = (face / (2.8 * 8.0)) / (floor / 32.0);
    printf("mesh: worst root distance from the seeding triangles %.3g m; face %d, floor %d roots, per m^2 face / "
           "floor %.3f; on the ledge's underside %d\n", worst, face, floor, ratio, ledge);
    CHECK(worst < 1e-5);
    CHECK(ledge == 0);
    CHECK(ratio > 0.6 && ratio < 1.67);

    free(cpu);
    free(gpu);
    bb_layout_free(&lay);
    bb_field_destroy(f);
    terrain_free(&terrain);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    test_mesh_wall();
    terrain_mesh_t terrain;
    CHECK(terrain_make_heightfield(&terrain, &(terrain_desc_t){.size = 16, .resolution = 16, .height = 0.8f}, 7));

    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    bb_field_t *f = bb_field_make(&(bb_field_desc_t){.terrain = &terrain, .seed = 1234, .octree_depth = 3,
                                                     .density = 25, .layout = {.size = 64, .clump_size = 32}});
    clock_gettime(CLOCK_MONOTONIC, &t1);
    CHECK(f);
    if (!f) return 1;
    bb_field_info_t fi;
    bb_field_info(f, &fi);
    printf("make: %.1f ms, %d billboards of %d candidates\n",
           (double)(t1.tv_sec - t0.tv_sec) * 1e3 + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-6, fi.billboards,
           fi.capacity);

    /* CPU reference over every candidate cell. */
    bb_layout_t lay;
    CHECK(bb_layout_generate(&lay, &fi.desc.layout));
    bb_point_t *cpu = malloc(sizeof *cpu * (size_t)fi.capacity);
    int ncpu = 0;
    for (int iz = 0; iz < fi.cells[1]; iz++) {
        for (int ix = 0; ix < fi.cells[0]; ix++) {
            bb_point_t p;
            if (!bb_layout_sample(&lay, &fi.gen, ix, iz, &p)) continue;
            if (p.position[0] > fi.tree->desc.max[0] || p.position[2] > fi.tree->desc.max[2]) continue;
            p.position[1] = terrain_height_at(&terrain, p.position[0], p.position[2], NULL);
            cpu[ncpu++] = p;
        }
    }
    bb_point_t *gpu = malloc(sizeof *gpu * (size_t)(fi.billboards + 1));
    CHECK(bb_field_read(f, BB_DATA_POINTS, 0, (size_t)fi.billboards, gpu));
    printf("gpu %d, cpu %d billboards\n", fi.billboards, ncpu);
    CHECK(fi.billboards == ncpu);
    CHECK(ncpu > 1000);

    compare_points(gpu, fi.billboards, cpu, ncpu, 1e-4);
    check_leaf_order(&fi, gpu);

    bb_stats_t st;
    bb_field_stats(f, true, &st);
    CHECK(st.billboards == fi.billboards && st.deformed == 0 && st.pool_capacity == 4096);
    CHECK(st.leaves[BB_NODE_IDLE] > 1 && st.leaves[BB_NODE_COLLIDING] == 0);
    /* Generation timing: GPU timestamps inside the CPU wall time of make. */
    printf("generation pass %.2f ms (GPU timestamps), make %.2f ms (wall)\n", st.generate_ms, st.make_ms);
    CHECK(st.make_ms > 0 && st.make_ms < 60000);
    CHECK(st.generate_ms == -1.0f || (st.generate_ms >= 0 && st.generate_ms <= st.make_ms));

    free(cpu);
    free(gpu);
    bb_layout_free(&lay);
    bb_field_destroy(f);
    terrain_free(&terrain);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

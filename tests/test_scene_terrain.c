/* test_scene_terrain: heightfield determinism and exact height lookups
 * against an independent brute-force triangle search; assimp mesh loading of
 * generated OBJ files (merging, scaling, triangulation) and ray-cast heights;
 * clear errors for missing, empty and NaN meshes. */
#include <float.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "core/core.h"
#include "terrain/terrain.h"
#include "test.h"

/* Independent reference: highest triangle under (x, z) by testing every
 * triangle with 2D edge functions. */
static float brute_height(const terrain_mesh_t *m, float x, float z)
{
    double best = -FLT_MAX;
    for (uint32_t t = 0; t < m->index_count; t += 3) {
        const float *p[3];
        for (int k = 0; k < 3; k++) p[k] = &m->positions[3 * m->indices[t + k]];
        double e[3], area = 0;
        for (int k = 0; k < 3; k++) {
            const float *a = p[(k + 1) % 3], *b = p[(k + 2) % 3];
            e[k] = ((double)b[0] - a[0]) * ((double)z - a[2]) - ((double)b[2] - a[2]) * ((double)x - a[0]);
            area += e[k];
        }
        if (fabs(area) < 1e-12) continue;
        double w0 = e[0] / area, w1 = e[1] / area, w2 = e[2] / area;
        if (w0 < -1e-6 || w1 < -1e-6 || w2 < -1e-6) continue;
        double y = w0 * p[0][1] + w1 * p[1][1] + w2 * p[2][1];
        if (y > best) best = y;
    }
    return (float)best;
}

static void test_heightfield(void)
{
    terrain_desc_t d = {.size = 20, .resolution = 32, .height = 2};
    terrain_mesh_t a, b, c;
    CHECK(terrain_make_heightfield(&a, &d, 1));
    CHECK(terrain_make_heightfield(&b, &d, 1));
    CHECK(terrain_make_heightfield(&c, &d, 2));
    CHECK(a.vertex_count == 33 * 33 && a.index_count == 32 * 32 * 6);
    uint64_t ha = terrain_hash(&a), hb = terrain_hash(&b), hc = terrain_hash(&c);
    printf("heightfield hash seed 1: %016llx, seed 2: %016llx\n", (unsigned long long)ha,
           (unsigned long long)hc);
    CHECK(ha == hb);
    CHECK(ha != hc);

    /* Shape: centred, bounded by the amplitude, not flat. */
    CHECK_NEAR(a.aabb_min[0], -10, 1e-5);
    CHECK_NEAR(a.aabb_max[2], 10, 1e-5);
    CHECK(a.aabb_min[1] >= -2 && a.aabb_max[1] <= 2);
    CHECK_MSG(a.aabb_max[1] - a.aabb_min[1] > 0.2f, "relief only %g m",
              (double)(a.aabb_max[1] - a.aabb_min[1]));

    /* Exact at every grid vertex; normals unit and pointing up. */
    int bad = 0;
    for (uint32_t v = 0; v < a.vertex_count; v++) {
        const float *p = &a.positions[3 * v];
        float h = terrain_height_at(&a, p[0], p[2], NULL);
        if (fabsf(h - p[1]) > 1e-5f) bad++;
        const float *n = &a.normals[3 * v];
        if (fabsf(sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) > 1e-5f || n[1] <= 0) bad++;
    }
    CHECK_MSG(bad == 0, "%d grid vertices wrong", bad);

    /* Between vertices: matches the brute-force search, and the ray-cast path
     * (same triangles, grid_res cleared) matches too. */
    terrain_mesh_t r = b;
    r.grid_res = 0;
    CHECK(terrain_build_grid(&r));
    core_rng_t rng;
    core_rng_seed(&rng, 5, 0);
    float max_err = 0, max_err_ray = 0;
    for (int i = 0; i < 500; i++) {
        float x = core_rng_range(&rng, -10, 10), z = core_rng_range(&rng, -10, 10);
        vec3 n;
        float h = terrain_height_at(&a, x, z, n);
        float ref = brute_height(&a, x, z);
        max_err = fmaxf(max_err, fabsf(h - ref));
        max_err_ray = fmaxf(max_err_ray, fabsf(terrain_height_at(&r, x, z, NULL) - ref));
        CHECK(n[1] > 0 && fabsf(glm_vec3_norm(n) - 1) < 1e-5f);
    }
    printf("height_at max error vs brute force: grid %g, ray %g\n", (double)max_err,
           (double)max_err_ray);
    CHECK(max_err < 1e-4f);
    CHECK(max_err_ray < 1e-4f);

    /* A hand-checked point: centre of cell (0,0), u = 0.25, v = 0.75 lies in
     * triangle (v00, v01, v11): h = h00 + u (h11 - h01) + v (h01 - h00). */
    {
        float cell = 20.0f / 32, u = 0.25f, v = 0.75f;
        float h00 = a.positions[1], h01 = a.positions[3 * 33 + 1], h11 = a.positions[3 * 34 + 1];
        float want = h00 + u * (h11 - h01) + v * (h01 - h00);
        CHECK_NEAR(terrain_height_at(&a, -10 + u * cell, -10 + v * cell, NULL), want, 1e-5);
    }
    /* Outside the square clamps to the border. */
    CHECK_NEAR(terrain_height_at(&a, -50, -10, NULL), a.positions[1], 1e-6);

    /* Defaults. */
    terrain_desc_t z = {0};
    terrain_desc_t dd = terrain_desc_defaults(&z);
    CHECK(dd.size == 40 && dd.resolution == 64 && dd.height == 1.5f && dd.scale == 1);

    free(r.cell_start);
    free(r.cell_tris);
    terrain_free(&a);
    terrain_free(&b);
    terrain_free(&c);
    CHECK(a.positions == NULL && a.vertex_count == 0);
}

static bool write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (!f) return false;
    fputs(text, f);
    return fclose(f) == 0;
}

static void test_mesh(void)
{
    char dir[256], obj[300], empty[300], nan[300], err[512];
    snprintf(dir, sizeof dir, "/tmp/meadow_test_scene_terrain_%ld", (long)getpid());
    CHECK(core_fs_mkdirs(dir));
    snprintf(obj, sizeof obj, "%s/ground.obj", dir);
    snprintf(empty, sizeof empty, "%s/empty.obj", dir);
    snprintf(nan, sizeof nan, "%s/nan.obj", dir);
    /* Object 1: slanted ground y = 0.5 x + 1 over [0,2]x[0,1] as two quads.
     * Object 2: closed unit cube [2,3]^2 x [0,1] (outward winding). */
    CHECK(write_text(obj,
                     "o ground\n"
                     "v 0 1 0\nv 1 1.5 0\nv 2 2 0\nv 0 1 1\nv 1 1.5 1\nv 2 2 1\n"
                     "f 1 4 5 2\nf 2 5 6 3\n"
                     "o cube\n"
                     "v 2 0 2\nv 3 0 2\nv 3 0 3\nv 2 0 3\nv 2 1 2\nv 3 1 2\nv 3 1 3\nv 2 1 3\n"
                     "f 7 8 9 10\nf 11 14 13 12\nf 7 11 12 8\nf 8 12 13 9\nf 9 13 14 10\nf 10 14 11 7\n"));
    CHECK(write_text(empty, "v 0 0 0\nv 1 0 0\nv 0 0 1\n"));
    CHECK(write_text(nan, "v 0 0 0\nv nan 0 0\nv 0 0 1\nf 1 2 3\n"));

    terrain_mesh_t m;
    bool ok = terrain_load_mesh(&m, obj, 2.0f, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    if (ok) {
        printf("mesh: %u vertices, %u triangles, grid %dx%d\n", m.vertex_count, m.index_count / 3,
               m.cells_x, m.cells_z);
        CHECK(m.index_count == (4 + 12) * 3);
        CHECK_NEAR(m.aabb_min[0], 0, 1e-6);
        CHECK_NEAR(m.aabb_max[0], 6, 1e-6);
        CHECK_NEAR(m.aabb_max[1], 4, 1e-6);
        /* Scaled ground: y = 2 (0.5 (x/2) + 1) = 0.5 x + 2. */
        const float xs[] = {0.1f, 1.0f, 2.5f, 3.9f}, zs[] = {0.1f, 1.3f, 1.9f, 0.5f};
        for (int i = 0; i < 4; i++) {
            vec3 n;
            float h = terrain_height_at(&m, xs[i], zs[i], n);
            CHECK_NEAR(h, 0.5 * xs[i] + 2, 1e-5);
            /* Normal of the plane y = 0.5x + c: (-0.5, 1, 0) normalised. */
            CHECK_NEAR(n[0], -0.5 / sqrt(1.25), 1e-5);
            CHECK_NEAR(n[1], 1 / sqrt(1.25), 1e-5);
        }
        /* Over the cube: the top face (y = 2) is the ground, not the bottom. */
        vec3 n;
        CHECK_NEAR(terrain_height_at(&m, 5.0f, 5.0f, n), 2.0, 1e-5);
        CHECK_NEAR(n[1], 1.0, 1e-5);
        /* Nothing under a point outside the mesh or in the gap between objects. */
        CHECK(terrain_height_at(&m, 100, 100, n) == -FLT_MAX && n[1] == 1);
        CHECK(terrain_height_at(&m, 1.0f, 3.0f, NULL) == -FLT_MAX);
        /* Random points agree with brute force. */
        core_rng_t rng;
        core_rng_seed(&rng, 9, 0);
        int bad = 0;
        for (int i = 0; i < 300; i++) {
            float x = core_rng_range(&rng, -1, 7), z = core_rng_range(&rng, -1, 7);
            float h = terrain_height_at(&m, x, z, NULL), ref = brute_height(&m, x, z);
            if (!(h == ref || fabsf(h - ref) < 1e-4f)) bad++;
        }
        CHECK_MSG(bad == 0, "%d ray casts disagree with brute force", bad);
        for (uint32_t v = 0; v < m.vertex_count; v++)
            CHECK(fabsf(glm_vec3_norm(&m.normals[3 * v]) - 1) < 1e-4f);
        terrain_free(&m);
    }

    CHECK(!terrain_load_mesh(&m, "/nonexistent/dir/x.obj", 1, err, sizeof err));
    CHECK_MSG(strstr(err, "/nonexistent/dir/x.obj: cannot read") != NULL, "%s", err);
    CHECK(!terrain_load_mesh(&m, "models/does_not_exist_scene_test.obj", 1, err, sizeof err));
    CHECK_MSG(strstr(err, "does_not_exist_scene_test.obj: cannot read") != NULL, "%s", err);
    CHECK(!terrain_load_mesh(&m, empty, 1, err, sizeof err));
    CHECK_MSG(strstr(err, "empty.obj") != NULL, "%s", err);
    printf("empty mesh: %s\n", err);
    CHECK(!terrain_load_mesh(&m, nan, 1, err, sizeof err));
    CHECK_MSG(strstr(err, "nan.obj") != NULL, "%s", err);
    printf("nan mesh: %s\n", err);
    CHECK(m.positions == NULL);

    unlink(obj);
    unlink(empty);
    unlink(nan);
    rmdir(dir);
}

int main(void)
{
    core_log_set_quiet(true);
    test_heightfield();
    test_mesh();
    TEST_END();
}

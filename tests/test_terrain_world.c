/* test_terrain_world: the open world's height function (terrain_world.h):
 * determinism per seed, heights within [-height, height], analytic normals
 * against central differences, continuity across every lattice line (16 m
 * multiples), the character (flat meadows and hills both present, steep
 * ground rare), the defines for world_height.glsl, terrain_height_at's
 * dispatch and the scene's terrain.type "world" with its size limit. */
#include <stdio.h>
#include <string.h>

#include "core/core.h"
#include "scene/scene.h"
#include "terrain/terrain.h"
#include "test.h"

static terrain_world_t world(float size, float height, uint64_t seed)
{
    return terrain_world_make(&(terrain_desc_t){.type = TERRAIN_WORLD, .size = size, .height = height}, seed);
}

static void test_determinism_and_range(void)
{
    terrain_world_t a = world(4096, 30, 7), b = world(4096, 30, 7), c = world(4096, 30, 8);
    int same = 0, differ = 0, n = 0;
    float lo = 1e9f, hi = -1e9f;
    for (int j = 0; j < 200; j++)
        for (int i = 0; i < 200; i++, n++) {
            float x = -2048.0f + 20.48f * (float)i + 0.37f, z = -2048.0f + 20.48f * (float)j + 0.11f;
            float ha = terrain_world_height(&a, x, z, NULL);
            same += ha == terrain_world_height(&b, x, z, NULL);
            differ += fabsf(ha - terrain_world_height(&c, x, z, NULL)) > 0.1f;
            lo = fminf(lo, ha);
            hi = fmaxf(hi, ha);
        }
    printf("4 km world, height 30: heights in [%.2f, %.2f] m; seed 8 differs by > 0.1 m at %.1f%% of points\n",
           (double)lo, (double)hi, 100.0 * differ / n);
    CHECK(same == n);
    CHECK(differ > n * 9 / 10);
    CHECK(lo >= -30.0f && hi <= 30.0f);
    CHECK_MSG(hi - lo > 20.0f, "relief only %g m", (double)(hi - lo));
}

/* Central differences of the height against the analytic normal. */
static void test_normals(void)
{
    terrain_world_t w = world(2048, 30, 3);
    core_rng_t rng;
    core_rng_seed(&rng, 5, 1);
    double worst = 0.0;
    for (int k = 0; k < 2000; k++) {
        float x = core_rng_range(&rng, -1024, 1024), z = core_rng_range(&rng, -1024, 1024);
        vec3 n;
        terrain_world_height(&w, x, z, n);
        const float e = 0.05f;
        double dx = ((double)terrain_world_height(&w, x + e, z, NULL) - terrain_world_height(&w, x - e, z, NULL)) /
                    (double)((x + e) - (x - e));
        double dz = ((double)terrain_world_height(&w, x, z + e, NULL) - terrain_world_height(&w, x, z - e, NULL)) /
                    (double)((z + e) - (z - e));
        double len = sqrt(dx * dx + 1.0 + dz * dz);
        double want[3] = {-dx / len, 1.0 / len, -dz / len};
        CHECK_NEAR(glm_vec3_norm(n), 1.0, 1e-5);
        for (int c = 0; c < 3; c++) worst = fmax(worst, fabs(n[c] - want[c]));
    }
    printf("analytic normal vs central differences (e = 5 cm, 2000 points): worst %.2g\n", worst);
    CHECK(worst < 2e-3);
}

/* No steps in height or normal across the lattice lines of any octave
 * (all are multiples of 16 m): 1 mm either side. */
static void test_continuity(void)
{
    terrain_world_t w = world(2048, 30, 11);
    double worst_h = 0.0, worst_n = 0.0;
    for (int line = -64; line <= 64; line++) {
        float at = 16.0f * (float)line;
        for (int k = 0; k < 64; k++) {
            float along = -1000.0f + 31.25f * (float)k + 0.5f;
            for (int axis = 0; axis < 2; axis++) {
                float x0 = axis ? along : at - 1e-3f, z0 = axis ? at - 1e-3f : along;
                float x1 = axis ? along : at + 1e-3f, z1 = axis ? at + 1e-3f : along;
                vec3 n0, n1;
                float h0 = terrain_world_height(&w, x0, z0, n0), h1 = terrain_world_height(&w, x1, z1, n1);
                worst_h = fmax(worst_h, fabs(h1 - h0));
                worst_n = fmax(worst_n, glm_vec3_distance(n0, n1));
            }
        }
    }
    printf("across lattice lines (2 mm apart): worst height step %.2g m, normal step %.2g\n", worst_h, worst_n);
    CHECK(worst_h < 2e-3);  /* slope < 1 over 2 mm, plus float rounding at 30 m */
    CHECK(worst_n < 5e-3);
}

/* Slopes over a 2 km world: meadows (< 5 deg), hills (> 15 deg), cliffs rare. */
static void test_character(void)
{
    terrain_world_t w = world(2048, 30, 1);
    int n = 0, flat = 0, hill = 0, steep = 0;
    double sum = 0.0;
    for (float z = -1024.0f; z < 1024.0f; z += 4.0f)
        for (float x = -1024.0f; x < 1024.0f; x += 4.0f, n++) {
            vec3 nrm;
            terrain_world_height(&w, x, z, nrm);
            double deg = acos(fmin(nrm[1], 1.0f)) * 180.0 / GLM_PI;
            sum += deg;
            flat += deg < 5.0;
            hill += deg > 15.0;
            steep += deg > 35.0;
        }
    printf("slopes over 2 km, height 30: mean %.1f deg; < 5 deg %.1f%%, > 15 deg %.1f%%, > 35 deg %.2f%%\n",
           sum / n, 100.0 * flat / n, 100.0 * hill / n, 100.0 * steep / n);
    CHECK(flat > n / 5);
    CHECK(hill > n / 50);
    CHECK(steep < n / 100);
}

/* The uniforms of world_height.glsl: one key per layer, as the CPU side
 * hashes the seed words (the GPU test checks the heights they give). */
static void test_gpu_params(void)
{
    terrain_world_t w = world(2048, 30, 0x123456789abcdefULL);
    terrain_world_gpu_t g = terrain_world_gpu(&w);
    CHECK(g.height == 30.0f);
    for (uint32_t k = 0; k < TERRAIN_WORLD_LAYERS; k++)
        CHECK(g.keys[k] == core_hash_u32(0x89abcdefu ^ core_hash_u32(0x01234567u ^ k)));
    terrain_world_t other = w;
    other.seed[1] ^= 1u;
    terrain_world_gpu_t h = terrain_world_gpu(&other);
    int same = 0;
    for (int k = 0; k < TERRAIN_WORLD_LAYERS; k++) same += h.keys[k] == g.keys[k];
    CHECK(same == 0);
}

/* A world terrain through terrain.h: no vertices, its square as the box,
 * terrain_height_at is the world's function, the hash covers the params. */
static void test_dispatch(void)
{
    terrain_desc_t d = {.type = TERRAIN_WORLD, .size = 4096, .height = 25};
    terrain_mesh_t a, b, c;
    CHECK(terrain_make_heightfield(&a, &d, 9));
    CHECK(terrain_make_world(&b, &d, 9));
    d.size = 1024;
    CHECK(terrain_make_world(&c, &d, 9));
    CHECK(a.type == TERRAIN_WORLD && a.vertex_count == 0 && a.index_count == 0 && !a.positions && a.grid_res == 0);
    CHECK_NEAR(a.aabb_min[0], -2048, 0);
    CHECK_NEAR(a.aabb_max[2], 2048, 0);
    CHECK_NEAR(a.aabb_min[1], -25, 0);
    CHECK_NEAR(a.aabb_max[1], 25, 0);
    CHECK(terrain_hash(&a) == terrain_hash(&b));
    CHECK(terrain_hash(&a) != terrain_hash(&c));
    for (int k = 0; k < 100; k++) {
        float x = -3000.0f + 61.3f * (float)k, z = 1500.0f - 37.1f * (float)k;
        vec3 n0, n1;
        CHECK(terrain_height_at(&a, x, z, n0) == terrain_world_height(&a.world, x, z, n1));
        CHECK(glm_vec3_eqv(n0, n1));
    }
    d.size = 9000;
    CHECK(!terrain_make_world(&c, &d, 9));
    terrain_free(&a);
    terrain_free(&b);
}

static void test_scene(void)
{
    scene_desc_t s;
    char err[512];
    CHECK(scene_parse(&s, "{\"terrain\": {\"type\": \"world\", \"size\": 8192, \"height\": 30}}", "w.json", err,
                      sizeof err));
    CHECK(s.terrain.type == TERRAIN_WORLD && s.terrain.size == 8192.0f && s.terrain.height == 30.0f);
    CHECK(!scene_parse(&s, "{\"terrain\": {\"type\": \"world\", \"size\": 8193}}", "w.json", err, sizeof err));
    printf("%s\n", err);
    CHECK(strstr(err, "terrain.size") && strstr(err, "8192"));
    CHECK(!scene_parse(&s, "{\"terrain\": {\"type\": \"world\", \"resolution\": 64}}", "w.json", err, sizeof err));
}

int main(void)
{
    test_determinism_and_range();
    test_normals();
    test_continuity();
    test_character();
    test_gpu_params();
    test_dispatch();
    test_scene();
    TEST_END();
}

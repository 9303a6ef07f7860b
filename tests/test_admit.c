/* test_admit: resource admission (admit.h).
 * - The estimate made before allocating matches what the gfx layer counts
 *   after start-up (summary.txt: gpu_memory_estimate_mb against
 *   gpu_memory_mb) within 15 % for scenes/tiny.json in every mode and
 *   scenes/meadow.json with 4x MSAA, through the whole program.
 * - GL-free: the estimate grows with density and size; a scene over a
 *   budget is refused naming the key that deviates most from its default,
 *   and the value it names fits while 5 % beyond it does not; the cube
 *   maps of a huge character name grass.cube_texel; a GL limit (geometry-
 *   shader output) names grass.subdiv, the texture size a size that fits;
 *   the blade physics' sphere proxies past ADMIT_MAX_SPHERES name the
 *   characters or the capsule that takes them, 16 humanoids fit. */
#include "app/app.h"
#include "admit/admit.h"
#include "collide/collide_shape.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* gpu_memory_mb and gpu_memory_estimate_mb of a run's summary. */
static bool run_memory(const char *scene, const char *mode, const char *size, double *measured, double *estimate)
{
    char out[512];
    snprintf(out, sizeof out, "%s/%s-%s", test_out_dir(), strrchr(scene, '/') + 1, mode);
    char *argv[] = {"meadow", "--headless", "--quiet", "--scene", (char *)scene, "--frames", "2", "--size",
                    (char *)size, "--screenshot-every", "0", "--mode", (char *)mode, "--out", out};
    app_options_t o;
    char err[256];
    if (app_parse_args((int)(sizeof argv / sizeof argv[0]), argv, &o, err, sizeof err) != 0) return false;
    int rc = app_run(&o, NULL);
    if (rc != 0) {
        fprintf(stderr, "%s %s: app_run exited %d\n", scene, mode, rc);
        return false;
    }
    char path[600], line[512];
    snprintf(path, sizeof path, "%s/summary.txt", out);
    FILE *f = fopen(path, "r");
    if (!f) return false;
    *measured = *estimate = -1.0;
    while (fgets(line, sizeof line, f)) {
        sscanf(line, "gpu_memory_mb: %lf", measured);
        sscanf(line, "gpu_memory_estimate_mb: %lf", estimate);
    }
    fclose(f);
    return *measured > 0.0 && *estimate > 0.0;
}

static void check_against_gfx(void)
{
    static const struct {
        const char *scene, *mode, *size;
    } runs[] = {{"scenes/tiny.json", "billboard", "64x36"},
                {"scenes/tiny.json", "blade", "64x36"},
                {"scenes/tiny.json", "hybrid", "64x36"},
                {"scenes/meadow.json", "hybrid", "320x180"},
                {"scenes/meadow.json", "blade", "320x180"}};
    for (size_t i = 0; i < sizeof runs / sizeof runs[0]; i++) {
        double m = 0.0, e = 0.0;
        CHECK_MSG(run_memory(runs[i].scene, runs[i].mode, runs[i].size, &m, &e), "%s %s", runs[i].scene,
                  runs[i].mode);
        printf("%s %s %s: gfx counted %.1f MB, admission estimated %.1f MB (%+.1f %%)\n", runs[i].scene,
               runs[i].mode, runs[i].size, m, e, 100.0 * (e - m) / m);
        CHECK_MSG(fabs(e - m) <= 0.15 * m, "%s %s: estimate %.1f MB, counted %.1f MB", runs[i].scene, runs[i].mode,
                  e, m);
    }
}

/* A hybrid heightfield scene of the defaults, 40 m, 1280x720. */
static void base_scene(scene_desc_t *s, terrain_mesh_t *t, admit_world_t *w)
{
    char err[256];
    CHECK(scene_parse(s, "{}", "base.json", err, sizeof err));
    memset(t, 0, sizeof *t);
    t->grid_res = s->terrain.resolution;
    t->grid_size = s->terrain.size;
    t->aabb_max[0] = t->aabb_max[2] = s->terrain.size;
    *w = (admit_world_t){.terrain = t, .terrain_area = s->terrain.size * s->terrain.size, .billboards = true,
                             .tiles = true, .target_samples = 4};
}

static void check_gl_free(void)
{
    scene_desc_t s;
    terrain_mesh_t t;
    admit_world_t w;
    base_scene(&s, &t, &w);
    admit_t a, b;
    admit_estimate(&s, &w, &a);
    CHECK(a.gpu[ADMIT_TILES] > 0.0 && a.gpu[ADMIT_BILLBOARDS] > 0.0 && a.gpu[ADMIT_BLADES] == 0.0);
    s.grass.population.density *= 4.0f;
    s.size[0] *= 2;
    admit_estimate(&s, &w, &b);
    CHECK(b.gpu[ADMIT_TILES] > 2.0 * a.gpu[ADMIT_TILES]);
    CHECK(b.gpu[ADMIT_TARGETS] == 2.0 * a.gpu[ADMIT_TARGETS]);

    /* 512 MB and a dense field: refused, naming grass.density (4x its
     * default), and the value it names fits where 5 % more does not. */
    admit_limits_t lim = {.host_bytes = 512e6};
    base_scene(&s, &t, &w);
    s.grass.population.density = 8000.0f;
    char err[512];
    CHECK(!admit_check(&s, &w, &lim, err, sizeof err));
    printf("refused: %s\n", err);
    float largest = 0.0f;
    const char *at = strstr(err, "the largest grass.density that fits is ");
    CHECK_MSG(at && sscanf(at + strlen("the largest grass.density that fits is "), "%f", &largest) == 1, "%s", err);
    CHECK(strstr(err, "grass.density 8000 needs ") == err);
    s.grass.population.density = largest;
    CHECK_MSG(admit_check(&s, &w, &lim, err, sizeof err), "%g: %s", (double)largest, err);
    s.grass.population.density = largest * 1.05f;
    CHECK(!admit_check(&s, &w, &lim, err, sizeof err));

    /* A full blade field past 50 M blades names the density too. */
    base_scene(&s, &t, &w);
    w.tiles = false;
    w.full_field = true;
    s.terrain.size = t.grid_size = 1000.0f;
    w.terrain_area = 1e6;
    s.grass.population.density = 100.0f;
    CHECK(!admit_check(&s, &w, &(admit_limits_t){0}, err, sizeof err));
    CHECK_MSG(strstr(err, "more than the 50000000") && strstr(err, "the largest terrain.size that fits is 707"),
              "%s", err);
    s.terrain.size = 300.0f; /* 7.5x its default: now the density, at 8x, is the key */
    s.grass.population.density = 1600.0f;
    CHECK(!admit_check(&s, &w, &(admit_limits_t){0}, err, sizeof err));
    CHECK_MSG(strstr(err, "the largest grass.density that fits is 555"), "%s", err);

    /* A 1000x character (bounding radius 950 m) with grass.cube_texel: the
     * cube maps, capped at 16384 / 6 texels a side, name cube_texel. */
    base_scene(&s, &t, &w);
    s.grass.cube_texel = 0.01f;
    w.collider_radius = 950.0f;
    w.objects = 4;
    lim = (admit_limits_t){.host_bytes = 1.5e9};
    CHECK(!admit_check(&s, &w, &lim, err, sizeof err));
    CHECK_MSG(strstr(err, "(cube maps 2.86 GB)") && strstr(err, "the smallest grass.cube_texel that fits is 0.9"),
              "%s", err);

    /* The geometry shader's output: llvmpipe's and NVIDIA's 1024 components. */
    base_scene(&s, &t, &w);
    s.grass.subdiv[0] = s.grass.subdiv[1] = 8;
    lim = (admit_limits_t){.max_gs_vertices = 256, .max_gs_components = 1024};
    CHECK(!admit_check(&s, &w, &lim, err, sizeof err));
    CHECK_MSG(strstr(err, "grass.subdiv [8, 8]") && strstr(err, "the largest that fits is [8, 5]"), "%s", err);
    s.grass.subdiv[1] = 5;
    CHECK(admit_check(&s, &w, &lim, err, sizeof err));
    lim.max_texture_size = 4096;
    s.size[0] = 8192;
    s.size[1] = 1024;
    CHECK(!admit_check(&s, &w, &lim, err, sizeof err));
    CHECK_MSG(strstr(err, "the largest size of this shape that fits is [4096, 512]"), "%s", err);
}

/* The blade physics' sphere proxies: 16 humanoids (38 each, 608; refused
 * at 512 before the buffers grew with the scene) fit; past
 * ADMIT_MAX_SPHERES the refusal names the key that takes them, and a
 * capsule of radius 0 (COLLIDE_PACK_SATURATED spheres) overflows nothing. */
static void check_spheres(void)
{
    scene_desc_t s;
    terrain_mesh_t t;
    admit_world_t w;
    char err[512];
    int chars[16], colliders[2] = {1, 1};
    base_scene(&s, &t, &w);
    for (int i = 0; i < 16; i++) chars[i] = 38;
    s.collider_count = 1;
    s.colliders[0] = (scene_collider_t){.type = SCENE_COLLIDER_SPHERE, .radius = 0.4f};
    w.collider_spheres = colliders;
    w.character_spheres = chars;
    w.characters = 16;
    w.objects = 17;
    CHECK_MSG(admit_check(&s, &w, &(admit_limits_t){0}, err, sizeof err), "%s", err);

    /* characters of 300 spheres each: 13 fit beside the collider */
    for (int i = 0; i < 16; i++) chars[i] = 300;
    CHECK(!admit_check(&s, &w, &(admit_limits_t){0}, err, sizeof err));
    CHECK_MSG(strstr(err, "characters: 16 characters take 4800 of the blade physics' sphere proxies, 4801") == err &&
                  strstr(err, "more than its 4096: the most characters that fit is 13"),
              "%s", err);

    /* a thin capsule beside 16 humanoids: its length is the key */
    for (int i = 0; i < 16; i++) chars[i] = 38;
    s.colliders[0] = (scene_collider_t){.type = SCENE_COLLIDER_CAPSULE, .radius = 0.01f, .length = 50.0f};
    colliders[0] = 5001;
    CHECK(!admit_check(&s, &w, &(admit_limits_t){0}, err, sizeof err));
    const char *largest = "5609 with the rest, more than its 4096: the largest colliders[0].length that fits is ";
    const char *at = strstr(err, largest);
    CHECK_MSG(strstr(err, "colliders[0].length 50 over radius 0.01 takes 5001") == err && at, "%s", err);
    float fits = 0.0f;
    CHECK(at && sscanf(at + strlen(largest), "%f", &fits) == 1 && fits > 34.8f);
    for (int more = 0; more < 2; more++) {
        s.colliders[0].length = fits + (float)more * 5e-3f;
        collide_shape_t shape = scene_collider_shape(&s.colliders[0]);
        colliders[0] = collide_pack_spheres(&shape, (float[3]){0}, NULL, 0);
        CHECK_MSG(admit_check(&s, &w, &(admit_limits_t){0}, err, sizeof err) == !more, "%g: %s",
                  (double)s.colliders[0].length, err);
    }

    /* radius 0: saturated, refused (two of them overflowed an int sum) */
    s.collider_count = 2;
    s.colliders[0].radius = 0.0f;
    s.colliders[1] = s.colliders[0];
    colliders[0] = colliders[1] = 1 + COLLIDE_PACK_SATURATED;
    collide_shape_t zero_radius = scene_collider_shape(&s.colliders[0]);
    CHECK(collide_pack_spheres(&zero_radius, (float[3]){0}, NULL, 0) == colliders[0]);
    w.objects = 18;
    CHECK(!admit_check(&s, &w, &(admit_limits_t){0}, err, sizeof err));
    CHECK_MSG(strstr(err, "colliders: 2 colliders and the characters need 2000000610 sphere proxies") == err &&
                  strstr(err, "the most colliders that fit is 0"),
              "%s", err);
}

int main(void)
{
    check_gl_free();
    check_spheres();
    test_gl_require_context();
    check_against_gfx();
    TEST_END();
}

/* test_walker_spheres: every walker's proxy spheres reach the blade pass,
 * more than 512 of them (the old fixed budget) in all.
 * - 16 humanoids (38 spheres each, 608) walking on a heightfield in blade
 *   mode (the full field) and on a world terrain (the tiles, near the
 *   camera): the sphere buffer the physics read, read back from the GPU,
 *   holds each character's spheres in order, nothing is counted as
 *   dropped and no warning is logged.
 * - A character array too small is warned and counted at every call
 *   ("character.spheres_dropped"), not once per process.
 * - blade_physics.comp with 1536 spheres (three chunks of its mask), 512
 *   or 1024 of them near every work group (its list, then past the list:
 *   every sphere tested) against the CPU reference blade_ref_step. */
#include "blade/blade.h"
#include "blade/blade_tiles.h"
#include "character/character.h"
#include "grass/grass_harness.h"
#include "test.h"
#include "test_gl.h"
#include "world/world.h"
#include "world/world_harness.h"

#include <string.h>

#define WALKERS 16

/* The item's total in gfx's counts (0: never counted). */
static double count_of(const char *item)
{
    gfx_count_flush();
    for (int i = 0; i < gfx_count_item_count(); i++)
        if (strcmp(gfx_count_item_name(i), item) == 0) return gfx_count_item_total(i);
    return 0.0;
}

/* A scene of WALKERS humanoids in a 4 x 4 grid 6 m apart, each walking
 * 1 m back and forth, around (x0, z0), the camera 12 m away. The tiles are
 * 2 m. */
static void write_scene(const char *path, const char *terrain, float x0, float z0)
{
    FILE *f = fopen(path, "w");
    CHECK(f);
    if (!f) return;
    fprintf(f, "{ \"seed\": 3, \"mode\": \"blade\", \"raster\": \"hw\", \"size\": [160, 90], \"msaa\": 1,\n");
    fprintf(f, "  \"terrain\": %s,\n  \"grass\": { \"density\": 20, \"tile_size\": 2, \"blade_distance\": 30 },\n",
            terrain);
    fprintf(f, "  \"camera\": { \"position\": [%g, 4, %g], \"target\": [%g, 0, %g] },\n  \"characters\": [",
            (double)x0, (double)(z0 + 12.0f), (double)x0, (double)z0);
    for (int i = 0; i < WALKERS; i++) {
        float x = x0 + 6.0f * (float)(i % 4) - 9.0f, z = z0 + 6.0f * (float)(i / 4) - 9.0f;
        fprintf(f, "%s\n    { \"model\": \"models/humanoid.gltf\", \"path\": [[%g, %g], [%g, %g]] }", i ? "," : "",
                (double)x, (double)(z - 0.5f), (double)x, (double)(z + 0.5f));
    }
    fprintf(f, "\n  ]\n}\n");
    fclose(f);
}

static bool same_sphere(const blade_sphere_t *s, const float *c)
{
    return memcmp(s->centre_radius, c, 4 * sizeof(float)) == 0;
}

static void check_walkers(const char *name, const char *terrain, float x0, float z0)
{
    char path[600];
    snprintf(path, sizeof path, "%s/%s.json", test_out_dir(), name);
    write_scene(path, terrain, x0, z0);
    world_t *w = NULL;
    CHECK(world_load(&(world_options_t){.scene = path, .width = 160, .height = 90}, &w) == 0);
    CHECK_MSG(w && world_make_gpu(w), "%s", name);
    if (!w || !world_info(w).characters) {
        world_destroy(w);
        return;
    }
    double dropped = count_of("grass.spheres_dropped");
    int warns = core_log_warn_count();
    for (int f = 1; f <= 3; f++) world_update(w, (float)f / 30.0f, 1.0f / 30.0f);
    const character_set_t *chars = world_info(w).characters;
    grass_drivers_t in = grass_drivers(world_info(w).grass);
    static blade_sphere_t got[BLADE_MAX_SPHERES];
    int n = in.tiles ? blade_tiles_read_spheres(in.tiles, got, BLADE_MAX_SPHERES)
                     : blade_gpu_read_spheres(in.blades, got, BLADE_MAX_SPHERES);
    int need = 0, reached = 0;
    for (int i = 0; i < chars->count; i++) need += chars->items[i].sphere_count;
    /* the scene has no colliders: the characters' spheres, in order */
    int at = 0;
    for (int i = 0; i < chars->count; i++) {
        const character_instance_t *c = &chars->items[i];
        bool all = at + c->sphere_count <= n;
        for (int k = 0; all && k < c->sphere_count; k++) all = same_sphere(&got[at + k], c->spheres[k]);
        CHECK_MSG(all, "%s: character %d's %d spheres are not at %d of the %d the physics read", name, i,
                  c->sphere_count, at, n);
        reached += all;
        at += c->sphere_count;
    }
    printf("%s: %d characters, %d proxy spheres; the %s physics read %d, every sphere of %d characters\n", name,
           chars->count, need, in.tiles ? "tiles'" : "blades'", n, reached);
    CHECK(chars->count == WALKERS && need > 512 && n == need && reached == WALKERS);
    CHECK(count_of("grass.spheres_dropped") == dropped);
    CHECK_MSG(core_log_warn_count() == warns, "%s: %d warning(s) while stepping", name,
              core_log_warn_count() - warns);

    /* an array too small: warned and counted at every call */
    static float few[100][4];
    double before = count_of("character.spheres_dropped");
    warns = core_log_warn_count();
    for (int k = 0; k < 2; k++) CHECK(character_set_spheres(chars, few, 100) == need);
    CHECK(core_log_warn_count() == warns + 2);
    CHECK(count_of("character.spheres_dropped") == before + 2.0 * (need - 100));
    world_destroy(w);
}

/* A flat 2 x 2 m square at y = 0. */
static bool seed_square(blade_field_t *f)
{
    static const float pos[] = {-1, 0, -1, 1, 0, -1, 1, 0, 1, -1, 0, 1};
    static const float nrm[] = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
    static const uint32_t idx[] = {0, 2, 1, 0, 3, 2};
    blade_mesh_t mesh = {pos, nrm, 4, idx, 6};
    return blade_seed_mesh(&mesh,
                           &(blade_seed_desc_t){.seed = 5, .population = {.density = 150.0f, .height = {0.2f, 0.6f},
                                                                          .stiffness = {1.0f, 9.0f}}},
                           f);
}

/* 1536 spheres: `near` of every three over the square (small, low, some
 * swept), the rest 50 m away. */
static void many_spheres(collide_set_t *set, core_rng_t *rng, int near)
{
    memset(set, 0, sizeof *set);
    set->sphere_count = 1536;
    for (int k = 0; k < set->sphere_count; k++) {
        blade_sphere_t *s = &set->spheres[k];
        bool is_near = k % 3 < near;
        float x = core_rng_range(rng, -1, 1), z = core_rng_range(rng, -1, 1);
        *s = (blade_sphere_t){.centre_radius = {is_near ? x : x + 50.0f, core_rng_range(rng, 0.05f, 0.3f), z,
                                                core_rng_range(rng, 0.01f, 0.05f)}};
        if (k % 5 == 0) s->sweep[0] = core_rng_range(rng, -0.2f, 0.2f);
    }
}

static void check_against_reference(void)
{
    blade_field_t f;
    CHECK(seed_square(&f));
    size_t n = f.padded_count;
    blade_t *cpu = malloc(2 * n * sizeof *cpu), *gpu = cpu + n; /* the reference's, then the GPU's */
    float *eta = malloc(n * sizeof *eta);
    core_rng_t rng;
    core_rng_seed(&rng, 17, 3);
    static collide_set_t set;
    static blade_sphere_t back[BLADE_MAX_SPHERES];
    for (int near = 1; near <= 2; near++) {
        /* a fresh field each time: its sphere buffer grows from 512 */
        blade_gpu_t *g = blade_gpu_make(&(blade_gpu_desc_t){.field = &f, .label = "walker_spheres"});
        CHECK(g);
        if (!g) break;
        memcpy(cpu, f.blades, n * sizeof *cpu);
        memcpy(eta, f.eta, n * sizeof *eta);
        double worst = 0.0;
        size_t over = 0;
        for (int step = 0; step < 3; step++) {
            many_spheres(&set, &rng, near);
            blade_env_t env = {.dt = 1.0f / 60.0f, .time = (float)step / 60.0f};
            blade_gpu_update(g, &env, &set);
            blade_ref_step(cpu, eta, n, &env, &set);
            blade_gpu_read_blades(g, gpu, NULL);
            CHECK(blade_gpu_read_spheres(g, back, BLADE_MAX_SPHERES) == set.sphere_count);
            CHECK(memcmp(back, set.spheres, (size_t)set.sphere_count * sizeof *back) == 0);
            for (size_t i = 0; i < n; i++) {
                double d = fmax(test_dist3(cpu[i].v1, gpu[i].v1), test_dist3(cpu[i].v2, gpu[i].v2));
                worst = fmax(worst, d);
                over += d > 1e-4;
            }
        }
        printf("1536 spheres, %d over the square: %zu blades, worst |gpu-cpu| %.2e m, over 1e-4 m: %zu\n",
               512 * near, n, worst, over);
        /* as test_blade_gpu_physics: a blade on a collision-exit branch
         * boundary may take the other side under an fma */
        CHECK(over <= 1 + n / 200);
        CHECK(worst < 1e-2);
        blade_gpu_destroy(g);
    }
    free(cpu);
    free(eta);
    blade_field_free(&f);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    check_against_reference();
    check_walkers("heightfield", "{ \"type\": \"heightfield\", \"size\": 24, \"resolution\": 24, \"height\": 0.3 }",
                  0.0f, 0.0f);
    check_walkers("world", "{ \"type\": \"world\", \"size\": 256, \"height\": 4 }", 20.0f, -30.0f);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

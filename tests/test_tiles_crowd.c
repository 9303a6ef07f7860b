/* test_tiles_crowd: a crowd on the tiles (issue 47 item 5, no cap the user
 * cannot see). The per-tile object lists held at most 128 objects
 * (HYBRID_TILE_MAX_OBJECTS, gone); past that, spheres were left out with a
 * warning on doubling and bent no blades there.
 *   a) hybrid alone: 16 humanoid-like columns of 38 spheres 1.5 m apart
 *      on 4 m tiles (608 spheres): every tile's list is exactly the
 *      objects the brute-force test says touch it, in ascending order, and
 *      the fullest tile lists more than 128;
 *   b) the GPU physics: 300 spheres packed over one 4 m tile (all listed
 *      there, the old list's first 128 only) arrive on its slot at rest:
 *      the step
 *      equals blade_ref_step with every sphere, and the spheres past the
 *      128th move some of its blades (so a list cut at 128 fails). */
#include "blade/blade_tiles.h"
#include "collide_test_util.h"
#include "terrain_test_util.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define OLD_CAP 128 /* the old HYBRID_TILE_MAX_OBJECTS */
#define WALKERS 16
#define WALKER_SPHERES 38
#define PACKED 300

/* ---- a) ------------------------------------------------------------------ */
static void test_lists(void)
{
    hybrid_grid_t g;
    CHECK(hybrid_grid_make(&g, &(hybrid_desc_t){.size_x = 16.0f, .size_z = 16.0f, .tile_size = 4.0f}));
    static hybrid_object_t o[WALKERS * WALKER_SPHERES];
    int n = 0;
    for (int w = 0; w < WALKERS; w++)
        for (int k = 0; k < WALKER_SPHERES; k++) {
            float x = 6.0f + 1.5f * (float)(w % 4) + 0.1f * (float)(k % 3);
            float z = 6.0f + 1.5f * (float)(w / 4) + 0.1f * (float)(k % 5);
            /* radius grown by a blade reach of 0.5 m, as blade_tiles does */
            o[n++] = (hybrid_object_t){{x, 0.05f * (float)k, z, 0.15f + 0.5f}};
        }
    const float cam[3] = {8.0f, 3.0f, 20.0f};
    hybrid_grid_update(&g, cam, o, n, NULL, 1.0f / 60.0f);
    int fullest = 0, wrong = 0, listed = 0;
    for (int i = 0; i < g.nx * g.nz; i++) {
        const hybrid_tile_t *t = &g.tiles[i];
        const uint32_t *list = g.objects + t->object_first;
        int at = 0;
        for (int k = 0; k < n; k++) {
            if (!hybrid_tile_touched_brute(&g, i, &o[k], 1)) continue;
            wrong += at >= t->object_count || list[at] != (uint32_t)k;
            at++;
        }
        wrong += at != t->object_count;
        listed += t->object_count;
        fullest = t->object_count > fullest ? t->object_count : fullest;
    }
    printf("crowd of %d spheres on 4 m tiles: fullest tile lists %d (the old cap %d), %d entries in all, "
           "%d wrong\n",
           n, fullest, OLD_CAP, listed, wrong);
    CHECK(wrong == 0 && fullest > OLD_CAP && listed == g.stats.listed);
    hybrid_grid_free(&g);
}

/* ---- b) ------------------------------------------------------------------ */
static float dist3(const float *a, const float *b)
{
    float dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrtf(dx * dx + dy * dy + dz * dz);
}

static void test_physics(void)
{
    terrain_mesh_t m;
    CHECK(terrain_make_heightfield(&m, &(terrain_desc_t){.size = 8.0f, .resolution = 8, .height = 0.0f}, 7));
    test_terrain_flatten(&m);
    blade_tiles_desc_t d = {
        .terrain = &m,
        .tile_size = 4.0f,
        .population = {.density = 16.0f, .height = {0.3f, 0.5f}, .width = {0.02f, 0.03f}, .stiffness = {8.0f, 12.0f}},
        .seed = 3,
        .pool_slots = 8,
        .switch_distance = 12.0f,
        .cull = {.disable = BLADE_CULL_ORIENTATION | BLADE_CULL_FRUSTUM | BLADE_CULL_DISTANCE}};
    d.winds[0] = blade_wind_wave(1.0f, 0.4f, 1.5f, 6.0f, 0.0f);
    d.wind_count = 1;
    blade_tiles_t *t = blade_tiles_make(&d);
    CHECK(t);
    if (!t) {
        terrain_free(&m);
        return;
    }
    blade_tiles_info_t ti = blade_tiles_info(t);
    uint32_t B = ti.template_blades;
    int tile = hybrid_tile_at(ti.grid, 1.0f, 1.0f);
    const hybrid_tile_t *tl = &ti.grid->tiles[tile];
    /* PACKED spheres in rows over the tile's inner 3.6 m square, low enough
     * to bend every blade under them */
    static float spheres[PACKED][4];
    for (int k = 0; k < PACKED; k++) {
        spheres[k][0] = tl->min[0] + 0.2f + 3.6f * (float)(k % 15) / 14.0f;
        spheres[k][1] = 0.25f;
        spheres[k][2] = tl->min[2] + 0.2f + 3.6f * (float)(k / 15) / 19.0f;
        spheres[k][3] = 0.12f;
    }
    const float cam[3] = {0.0f, 3.0f, 10.0f};
    blade_env_t env = {.dt = 1.0f / 60.0f, .time = 1.0f, .gravity = 1.0f};
    /* the first sphere takes the slot; the crowd arrives at the next step */
    blade_tiles_update(t, cam, test_sphere_set((const float (*)[4])spheres, 1), &env);
    int slot = tl->slot;
    CHECK(slot >= 0 && tl->object_count == 1);
    blade_t *before = malloc(B * sizeof *before), *after = malloc(B * sizeof *after);
    blade_t *ref = malloc(B * sizeof *ref), *cut = malloc(B * sizeof *cut);
    float *eta = malloc(B * sizeof *eta), *eta_cut = malloc(B * sizeof *eta_cut);
    float *eta_gpu = malloc(B * sizeof *eta_gpu);
    blade_tiles_read_slot(t, slot, before, eta);
    env.time += env.dt;
    blade_tiles_update(t, cam, test_sphere_set((const float (*)[4])spheres, PACKED), &env);
    CHECK(blade_tiles_slot_owner(t, slot) == tile && tl->object_count == PACKED);
    blade_tiles_read_slot(t, slot, after, eta_gpu);
    blade_env_t ce = env;
    ce.winds[0] = blade_tiles_info(t).env.winds[0];
    ce.wind_count = 1;
    memcpy(ref, before, B * sizeof *ref);
    memcpy(cut, before, B * sizeof *cut);
    memcpy(eta_cut, eta, B * sizeof *eta_cut);
    blade_ref_step(ref, eta, B, &ce, test_sphere_set((const float (*)[4])spheres, PACKED));
    blade_ref_step(cut, eta_cut, B, &ce, test_sphere_set((const float (*)[4])spheres, OLD_CAP));
    int blades = 0, over = 0, moved_late = 0;
    float worst = 0.0f;
    for (uint32_t k = 0; k < B; k++) {
        if (ref[k].v1[3] <= 0) continue;
        blades++;
        float e = fmaxf(fmaxf(dist3(ref[k].v2, after[k].v2), dist3(ref[k].v1, after[k].v1)),
                        fabsf(eta[k] - eta_gpu[k]));
        if (e > 1e-4f) over++;
        else worst = fmaxf(worst, e);
        moved_late += dist3(ref[k].v2, cut[k].v2) > 1e-3f;
    }
    printf("%d spheres over one tile of %d blades: %d blades off the CPU step by more than 1e-4 (worst of the "
           "rest %.2g); %d blades bent by the spheres past the %dth\n",
           PACKED, blades, over, (double)worst, moved_late, OLD_CAP);
    CHECK(blades > 100 && over == 0);
    CHECK(moved_late > blades / 4);
    free(before);
    free(after);
    free(ref);
    free(cut);
    free(eta);
    free(eta_cut);
    free(eta_gpu);
    blade_tiles_destroy(t);
    terrain_free(&m);
}

int main(void)
{
    test_lists();
    test_gl_init();
    gfx_target_t target = gfx_target_make(&(gfx_target_desc_t){.w = 32, .h = 32, .samples = 1, .label = "crowd.test"});
    gfx_target_bind(&target);
    test_physics();
    gfx_target_destroy(&target);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

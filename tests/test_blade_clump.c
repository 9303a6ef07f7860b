/* test_blade_clump: the clump bake (blade_clump.h) on its own, GL-free:
 * view v of a layer lands at index v * stride and nothing else is written,
 * the same seed gives the same bytes, each view's calibration took at
 * least the asked blades and reached its target (or the pool's end), the
 * covered texels' albedo lies on the root -> tip line of the population,
 * and a light image is opaque. The images against the billboards' use are
 * test_bb_layout's. */
#include "blade/blade_clump.h"
#include "core/core.h"
#include "test.h"

#include <string.h>

#define SIDE 24
#define VIEWS 2
#define STRIDE 2

static const float angles[VIEWS][2] = {{0.0f, 0.0f}, {0.5f, 1.5f}};

/* Bakes `desc` into fresh images (every byte 7 first); false on failure. */
static bool bake(const blade_clump_desc_t *desc, core_image_t *albedo, core_image_t *light,
                 blade_clump_stats_t *stats)
{
    for (int i = 0; i < VIEWS * STRIDE; i++) {
        if (!core_image_alloc(&albedo[i], SIDE, SIDE, 4) || !core_image_alloc(&light[i], SIDE, SIDE, 4)) return false;
        memset(albedo[i].px, 7, (size_t)SIDE * SIDE * 4);
        memset(light[i].px, 7, (size_t)SIDE * SIDE * 4);
    }
    memset(stats, 0, sizeof *stats * VIEWS * STRIDE);
    return blade_clump_bake(desc, &(blade_clump_bake_t){.seed = 11,
                                                        .layer = 1,
                                                        .blades = 30,
                                                        .views_on = true,
                                                        .views = VIEWS,
                                                        .angles = angles,
                                                        .albedo = albedo,
                                                        .light = light,
                                                        .stats = stats,
                                                        .stride = STRIDE});
}

static void release(core_image_t *albedo, core_image_t *light)
{
    for (int i = 0; i < VIEWS * STRIDE; i++) {
        core_image_free(&albedo[i]);
        core_image_free(&light[i]);
    }
}

int main(void)
{
    core_log_set_quiet(true);
    blade_clump_desc_t desc = {.wind = 1.0f};
    core_image_t a[VIEWS * STRIDE], l[VIEWS * STRIDE], a2[VIEWS * STRIDE], l2[VIEWS * STRIDE];
    blade_clump_stats_t st[VIEWS * STRIDE], st2[VIEWS * STRIDE];
    CHECK(bake(&desc, a, l, st));
    CHECK(bake(&desc, a2, l2, st2));
    blade_population_t pop = blade_population_defaults(NULL);
    size_t bytes = (size_t)SIDE * SIDE * 4;
    for (int i = 0; i < VIEWS * STRIDE; i++) {
        bool baked = i % STRIDE == 0;
        int untouched = 0, opaque_light = 0, covered = 0, on_line = 0;
        for (size_t k = 0; k < bytes; k++) untouched += a[i].px[k] == 7 && l[i].px[k] == 7;
        CHECK_MSG(baked ? untouched < (int)bytes : untouched == (int)bytes, "image %d: %d bytes untouched", i,
                  untouched);
        CHECK(memcmp(a[i].px, a2[i].px, bytes) == 0 && memcmp(l[i].px, l2[i].px, bytes) == 0);
        if (!baked) continue;
        CHECK_MSG(st[i].blades >= 30 && st[i].alpha > 0.0f && st[i].target > 0.0f, "view %d: %d blades, alpha %g",
                  i / STRIDE, st[i].blades, st[i].alpha);
        CHECK_MSG(st[i].alpha >= st[i].target || st[i].blades == 4 * 30, "view %d: alpha %g < target %g", i / STRIDE,
                  st[i].alpha, st[i].target);
        for (int t = 0; t < SIDE * SIDE; t++) {
            const uint8_t *px = a[i].px + (size_t)t * 4;
            opaque_light += l[i].px[(size_t)t * 4 + 3] == 255;
            if (px[3] == 0) continue;
            covered++;
            /* Green between the root's and the tip's (one byte of rounding). */
            on_line += px[1] >= pop.albedo_root[1] * 255.0f - 1.0f && px[1] <= pop.albedo_tip[1] * 255.0f + 1.0f;
        }
        CHECK(opaque_light == SIDE * SIDE);
        CHECK_MSG(covered > 0 && on_line == covered, "view %d: %d of %d covered texels on the albedo line", i / STRIDE,
                  on_line, covered);
    }
    release(a, l);
    release(a2, l2);
    TEST_END();
}

/* test_world_reference: the image error's reference on a world terrain
 * (GRASS_REFERENCE_REACH), which has no field of vertices to seed every
 * blade from: scenes/bench/world.json thinned to 2 blades per m^2 with no
 * characters, in blade mode, on llvmpipe at 160x90.
 * 1. Its tiles reach GRASS_REFERENCE_REACH with no thinning, 16 segments
 *    and no orientation or occlusion culling; no billboards.
 * 2. Drawn, its blades reach past where the scene's own tiles end (blade
 *    mode's GRASS_BLADE_DISTANCE) and none past the reach's band, and
 *    every blade the cull kept is whole (no thinning's shrink).
 * 3. Its templates follow the placement seed (the noise floor's other
 *    placements), the same seed giving the same templates, and none of
 *    them is the scene's own tiles'. */
#include "blade/blade_tiles.h"
#include "measure/measure.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static void sparse(scene_desc_t *s, void *user)
{
    (void)user;
    s->grass.population.density = 2.0f;
    s->character_count = 0;
}

static world_t *make_world(bool reference, uint32_t placement)
{
    world_t *w;
    CHECK(world_load(&(world_options_t){.scene = "scenes/bench/world.json"}, &w) == 0);
    CHECK(world_setup(w, &(world_setup_t){.mode = SCENE_MODE_BLADE, .mode_set = true, .reference = reference,
                                          .tuning.placement_seed = placement, .tweak = sparse}));
    CHECK(world_make_gpu(w));
    return w;
}

/* The first template's first blade (tile-local, as seeded). */
static blade_t first_blade(world_t *w)
{
    blade_tiles_info_t ti = blade_tiles_info(measure_drivers(w).tiles);
    blade_t *b = malloc(sizeof *b * ti.template_blades);
    blade_tiles_read_template(measure_drivers(w).tiles, 0, b);
    blade_t out = b[0];
    free(b);
    return out;
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);

    /* 1. What the reference's tiles are. */
    world_t *w = make_world(true, 0);
    CHECK(measure_drivers(w).tiles != NULL && measure_drivers(w).billboards == NULL);
    CHECK(measure_drivers(w).blades == NULL);
    blade_tiles_info_t ti = blade_tiles_info(measure_drivers(w).tiles);
    CHECK(ti.desc.switch_distance == GRASS_REFERENCE_REACH);
    CHECK(ti.desc.cull.lod.rule == BLADE_LOD_OFF);
    CHECK(ti.desc.max_level == 16 && ti.desc.lod_distance == GRASS_REFERENCE_REACH);
    CHECK(ti.desc.cull.disable == (BLADE_CULL_ORIENTATION | BLADE_CULL_OCCLUSION));

    /* 2. Drawn: past the scene's own tiles, not past the reach. */
    const scene_desc_t *s = world_info(w).scene;
    gfx_target_t t = gfx_target_make(&(gfx_target_desc_t){.w = 160, .h = 90, .samples = 1, .label = "reference"});
    cam_t cam;
    scene_camera_init(s, &cam);
    grass_view_t v;
    world_update(w, 1.0f / 60.0f, 1.0f / 60.0f);
    world_view_make(&v, &cam, t.w, t.h, 1.0f / 60.0f, 1.0f / 60.0f);
    gfx_target_bind(&t);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    world_draw(w, &v, &t);
    blade_t *drawn = malloc(sizeof *drawn * ti.draw_capacity);
    uint32_t n = blade_tiles_read_drawn(measure_drivers(w).tiles, drawn, NULL);
    float far = 0.0f;
    int shrunk = 0;
    for (uint32_t i = 0; i < n; i++) {
        float d = sqrtf(powf(drawn[i].v0[0] - v.camera[0], 2) + powf(drawn[i].v0[1] - v.camera[1], 2) +
                        powf(drawn[i].v0[2] - v.camera[2], 2));
        far = fmaxf(far, d);
        shrunk += drawn[i].v1[3] <= 0.0f;
    }
    printf("reference: %u blades drawn, the farthest %.1f m from the camera (reach %.0f m, blade mode's tiles "
           "%.0f m), %d with no height\n",
           n, (double)far, (double)GRASS_REFERENCE_REACH, (double)GRASS_BLADE_DISTANCE, shrunk);
    CHECK(n > 1000);
    CHECK(far > GRASS_BLADE_DISTANCE + 5.0f && far <= GRASS_REFERENCE_REACH + GRASS_SWITCH_FADE + 1.0f);
    CHECK(shrunk == 0);
    free(drawn);
    gfx_target_destroy(&t);
    blade_t ref0 = first_blade(w);
    world_destroy(w);

    /* 3. The templates follow the placement seed. */
    w = make_world(true, 0);
    blade_t again = first_blade(w);
    world_destroy(w);
    w = make_world(true, 0x85ebca6bu);
    blade_t other = first_blade(w);
    world_destroy(w);
    w = make_world(false, 0);
    blade_t own = first_blade(w);
    world_destroy(w);
    CHECK(memcmp(&ref0, &again, sizeof ref0) == 0);
    CHECK(memcmp(&ref0, &other, sizeof ref0) != 0);
    CHECK(memcmp(&ref0, &own, sizeof ref0) != 0);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

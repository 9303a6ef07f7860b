/* test_scene_defaults: the modules default to the program's values. For
 * every knob a scene key shares with a module desc, the module's
 * *_desc_defaults of a zero desc equals the scene's resolved default (the
 * constants of scene/scene_fields.h); the scene's accepted ranges equal the
 * modules' limits. Fails when either side drifts. GL-free: only the
 * *_desc_defaults functions are called. */
#include <string.h>

#include "billboard/bb.h"
#include "blade/blade_seed.h"
#include "blade/blade_tiles.h"
#include "core/core.h"
#include "hybrid/hybrid.h"
#include "scene/scene.h"
#include "scene/scene_fields.h"
#include "test.h"

static scene_desc_t scene; /* large: keep off the stack */

static void test_billboards(const scene_grass_desc_t *g)
{
    bb_field_desc_t bb = bb_field_desc_defaults(&(bb_field_desc_t){0});
    CHECK_MSG(bb.density == g->billboard_density, "bb density %g, scene %g", bb.density, g->billboard_density);
    CHECK(bb.size[0] == g->billboard_size[0] && bb.size[1] == g->billboard_size[1]);
    CHECK(bb.subdiv[0] == g->subdiv[0] && bb.subdiv[1] == g->subdiv[1]);
    CHECK_MSG(bb.iterations == g->spring_iterations, "bb iterations %d, scene %d", bb.iterations,
              g->spring_iterations);
    CHECK_MSG(bb.cube_res == g->cube_resolution, "bb cube_res %d, scene %d", bb.cube_res, g->cube_resolution);
    CHECK_MSG(bb.recover_time == g->recover_time, "bb recover_time %g, scene %g", bb.recover_time,
              g->recover_time);
    /* The clump layers are drawn from the scene's blades (bb_layout.h). */
    const bb_clump_desc_t *c = &bb.layout.clump;
    CHECK(c->size[0] == g->billboard_size[0] && c->size[1] == g->billboard_size[1]);
    CHECK(c->height[0] == g->height[0] && c->height[1] == g->height[1]);
    CHECK(c->width[0] == g->width[0] && c->width[1] == g->width[1]);
    CHECK(c->stiffness[0] == g->stiffness[0] && c->stiffness[1] == g->stiffness[1]);
    CHECK(c->shape == (int)g->shape && c->gravity == SCENE_DEFAULT_BLADE_GRAVITY);
    CHECK_MSG(bb.layout.blades == bb_clump_blades(g->density, g->billboard_density), "bb clump blades %d",
              bb.layout.blades);
    /* The scene accepts exactly the subdivisions bb_field_make accepts. */
    const scene_field_t *subdiv = scene_field_find(SCENE_SEC_GRASS, "subdiv");
    CHECK(subdiv && subdiv->lo == SCENE_SUBDIV_MIN && subdiv->hi == SCENE_SUBDIV_MAX);
    CHECK(subdiv && (subdiv->flags & SCENE_FIELD_ZERO_OK));
}

static void test_blades(const scene_grass_desc_t *g)
{
    blade_seed_desc_t sd = blade_seed_desc_defaults(&(blade_seed_desc_t){0});
    CHECK_MSG(sd.density == g->density, "blade_seed density %g, scene %g", sd.density, g->density);
    CHECK(sd.height_min == g->height[0] && sd.height_max == g->height[1]);
    CHECK(sd.width_min == g->width[0] && sd.width_max == g->width[1]);
    CHECK(sd.stiffness_min == g->stiffness[0] && sd.stiffness_max == g->stiffness[1]);

    blade_tiles_desc_t td = blade_tiles_desc_defaults(&(blade_tiles_desc_t){0});
    CHECK_MSG(td.tile_size == g->tile_size, "blade_tiles tile_size %g, scene %g", td.tile_size, g->tile_size);
    CHECK(td.density == g->density && td.height_min == g->height[0] && td.height_max == g->height[1]);
    CHECK(td.width_min == g->width[0] && td.width_max == g->width[1]);
    CHECK(td.stiffness_min == g->stiffness[0] && td.stiffness_max == g->stiffness[1]);
    CHECK(td.switch_distance == g->switch_distance && td.shape == g->shape);
    CHECK_MSG(td.slope_recover == g->recover_time, "blade_tiles slope_recover %g, scene recover_time %g",
              td.slope_recover, g->recover_time);
    CHECK(td.motion_epsilon == SCENE_DEFAULT_MOTION_EPSILON);
}

static void test_hybrid(const scene_grass_desc_t *g)
{
    hybrid_desc_t hd = hybrid_desc_defaults(&(hybrid_desc_t){0});
    blade_tiles_desc_t td = blade_tiles_desc_defaults(&(blade_tiles_desc_t){0});
    CHECK_MSG(hd.tile_size == g->tile_size, "hybrid tile_size %g, scene %g", hd.tile_size, g->tile_size);
    CHECK(hd.switch_distance == g->switch_distance);
    CHECK_MSG(hd.memory == g->recover_time, "hybrid memory %g, scene recover_time %g", hd.memory, g->recover_time);
    /* Not a scene key: the tiles hand theirs to hybrid, so both agree. */
    CHECK_MSG(hd.motion_epsilon == td.motion_epsilon, "hybrid motion_epsilon %g, blade_tiles %g", hd.motion_epsilon,
              td.motion_epsilon);
    CHECK(hd.recover_timeout == td.recover_timeout && hd.pool_slots == td.pool_slots);
}

static void test_terrain_camera(void)
{
    terrain_desc_t t = terrain_desc_defaults(&(terrain_desc_t){0});
    CHECK(t.type == scene.terrain.type && t.size == scene.terrain.size);
    CHECK(t.resolution == scene.terrain.resolution && t.height == scene.terrain.height);
    CHECK(t.scale == scene.terrain.scale);
    CHECK(scene_field_find(SCENE_SEC_TERRAIN, "resolution")->hi == SCENE_TERRAIN_RESOLUTION_MAX);

    cam_t cam = {0};
    cam_defaults(&cam);
    CHECK(cam.fov == scene.camera.fov && cam.near == scene.camera.near && cam.far == scene.camera.far);
    CHECK(glm_vec3_eqv(cam.position, scene.camera.position) && glm_vec3_eqv(cam.target, scene.camera.target));
}

int main(void)
{
    core_log_set_quiet(true);
    char err[256];
    CHECK(scene_parse(&scene, "{}", "defaults.json", err, sizeof err));
    test_billboards(&scene.grass);
    test_blades(&scene.grass);
    test_hybrid(&scene.grass);
    test_terrain_camera();
    TEST_END();
}

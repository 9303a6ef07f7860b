/* test_scene_defaults: the modules default to the program's values. For
 * every knob a scene key shares with a module desc, the module's
 * *_desc_defaults of a zero desc equals the scene's resolved default (the
 * constants of scene/scene_fields.h); the scene's accepted ranges equal the
 * modules' limits. Fails when either side drifts. GL-free: only the
 * *_desc_defaults functions are called. */
#include <string.h>

#include "billboard/bb.h"
#include "blade/blade_canopy.h"
#include "blade/blade_ref.h"
#include "blade/blade_seed.h"
#include "blade/blade_tiles.h"
#include "core/core.h"
#include "hybrid/hybrid.h"
#include "scene/scene.h"
#include "scene/scene_fields.h"
#include "test.h"

static scene_desc_t scene; /* large: keep off the stack */

/* Whether a module's resolved population is the scene's: its keys as the
 * scene resolved them, the rest (albedo, gravity: not keys, left 0 by the
 * scene) as blade_population_defaults resolves them. */
static bool same_population(const blade_population_t *m, const scene_grass_desc_t *g)
{
    blade_population_t p = blade_population_defaults(&g->population);
    return m->density == g->population.density && m->height[0] == g->population.height[0] &&
           m->height[1] == g->population.height[1] && m->width[0] == g->population.width[0] &&
           m->width[1] == g->population.width[1] && m->stiffness[0] == g->population.stiffness[0] &&
           m->stiffness[1] == g->population.stiffness[1] && m->shape == g->population.shape &&
           memcmp(m->albedo_root, p.albedo_root, sizeof p.albedo_root) == 0 &&
           memcmp(m->albedo_tip, p.albedo_tip, sizeof p.albedo_tip) == 0 && m->gravity == p.gravity;
}

/* The scene's keys default to the population's defaults. */
static void test_population(const scene_grass_desc_t *g)
{
    blade_population_t p = blade_population_defaults(NULL);
    CHECK_MSG(p.density == g->population.density, "population density %g, scene %g", p.density, g->population.density);
    CHECK(p.height[0] == g->population.height[0] && p.height[1] == g->population.height[1]);
    CHECK(p.width[0] == g->population.width[0] && p.width[1] == g->population.width[1]);
    CHECK(p.stiffness[0] == g->population.stiffness[0] && p.stiffness[1] == g->population.stiffness[1]);
    CHECK(p.shape == g->population.shape && p.gravity == BLADE_DEFAULT_GRAVITY);
}

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
    const blade_clump_desc_t *c = &bb.layout.clump;
    CHECK(c->size[0] == g->billboard_size[0] && c->size[1] == g->billboard_size[1]);
    CHECK_MSG(same_population(&c->population, g), "bb clump population");
    CHECK_MSG(bb.layout.blades == bb_clump_blades(g->population.density, g->billboard_density), "bb clump blades %d",
              bb.layout.blades);
    /* The clump baker's own defaults (a zero desc) are the scene's too. */
    blade_clump_desc_t z = blade_clump_desc_defaults(NULL);
    CHECK(z.size[0] == g->billboard_size[0] && z.size[1] == g->billboard_size[1]);
    CHECK_MSG(z.depth == 1.5707963f / (g->billboard_size[0] * g->billboard_density), "clump depth %g", z.depth);
    /* The scene accepts exactly the subdivisions bb_field_make accepts. */
    const scene_field_t *subdiv = scene_field_find(SCENE_SEC_GRASS, "subdiv");
    CHECK(subdiv && subdiv->lo == BB_SUBDIV_MIN && subdiv->hi == BB_SUBDIV_MAX);
    CHECK(subdiv && (subdiv->flags & SCENE_FIELD_ZERO_OK));
}

static void test_blades(const scene_grass_desc_t *g)
{
    blade_seed_desc_t sd = blade_seed_desc_defaults(&(blade_seed_desc_t){0});
    CHECK_MSG(same_population(&sd.population, g), "blade_seed population, density %g, scene %g", sd.population.density,
              g->population.density);
    blade_canopy_desc_t cd = blade_canopy_desc_defaults(&(blade_canopy_desc_t){0});
    CHECK_MSG(same_population(&cd.population, g), "blade_canopy population");

    blade_tiles_desc_t td = blade_tiles_desc_defaults(&(blade_tiles_desc_t){0});
    CHECK_MSG(td.tile_size == g->tile_size, "blade_tiles tile_size %g, scene %g", td.tile_size, g->tile_size);
    CHECK_MSG(same_population(&td.population, g), "blade_tiles population");
    CHECK(td.switch_distance == g->switch_distance);
    CHECK_MSG(td.slope_recover == g->recover_time, "blade_tiles slope_recover %g, scene recover_time %g",
              td.slope_recover, g->recover_time);
    CHECK(td.motion_epsilon == HYBRID_DEFAULT_MOTION_EPSILON);
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
    CHECK(scene_field_find(SCENE_SEC_TERRAIN, "resolution")->hi == TERRAIN_RESOLUTION_MAX);

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
    test_population(&scene.grass);
    test_billboards(&scene.grass);
    test_blades(&scene.grass);
    test_hybrid(&scene.grass);
    test_terrain_camera();
    /* The CPU bakes (clump layers, canopy) settle blades with the scene's step. */
    CHECK(BLADE_SETTLE_DT == scene.dt);
    TEST_END();
}

/* bench_run: `meadow bench` sweeps configurations of deterministic scenes
 * headless (fixed seed, dt, camera and colliders) and writes per-pass GPU
 * times, CPU time, accuracy metrics (docs/METRICS.md) and image error
 * against the reference rendering to bench.csv and bench.json, with a
 * speed-vs-accuracy chart per sweep (x the GPU ms of the passes its knob
 * changes, y its accuracy measure; PNG and SVG through gnuplot) and the
 * Pareto front. The sweeps are `charts[]` below: billboard collision and
 * springs (Orthmann et al. 2009), blade proxies and levels of detail
 * (Jahrmann & Wimmer 2017), the hybrid's switch and canopy distances, and
 * the modes x density x render path. --quick runs two to five
 * configurations per sweep for CI. --stability (stability.c), --scaling
 * (perf_scaling.c), --report DIR (all of them and `meadow compare`, into
 * DIR/RESULTS.md), --perf and --baseline (perf.c, perf_baseline.c) and
 * --papers DIR (perf_papers.c) run the other parts of the harness. */
#include "bench/bench_local.h"
#include "bench/bench_lod.h"

#include <assert.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "eval/eval_image.h"
#include "platform/plat.h"

typedef enum bench_proxy_t {
    PROXY_WORLD = 0,  /* app_world's own (not replaced) */
    PROXY_BOUND,      /* one sphere: the box's bounding sphere */
    PROXY_INSCRIBED,  /* one sphere: the largest inside the box */
    PROXY_COVER,      /* a grid of spheres, each through its cell's corners */
    PROXY_INNER,      /* a grid of spheres, each inscribed in its cell */
    PROXY_CUBE,       /* no spheres: the box's depth cube map (tuning.blade_cube_proxies) */
} bench_proxy_t;

typedef struct bench_config_t {
    const char *group; /* one chart per group */
    char label[48];
    scene_mode_t mode;
    int cube_resolution, subdiv, springs; /* billboard knobs, 0 = scene */
    float switch_distance;                /* hybrid knob, 0 = scene */
    float canopy_distance;                /* hybrid knob, 0 = scene */
    float density_scale;                  /* grass and billboard density factor, 0 = 1 */
    float bb_density_scale;               /* billboard density factor alone, 0 = 1 */
    int billboards;                       /* hybrid: 0 = scene, else 1 + scene_hybrid_billboards_t */
    float lod_width_px;                   /* grass.lod.width_px, 0 = scene */
    bool lod_thin, lod_soil;              /* grass.lod.no_compensation, grass.lod.no_ground */
    int blade_render;                     /* 0 = the options', else 1 + scene_blade_render_t (1 pull, 2 tess) */
    int raster;                           /* 0 = the options', else 1 + scene_raster_t */
    int raster_samples;                   /* compute rasterizer samples per pixel, 0 = the options' */
    int lod_levels;                       /* grass.lod: the LEVELS rule (eq. 19-20) with n levels, 0 = scene */
    bench_proxy_t proxy;
    const char *scene;                    /* NULL: the sweep's (--scene) */
    bool ball;                            /* the ball (BALL_RADIUS) is the only collider */
    bool no_colliders;                    /* ablation: no collider, no character */
    int grid[3];                          /* PROXY_COVER / PROXY_INNER spheres per axis */
    grass_tuning_t tuning;
} bench_config_t;

/* The box that blade_proxies runs on the first collider's path: 1 x 0.32
 * x 0.32 m. Colliders are axis aligned, and so are the blades' cube maps
 * (centred on the box, half size its bounding radius 0.5488 m): the box's
 * faces come out exact at every resolution and only its edges snap to
 * texel borders (texels whose centre ray hits the box). The 1 x 0.4 x 0.4 m
 * box had its edges at 14.96 and 10.78 texels of 16 (29.92 and 21.57 of
 * 32): the same borders at both, so cubemap_16 and cubemap_32 ran the same
 * shape. This one's edges lie at 15.29 and 10.33 of 16, 30.58 and 20.66
 * of 32, 61.15 and 41.33 of 64: each resolution snaps them elsewhere
 * (under, over, nearly exact). */
static const float proxy_box[3] = {0.5f, 0.16f, 0.16f};

/* The scene of the hybrid_canopy_distance chart (unless --chart names it
 * alone: then the --scene, whose lod.json it writes): ground from 10 to
 * 195 m in view, where the canopy distances 35-90 m each change the
 * picture (meadow.json's 40 m field ends before the first). */
#define CANOPY_SCENE "scenes/bench/canopy.json"

/* The ball that billboard_collision runs on that path, its lowest point
 * at half the billboards' height. Not the box: the cube maps are
 * orthographic and axis aligned, so an axis-aligned box's faces come out
 * exact at every resolution and its edges snap to the same texel borders
 * at 16 and 32 texels: the runs were identical. A sphere's depth varies
 * inside every texel. Lower, it pinned billboards to the ground under it,
 * where no push can free them (their length and bend limits hold them up):
 * penetration read about 0.2 m at every setting. */
#define BALL_RADIUS 0.3f

/* The least canopy distance beyond a switch distance: the two fade bands apart. */
#define CANOPY_GAP (GRASS_SWITCH_FADE + GRASS_CANOPY_FADE)

static void tweak(scene_desc_t *s, void *user)
{
    const bench_config_t *c = user;
    if (c->cube_resolution) s->grass.cube_resolution = c->cube_resolution;
    if (c->subdiv) s->grass.subdiv[0] = s->grass.subdiv[1] = c->subdiv;
    if (c->springs) s->grass.spring_iterations = c->springs;
    if (c->switch_distance > 0) s->grass.switch_distance = c->switch_distance;
    if (c->canopy_distance > 0) s->grass.canopy_distance = c->canopy_distance;
    /* A switch sweep keeps the canopy's band beyond the blades' (world_load's rule). */
    s->grass.canopy_distance = fmaxf(s->grass.canopy_distance, s->grass.switch_distance + CANOPY_GAP);
    if (c->density_scale > 0) {
        s->grass.population.density *= c->density_scale;
        s->grass.billboard_density *= c->density_scale;
    }
    if (c->bb_density_scale > 0) s->grass.billboard_density *= c->bb_density_scale;
    if (c->lod_levels) {
        s->grass.lod.rule = BLADE_LOD_LEVELS;
        s->grass.lod.levels = c->lod_levels;
    }
    /* A row that names its chain measures it, not the scene's lod table's. */
    if (c->billboards) {
        s->grass.billboards = (scene_hybrid_billboards_t)(c->billboards - 1);
        s->grass.lod_table[0] = '\0';
    }
    if (c->lod_width_px > 0) s->grass.lod.width_px = c->lod_width_px;
    if (c->lod_thin) s->grass.lod.no_compensation = true;
    if (c->lod_soil) s->grass.lod.no_ground = true;
    if (c->no_colliders) s->collider_count = s->character_count = 0;
    if (c->proxy != PROXY_WORLD || c->ball) {
        /* Characters would keep their own proxy spheres (the variants could
         * not be told apart): only the box (the ball) collides. A scene
         * without colliders gets one crossing the camera's view at t = 0. */
        s->character_count = 0;
        scene_collider_t *k = &s->colliders[0];
        if (s->collider_count == 0) {
            cam_t cam;
            scene_camera_init(s, &cam);
            vec3 fwd, right;
            glm_vec3_sub(cam.target, cam.position, fwd);
            glm_vec3_crossn(fwd, (vec3){0.0f, 1.0f, 0.0f}, right);
            *k = (scene_collider_t){.path.count = 2, .path.keys[1].t = 2.0f};
            for (int e = 0; e < 2; e++) {
                glm_vec3_copy(cam.target, k->path.keys[e].position);
                glm_vec3_muladds(right, e ? 1.5f : -1.5f, k->path.keys[e].position);
            }
        }
        k->type = c->ball ? SCENE_COLLIDER_SPHERE : SCENE_COLLIDER_BOX;
        k->radius = BALL_RADIUS;
        glm_vec3_copy((float *)proxy_box, k->half_extents);
        float y = c->ball ? BALL_RADIUS + 0.5f * s->grass.billboard_size[1] : proxy_box[1];
        for (int i = 0; i < k->path.count; i++) k->path.keys[i].position[1] = y;
        s->collider_count = 1;
    }
}

/* Per-frame measures of one run of a configuration (sweep_frame). */
typedef struct sweep_run_t {
    const bench_config_t *c;
    int warmup, frames;
    bool depth, overpush, pose; /* what this configuration measures */
    bool tested;                /* depth: of the blades' tested points alone (measure_metrics_ext_t.tested_max) */
    double *depths;             /* the deepest sample of every measured frame */
    long nd;
    float *eta_prev;            /* over-push: eta of the frame before */
    double *push;               /* over-push distances of every measured frame */
    long np, push_cap;
    measure_bb_pose_t *pose_out;  /* the last frame's billboard shape */
} sweep_run_t;

/* Sphere proxies of the blade_proxies sweep for box colliders (other
 * colliders get their bounding sphere). */
static int proxy_spheres(world_t *w, collide_sphere_t *out, int max, void *user)
{
    const bench_config_t *c = ((const sweep_run_t *)user)->c;
    int n = 0;
    for (int i = 0; i < world_collider_count(w) && n < max; i++) {
        const world_collider_info_t k = world_collider(w, i);
        const float *p = k.position;
        if (k.desc.type != SCENE_COLLIDER_BOX || c->proxy == PROXY_BOUND) {
            out[n++] = (collide_sphere_t){.centre_radius = {p[0], p[1], p[2], k.bound_radius}};
            continue;
        }
        const float *h = k.desc.half_extents;
        if (c->proxy == PROXY_INSCRIBED) {
            out[n++] = (collide_sphere_t){.centre_radius = {p[0], p[1], p[2], fminf(h[0], fminf(h[1], h[2]))}};
            continue;
        }
        float cell[3] = {h[0] / (float)c->grid[0], h[1] / (float)c->grid[1], h[2] / (float)c->grid[2]};
        float r = c->proxy == PROXY_COVER ? sqrtf(cell[0] * cell[0] + cell[1] * cell[1] + cell[2] * cell[2])
                                          : fminf(cell[0], fminf(cell[1], cell[2]));
        for (int a = 0; a < c->grid[0]; a++)
            for (int b = 0; b < c->grid[1]; b++)
                for (int d = 0; d < c->grid[2] && n < max; d++)
                    out[n++] = (collide_sphere_t){.centre_radius = {p[0] - h[0] + cell[0] * (2 * a + 1),
                                                                  p[1] - h[1] + cell[1] * (2 * b + 1),
                                                                  p[2] - h[2] + cell[2] * (2 * d + 1), r}};
    }
    return n;
}

#define MAX_CONFIGS 128

/* Placement seed of the noise-floor reference (grass_tuning_t.placement_seed). */
#define FLOOR_PLACEMENT_SEED 0x9e3779b9u

/* The reference's grass-free view (the image error's background): a blade
 * field too thin to hold a blade; on a world, whose reference is tiles (a
 * tile must hold one), blades a micrometre tall and wide. */
static void no_grass(scene_desc_t *s, void *user)
{
    (void)user;
    blade_population_t *p = &s->grass.population;
    if (s->terrain.type != TERRAIN_WORLD) {
        p->density = 1e-7f;
        return;
    }
    p->height[0] = p->height[1] = p->width[0] = p->width[1] = 1e-6f;
}

static bench_config_t *add(bench_config_t *c, int *n, const char *group, scene_mode_t mode)
{
    assert(*n < MAX_CONFIGS);
    bench_config_t *x = &c[(*n)++];
    *x = (bench_config_t){.group = group, .mode = mode};
    return x;
}

/* The timings of `from` (frame, passes, CPU) into `to`, its accuracy kept. */
static void keep_timing(measure_metrics_t *to, const measure_metrics_t *from)
{
    to->frame_ms = from->frame_ms;
    to->cpu_ms = from->cpu_ms;
    to->gpu_mb = from->gpu_mb;
    to->pass_count = from->pass_count;
    memcpy(to->pass_ms, from->pass_ms, sizeof to->pass_ms);
    memcpy(to->pass_name, from->pass_name, sizeof to->pass_name);
}

/* Jahrmann & Wimmer's ablation (perf_ablations) on the sweep's scene, for
 * its image error (costs and culled counts on the papers' own scenes:
 * bench --papers). Returns the new count. */
static int add_paper_configs(bench_config_t *c, int n, bool quick)
{
    for (int i = 0; i < (quick ? 2 : PERF_ABLATION_COUNT); i++) {
        bench_config_t *x = add(c, &n, "blade_ablation", SCENE_MODE_BLADE);
        x->no_colliders = perf_ablations[i].no_collision;
        x->tuning.cull_disable = perf_ablations[i].cull_disable;
        snprintf(x->label, sizeof x->label, "%s", perf_ablations[i].name);
    }
    return n;
}

/* The tiers of the field on both rasterizer paths, on canopy_scene (NULL:
 * the sweep's): blade mode with its thinning drawn to the field's edge
 * (grass.blade_distance's default: the budget), the tiles thinned to D
 * and then the canopy without billboards (D = 40, 50, 55, 60, 80 m), the hybrid
 * with billboards to a canopy at 60 m (at the scene's billboard density and
 * at half of it) and at 90 m, then billboard mode. Returns the new count. */
static int add_canopy_configs(bench_config_t *c, int n, bool quick, const char *canopy_scene)
{
    static const float tiles_to[] = {40, 50, 55, 60, 80};
    static const struct {
        float canopy, bb_scale;
    } ring[] = {{60, 1}, {60, 0.5f}, {90, 1}};
    int ntiles = quick ? 1 : (int)(sizeof tiles_to / sizeof tiles_to[0]), nring = quick ? 1 : 3;
    for (int r = 0; r < (quick ? 1 : 2); r++) {
        const char *path = r ? "_compute" : "";
        int raster = r ? 1 + SCENE_RASTER_COMPUTE : 1 + SCENE_RASTER_HW;
        if (!quick) {
            bench_config_t *x = add(c, &n, "hybrid_canopy_distance", SCENE_MODE_BLADE);
            x->raster = raster;
            x->scene = canopy_scene;
            snprintf(x->label, sizeof x->label, "blade%s", path);
        }
        for (int i = 0; i < ntiles; i++) {
            bench_config_t *x = add(c, &n, "hybrid_canopy_distance", SCENE_MODE_HYBRID);
            x->switch_distance = quick ? 8.0f : tiles_to[i];
            x->billboards = 1 + SCENE_HYBRID_BILLBOARDS_NONE;
            x->scene = canopy_scene;
            x->raster = raster;
            snprintf(x->label, sizeof x->label, "tiles%gm%s", (double)x->switch_distance, path);
        }
        for (int i = 0; i < nring; i++) {
            bench_config_t *x = add(c, &n, "hybrid_canopy_distance", SCENE_MODE_HYBRID);
            x->canopy_distance = ring[i].canopy;
            x->bb_density_scale = ring[i].bb_scale;
            x->billboards = 1 + SCENE_HYBRID_BILLBOARDS_RING;
            x->scene = canopy_scene;
            x->raster = raster;
            snprintf(x->label, sizeof x->label, "ring%gm%s%s", (double)x->canopy_distance,
                     ring[i].bb_scale < 1 ? "_sparse" : "", path);
        }
    }
    for (int r = 0; r < 2 && !quick; r++) {
        bench_config_t *x = add(c, &n, "hybrid_canopy_distance", SCENE_MODE_BILLBOARD);
        x->raster = r ? 1 + SCENE_RASTER_COMPUTE : 1 + SCENE_RASTER_HW;
        x->scene = canopy_scene;
        snprintf(x->label, sizeof x->label, "billboard%s", r ? "_compute" : "");
    }
    return n;
}

/* The grass-shaded ground against the thinning's strength (compute path):
 * the tiles to 60 m then the canopy, no billboards, thinning from 1.5 and
 * from 4 px of projected width, with the kept blades widened (the
 * default), thinned without widening over grass-shaded ground, and thinned
 * over soil. Returns the new count. */
static int add_ground_configs(bench_config_t *c, int n)
{
    static const float widths[] = {1.5f, 4.0f};
    static const char *const kinds[] = {"widened", "ground", "soil"};
    for (int i = 0; i < 2; i++)
        for (int k = 0; k < 3; k++) {
            bench_config_t *x = add(c, &n, "lod_ground", SCENE_MODE_HYBRID);
            x->switch_distance = 60.0f;
            x->billboards = 1 + SCENE_HYBRID_BILLBOARDS_NONE;
            x->raster = 1 + SCENE_RASTER_COMPUTE;
            x->lod_width_px = widths[i];
            x->lod_thin = k > 0;
            x->lod_soil = k == 2;
            snprintf(x->label, sizeof x->label, "w%gpx_%s", (double)widths[i], kinds[k]);
        }
    return n;
}

/* canopy_scene: the hybrid_canopy_distance rows' scene (NULL: the sweep's). */
static int build_configs(bench_config_t *c, bool quick, const char *canopy_scene)
{
    int n = 0;
    static const int cubes[] = {8, 16, 32}, subdivs[] = {2, 4, 6}, springs[] = {1, 2, 4};
    /* --quick: the two finest cube maps on the 6 x 6 mesh, so CI sees the
     * penetration measure respond to the resolution where it once did not
     * (bench_quick.sh). */
    int nc = quick ? 2 : 3, ns = quick ? 1 : 3, nk = quick ? 1 : 3;
    for (int a = 0; a < nc; a++)
        for (int b = 0; b < ns; b++)
            for (int k = 0; k < nk; k++) {
                int cube = cubes[quick ? 1 + a : a], sub = subdivs[quick ? 2 : b], spr = springs[quick ? 1 : k];
                bench_config_t *x = add(c, &n, "billboard_collision", SCENE_MODE_BILLBOARD);
                x->cube_resolution = cube;
                x->subdiv = sub;
                x->springs = spr;
                x->ball = true;
                snprintf(x->label, sizeof x->label, "cube%d_sub%d_k%d", cube, sub, spr);
            }
    /* The billboards' reference: the finest cube map, the 6 x 6 mesh (8 x 8
     * exceeds the geometry shader's output) and 8 spring sweeps; the
     * billboard_springs chart's shape deviation is taken from it. */
    bench_config_t *bref = add(c, &n, "billboard_reference", SCENE_MODE_BILLBOARD);
    bref->cube_resolution = quick ? 32 : 64;
    bref->subdiv = 6;
    bref->springs = 8;
    bref->ball = true;
    snprintf(bref->label, sizeof bref->label, "cube%d_sub6_k8", bref->cube_resolution);
    static const struct {
        bench_proxy_t p;
        int g[3];
        const char *name;
    } proxies[] = {{PROXY_BOUND, {1, 1, 1}, "bound_1"},     {PROXY_COVER, {4, 2, 2}, "cover_16"},
                   {PROXY_INSCRIBED, {1, 1, 1}, "inscribed_1"}, {PROXY_COVER, {2, 1, 1}, "cover_2"},
                   {PROXY_COVER, {8, 4, 4}, "cover_128"},   {PROXY_INNER, {4, 2, 2}, "inner_16"},
                   {PROXY_INNER, {8, 4, 4}, "inner_128"}};
    /* --quick: the bounding sphere, a cover and the inscribed sphere (left
     * out of the over-push chart: bench_quick.sh). */
    int np = quick ? 3 : (int)(sizeof proxies / sizeof proxies[0]);
    for (int i = 0; i < np; i++) {
        bench_config_t *x = add(c, &n, "blade_proxies", SCENE_MODE_BLADE);
        x->proxy = proxies[i].p;
        memcpy(x->grid, proxies[i].g, sizeof x->grid);
        snprintf(x->label, sizeof x->label, "%s", proxies[i].name);
    }
    /* --quick: 16 and 32 texels, once identical (proxy_box). */
    static const int cube_res[] = {16, 32, 64};
    for (int i = 0; i < (quick ? 2 : 3); i++) {
        bench_config_t *x = add(c, &n, "blade_proxies", SCENE_MODE_BLADE);
        x->proxy = PROXY_CUBE;
        x->cube_resolution = cube_res[i];
        x->tuning.blade_cube_proxies = true;
        snprintf(x->label, sizeof x->label, "cubemap_%d", x->cube_resolution);
    }
    n = add_paper_configs(c, n, quick);
    static const int tess[] = {1, 2, 3, 5, 7, 10}, levels[] = {1, 2, 4, 8, 16, 32};
    static const float sw[] = {2, 4, 8, 12, 16, 20, 25, 30, 40};
    int nt = quick ? 2 : 6;
    for (int i = 0; i < nt; i++) {
        /* tess_max caps the segments of both hardware paths (the pulled
         * strip's length and its levels as well); the chart is about
         * tessellation, so it draws with the tessellation shaders. Its
         * reference (shared by every chart) is drawn with 16 segments by
         * the scene's path, the surface tessellation builds at 16 too
         * (test_blade_render: tessellation vs pulling mean 0.000). */
        bench_config_t *x = add(c, &n, "blade_tessellation", SCENE_MODE_BLADE);
        x->tuning.tess_max = tess[i];
        x->blade_render = 1 + SCENE_BLADE_RENDER_TESS;
        snprintf(x->label, sizeof x->label, "tess%d", tess[i]);
    }
    for (int i = 0; i < nt; i++) {
        bench_config_t *x = add(c, &n, "blade_distance_levels", SCENE_MODE_BLADE);
        x->lod_levels = levels[i];
        snprintf(x->label, sizeof x->label, "levels%d", levels[i]);
    }
    int nsw = quick ? 2 : (int)(sizeof sw / sizeof sw[0]);
    for (int i = 0; i < nsw; i++) {
        bench_config_t *x = add(c, &n, "hybrid_switch_distance", SCENE_MODE_HYBRID);
        x->switch_distance = sw[i];
        snprintf(x->label, sizeof x->label, "switch%gm", sw[i]);
    }
    n = add_canopy_configs(c, n, quick, canopy_scene);
    if (!quick) n = add_ground_configs(c, n);
    static const scene_mode_t modes[3] = {SCENE_MODE_BILLBOARD, SCENE_MODE_BLADE, SCENE_MODE_HYBRID};
    for (int d = 0; d < (quick ? 1 : 2); d++)
        for (int i = 0; i < 3; i++) {
            bench_config_t *x = add(c, &n, "modes", modes[i]);
            x->density_scale = (float)(d + 1);
            snprintf(x->label, sizeof x->label, "%s_x%d", scene_mode_name(modes[i]), d + 1);
        }
    for (int i = 1; i < 3 && !quick; i++) {
        bench_config_t *x = add(c, &n, "modes", modes[i]);
        x->blade_render = 2;
        snprintf(x->label, sizeof x->label, "%s_x1_tess", scene_mode_name(modes[i]));
    }
    /* The compute rasterizer (docs/RASTER.md) beside the hardware rows. */
    for (int i = 0; i < 3 && !quick; i++) {
        bench_config_t *x = add(c, &n, "modes", modes[i]);
        x->raster = 1 + SCENE_RASTER_COMPUTE;
        snprintf(x->label, sizeof x->label, "%s_x1_compute", scene_mode_name(modes[i]));
    }
    /* Its samples per pixel: 1 (the pixel centre) against the 4 above, cost
     * against image error. */
    for (int i = 0; i < 3 && !quick; i++) {
        bench_config_t *x = add(c, &n, "modes", modes[i]);
        x->raster = 1 + SCENE_RASTER_COMPUTE;
        x->raster_samples = 1;
        snprintf(x->label, sizeof x->label, "%s_x1_compute_s1", scene_mode_name(modes[i]));
    }
    return n;
}

/* One chart: a group's runs with y taken from one measure and x the GPU
 * time of the passes its knob changes (`passes`: the pass names whose
 * medians are summed, up to a NULL; none: the whole frame), the frame
 * beside it in the tables. Timing only those passes keeps a knob's cost
 * from drowning in the run-to-run noise of the rest of the frame. */
typedef enum bench_y_t { Y_IMAGE = 0, Y_PEN_MAX, Y_SPRING, Y_OVERPUSH, Y_COUNT } bench_y_t;
#define CHART_PASSES 4
typedef struct bench_chart_t {
    const char *name, *group, *ylabel;
    bench_y_t y;
    const char *passes[CHART_PASSES];
} bench_chart_t;

#define BB_KNOB_PASSES {"bb.cubemaps", "bb.collide", "bb.recover"}
#define DRAW_PASSES {"blade.cull", "blade.draw", "blade.raster"}
static const bench_chart_t charts[] = {
    {"billboard_collision", "billboard_collision", "penetration depth p95 (m, exact ball)", Y_PEN_MAX,
     BB_KNOB_PASSES},
    {"billboard_springs", "billboard_collision", "shape deviation from the finest configuration (m)", Y_SPRING,
     BB_KNOB_PASSES},
    {"blade_proxies", "blade_proxies", "tested-point depth p95 (m, tip and midpoint in the exact box)", Y_PEN_MAX,
     {"blade.physics"}},
    {"blade_proxies_overpush", "blade_proxies", "over-push p95 (m beyond the exact box)", Y_OVERPUSH,
     {"blade.physics"}},
    {"blade_ablation", "blade_ablation", "image error (eval_image vs reference)", Y_IMAGE,
     {"blade.physics", "blade.cull", "blade.draw", "blade.raster"}},
    {"blade_tessellation", "blade_tessellation", "image error (eval_image vs reference)", Y_IMAGE, DRAW_PASSES},
    {"blade_distance_levels", "blade_distance_levels", "image error (eval_image vs reference)", Y_IMAGE,
     DRAW_PASSES},
    {"hybrid_switch_distance", "hybrid_switch_distance", "image error (eval_image vs reference)", Y_IMAGE, {NULL}},
    {"hybrid_canopy_distance", "hybrid_canopy_distance", "image error (eval_image vs reference)", Y_IMAGE, {NULL}},
    {"lod_ground", "lod_ground", "image error (eval_image vs reference)", Y_IMAGE, {NULL}},
    {"modes", "modes", "image error (eval_image vs reference)", Y_IMAGE, {NULL}},
};
#define CHART_COUNT ((int)(sizeof charts / sizeof charts[0]))

/* The GPU ms of a chart's knob passes in a run (the frame when the chart
 * names none). */
static double knob_ms(const bench_chart_t *ch, const measure_metrics_t *m)
{
    if (!ch->passes[0]) return m->frame_ms;
    double sum = 0.0;
    for (int p = 0; p < m->pass_count; p++)
        for (int k = 0; k < CHART_PASSES && ch->passes[k]; k++)
            if (strcmp(m->pass_name[p], ch->passes[k]) == 0) sum += m->pass_ms[p];
    return sum;
}

/* "GPU ms of bb.cubemaps + bb.collide + bb.recover per frame" or of the frame. */
static void knob_label(const bench_chart_t *ch, char *out, size_t size)
{
    if (!ch->passes[0]) {
        snprintf(out, size, "GPU ms per frame");
        return;
    }
    int n = snprintf(out, size, "GPU ms of");
    for (int k = 0; k < CHART_PASSES && ch->passes[k] && n > 0 && (size_t)n < size; k++)
        n += snprintf(out + n, size - (size_t)n, "%s %s", k ? " +" : "", ch->passes[k]);
    if (n > 0 && (size_t)n < size) snprintf(out + n, size - (size_t)n, " per frame");
}

/* floor >= 0: a dashed line at the image error's noise floor. */
static void write_chart(const char *out, const bench_chart_t *ch, double floor)
{
    char name[64], data[1200], body[6144], floor_plot[160] = "", xlabel[160];
    knob_label(ch, xlabel, sizeof xlabel);
    if (floor >= 0)
        snprintf(floor_plot, sizeof floor_plot, ", %.6f with lines dt 2 lw 2 lc rgb 'gray40' title 'noise floor "
                 "(reference, other placement seed)'", floor);
    snprintf(name, sizeof name, "bench_%s", ch->name);
    snprintf(data, sizeof data, "%s/bench_%s.dat", out, ch->name);
    snprintf(body, sizeof body,
             "set title '%s: speed vs accuracy'\nset xlabel '%s'\nset ylabel '%s'\n"
             "set grid\nset key below\nset offsets graph 0.05, graph 0.05, graph 0.08, graph 0.05\n"
             "plot '%s' using 1:2 with points pt 7 ps 1.2 title 'configurations', "
             "'' using 1:2:3 with labels offset 0,1 font ',8' notitle, "
             "'< grep -E \"^[^ ]+ [^ ]+ [^ ]+ 1( |$)\" %s | sort -g' using 1:2 with linespoints lw 2 pt 6 ps 2 "
             "title 'Pareto front, hardware path', "
             "'< grep -E \"^[^ ]+ [^ ]+ [^ ]+ 2( |$)\" %s | sort -g' using 1:2 with linespoints lw 2 dt 3 pt 8 ps 2 "
             "title 'Pareto front, compute path'%s",
             ch->name, xlabel, ch->ylabel, data, data, data, floor_plot);
    eval_gnuplot_chart(out, name, body);
}

/* Runs of every configuration, each with its own placement seed (and
 * the reference drawn with that seed). */
#define SWEEP_RUNS 3

/* Per configuration: each run's timings and measures, and what the charts
 * take from them (-1: not measured). */
typedef struct bench_acc_t {
    measure_metrics_t runs[SWEEP_RUNS];
    double y_runs[Y_COUNT][SWEEP_RUNS]; /* each run's value of every chart measure */
    double y[Y_COUNT];                  /* the chart value: image error and deviation the mean,
                                           depth and over-push the p95 over every run's frames */
    measure_bb_pose_t pose[SWEEP_RUNS];   /* billboard configurations: the last frame's shape */
} bench_acc_t;

/* The references of one scene: one per placement seed, its grass-free
 * view, and its image error's noise floor. */
typedef struct bench_refs_t {
    const char *scene;            /* NULL: the sweep's (--scene) */
    const char *tag;              /* its frames' file name prefix ("" or "canopy_") */
    core_image_t img[SWEEP_RUNS]; /* the reference drawn with placements[k] */
    core_image_t bg;              /* the grass-free view (the image error's background) */
    double floor;        /* eval_image score of a reference against another placement's, mean of SWEEP_RUNS pairs */
    double floor_spread; /* half the range of those */
    double floor_ssim;   /* 1 - SSIM of the first pair */
    bool made;           /* rendered (a configuration runs on this scene) */
} bench_refs_t;
/* The sweep's scene (0) and the canopy chart's (1: CANOPY_SCENE). */
#define REF_SETS 2

typedef struct bench_run_t {
    int n;
    bench_config_t *cfg;
    measure_metrics_t *met;  /* the first run's accuracy with the fastest run's timings */
    double *err;       /* eval_image score against the reference (mean over the runs) */
    double *ssim_err;  /* 1 - SSIM against the reference (first run) */
    eval_image_error_t *terms; /* the image error's terms (first run) */
    bench_acc_t *acc;
    bench_refs_t refs[REF_SETS];
    char renderer[256];
    int frames;
} bench_run_t;

static double y_of(const bench_chart_t *ch, const bench_run_t *b, int i) { return b->acc[i].y[ch->y]; }

/* The references configuration c is measured against. */
static const bench_refs_t *refs_of(const bench_run_t *b, const bench_config_t *c) { return &b->refs[c->scene ? 1 : 0]; }

/* Proxies inside the exact box: over-push 0 by construction. Spheres
 * inscribed in it or in its cells; a cube map whose every edge snaps
 * inward (proxy_box: the texels whose centre ray hits the box, at
 * (h / R + 1) / 2 x N texels for an edge at h, R the bounding radius). */
static bool proxy_inside(const bench_config_t *c)
{
    if (c->proxy == PROXY_INSCRIBED || c->proxy == PROXY_INNER) return true;
    if (c->proxy != PROXY_CUBE) return false;
    float r = sqrtf(proxy_box[0] * proxy_box[0] + proxy_box[1] * proxy_box[1] + proxy_box[2] * proxy_box[2]);
    bool inward = true;
    for (int k = 0; k < 3; k++) {
        float edge = 0.5f * (proxy_box[k] / r + 1.0f) * (float)c->cube_resolution;
        inward = inward && edge - floorf(edge) < 0.5f;
    }
    return inward;
}

/* Whether configuration c is a point of chart ch: the over-push chart
 * leaves out the proxies inside the shape (their penetration is charted). */
static bool in_chart(const bench_chart_t *ch, const bench_config_t *c)
{
    return strcmp(c->group, ch->group) == 0 && !(ch->y == Y_OVERPUSH && proxy_inside(c));
}

/* Half the range of v[0..n) over its non-negative entries (0 when fewer than two). */
static double half_range(const double *v, int n)
{
    double lo = INFINITY, hi = -INFINITY;
    int k = 0;
    for (int j = 0; j < n; j++)
        if (v[j] >= 0.0) lo = fmin(lo, v[j]), hi = fmax(hi, v[j]), k++;
    return k > 1 ? 0.5 * (hi - lo) : 0.0;
}

/* A configuration's x: the fastest run's knob ms; its spread ex: the
 * second fastest's minus it (one slow run, as the H100 showed now and
 * then, widens nothing). */
static double x_of(const bench_chart_t *ch, const bench_run_t *b, int i, double *ex)
{
    double r[SWEEP_RUNS];
    int n = 0;
    for (int k = 0; k < SWEEP_RUNS; k++)
        if (b->acc[i].runs[k].pass_count > 0) r[n++] = knob_ms(ch, &b->acc[i].runs[k]);
    for (int a = 1; a < n; a++)
        for (int c = a; c > 0 && r[c - 1] > r[c]; c--) {
            double t = r[c];
            r[c] = r[c - 1];
            r[c - 1] = t;
        }
    *ex = n > 1 ? r[1] - r[0] : 0.0;
    return n ? r[0] : knob_ms(ch, &b->met[i]);
}

/* A chart's configurations (idx, xs, ys and their spreads: k of them) and
 * their Pareto fronts, one per rasterizer path: a configuration is compared
 * only with those drawn by the same path (the modes chart holds both), as
 * the path is a property of the GPU rather than a knob of the method; a
 * configuration dominates another only beyond their measured spreads
 * (eval_pareto_noise). front[j]: 0 off the fronts, 1 on the hardware
 * path's, 2 on the compute path's. */
static int chart_points(const bench_run_t *b, const bench_chart_t *ch, int *idx, double *xs, double *ys,
                        double *exs, double *eys, int *front)
{
    int k = 0;
    for (int i = 0; i < b->n; i++)
        if (in_chart(ch, &b->cfg[i])) {
            idx[k] = i;
            xs[k] = x_of(ch, b, i, &exs[k]);
            ys[k] = y_of(ch, b, i);
            eys[k] = half_range(b->acc[i].y_runs[ch->y], SWEEP_RUNS);
            k++;
        }
    for (int path = 0; path < 2; path++) {
        double px[MAX_CONFIGS], py[MAX_CONFIGS], pex[MAX_CONFIGS], pey[MAX_CONFIGS];
        bool on[MAX_CONFIGS];
        int map[MAX_CONFIGS], m = 0;
        for (int j = 0; j < k; j++)
            if ((int)b->met[idx[j]].raster_compute == path) {
                px[m] = xs[j], py[m] = ys[j], pex[m] = exs[j], pey[m] = eys[j];
                map[m++] = j;
            }
        eval_pareto_noise(px, py, pex, pey, m, on);
        for (int j = 0; j < m; j++) front[map[j]] = on[j] ? 1 + path : 0;
    }
    return k;
}

/* Configurations of a chart whose accuracy is identical (to 1e-12 m or
 * score) to another's: a y that does not answer the knob between them.
 * Writes "a = b, ..." into out; returns the number of such pairs. */
static int identical_rows(const bench_run_t *b, const bench_chart_t *ch, char *out, size_t size)
{
    int pairs = 0;
    size_t len = 0;
    out[0] = 0;
    for (int i = 0; i < b->n; i++) {
        if (!in_chart(ch, &b->cfg[i]) || y_of(ch, b, i) < 0.0) continue;
        for (int j = i + 1; j < b->n; j++) {
            if (!in_chart(ch, &b->cfg[j]) || fabs(y_of(ch, b, i) - y_of(ch, b, j)) > 1e-12) continue;
            pairs++;
            if (len + 1 < size)
                len += (size_t)snprintf(out + len, size - len, "%s%s = %s", len ? ", " : "", b->cfg[i].label,
                                        b->cfg[j].label);
        }
    }
    return pairs;
}

static const char *front_name(int front) { return front == 1 ? "hardware" : front == 2 ? "compute" : "-"; }

/* A row's wall time per frame: the larger of its GPU pass sum and its
 * CPU's wall clock, so a CPU-bound configuration counts as slow. */
static double row_wall(const measure_metrics_t *m) { return fmax(m->frame_ms, m->cpu_ms); }

/* Row i is a measured row of the hybrid_canopy_distance chart on path
 * path_k (0 hw, 1 compute). */
static bool lod_row(const bench_run_t *b, int i, int path_k)
{
    const bench_config_t *c = &b->cfg[i];
    bool compute = c->raster == 1 + SCENE_RASTER_COMPUTE;
    return strcmp(c->group, "hybrid_canopy_distance") == 0 && compute == (path_k == 1) && b->err[i] >= 0.0;
}

/* lod.json (scene_lod.h) from the hybrid_canopy_distance rows: per path,
 * bench_lod_pick over its rows, with BENCH_LOD_ERROR and BENCH_LOD_GPU_MB,
 * and blade mode's figures when the run has its row. Rows that leave a
 * distance at 0 take the scene's. Nothing when the run holds no such
 * rows. */
static bool write_lod(const char *out, const world_options_t *o, const bench_run_t *b)
{
    int first = 0;
    while (first < b->n && strcmp(b->cfg[first].group, "hybrid_canopy_distance") != 0) first++;
    if (first == b->n) return true;
    const bench_refs_t *R = refs_of(b, &b->cfg[first]);
    const char *scene_path = R->scene ? R->scene : o->scene ? o->scene : "scenes/meadow.json";
    scene_desc_t s;
    char err[1024], path[1200];
    if (!scene_load(&s, scene_path, err, sizeof err)) return false;
    core_buf_t json = {0};
    core_buf_printf(&json, "{\n  \"renderer\": \"%s\",\n  \"scene\": \"%s\",\n  \"size\": [%d, %d],\n"
                           "  \"frames\": %d,\n  \"budget\": \"the least wall time within an image error of %g and %g MiB\",\n"
                           "  \"paths\": {",
                    b->renderer, scene_path, o->width ? o->width : s.size[0], o->width ? o->height : s.size[1],
                    b->frames, BENCH_LOD_ERROR, BENCH_LOD_GPU_MB);
    int written = 0;
    for (int path_k = 0; path_k < 2; path_k++) {
        int blade = -1, candidates = 0, idx[MAX_CONFIGS], m = 0;
        bench_lod_row_t rows[MAX_CONFIGS];
        for (int i = 0; i < b->n; i++) {
            if (!lod_row(b, i, path_k)) continue;
            if (b->cfg[i].mode == SCENE_MODE_BLADE) blade = i;
            bool hybrid = b->cfg[i].mode == SCENE_MODE_HYBRID;
            candidates += hybrid;
            idx[m] = i;
            rows[m++] = (bench_lod_row_t){.candidate = hybrid, .wall_ms = row_wall(&b->met[i]), .error = b->err[i],
                                          .gpu_mb = b->met[i].gpu_mb};
        }
        bool met = false;
        int k = bench_lod_pick(rows, m, BENCH_LOD_ERROR, BENCH_LOD_GPU_MB, &met);
        if (k < 0) continue;
        int pick = idx[k];
        const bench_config_t *c = &b->cfg[pick];
        float sw = c->switch_distance > 0 ? c->switch_distance : s.grass.switch_distance;
        float cd = c->canopy_distance > 0 ? c->canopy_distance : s.grass.canopy_distance;
        cd = fmaxf(cd, sw + CANOPY_GAP);
        scene_hybrid_billboards_t bb = c->billboards ? (scene_hybrid_billboards_t)(c->billboards - 1) : s.grass.billboards;
        core_buf_printf(&json,
                        "%s\n    \"%s\": {\"switch_distance\": %g, \"canopy_distance\": %g, \"billboards\": \"%s\", "
                        "\"wall_ms\": %.4f, \"gpu_ms\": %.4f, \"image_error\": %.6f, \"budget\": %.6f, \"met\": %s, "
                        "\"gpu_mb\": %.1f, \"memory_budget_mb\": %g, \"label\": \"%s\", \"candidates\": %d",
                        written ? "," : "", path_k ? "compute" : "hw", (double)sw, (double)cd,
                        bb == SCENE_HYBRID_BILLBOARDS_NONE ? "none" : "ring", row_wall(&b->met[pick]),
                        b->met[pick].frame_ms, b->err[pick], BENCH_LOD_ERROR, met ? "true" : "false", b->met[pick].gpu_mb,
                        BENCH_LOD_GPU_MB, c->label, candidates);
        if (blade >= 0)
            core_buf_printf(&json,
                            ", \"blade_wall_ms\": %.4f, \"blade_ms\": %.4f, \"blade_error\": %.6f, \"blade_gpu_mb\": %.1f",
                            row_wall(&b->met[blade]), b->met[blade].frame_ms, b->err[blade], b->met[blade].gpu_mb);
        core_buf_printf(&json, "}");
        written++;
    }
    core_buf_printf(&json, "\n  }\n}\n");
    snprintf(path, sizeof path, "%s/lod.json", out);
    bool ok = written == 0 || core_buf_write(&json, path);
    if (written && ok) core_log_info("bench: wrote %s (the hybrid's distances by measurement, scene_lod.h)", path);
    core_buf_free(&json);
    return ok;
}

/* Placement seeds of a configuration's runs (grass_tuning_t.placement_seed;
 * 0: the scene's), each run compared with the reference of its own. */
static const uint32_t placements[SWEEP_RUNS] = {0, FLOOR_PLACEMENT_SEED, 0x85ebca6bu};
#define MEASURE_EVERY 4 /* frames between per-frame measures after warm-up */

static void sweep_frame(world_t *w, int f, float t, void *user)
{
    (void)t;
    sweep_run_t *r = user;
    if (r->pose && f + 1 == r->frames && !measure_bb_pose(w, r->pose_out))
        core_log_warn("bench: no memory for the billboard shape of %s", r->c->label);
    if (f < r->warmup) return;
    int phase = f % MEASURE_EVERY;
    if (r->depth && phase == 0 && r->nd < r->frames) {
        measure_metrics_t m;
        measure_metrics_ext_t x;
        measure_metrics(w, &m, &x);
        if (m.penetration_max >= 0.0) r->depths[r->nd++] = r->tested ? x.tested_max : m.penetration_max;
    }
    if (!r->overpush || !world_info(w).blades || (phase != 0 && phase != MEASURE_EVERY - 1)) return;
    measure_grass_t mg;
    measure_grass(w, MEASURE_GRASS_SIZES, false, &mg);
    uint32_t padded = mg.blade_padded;
    if (!r->eta_prev) r->eta_prev = calloc(padded, sizeof(float));
    if (r->np + (long)padded > r->push_cap) {
        long cap = r->np + (long)padded * 4;
        double *p = realloc(r->push, sizeof *p * (size_t)cap);
        if (!p) return;
        r->push = p, r->push_cap = cap;
    }
    if (r->eta_prev) r->np += measure_blade_overpush(w, r->eta_prev, phase == 0, r->push + r->np);
}

/* The q95 of v[0..n) on a copy (-1 when n is 0: not measured). */
static double p95_copy(const double *v, long n)
{
    if (n <= 0) return -1.0;
    double *c = malloc(sizeof *c * (size_t)n);
    if (!c) return -1.0;
    memcpy(c, v, sizeof *c * (size_t)n);
    double q = measure_percentile(c, n, 0.95);
    free(c);
    return q;
}

/* The references of R's scene (one per placement seed), its grass-free
 * background and its noise floor: each reference against the next's
 * placement, mean and half range over the SWEEP_RUNS pairs. */
static int make_references(const world_options_t *oh, int frames, const char *out, bench_refs_t *R)
{
    char path[1200];
    world_options_t os = *oh;
    if (R->scene) os.scene = R->scene;
    measure_session_desc_t rd = {.world = os,
                                 .mode = SCENE_MODE_BLADE, .mode_set = true, .frames = frames,
                               .reference = true, .msaa = 8};
    core_log_info("bench: %d reference renderings of %s (%d frames, one per placement seed) and the grass-free view",
                  SWEEP_RUNS, os.scene ? os.scene : "the default scene", frames);
    int rc = 0;
    for (int k = 0; k < SWEEP_RUNS && rc == 0; k++) {
        measure_session_desc_t d = rd;
        d.tuning.placement_seed = placements[k];
        rc = measure_session_run(&d, &R->img[k], NULL);
    }
    measure_session_desc_t bd = rd;
    bd.tweak = no_grass;
    if (rc == 0) rc = measure_session_run(&bd, &R->bg, NULL);
    if (rc) return rc;
    snprintf(path, sizeof path, "%s/frames", out);
    if (!core_fs_mkdirs(path)) core_log_warn("bench: cannot create %s", path);
    const core_image_t *fixed[3] = {&R->img[0], &R->bg, &R->img[1]};
    static const char *names[3] = {"reference", "background", "floor"};
    for (int i = 0; i < 3; i++) {
        snprintf(path, sizeof path, "%s/frames/%s%s.png", out, R->tag, names[i]);
        if (!core_image_write_png(fixed[i], path)) return 1; /* logged with the path and why */
    }
    const eval_image_desc_t ed = {.background = &R->bg};
    double f[SWEEP_RUNS];
    R->floor = 0.0;
    for (int k = 0; k < SWEEP_RUNS; k++) {
        eval_image_error_t e = {0};
        f[k] = eval_image_error(&R->img[(k + 1) % SWEEP_RUNS], &R->img[k], &ed, &e) ? e.score : 0.0;
        R->floor += f[k] / SWEEP_RUNS;
    }
    R->floor_spread = half_range(f, SWEEP_RUNS);
    R->floor_ssim = 1.0 - eval_image_ssim(&R->img[1], &R->img[0]);
    core_log_info("bench: image error noise floor %.4f +- %.4f over %d placement pairs (1 - SSIM %.4f)", R->floor,
                  R->floor_spread, SWEEP_RUNS, R->floor_ssim);
    R->made = true;
    return 0;
}

/* Configuration i's SWEEP_RUNS runs: timings from the fastest, accuracy
 * of the first run in b->met, every chart measure per run and pooled. */
static int run_config(const world_options_t *oh, bench_run_t *b, int i, const char *out)
{
    bench_config_t *c = &b->cfg[i];
    bench_acc_t *acc = &b->acc[i];
    const bench_refs_t *R = refs_of(b, c);
    const core_image_t *refs = R->img, *bg = &R->bg;
    world_options_t oc = *oh;
    if (c->scene) oc.scene = c->scene;
    if (c->blade_render) oc.blade_render = c->blade_render;
    if (c->raster) oc.raster = c->raster;
    if (c->raster_samples) oc.raster_samples = c->raster_samples;
    bool depth = strcmp(c->group, "billboard_collision") == 0 || strcmp(c->group, "blade_proxies") == 0;
    bool pose = c->mode == SCENE_MODE_BILLBOARD && c->ball;
    long cap = (long)b->frames * SWEEP_RUNS;
    double *depths = depth ? malloc(sizeof *depths * (size_t)cap) : NULL;
    bool proxies = strcmp(c->group, "blade_proxies") == 0;
    sweep_run_t r = {.c = c, .frames = b->frames, .warmup = b->frames / 4, .depth = depths != NULL,
                     .tested = proxies, .overpush = proxies, .pose = pose};
    const eval_image_desc_t ed = {.background = bg};
    double err_sum = 0.0;
    int rc = 0;
    for (int y = 0; y < Y_COUNT; y++)
        for (int k = 0; k < SWEEP_RUNS; k++) acc->y_runs[y][k] = -1.0;
    for (int k = 0; k < SWEEP_RUNS && rc == 0; k++) {
        measure_session_desc_t d = {.world = oc,
                                    .mode = c->mode, .mode_set = true, .frames = b->frames,
                                  .tweak = tweak, .user = c, .tuning = c->tuning};
        d.tuning.placement_seed = placements[k];
        bool spheres = c->proxy != PROXY_WORLD && c->proxy != PROXY_CUBE;
        long nd0 = r.nd, np0 = r.np;
        r.depths = depths;
        r.pose_out = &acc->pose[k];
        free(r.eta_prev);
        r.eta_prev = NULL;
        measure_session_hooks_t h = {.blade_spheres = spheres ? proxy_spheres : NULL, .frame = sweep_frame, .user = &r};
        core_image_t img = {0};
        rc = measure_session_run_hooks(&d, &h, &img, &acc->runs[k]);
        if (rc) break;
        eval_image_error_t e = {0};
        acc->y_runs[Y_IMAGE][k] = eval_image_error(&img, &refs[k], &ed, &e) ? e.score : -1.0;
        err_sum += acc->y_runs[Y_IMAGE][k];
        acc->y_runs[Y_PEN_MAX][k] = p95_copy(depths ? depths + nd0 : NULL, r.nd - nd0);
        acc->y_runs[Y_OVERPUSH][k] = p95_copy(r.push ? r.push + np0 : NULL, r.np - np0);
        if (k == 0) {
            b->met[i] = acc->runs[0];
            b->terms[i] = e;
            b->ssim_err[i] = 1.0 - eval_image_ssim(&img, &refs[0]);
            char path[1200];
            snprintf(path, sizeof path, "%s/frames/%s_%s.png", out, c->group, c->label);
            if (!core_image_write_png(&img, path)) rc = 1; /* logged; the sweep stops: its output is incomplete */
        } else if (acc->runs[k].frame_ms < b->met[i].frame_ms) {
            keep_timing(&b->met[i], &acc->runs[k]);
        }
        core_image_free(&img);
    }
    acc->y[Y_IMAGE] = b->err[i] = err_sum / SWEEP_RUNS;
    acc->y[Y_PEN_MAX] = p95_copy(depths, r.nd);
    acc->y[Y_OVERPUSH] = p95_copy(r.push, r.np);
    acc->y[Y_SPRING] = -1.0;
    free(depths);
    free(r.push);
    free(r.eta_prev);
    return rc;
}

/* billboard_springs' y: each billboard configuration's shape deviation from
 * the billboard_reference run of the same placement, mean over the runs. */
static void shape_deviations(bench_run_t *b)
{
    int ref = -1;
    for (int i = 0; i < b->n; i++)
        if (strcmp(b->cfg[i].group, "billboard_reference") == 0) ref = i;
    for (int i = 0; i < b->n && ref >= 0; i++) {
        if (!(b->cfg[i].mode == SCENE_MODE_BILLBOARD && b->cfg[i].ball)) continue;
        double sum = 0.0;
        for (int k = 0; k < SWEEP_RUNS; k++) {
            b->acc[i].y_runs[Y_SPRING][k] = measure_bb_pose_deviation(&b->acc[i].pose[k], &b->acc[ref].pose[k]);
            sum += b->acc[i].y_runs[Y_SPRING][k];
        }
        b->acc[i].y[Y_SPRING] = sum / SWEEP_RUNS;
    }
}

/* --chart NAME keeps that chart's configurations (and the billboard
 * reference with billboard_collision); 2 after an error line when none. */
static int filter_chart(const char *chart, bench_run_t *b)
{
    int k = 0;
    bool bb = strcmp(chart, "billboard_collision") == 0;
    for (int i = 0; i < b->n; i++)
        if (strcmp(b->cfg[i].group, chart) == 0 || (bb && strcmp(b->cfg[i].group, "billboard_reference") == 0))
            b->cfg[k++] = b->cfg[i];
    if (k == 0 || (bb && k == 1)) {
        core_buf_t names = {0};
        for (int ci = 0; ci < CHART_COUNT; ci++)
            if (ci == 0 || strcmp(charts[ci].group, charts[ci - 1].group) != 0)
                core_buf_printf(&names, "%s%s", ci ? ", " : "", charts[ci].group);
        core_log_error("--chart '%s': no such chart (%s)", chart, names.data);
        core_buf_free(&names);
        return 2;
    }
    b->n = k;
    return 0;
}

/* Keeps the configurations whose label starts with one of the
 * comma-separated prefixes of `rows`; 2 (logged, with the labels) when
 * none does. */
static int filter_rows(const char *rows, bench_run_t *b)
{
    int k = 0;
    for (int i = 0; i < b->n; i++) {
        bool keep = false;
        for (const char *p = rows; *p && !keep;) {
            size_t len = strcspn(p, ",");
            keep = len > 0 && strncmp(b->cfg[i].label, p, len) == 0;
            p += len + (p[len] == ',');
        }
        if (keep) b->cfg[k++] = b->cfg[i];
    }
    if (k == 0) {
        core_buf_t names = {0};
        for (int i = 0; i < b->n; i++) core_buf_printf(&names, "%s%s", i ? ", " : "", b->cfg[i].label);
        core_log_error("--rows '%s': no label of the chart starts with one of them (labels: %s)", rows, names.data);
        core_buf_free(&names);
        return 2;
    }
    b->n = k;
    return 0;
}

/* bench.csv, bench.json, lod.json and one data file and chart per chart
 * entry (x GPU ms, y its measure, both with their spreads); warns of
 * charts whose accuracy is identical between configurations. */
static int write_sweep(const world_options_t *o, const char *out, const bench_run_t *b)
{
    char path[1200];
    int rc = 0, n = b->n;
    core_buf_t csv = {0}, json = {0};
    core_buf_printf(&csv, "group,label,mode,gpu_ms,cpu_ms,image_error,image_ssim_error,penetration_fraction,penetration_max,"
                          "blade_length_error,spring_error,depth_p95,shape_deviation,overpush_p95,image_error_spread,"
                          "passes\n");
    core_buf_printf(&json,
                    "{\n  \"renderer\": \"%s\",\n  \"frames\": %d,\n  \"image_error_floor\": %.6f,\n"
                    "  \"image_error_floor_spread\": %.6f,\n  \"runs\": %d,\n"
                    "  \"image_ssim_error_floor\": %.6f,\n",
                    b->renderer, b->frames, b->refs[0].floor, b->refs[0].floor_spread, SWEEP_RUNS,
                    b->refs[0].floor_ssim);
    const bench_refs_t *cr = &b->refs[1];
    if (cr->made)
        core_buf_printf(&json, "  \"canopy_scene\": \"%s\",\n  \"canopy_image_error_floor\": %.6f,\n"
                               "  \"canopy_image_error_floor_spread\": %.6f,\n",
                        cr->scene, cr->floor, cr->floor_spread);
    core_buf_printf(&json, "  \"configs\": [\n");
    for (int i = 0; i < n; i++) {
        const measure_metrics_t *m = &b->met[i];
        const bench_config_t *c = &b->cfg[i];
        const bench_acc_t *a = &b->acc[i];
        double espread = half_range(a->y_runs[Y_IMAGE], SWEEP_RUNS);
        core_buf_printf(&csv, "%s,%s,%s,%.4f,%.3f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,", c->group,
                        c->label, scene_mode_name(c->mode), m->frame_ms, m->cpu_ms, b->err[i], b->ssim_err[i],
                        m->penetration_fraction, m->penetration_max, m->blade_length_error, m->spring_error,
                        a->y[Y_PEN_MAX], a->y[Y_SPRING], a->y[Y_OVERPUSH], espread);
        core_buf_printf(&json,
                        "    { \"group\": \"%s\", \"label\": \"%s\", \"scene\": \"%s\", \"mode\": \"%s\", "
                        "\"gpu_ms\": %.4f, "
                        "\"cpu_ms\": %.3f, \"gpu_mb\": %.1f, \"image_error\": %.6f, \"image_ssim_error\": %.6f, "
                        "\"image_terms\": {\"colour\": %.4f, \"coverage\": %.4f, \"structure\": %.4f}, "
                        "\"penetration_fraction\": %.6f, "
                        "\"penetration_max\": %.6f, \"blade_length_error\": %.6f, \"spring_error\": %.6f, "
                        "\"depth_p95\": %.6f, \"shape_deviation\": %.6f, \"overpush_p95\": %.6f, "
                        "\"image_error_spread\": %.6f, \"passes\": {",
                        c->group, c->label, c->scene ? c->scene : o->scene ? o->scene : "scenes/meadow.json",
                        scene_mode_name(c->mode), m->frame_ms, m->cpu_ms, m->gpu_mb, b->err[i], b->ssim_err[i],
                        b->terms[i].colour, b->terms[i].coverage, b->terms[i].structure,
                        m->penetration_fraction, m->penetration_max, m->blade_length_error, m->spring_error,
                        a->y[Y_PEN_MAX], a->y[Y_SPRING], a->y[Y_OVERPUSH], espread);
        for (int p = 0; p < m->pass_count; p++) {
            core_buf_printf(&csv, "%s%s=%.4f", p ? ";" : "", m->pass_name[p], m->pass_ms[p]);
            core_buf_printf(&json, "%s\"%s\": %.4f", p ? ", " : "", m->pass_name[p], m->pass_ms[p]);
        }
        core_buf_printf(&csv, "\n");
        core_buf_printf(&json, "} }%s\n", i + 1 < n ? "," : "");
    }
    core_buf_printf(&json, "  ]\n}\n");
    snprintf(path, sizeof path, "%s/bench.csv", out);
    if (!core_buf_write(&csv, path)) rc = 1;
    snprintf(path, sizeof path, "%s/bench.json", out);
    if (!core_buf_write(&json, path)) rc = 1;
    if (!write_lod(out, o, b)) rc = 1;
    core_buf_free(&csv);
    core_buf_free(&json);
    /* One data file and chart per chart entry: x GPU ms, y its measure. */
    for (int ci = 0; ci < CHART_COUNT && rc == 0; ci++) {
        const bench_chart_t *ch = &charts[ci];
        double xs[MAX_CONFIGS], ys[MAX_CONFIGS], exs[MAX_CONFIGS], eys[MAX_CONFIGS];
        int front[MAX_CONFIGS], idx[MAX_CONFIGS];
        int k = chart_points(b, ch, idx, xs, ys, exs, eys, front);
        if (k == 0) continue;
        char same[1024];
        if (identical_rows(b, ch, same, sizeof same))
            core_log_warn("bench: chart %s: identical accuracy (the measure does not answer the knob): %s", ch->name,
                          same);
        core_buf_t dat = {0};
        char xlabel[160];
        knob_label(ch, xlabel, sizeof xlabel);
        core_buf_printf(&dat, "# x y label pareto frame_ms ex ey (x: %s; y: %s; pareto: 0 off, 1 hardware path's "
                              "front, 2 compute path's; ex, ey: the spreads over the runs)\n",
                        xlabel, ch->ylabel);
        for (int j = 0; j < k; j++)
            core_buf_printf(&dat, "%.5f %.6f %s %d %.5f %.5f %.6f\n", xs[j], ys[j], b->cfg[idx[j]].label, front[j],
                            b->met[idx[j]].frame_ms, exs[j], eys[j]);
        snprintf(path, sizeof path, "%s/bench_%s.dat", out, ch->name);
        if (!core_buf_write(&dat, path)) rc = 1;
        core_buf_free(&dat);
        write_chart(out, ch, ch->y == Y_IMAGE ? refs_of(b, &b->cfg[idx[0]])->floor : -1.0);
    }
    if (rc == 0) core_log_info("bench: wrote %s/bench.csv, bench.json and charts (%d configurations)", out, n);
    return rc;
}

static int run_sweep(const bench_options_t *bo, const char *out, bench_run_t *b)
{
    const world_options_t *o = &bo->world;
    const char *chart = bo->chart;
    bool quick = bo->quick;
    b->cfg = calloc(MAX_CONFIGS, sizeof *b->cfg);
    b->met = calloc(MAX_CONFIGS, sizeof *b->met);
    b->err = calloc(MAX_CONFIGS, sizeof(double));
    b->ssim_err = calloc(MAX_CONFIGS, sizeof(double));
    b->terms = calloc(MAX_CONFIGS, sizeof *b->terms);
    b->acc = calloc(MAX_CONFIGS, sizeof *b->acc);
    if (!b->cfg || !b->met || !b->err || !b->ssim_err || !b->terms || !b->acc) return 1;
    /* The canopy chart runs on its own scene unless --chart names it alone
     * (then on --scene: the lod.json of that scene) or --scene is that one. */
    bool canopy_alone = chart && strcmp(chart, "hybrid_canopy_distance") == 0;
    bool canopy_own = !canopy_alone && !(o->scene && strcmp(o->scene, CANOPY_SCENE) == 0);
    b->n = build_configs(b->cfg, quick, canopy_own ? CANOPY_SCENE : NULL);
    b->refs[0].tag = "";
    b->refs[1] = (bench_refs_t){.scene = CANOPY_SCENE, .tag = "canopy_"};
    /* Every row names its rasterizer path: hw unless the row or --raster
     * says otherwise (the scene default, auto, would pick one by timing). */
    world_options_t oh = *o;
    if (!oh.raster) oh.raster = 1 + SCENE_RASTER_HW;
    if (chart && filter_chart(chart, b)) return 2;
    if (bo->rows && filter_rows(bo->rows, b)) return 2;
    int n = b->n;
    b->frames = bo->frames_set ? bo->frames : (quick ? 8 : 120);
    int rc = 0;
    for (int r = 0; r < REF_SETS && rc == 0; r++) {
        bool used = false;
        for (int i = 0; i < n; i++) used = used || refs_of(b, &b->cfg[i]) == &b->refs[r];
        if (used) rc = make_references(&oh, b->frames, out, &b->refs[r]);
    }
    double t0 = plat_time();
    for (int i = 0; i < n && rc == 0; i++) {
        if (bo->interrupted()) {
            core_log_warn("bench: interrupted after %d of %d configurations; writing those", i, n);
            b->n = n = i;
            break;
        }
        rc = run_config(&oh, b, i, out);
        double el = plat_time() - t0;
        fprintf(stderr, "\rbench: %d/%d %-22s %-22s %8.3f ms  image %.4f  depth p95 %.4f m  (eta %.0f s)   ", i + 1, n,
                b->cfg[i].group, b->cfg[i].label, b->met[i].frame_ms, b->err[i], b->acc[i].y[Y_PEN_MAX],
                el / (i + 1) * (n - i - 1));
    }
    fputc('\n', stderr);
    for (int r = 0; r < REF_SETS; r++) {
        for (int k = 0; k < SWEEP_RUNS; k++) core_image_free(&b->refs[r].img[k]);
        core_image_free(&b->refs[r].bg);
    }
    if (rc) return rc;
    shape_deviations(b);
    snprintf(b->renderer, sizeof b->renderer, "%s", (const char *)glGetString(GL_RENDERER));
    return write_sweep(o, out, b);
}


static bool copy_file(const char *from, const char *to)
{
    char err[256];
    size_t size;
    char *data = core_fs_read(from, &size, err, sizeof err);
    if (!data) {
        core_log_error("report: %s", err);
        return false;
    }
    bool ok = core_fs_write_atomic(to, data, size);
    free(data);
    return ok;
}

/* Copies out/NAME.png and .svg into dir/images. */
static void copy_chart(const char *dir, const char *out, const char *name)
{
    char path[1200], to[1200];
    for (int e = 0; e < 2; e++) {
        snprintf(path, sizeof path, "%s/%s.%s", out, name, e ? "svg" : "png");
        snprintf(to, sizeof to, "%s/images/%s.%s", dir, name, e ? "svg" : "png");
        if (!copy_file(path, to)) core_log_warn("report: no chart %s (gnuplot missing?)", path);
    }
}

/* A table cell: `digits` decimals, or n/a for the -1 of a measure that does
 * not apply (docs/METRICS.md). */
static void cell(char out[32], double v, int digits)
{
    if (v < 0.0) snprintf(out, 32, "n/a");
    else snprintf(out, 32, "%.*f", digits, v);
}

/* What a chart's table leaves unsaid: the configurations it leaves out,
 * the scene it runs on when not the sweep's, identical accuracy. */
static void chart_notes(const bench_run_t *b, const bench_chart_t *ch, core_buf_t *r)
{
    core_buf_t out = {0};
    const bench_refs_t *R = NULL;
    for (int i = 0; i < b->n; i++) {
        const bench_config_t *c = &b->cfg[i];
        if (strcmp(c->group, ch->group) != 0) continue;
        if (!R) R = refs_of(b, c);
        if (!in_chart(ch, c)) core_buf_printf(&out, "%s%s", out.len ? ", " : "", c->label);
    }
    if (out.len)
        core_buf_printf(r, "\nLeft out: %s (inside the box: spheres inscribed in it or in its cells, cube maps whose "
                           "every edge snaps inward; over-push 0 by construction; their depth is in "
                           "blade_proxies).\n", out.data);
    if (R && R->scene)
        core_buf_printf(r, "\nOn `%s` (ground from 10 to 195 m in view; meadow.json's 40 m field ends before the "
                           "nearest canopy distance), against that scene's own references: noise floor %.4f +- %.4f "
                           "(1 - SSIM %.4f).\n", R->scene, R->floor, R->floor_spread, R->floor_ssim);
    char same[1024];
    if (identical_rows(b, ch, same, sizeof same))
        core_buf_printf(r, "\nIdentical accuracy (the measure does not answer the knob between these): %s.\n", same);
    core_buf_free(&out);
}

/* RESULTS.md's charts: each one's image (copied from out into dir/images)
 * and its table of points. */
static void report_charts(core_buf_t *r, const char *dir, const char *out, const bench_run_t *b)
{
    char path[1200];
    for (int ci = 0; ci < CHART_COUNT; ci++) {
        const bench_chart_t *ch = &charts[ci];
        snprintf(path, sizeof path, "bench_%s", ch->name);
        copy_chart(dir, out, path);
        char xlabel[160];
        knob_label(ch, xlabel, sizeof xlabel);
        core_buf_printf(r, "### %s\n\n![%s](images/bench_%s.png)\n\nx: %s.\n\n| configuration | x (ms) | "
                            "frame GPU ms | %s | image error | 1 - SSIM | pen. fraction | blade length err | "
                            "Pareto front |\n"
                            "| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n",
                        ch->name, ch->name, ch->name, xlabel, ch->ylabel);
        double xs[MAX_CONFIGS], ys[MAX_CONFIGS], exs[MAX_CONFIGS], eys[MAX_CONFIGS];
        int front[MAX_CONFIGS], idx[MAX_CONFIGS];
        int k = chart_points(b, ch, idx, xs, ys, exs, eys, front);
        for (int j = 0; j < k; j++) {
            int i = idx[j];
            const measure_metrics_t *m = &b->met[i];
            char v[5][32];
            cell(v[0], ys[j], 5);
            cell(v[1], b->err[i], 4);
            cell(v[2], b->ssim_err[i], 4);
            cell(v[3], m->penetration_fraction, 4);
            cell(v[4], m->blade_length_error, 4);
            core_buf_printf(r, "| %s | %.4f +- %.4f | %.3f | %s +- %.5f | %s | %s | %s | %s | %s |\n", b->cfg[i].label,
                            xs[j], exs[j], m->frame_ms, v[0], eys[j], v[1], v[2], v[3], v[4], front_name(front[j]));
        }
        chart_notes(b, ch, r);
        core_buf_printf(r, "\n");
    }
}

/* RESULTS.md: every chart with its numbers, the stability table, the
 * tile scaling sweeps, the comparison montage. */
static int write_report(const char *dir, const char *out, const bench_options_t *bo, const bench_run_t *b,
                        const char *stability_md, const char *scaling_md, const char *papers_md)
{
    const world_options_t *o = &bo->world;
    char path[1200], to[1200];
    snprintf(path, sizeof path, "%s/images", dir);
    if (!core_fs_mkdirs(path)) return 1;
    char size[32];
    snprintf(size, sizeof size, "%dx%d", o->width, o->height);
    core_buf_t r = {0};
    core_buf_printf(&r,
                    "# meadow results\n\n"
                    "Generated by one command (do not edit by hand):\n\n"
                    "    ./build/meadow bench --report %s --scene SCENE [--quick] [--frames N]\n\n"
                    "It runs the bench sweep, the stability suite, the tile scaling sweeps and `meadow compare`, writes the raw data "
                    "(bench.csv, bench.json, stability.csv, scaling.csv, *.dat, *.gp) to `--out` (default out/bench), and this "
                    "file with its charts and screenshots to `%s/images`. Metric definitions: docs/METRICS.md.\n\n"
                    "- this run: `meadow bench --report %s --scene %s --frames %d%s%s%s%s%s`\n"
                    "- renderer: `%s`\n- frames per configuration: %d%s\n\n",
                    dir, dir, dir, o->scene ? o->scene : "scenes/meadow.json", b->frames,
                    o->width ? " --size " : "", o->width ? size : "", bo->quick ? " --quick" : "",
                    bo->papers ? " --papers " : "", bo->papers ? bo->papers : "",
                    b->renderer[0] ? b->renderer : "?", b->frames,
                    "; every configuration runs 3 times, each with its own placement seed against the reference "
                    "of that seed: timings from the fastest run (spread: the second fastest's excess), image error "
                    "and shape deviation the mean over the runs (spread: half their range), depths and over-push "
                    "the 95th percentile over every run's frames after warm-up");
    if (strstr(b->renderer, "llvmpipe"))
        core_buf_printf(&r, "GPU times from llvmpipe are not meaningful (CPU rasteriser, timer queries are "
                            "coarse); rerun on a GPU for real timings. Accuracy columns do not depend on the "
                            "renderer.\n\n");
    core_buf_printf(&r, "## Speed vs accuracy\n\nEach chart: x = the summed GPU pass medians of the passes its "
                        "knob changes (named under the chart; the whole frame for the modes and the switch "
                        "distance), y = the measure named on the axis; the lines join the Pareto-optimal "
                        "configurations of each rasterizer path (solid: hardware, dotted: compute; a configuration "
                        "competes only with those of its own path). Image error: "
                        "the block-statistics score of docs/METRICS.md against the reference (0 = indistinguishable, "
                        "1 = one clearly visible unit); its noise floor, the reference against the reference drawn "
                        "with another placement seed (mean of 3 pairs), is %.4f +- %.4f (dashed line; 1 - SSIM of the "
                        "first pair: %.4f). A configuration leaves a front only for one that is no worse within the "
                        "two's spreads and better beyond them in x or y (eval_pareto_noise). n/a: the measure does not "
                        "apply to that mode.\n\n",
                    b->refs[0].floor, b->refs[0].floor_spread, b->refs[0].floor_ssim);
    report_charts(&r, dir, out, b);
    core_buf_printf(&r, "blade_proxies runs a 1 x 0.32 x 0.32 m box (axis aligned, as every collider: its faces "
                        "are exact in the axis-aligned cube maps at any resolution and only its edges snap to texel "
                        "borders; they lie at other fractions of a texel at 16, 32 and 64 texels, inward at 16 and "
                        "64, outward at 32), billboard_collision a ball of radius 0.3 m "
                        "whose lowest point stays 0.05 m above the ground (both on the scene's first collider's "
                        "path, or a path across the view, with the scene's characters removed); blade_proxies "
                        "compares sphere sets with the box's depth cube map (cubemap_N, N^2 texels per face, "
                        "rasterised on the CPU), billboard_collision the billboards' cube map resolution (cubeN), "
                        "mesh (subN) and spring iterations (kN). blade_proxies' depth is that of the points the "
                        "blades' collision tests (tip v2 and midpoint m, Jahrmann & Wimmer 2017 sec. 5.3) in the "
                        "exact box, the deepest per frame: the proxy's own error; the whole curve (pen. fraction) "
                        "also crosses the box between those points, alike for every proxy that fits the box. "
                        "Billboard penetration is sampled at the mesh vertices, inside its edges and at its cell "
                        "centres, for the collider only when no root of the columns a sample lies between is "
                        "inside it. billboard_springs charts the shape "
                        "deviation of the same runs from the billboards' reference (billboard_reference: the finest "
                        "cube map, the 6 x 6 mesh, 8 spring sweeps; not charted); blade_proxies_overpush the distance "
                        "from the exact box of the blades each step pushes (95th percentile).\n\n");
    core_buf_printf(&r, "## Stability: where each method breaks\n\nSmall scenes built in code "
                        "(src/stability/stability.c): 6 m heightfield, 60 blades/m^2, 6 billboards/m^2, cube maps "
                        "16^2, recover time 1 s. Screenshots show the first failing value (or the last value).\n\n%s\n",
                    stability_md ? stability_md : "(not run)\n");
    if (scaling_md) {
        copy_chart(dir, out, "scaling_field");
        copy_chart(dir, out, "scaling_active");
        core_buf_printf(&r, "## Simulation vs field size and active tiles\n\n`meadow bench --scaling` "
                            "(src/perf/perf_scaling.c): tiled blade physics (Fan et al. 2015 activation) at a fixed "
                            "active area over 1x-%dx the field area, and at a fixed field over 1-%d active tiles.\n\n"
                            "![scaling_field](images/scaling_field.png)\n\n![scaling_active](images/"
                            "scaling_active.png)\n\n%s\n",
                        bo->quick ? 16 : 64, bo->quick ? 16 : 32, scaling_md);
    }
    if (papers_md) {
        copy_chart(dir, bo->papers, "papers_leaves");
        core_buf_printf(&r, "## The papers' scenes, ablations and colliding leaves\n\n`meadow bench --papers DIR` "
                            "(src/perf/perf_papers.c).\n\n%s", papers_md);
    }
    snprintf(path, sizeof path, "%s/compare/compare.png", out);
    snprintf(to, sizeof to, "%s/images/bench_compare.jpg", dir);
    core_image_t montage = {0};
    if (core_image_load(&montage, path, 3) && core_image_write_jpg(&montage, to, 2560, 85))
        core_buf_printf(&r, "## Montage\n\n`meadow compare`: billboard, blade, hybrid and reference, with diff "
                            "heatmaps against the reference (a half-size JPEG; `compare.png` beside the run is "
                            "full size).\n\n![compare](images/bench_compare.jpg)\n");
    core_image_free(&montage);
    snprintf(path, sizeof path, "%s/RESULTS.md", dir);
    int rc = core_buf_write(&r, path) ? 0 : 1;
    core_buf_free(&r);
    if (rc == 0) core_log_info("report: wrote %s", path);
    return rc;
}

int bench_run(const bench_options_t *o)
{
    /* what stability and perf take of the program's options */
    perf_session_desc_t session = {.world = o->world, .frames = o->frames, .frames_set = o->frames_set,
                                   .interrupted = o->interrupted};
    if (o->perf || o->baseline)
        return perf_main(&(perf_options_t){.session = session, .out = o->out, .quick = o->quick, .perf = o->perf,
                                           .baseline = o->baseline, .perf_from = o->perf_from, .doc = o->doc,
                                           .force = o->force});
    char out[1024], err[1024], path[1200];
    snprintf(out, sizeof out, "%s", o->out ? o->out : "out/bench");
    if (!core_fs_check_writable_dir(out, err, sizeof err) || !core_fs_lock_dir(out, err, sizeof err)) {
        core_log_error("--out: %s", err);
        return 2;
    }
    const char *report = o->report;
    bool full = report && *report;
    bool stability = o->stability || full, scaling = o->scaling || full;
    bool sweep = (!o->stability && !o->scaling && !o->papers) || full;
    if (full && (!core_fs_mkdirs(report) || !core_fs_check_writable_dir(report, err, sizeof err))) {
        core_log_error("--report: %s", err);
        return 2;
    }
    if (!plat_init(&(plat_desc_t){.backend = PLAT_BACKEND_EGL}, err, sizeof err)) {
        core_log_error("no OpenGL 4.5 context: %s", err);
        return 1;
    }
    gfx_init();
    bench_run_t b = {0};
    core_buf_t md = {0}, scaling_md = {0}, papers_md = {0};
    perf_scaling_t sc;
    if (full) {
        snprintf(path, sizeof path, "%s/images", report);
        if (!core_fs_mkdirs(path)) core_log_warn("report: cannot create %s", path);
    }
    int rc = sweep ? run_sweep(o, out, &b) : 0;
    stability_desc_t sd = {.world = &session.world, .only_case = o->stability_case, .quick = o->quick};
    if (rc == 0 && stability) rc = stability_run(&sd, out, &md, full ? report : NULL);
    if (rc == 0 && scaling) rc = perf_scaling_run(&session, out, o->quick, &sc, &scaling_md);
    if (rc == 0 && o->papers) rc = perf_papers_run(&session, o->quick, o->papers, full ? &papers_md : NULL);
    gfx_shutdown(true);
    int gl_errors = plat_gl_error_count();
    plat_shutdown();
    if (gl_errors) {
        core_log_error("%d GL error(s) during bench", gl_errors);
        rc = rc ? rc : 1;
    }
    if (rc == 0 && full) {
        bench_options_t oc = *o;
        snprintf(path, sizeof path, "%s/compare", out);
        oc.out = path;
        if (!core_fs_mkdirs(path)) rc = 1;
        if (rc == 0) rc = bench_compare(&oc);
        if (rc == 0) rc = write_report(report, out, o, &b, md.data, scaling_md.data, papers_md.data);
    }
    core_buf_free(&papers_md);
    core_buf_free(&md);
    core_buf_free(&scaling_md);
    free(b.cfg);
    free(b.met);
    free(b.err);
    free(b.ssim_err);
    free(b.terms);
    for (int i = 0; b.acc && i < b.n; i++)
        for (int k = 0; k < SWEEP_RUNS; k++) measure_bb_pose_free(&b.acc[i].pose[k]);
    free(b.acc);
    return rc;
}

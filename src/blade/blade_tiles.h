/* blade_tiles: "simulate only what the scene needs" (Fan et al. 2015,
 * "Simulating and rendering a large-scale grass field") for the Bézier
 * blades of Jahrmann & Wimmer 2017.
 *
 * The field is a grid of square tiles (src/hybrid keeps the bookkeeping:
 * representation with hysteresis, ACTIVE / RECOVERING / IDLE, slot pool,
 * per-tile object lists), each an instance of one of a few template tiles
 * (blade_seed, Morton order) under one of the 8 symmetries of the square,
 * its roots on the heightfield or a world terrain's height function (mesh
 * terrains are rejected: use blade_gpu). On a world the grid is a window of
 * tiles that follows the camera (hybrid.h): every tile is a function of its
 * coordinates and the seed, so a tile streamed in again is the same.
 * Idle tiles have no per-blade state: they are drawn in the procedural pose
 * P(t), the equilibrium of the blade physics (eq. 3-16, eta = 0) under
 * gravity and the wind of time t. Active and recovering tiles own a slot of
 * a preallocated pool and run the Jahrmann step (tiles_physics.comp, the
 * twin of blade_physics.comp) against their tile's objects; a recovering
 * tile goes IDLE when its measured motion falls below motion_epsilon or
 * after recover_timeout. Drawing: CPU frustum test per tile, then
 * tiles_cull.comp (eq. 17-20 and the occlusion test) into a per-frame
 * buffer drawn by vertex pulling or, with desc.tessellate, one patch per
 * blade. At a representation switch a tile hands its deformation to the
 * billboards' slope cells and back (hybrid_slope.h). GPU memory: templates,
 * pool and draw buffer, independent of the field size.
 * The pose iteration, the activation bound, the drawing and the hand-over
 * with their measurements: docs/BLADES.md ("Tiled field") and
 * docs/HYBRID.md ("Simulation, hand-over, overlays").
 * Timer passes: "tiles.physics" (hand-over and seeding included),
 * "tiles.cull", "tiles.draw". */
#ifndef MEADOW_BLADE_TILES_H
#define MEADOW_BLADE_TILES_H

#include <stdbool.h>
#include <stdint.h>

#include "blade/blade.h"
#include "hybrid/hybrid.h"
#include "hybrid/hybrid_slope.h"
#include "terrain/terrain.h"

#define BLADE_TILES_MAX_TEMPLATES 8
/* Defaults the scene shares (its SCENE_DEFAULT_* of scene/scene_fields.h
 * equal these; test_scene_defaults checks): grass.tile_size (m),
 * grass.switch_distance (m), grass.recover_time (s, the hand-over's R),
 * and the motion below which a tile counts as at rest (m, not a key;
 * docs/BLADES.md). */
#define BLADE_TILES_DEFAULT_TILE_SIZE 4.0f
#define BLADE_TILES_DEFAULT_SWITCH_DISTANCE 12.0f
#define BLADE_TILES_DEFAULT_RECOVER_TIME 3.0f
#define BLADE_TILES_DEFAULT_MOTION_EPSILON 2e-3f
/* The focal length (px) the default draw buffer is sized for when the
 * cull desc names none: 2160 p at a 60 degree field of view is 1871. */
#define BLADE_TILES_CAPACITY_FOCAL 2000.0f

/* Zero means default; (scene) marks a default the scene shares
 * (BLADE_TILES_DEFAULT_* above):
 *   terrain          required, a heightfield (grid_res > 0) or a world
 *                    terrain (TERRAIN_WORLD); borrowed during make only
 *   window           tiles per side of the window that follows the camera
 *                    (hybrid_desc_t.window): 0 is the whole field on a
 *                    heightfield and, on a world, the smallest window that
 *                    holds every tile within switch_distance + 1 m of the
 *                    camera plus a tile. A window keeps the state of
 *                    recovering tiles (keep_state: no hand-over), also
 *                    away from the window (hybrid.h)
 *   tile_size        4 m (scene, grass.tile_size)
 *   template_count   4 (1..BLADE_TILES_MAX_TEMPLATES)
 *   population       the blades (blade_population.h, scene: density,
 *                    height, width, stiffness, shape); albedo and gravity
 *                    are not used here (blade_draw_desc_t and the env of
 *                    blade_tiles_update carry them)
 *   seed             0 is a valid seed (templates use seed + k)
 *   pool_slots       64 simulation slots of one template each
 *   switch_distance  12 m (scene): tiles nearer are drawn as blades (hybrid rule,
 *                    with hysteresis 1 m); far tiles are left to billboards
 *   recover_timeout  5 s; motion_epsilon 2 mm (scene, not a key;
 *                    docs/BLADES.md)
 *   winds            the procedural wind and the physics' winds; an env
 *                    passed to blade_tiles_update with wind_count > 0
 *                    replaces them from then on
 *   max_level (8 segments at the camera), lod_distance (30 m),
 *   displacement, width_correction, width_printed (0: off; eq. 23, eq.
 *                    24, eq. 24 as printed; scene, grass.displacement,
 *                    grass.width_correction): as blade_gpu_desc_t
 *   tessellate       false (default): the hardware path draws instanced
 *                    triangle strips by vertex pulling; true: GL_PATCHES
 *                    through blade.tesc / blade.tese (scene,
 *                    grass.blade_render). The debug overlays are drawn by
 *                    the pulled strips only; the compute rasterizer
 *                    (blade_tiles_raster) is the same either way
 *   cull             max_distance, orientation_threshold,
 *                    frustum_tolerance, depth_bias, disable, lod, focal_px
 *                    (blade_cull_desc_defaults; lod and focal_px change
 *                    per frame with blade_tiles_set_lod); the view comes
 *                    from the draw desc, the depth texture from the draw
 *                    call
 *   draw_capacity    blades the per-frame draw buffer holds; 0: of every
 *                    blade of every tile that can be within
 *                    switch_distance + 1 m of the camera, the share the
 *                    thinning can keep at each tile's nearest point
 *                    (cull.lod's kept share, the shrink window included,
 *                    over the population's widths at the focal length
 *                    cull.focal_px, 0: BLADE_TILES_CAPACITY_FOCAL); a
 *                    larger view drops what does not fit, counted in
 *                    stats.draw_overflow and logged)
 *   slope_cells_per_tile  slope cells per tile side: default the nearest
 *                    count to 0.5 m cells (at least 1), more where a cell
 *                    would hold more than HYBRID_SLOPE_MAX_PER_CELL blades
 *                    (an explicit count that does is an error)
 *   slope_recover    R of the hand-over (the billboards' recover time) and
 *                    how long a tile may carry deformation: default 3 s
 *                    (scene, grass.recover_time)
 *   keep_state       false (default): hand-over on; true: recovering tiles
 *                    keep their slot in any representation, nothing is
 *                    handed over (hybrid_desc_t.keep_state)
 *   label            "tiles" */
typedef struct blade_tiles_desc_t {
    const terrain_mesh_t *terrain;
    int window;
    float tile_size;
    int template_count;
    blade_population_t population;
    uint64_t seed;
    int pool_slots;
    float switch_distance;
    float recover_timeout;
    float motion_epsilon;
    blade_wind_t winds[BLADE_MAX_WINDS];
    int wind_count;
    int max_level;
    float lod_distance;
    float displacement;
    float width_correction;
    float width_printed[2];
    bool tessellate;
    blade_cull_desc_t cull;
    uint32_t draw_capacity;
    /* Optional coverage map shared with the billboards (bb_layout's extent
     * map, one channel): a blade with world id i (tile * B + k) is drawn
     * only if core_hash_u32(i ^ core_hash_u32(extent_seed ^ 0x5bd1e995)) %
     * 255 < E, E the extent byte of the texel
     * (floor((x - origin.x) / spacing) mod W, same for z): the billboards'
     * acceptance rule, so both representations share clearings. NULL: off. */
    const core_image_t *extent;
    float extent_origin[2];
    float extent_spacing;
    uint32_t extent_seed;
    int slope_cells_per_tile;
    float slope_recover;
    bool keep_state;
    const char *label;
} blade_tiles_desc_t;

typedef struct blade_tiles_stats_t {
    int tiles, idle, active, recovering;
    int blade_tiles;            /* tiles in blade representation */
    int slots_used, slots_total;
    int pool_denied;            /* tiles wanting a slot this update that got none */
    int handovers, seeded;      /* hand-overs to billboards / seedings from them, this update */
    long handovers_total, seeded_total; /* the same since make */
    long streamed_total;        /* window: tiles streamed in since make (hybrid_stats_t.streamed) */
    long detached_total, reattached_total; /* window: tiles that left it keeping their slot, and that
                                              came back to it, since make */
    int slots_dispatched;       /* slots simulated by the latest update */
    uint32_t blades_dispatched; /* physics invocations of the latest update */
    int tiles_drawn;            /* tiles passing the CPU frustum test, latest draw */
    uint32_t blades_drawn;      /* survivors of the latest cull read back (-1..2 frames late) */
    uint32_t draw_overflow;     /* survivors dropped for lack of capacity (logged) */
    uint32_t culled[4];         /* the same cull: blades culled by orientation, frustum, distance,
                                   occlusion (tiles_cull.comp, first failing test; blades of
                                   clearings included, they are dropped after the tests) */
    uint32_t tile_culled;       /* blades of the templates of blade tiles the CPU frustum test
                                   dropped (padding excluded), the same cull */
    uint32_t blades_per_template; /* padded */
    long triangles_max;         /* blades_drawn x 2 x max_level (upper bound) */
    size_t gpu_bytes;           /* buffers + textures held */
} blade_tiles_stats_t;

/* Billboards -> blades: called inside blade_tiles_update when tiles are
 * seeded, to add the deformed billboards' tilt offsets to `sums` (zeroed,
 * hybrid_slope_sum_t per cell of `grid`; bb_field_add_slopes does this). */
typedef void (*blade_tiles_slope_source_fn)(void *user, const hybrid_slope_grid_t *grid, gfx_buffer_t sums);

/* The tiled field (opaque; blade_local.h). */
typedef struct blade_tiles_t blade_tiles_t;

/* What a made field holds (blade_tiles_info). */
typedef struct blade_tiles_info_t {
    blade_tiles_desc_t desc;        /* resolved (desc.window: the window, 0 without one);
                                       desc.terrain and desc.extent are NULL */
    const hybrid_grid_t *grid;      /* the tile bookkeeping (read only; valid until destroy) */
    hybrid_slope_grid_t slope_grid; /* the slope cells of the hand-over */
    uint32_t template_blades;       /* blades per template, padded: the length of a slot */
    uint32_t template_real[BLADE_TILES_MAX_TEMPLATES]; /* blades per template, padding excluded */
    uint32_t draw_capacity;         /* blades the per-frame draw buffer holds */
    int max_draw_tiles;             /* tiles the per-frame tile list holds */
    float reach;                    /* height_max + width_max / 2: a tile's bounds grow by it */
    blade_env_t env;                /* the latest resolved env (gravity, winds) */
    float time;                     /* of the latest update (s) */
    GLuint extent_texture;          /* the desc's extent map as an R8 texture (owned by the
                                       field), 0 without one */
    GLuint ground_texture;          /* a heightfield's vertex normals and heights, RGBA32F (grid_res
                                       + 1)^2 (common/heightfield.glsl; owned by the field); 0 on a
                                       world */
    int grid_res;                   /* its cells a side */
    float field_size;               /* the heightfield's side (m), centred on the origin */
} blade_tiles_info_t;

blade_tiles_desc_t blade_tiles_desc_defaults(const blade_tiles_desc_t *desc);

/* Seeds the templates, uploads templates and ground, allocates the pool.
 * Returns NULL (one logged error, nothing held) for a mesh terrain, bad
 * sizes, or GL failure. */
blade_tiles_t *blade_tiles_make(const blade_tiles_desc_t *desc);
blade_tiles_info_t blade_tiles_info(const blade_tiles_t *t);
/* Debug overlays drawn over the tiled blades:
 *   STATE  tile state: active red, recovering yellow, idle unchanged
 *   LOD    level of detail: blue (1 segment) .. red (max_level)
 *   ETA    collision strength of simulated blades: white (0) .. red (1) */
enum { BLADE_TILES_OVERLAY_OFF = 0, BLADE_TILES_OVERLAY_STATE, BLADE_TILES_OVERLAY_LOD, BLADE_TILES_OVERLAY_ETA };
void blade_tiles_set_overlay(blade_tiles_t *t, int overlay);

/* Releases every object and t itself (NULL: nothing). */
void blade_tiles_destroy(blade_tiles_t *t);
/* The billboards' side of the billboards -> blades hand-over (NULL: only
 * the slope cells seed blades). */
void blade_tiles_set_slope_source(blade_tiles_t *t, blade_tiles_slope_source_fn fn, void *user);

/* One frame: representation from camera, activation from the spheres of
 * `colliders` (NULL: none; its objects and cube proxies are not read; any
 * number up to BLADE_MAX_SPHERES: the sphere buffer grows to hold them),
 * motion read back without stalling, slot initialisation, and one physics
 * step over the active and recovering slots (timer "tiles.physics"). env:
 * dt, time, gravity, collision and length settings (resolved with
 * blade_env_defaults). */
void blade_tiles_update(blade_tiles_t *t, const float camera[3], const collide_set_t *colliders,
                        const blade_env_t *env);

/* Culls (timer "tiles.cull") and draws (timer "tiles.draw") the blade-
 * representation tiles into the bound framebuffer; procedural pose at the
 * time of the latest update. depth_texture: a GL_TEXTURE_2D of opaque
 * window depth (single sample: gfx_target_resolve_depth's resolve_depth,
 * or raster_t.opaque_depth) for the occlusion test, 0 for none (as
 * blade_gpu_cull). Depth test on, two-sided. With a fade band
 * (desc->fade_end > fade_start) two draws: the blades rooted within
 * fade_start opaque (depth tested before shading), then the fading ones
 * with their sample mask (blade_fade_mask). Pulled strips or patches by
 * desc.tessellate. */
/* Starts building the compute programs blade_tiles_make will make for
 * tiles on `terrain` (gfx_programs_prefetch): they compile while the
 * caller goes on (on a fresh H100 the batch's wait was 0.54-0.70 s). */
void blade_tiles_prefetch(const terrain_mesh_t *terrain);
void blade_tiles_draw(blade_tiles_t *t, const blade_draw_desc_t *desc, GLuint depth_texture);
/* The same blades as blade_tiles_draw (same culling, timer "tiles.cull"),
 * drawn by the compute rasterizer (timer "tiles.raster"); between
 * raster_begin and raster_end. Debug overlays are drawn by the hardware
 * path only. False when the raster program cannot be made (logged). */
bool blade_tiles_raster(blade_tiles_t *t, raster_t *r, const blade_draw_desc_t *desc, GLuint depth_texture);
/* The culling alone (timer "tiles.cull"), read back with
 * blade_tiles_read_drawn: as blade_tiles_draw runs it (grouped false: a
 * place per blade, the blades in the order they reach the counter; split
 * at desc->fade_start when desc->fade_end is beyond it) or as
 * blade_tiles_raster does (grouped true: each workgroup's survivors placed
 * together, in order; never split). */
void blade_tiles_cull(blade_tiles_t *t, const blade_draw_desc_t *desc, GLuint depth_texture, bool grouped);

/* Statistics; blades_drawn without stalling unless wait (tests). */
/* The blades -> billboards slope hand-over the billboards draw with
 * (bb_draw_desc_t slope_map, slope_grid, slope_recover). */
void blade_tiles_slope(const blade_tiles_t *t, gfx_buffer_t *map, hybrid_slope_grid_t *grid, float *recover);
blade_tiles_stats_t blade_tiles_stats(blade_tiles_t *t, bool wait);

/* Replaces the cull settings (tests; the resolved desc.cull of
 * blade_tiles_info with changes): used from the next draw on, taken as
 * they are (no defaults); its view and depth are not read. */
void blade_tiles_set_cull(blade_tiles_t *t, const blade_cull_desc_t *cull);
/* The thinning of the next draws (cull.lod, resolved here; blade_lod.h)
 * and the frame's focal length (blade_lod_focal; 0: 1000 px). */
void blade_tiles_set_lod(blade_tiles_t *t, const blade_lod_t *lod, float focal_px);

/* The segments the hardware path draws along a blade rooted `distance`
 * from the camera (C twin of blade_lod in blade_geom.glsl): max_level at
 * the camera, falling linearly to max(max_level / 4, 1) at lod_distance
 * and beyond (the desc's defaults resolved). */
int blade_tiles_segments_at(const blade_tiles_desc_t *desc, float distance);

/* ---- test helpers (blocking) ---------------------------------------------- */
/* The template_blades blades (and eta, may be NULL) of a pool slot. */
void blade_tiles_read_slot(const blade_tiles_t *t, int slot, blade_t *out, float *eta_out);
/* The whole pool: pool_slots * template_blades blades. */
void blade_tiles_read_pool(const blade_tiles_t *t, blade_t *out);
/* Survivors of the latest cull (whole blades, count returned; out holds
 * draw_capacity): the solid blades, then those of a split cull's fade list;
 * ids (may be NULL) receives tile * template_blades + blade per survivor. */
uint32_t blade_tiles_read_drawn(const blade_tiles_t *t, blade_t *out, uint32_t *ids);
/* The sphere proxies the latest update's physics read (its buffer, as the
 * GPU holds it): writes at most max and returns their count. */
int blade_tiles_read_spheres(const blade_tiles_t *t, blade_sphere_t *out, int max);
/* The slope cells (slope_grid.nx * slope_grid.nz). */
void blade_tiles_read_slopes(const blade_tiles_t *t, hybrid_slope_cell_t *out);
/* Replaces the slope cells (slope_grid.nx * slope_grid.nz); zeroed cells
 * draw the billboards as without the hand-over. */
void blade_tiles_write_slopes(blade_tiles_t *t, const hybrid_slope_cell_t *cells);
/* The tile list of the latest cull as the GPU read it, nearest first:
 * (tile, slot or 0xffffffff) per listed tile; returns the count (out holds
 * 2 * max_draw_tiles). */
int blade_tiles_read_tile_list(const blade_tiles_t *t, uint32_t *out);
/* The template_blades blades of template `index` as seeded (tile-local;
 * from the CPU copy, no GL). */
void blade_tiles_read_template(const blade_tiles_t *t, int index, blade_t *out);
/* The tile owning a pool slot, -1 when free. */
int blade_tiles_slot_owner(const blade_tiles_t *t, int slot);
/* Latest motion per slot as read back (m). */
float blade_tiles_slot_motion(const blade_tiles_t *t, int slot);
/* CPU twin of the GPU root placement: world root and up of template blade
 * `b` (as seeded, tile-local) in tile `tile`. */
void blade_tiles_root(const blade_tiles_t *t, int tile, const float local_xz[2], float root[3], float up[3]);
/* CPU twin of tiles_pose(tiles_rest(tile, k)) at the time of the latest
 * update: template blade k of tile `tile` in the procedural pose. */
void blade_tiles_pose(const blade_tiles_t *t, int tile, uint32_t k, blade_t *out);
/* The template (0..template_count-1) and symmetry (0..7) of a tile. */
void blade_tiles_instance(const blade_tiles_t *t, int tile, int *template_index, int *symmetry);
/* GPU bytes a field would hold (what stats.gpu_bytes reports), without
 * making it: for the memory comparison with blade_gpu. */
size_t blade_tiles_estimate_bytes(const blade_tiles_desc_t *desc, uint32_t *template_blades_out);

#endif

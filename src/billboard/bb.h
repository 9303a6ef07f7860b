/* bb: the GPU half of the responsive billboard grass of Orthmann,
 * Rezk-Salama & Kolb 2009 ("GPU-based Responsive Grass") on OpenGL 4.5.
 *
 *   make:    layout textures + clump texture array (bb_layout), then a
 *            geometry shader that runs once per tile of candidate cells and
 *            emits one point per billboard (bb_generate.geom), captured with
 *            transform feedback into ONE buffer ordered by octree leaf.
 *   update:  CPU broad phase (bb_octree_update on the objects' bounding
 *            spheres); for COLLIDING leaves only: depth cube maps of the
 *            objects (eq. 1-3 lookups), the collision geometry shader
 *            bb_collide.geom (push-out eq. 4-5, springs eq. 6-7) with
 *            transform feedback in and out, in batches of leaves that each
 *            see at most BB_PASS_OBJECTS objects; for COLLIDING and
 *            RECOVERING leaves: the recovery compute pass bb_recover.comp
 *            (eq. 8). Idle leaves cost nothing.
 *   draw:    frustum-culled octree leaves, nearest first: the plain quads
 *            of idle leaves by vertex pulling with no geometry shader
 *            (bb_quad.vert), the other leaves' wind-animated quads and
 *            deformed N x M meshes by bb_render.geom; coverage written as
 *            the sample mask, two-sided lighting, distance fades.
 *
 * Heightfields and mesh terrains (candidates per triangle), the pool of
 * deformed meshes (desc.max_deformed slots, the slot index in
 * bb_point_t.pad[0]) and every departure with its measurement:
 * docs/BILLBOARDS.md. */
#ifndef MEADOW_BB_H
#define MEADOW_BB_H

#include <stdbool.h>
#include <stdint.h>

#include "grass_view/grass_view.h"
#include "billboard/bb_layout.h"
#include "billboard/bb_octree.h"
#include "billboard/bb_ref.h"
#include "blade/blade_lod.h"
#include "collide/collide_set.h"
#include "core/core.h"
#include "gfx/gfx.h"
#include "gi/gi.h"
#include "raster/raster.h"
#include "hybrid/hybrid_slope.h"
#include "billboard/bb_defaults.h"
#include "terrain/terrain.h"

/* Objects one field can collide against per update (desc.max_objects; the
 * cube-map array holds 6 layers for each). */
#define BB_MAX_OBJECTS COLLIDE_MAX_OBJECTS
/* Objects one collide pass (bb_collide.geom) tests. bb_field_update groups
 * the colliding leaves into batches whose objects number at most this; a
 * leaf that overlaps more is split into runs of billboards, and a single
 * billboard whose bounding sphere meets more keeps the nearest ones
 * (counted in bb_stats_t.objects_dropped, warned once). */
#define BB_PASS_OBJECTS 16
/* bb_point_t.pad[0] of a billboard without a deformed mesh (else its slot
 * in the pool, below desc.max_deformed). */
#define BB_NO_SLOT 0xffffffffu

/* The field (bb_local.h): GPU buffers, octree, programs; made, updated,
 * drawn and read only through the functions below. */
typedef struct bb_field_t bb_field_t;

typedef struct bb_field_desc_t {
    const terrain_mesh_t *terrain; /* required; only read during make. A world terrain
                                      (TERRAIN_WORLD) makes the ring instead of the
                                      octree's field (bb_ring.h, docs/WORLD.md) */
    uint32_t seed;                 /* any value (0 included) */
    uint32_t placement_seed;       /* seeds the generation rule (where billboards stand)
                                      instead of `seed` when non-zero; the layout
                                      textures (clearings, clumps) keep `seed` */
    /* Defaults marked (scene) are BB_DEFAULT_* of bb_defaults.h, which the
     * scene keys in brackets share. */
    float density;                 /* candidate billboards per m^2 (the extent map
                                      accepts a fraction), default 6 (scene,
                                      grass.billboard_density) */
    float size[2];                 /* base width, height in m, default 1.0 x 0.6
                                      (scene, grass.billboard_size) */
    int subdiv[2];                 /* refined mesh N columns x M rows, default 4 x 4
                                      (scene, grass.subdiv), each in [BB_SUBDIV_MIN,
                                      BB_SUBDIV_MAX] = [2, 8], limited by the GPU's
                                      geometry shader output (checked, logged) */
    bool occlusion;                /* occlusion culling of leaf batches (bb_occlude.c;
                                      scene, grass.bb_occlusion); default off */
    bool gi;                       /* per-vertex global illumination compiled in
                                   (BB_GI; scene, grass.gi): 6 more geometry-shader
                                   output components per vertex; lit once a draw
                                   desc's gi is on */
    int iterations;                /* spring sweeps K, default 2 (scene,
                                      grass.spring_iterations) */
    float r1, r2;                  /* spring responsiveness, default 1.0, 0.5 */
    bool paper;                    /* the paper's collision as printed
                                      (bb_collide_desc_t.paper), default false;
                                      may change between updates */
    int cube_res;                  /* depth cube map side in texels, default 32 (scene,
                                      grass.cube_resolution); the
                                      array takes 6 * max_objects * res^2 * 16 bytes
                                      (128 objects at 32: 12 MiB) */
    float recover_time;            /* seconds to recover, default 3 (scene,
                                      grass.recover_time) */
    int max_objects;               /* objects per update, default 8, at most
                                      BB_MAX_OBJECTS */
    int max_deformed;              /* deformed-mesh pool slots, default 4096 */
    int octree_depth;              /* default 4, at most BB_OCTREE_MAX_DEPTH */
    float ring_reach;              /* world terrains: billboards held out to this distance
                                      from the camera (m), default BB_RING_REACH_DEFAULT 64 */
    float ring_cell;               /* world terrains: ring cell side (m), rounded to whole
                                      generation tiles of candidates, default
                                      BB_RING_CELL_DEFAULT 8 */
    bb_wind_desc_t wind;           /* see bb_wind_desc_defaults */
    bb_layout_desc_t layout;       /* layout textures; its seed is replaced by `seed`, its
                                      clump.size defaults to `size` (the clump blades:
                                      bb_layout.h) */
} bb_field_desc_t;
bb_field_desc_t bb_field_desc_defaults(const bb_field_desc_t *desc);

typedef struct bb_draw_desc_t {
    grass_view_t view;    /* the frame's view (planes: the frustum the octree culls by) */
    float fade_start;    /* invisible nearer than this (0 = fade off) */
    float fade_end;      /* fully visible beyond this */
    float far_start;     /* the canopy's fade: fully visible nearer than this, */
    float far_end;       /* none beyond this, nor drawn (0 = off) */
    int overlay;         /* 1: tint colliding (red) and recovering (yellow) billboards */
    /* Slope cells handed over by blades (hybrid_slope.h), drawn on plain
     * billboards: a buffer of hybrid_slope_cell_t per cell of slope_grid
     * (slope_map.id 0: off), slope_recover R (0: desc.recover_time). */
    gfx_buffer_t slope_map;
    hybrid_slope_grid_t slope_grid;
    float slope_recover;
    gi_bind_t gi;        /* global illumination (common/gi.glsl); zero: off; read only
                            by a field made with desc.gi */
    const blade_lod_t *lod; /* the cards thinned with distance by this rule, the
                               kept ones widened (bb_lod.h; scene, grass.bb_lod
                               with grass.lod); NULL: off, every card drawn */
    float focal_px;      /* with lod: pixels per unit tangent (blade_lod_focal) */
} bb_draw_desc_t;

/* Stages of bb_field_make, timed with a wall clock: layout textures (CPU)
 * and their upload, shader programs (compile and link), the GPU generation
 * pass with its count readback and the node-range check, and the read-back
 * of the bounding spheres. */
enum { BB_MAKE_LAYOUT, BB_MAKE_PROGRAMS, BB_MAKE_GENERATE, BB_MAKE_SPHERES, BB_MAKE_STAGES };
const char *bb_make_stage_name(int stage);

typedef struct bb_stats_t {
    int billboards;
    int leaves[3];        /* non-empty leaves per BB_NODE_* state */
    int deformed;         /* pool slots in use (see bb_field_stats: exact or late) */
    int pool_capacity;
    int pool_exhausted;   /* allocations refused so far */
    int batches;          /* collide passes (object batches) of the last update */
    int objects_dropped;  /* object hits left out so far: billboards whose
                             bounding sphere met more than BB_PASS_OBJECTS
                             objects, summed over the excess objects */
    int objects_hidden;   /* objects of the last update left out because they
                             cannot reach a drawn billboard (bb_field_set_hidden) */
    float generate_ms;    /* GPU time of the make-time generation pass: two
                             GL_TIMESTAMP queries around it; -1 when the GPU
                             has no timestamp counter */
    int occluded;         /* leaves the last draw skipped as occluded (desc.occlusion) */
    long triangles;       /* drawn per frame at most: 2 per plain billboard, the
                             mesh's 2 (N-1)(M-1) per deformed one */
    float make_ms;        /* CPU wall time of bb_field_make (ends after the
                             generation results were read back) */
    float make_stage_ms[BB_MAKE_STAGES]; /* make_ms split by stage (wall
                             clock, see bb_make_stage_name) */
    int occlusion_hidden; /* leaves whose latest occlusion query passed no
                             sample (desc.occlusion; skipped by the next draw) */
} bb_stats_t;

/* What a field holds, for callers that size arrays or rebuild poses on the
 * CPU (tests, the bench's metrics). `tree` points into the field: read
 * only, valid until bb_field_destroy; its leaves' node ranges index the
 * points buffer (bb_field_read). */
typedef struct bb_field_info_t {
    bb_field_desc_t desc;      /* resolved (bb_field_desc_defaults) */
    bb_gen_desc_t gen;         /* the generation rule (spacing, origin, seed, layers) */
    int billboards;            /* valid points, leaf-ordered */
    int capacity;              /* points the buffer holds (an upper bound on billboards) */
    int cells[2];              /* heightfields: candidate cells along x, z (0 on meshes) */
    int triangles;             /* mesh terrains: triangles that seed billboards (0 on heightfields) */
    int mesh_vertices;         /* desc.subdiv[0] * desc.subdiv[1]: vec4 per deformed mesh */
    float sphere_max;          /* the largest billboard bounding-sphere radius */
    float time;                /* of the latest bb_field_update (wind pose) */
    int ring_side, ring_cand;  /* world terrains: W cells per side of the ring, K candidates
                                  per cell side (slot s holds points [s K^2, (s+1) K^2),
                                  all valid, dead candidates of size 0); 0 otherwise */
    long ring_generated;       /* world terrains: cells generated so far */
    uint32_t extent_texture;   /* the layout's extent map (GL texture, the field's) */
    const bb_octree_t *tree;
} bb_field_info_t;

/* The field's GPU data bb_field_read copies, in elements of: */
typedef enum bb_data_t {
    BB_DATA_POINTS, /* bb_point_t; [0, info.billboards) valid */
    BB_DATA_MESHES, /* one deformed mesh: info.mesh_vertices float[4] (world
                       space, row-major N x M), slot s for a point whose
                       pad[0] is s; [0, desc.max_deformed) */
    BB_DATA_POOL,   /* uint32_t: free top, exhausted count, 2 pad, then the
                       free stack; [0, 4 + desc.max_deformed) */
    BB_DATA_CUBES   /* one cube-map layer: desc.cube_res^2 float[4] (RGBA32F);
                       object k's faces are layers 6k .. 6k+5;
                       [0, 6 * desc.max_objects) */
} bb_data_t;

/* NULL when the field cannot be made (logged: desc out of range, the GPU's
 * limits, out of memory, generation overflow). On a world terrain the
 * field is the ring of cells around the camera (bb_ring.h): no octree, no
 * cells until the first follow; its update collides with the held
 * cells (the slots stand in for the octree's leaves), its draws follow
 * their camera first. */
bb_field_t *bb_field_make(const bb_field_desc_t *desc);
/* Frees the field and its GL objects; NULL is ignored. */
void bb_field_destroy(bb_field_t *f);
void bb_field_info(const bb_field_t *f, bb_field_info_t *out);
/* Copies elements [first, first + count) of `what` into out (blocking:
 * gfx_buffer_read's staging copy, never a direct read of a buffer the
 * passes use; tests and the bench's metrics, not per frame). False, out
 * untouched, when the range lies outside the data or the copy fails. */
bool bb_field_read(const bb_field_t *f, bb_data_t what, size_t first, size_t count, void *out);
/* Broad phase, cube maps, collision, recovery (timers "bb.cubemaps",
 * "bb.collide", "bb.recover") against the objects of `colliders` (NULL:
 * none; at most desc.max_objects, assert; its spheres and cube proxies are
 * not read).
 * An object's cube map covers the cube [centre - radius, centre + radius]^3
 * of its object space ("cube space" = object space) and is drawn from its
 * mesh (vao), or, for vao 0, is the CPU cube map given to bb_field_set_cube
 * for that object index (CPU-rasterised proxies, tests). The
 * colliding leaves are grouped greedily (Morton order) into batches whose
 * objects number at most BB_PASS_OBJECTS; a leaf whose margin-grown box
 * meets more is split into runs of billboards by their bounding spheres.
 * All batches' object entries are uploaded at once (one aligned region
 * each) and drawn in one transform feedback, each batch with its own
 * range of the buffer bound. Never
 * waits for the GPU: after GPU work the pool header is copied into a
 * readback slot followed by a timestamp query, and later updates read the
 * slots whose query is available (typically one or two updates late); pool
 * exhaustion is logged from those copies. */
void bb_field_update(bb_field_t *f, const collide_set_t *colliders, float time, float dt);
/* Billboards nearer to `camera` than `fade_start` are not drawn (the
 * hybrid's blade region: bb_draw_desc_t.fade_start). From the next
 * bb_field_update on, an object whose bound lies within fade_start minus
 * three of the largest billboard bounding spheres of `camera` cannot reach
 * a drawn billboard: it is left out of the broad phase, the cube maps and
 * the narrow phase (counted in bb_stats_t.objects_hidden). The blade tiles
 * simulate there and hand their state to the billboards when they switch
 * (hybrid.h). fade_start <= 0: every object collides (the default). The
 * hybrid calls it with the camera of its last draw. */
void bb_field_set_hidden(bb_field_t *f, const float camera[3], float fade_start);
/* Draws into the bound framebuffer (MSAA expected for alpha-to-coverage);
 * timer "bb.render". With desc.occlusion, leaves whose box was hidden at
 * their latest query are skipped, and the boxes of the leaves in the
 * frustum are queried after the draw (timer "bb.occlusion"). */
void bb_field_draw(bb_field_t *f, const bb_draw_desc_t *d);
/* The same billboards as bb_field_draw, drawn by the compute rasterizer
 * (timer "bb.raster"): every billboard is tested against the frustum on
 * the GPU (no octree walk), coverage comes from r's samples instead
 * of alpha-to-coverage. Between raster_begin and raster_end. False when
 * the raster program cannot be made (logged). */
bool bb_field_raster(bb_field_t *f, raster_t *r, const bb_draw_desc_t *d);
/* Starts building the programs bb_field_make(desc) will make
 * (gfx_programs_prefetch), the ring's on world terrains, and with raster
 * non-NULL bb_field_raster's for a raster_t from it, so they compile while
 * the caller goes on (on a fresh H100 bb.collide alone takes 0.7 s).
 * Nothing when the desc is out of range (bb_field_make says why). */
void bb_field_prefetch(const bb_field_desc_t *desc, const raster_desc_t *raster);
/* World terrains: centres the ring on `camera`, generating the cells that
 * enter it into the slots of those that left (timer "bb.ring", counter
 * "bb.ring_cells"); bb_field_draw and bb_field_raster call it with their
 * camera. Nothing on other terrains. */
void bb_field_follow(bb_field_t *f, const float camera[3]);
/* World terrains: the slot holding ring cell `cell` (bb_ring.h), -1 when
 * the ring does not hold it (or the field is not a ring). */
int bb_field_ring_slot(const bb_field_t *f, const int32_t cell[2]);
/* wait: reads the pool header now (blocks until the last update finished;
 * exact, for tests). !wait: pool numbers from the newest readback that
 * already reached the CPU (no stall, a few updates late; HUDs). */
void bb_field_stats(const bb_field_t *f, bool wait, bb_stats_t *out);

/* Billboards -> blades hand-over (hybrid_slope.h): adds the tilt offset of
 * every deformed billboard (top row centre against the wind pose of the
 * latest update's time) to `sums` (hybrid_slope_sum_t per cell of g). Fits
 * blade_tiles_slope_source_fn through a one-line adapter. */
void bb_field_add_slopes(bb_field_t *f, const hybrid_slope_grid_t *g, gfx_buffer_t sums);

/* Uploads a CPU cube map for object index `object` (used when that object's
 * vao is 0). res must equal desc.cube_res. */
void bb_field_set_cube(bb_field_t *f, int object, const collide_cubemap_t *cube);
/* Lends the field's cube maps to the blades (beyond both papers): appends to
 * colliders->cubes the cube proxy of every object of `colliders` (the set
 * of the latest bb_field_update, in order, at most COLLIDE_MAX_CUBES; proxy
 * k reads layers 6k .. 6k+5, so the set must start with cube_count 0), a
 * skipped proxy (all zero) for an object whose cube map no update has
 * rendered, and names the field's cube array as colliders->cube_texture /
 * cube_res. A character's map keeps the pose of its last render. */
void bb_field_lend_cubes(const bb_field_t *f, collide_set_t *colliders);
/* The quad frame of a billboard (twin of bb_frame in
 * shaders/billboard/bb_points.glsl): up = growth, right = the horizontal
 * direction (cos angle, 0, sin angle) made orthogonal to up, or
 * (-sin angle, 0, cos angle) when up is (nearly) along the first. */
void bb_point_frame(const bb_point_t *p, vec3 right, vec3 up);

#endif

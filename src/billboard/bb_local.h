/* bb_local: the billboard field's state and the functions its files share
 * (private to src/billboard/). The field is split by stage of its life:
 *   bb.c           desc defaults, make (limits, programs, buffers), destroy,
 *                  the read APIs (info, read, stats), shared uniform helpers
 *   bb_generate.c  make's layout and height textures and the generation pass
 *                  into the leaf-ordered points buffer, the bounding spheres
 *   bb_update.c    bb_field_update: cube maps, collide, recover, the pool
 *                  readback; hidden objects; cube maps lent to the blades
 *   bb_batch.c     the collide batches (BB_PASS_OBJECTS) and their pass
 *   bb_draw.c      bb_field_draw, bb_field_raster, bb_field_add_slopes
 *   bb_occlude.c   occlusion culling of leaf batches
 *   bb_ring.c      world terrains: the ring of cells streamed around the
 *                  camera (bb_ring.h) instead of the octree's field
 * Callers see only bb.h. */
#ifndef MEADOW_BB_LOCAL_H
#define MEADOW_BB_LOCAL_H

#include "billboard/bb.h"
#include "billboard/bb_lod.h"
#include "billboard/bb_ring.h"
#include "blade/blade.h"
#include "common/bindings_billboard.glsl"
#include "common/bindings_hybrid.glsl"

/* Pool-header readbacks in flight (see bb_field_update): the CPU reads a
 * copy once its timestamp query is available, never waiting on the GPU. */
#define BB_READBACK_SLOTS 3

/* std140 twin of struct bb_object in bb_collide.geom. */
typedef struct bb_object_gpu_t {
    float w2c[16];
    float c2w[16];
    float cube[4];
    float sphere[4];
    int32_t layer[4]; /* first cube-array layer (6 * object index), 3 pad */
    float sweep[4];   /* previous - current world position (swept collision), 0 pad */
} bb_object_gpu_t;

/* Object batches of one collide update (see BB_PASS_OBJECTS): batch b draws
 * the ranges [range_start[b], range_start[b+1]) of first/count and tests
 * objects obj[b][0..obj_count[b]) (global indices, ascending). Capacities
 * grow on demand. */
typedef struct bb_batch_plan_t {
    int count, cap, range_count, range_cap;
    int *range_start;              /* cap + 1 */
    int *obj_count;                /* cap */
    int (*obj)[BB_PASS_OBJECTS];   /* cap */
    GLint *first;                  /* range_cap */
    GLsizei *size;                 /* range_cap */
} bb_batch_plan_t;

struct bb_field_t {
    bb_field_desc_t desc; /* resolved */
    bb_octree_t tree;
    bb_gen_desc_t gen;
    int cells[2];          /* heightfields: candidate cells along x, z (0 on mesh terrains) */
    int triangles;         /* mesh terrains: triangles that seed billboards
                              (bb_gen_tri_make; 0 on heightfields) */
    int billboards;
    int capacity;          /* points buffer size in billboards (upper bound) */
    gfx_texture_t extent, direction, messiness, clumps, heights;
    bb_view_desc_t views;  /* the clump array's views (bb_view.h): the V L albedo layers,
                              then (views on) their V L light layers */
    size_t clump_bytes;    /* the clump array with its mipmaps */
    float hgrid[5];        /* heights: first vertex (x, z), clamp bound (x, z), cell */
    gfx_texture_t cubes;   /* RGBA32F 2D array, 6 layers per object */
    gfx_layered_target_t cube_target; /* over `cubes`: each object's faces in one draw */
    gfx_buffer_t points;   /* capacity bb_point_t, leaf-ordered; first `billboards` valid */
    gfx_buffer_t scratch;  /* transform-feedback target of the collide/recover passes */
    gfx_buffer_t pool;     /* int free_top, uint exhausted, 2 pad, uint free_stack[max_deformed] */
    gfx_buffer_t meshes;   /* max_deformed * N*M vec4, world space */
    gfx_buffer_t objects, counts;
    GLuint points_vao, empty_vao, tf;
    gfx_program_t gen_prog, collide_prog, recover_prog, render_prog, quad_prog, cube_prog, slope_prog;
    char defines[256];          /* the programs' mesh size and limits */
    raster_program_t raster_prog; /* made on the first bb_field_raster */
    bool programs_failed;         /* render_prog and quad_prog, made on the first bb_field_draw, did not build */
    bb_range_t *ranges;    /* leaf_count scratch */
    bb_range_key_t *sort_keys; /* leaf_count scratch of bb_octree_sort_near_first */
    GLint *firsts;
    GLsizei *counts_gl;
    uint32_t *recover_ranges;      /* leaf_count x (first, count, first thread, 0) */
    gfx_buffer_t recover_range_buf; /* the same, for bb_recover.comp */
    float cube_half[BB_MAX_OBJECTS], cube_centre[BB_MAX_OBJECTS][3];
    /* Collide batches: each billboard's bounding sphere (centre, radius, as
     * bb_collide.geom computes it) read back once after generation, for
     * splitting leaves that overlap more than BB_PASS_OBJECTS objects; the
     * batch plan of one update (draw ranges, per-batch object lists) and the
     * objects uniform buffer, one aligned region of BB_PASS_OBJECTS entries
     * per batch (grown on demand). */
    float (*spheres)[4];
    float sphere_max;      /* the largest of their radii */
    float hidden[4];       /* bb_field_set_hidden: camera, fade start (0: off) */
    int hidden_last;       /* objects left out by it in the last update */
    bb_batch_plan_t plan;
    size_t objects_stride, objects_size;
    int batches_last, dropped, dropped_logged;
    /* Pool header copies (16 bytes each), BB_READBACK_SLOTS deep. */
    gfx_readback_t readback;
    int deformed_last, exhausted_last; /* newest pool header that reached the CPU */
    int exhausted_logged;              /* refused count of the last warning */
    float generate_ms, make_ms;
    float make_stage_ms[BB_MAKE_STAGES];
    float time;
    /* Occlusion culling (desc.occlusion, bb_occlude.c): per leaf its query
     * (made on first use), BB_OCC_* state and the draw it was last queried
     * in; the leaves of this draw to query; leaves skipped by this and by
     * the last draw; draws so far. */
    GLuint *occ_query;
    uint8_t *occ_state;
    uint32_t *occ_frame;
    uint32_t *occ_tested;
    int occ_tested_count, occ_skipped, occluded_last;
    uint32_t occ_draws;
    gfx_program_t occlude_prog;
    /* World terrains (bb_ring.c): the window of cells, each slot's K^2
     * points at slot * K^2 of `points` (capacity W^2 K^2, every one valid:
     * dead candidates are points of size 0); the world square's
     * candidate cells and far corner, the height range of
     * the billboards (for the per-cell culling), cells generated so far,
     * and follow's scratch (W^2 slots, cells and dropped flags). */
    bool ring_on;
    bb_ring_window_t ring;
    int ring_cells[2];
    float ring_max[2], ring_y[2];
    long ring_generated;
    int *ring_slots;
    int32_t (*ring_coords)[2];
    bool *ring_dropped;
    /* The ring's collision: slots one collide pass takes at most (the
     * scratch's size), slots left out of a pass so far (warned once), and
     * the pass that frees a leaving cell's deformed meshes. */
    int ring_collide_slots;
    long ring_skipped;
    int ring_released;
    gfx_program_t release_prog;
};

/* Occlusion query state of a leaf: a query is in flight; its latest result
 * passed no sample. */
enum { BB_OCC_PENDING = 1, BB_OCC_HIDDEN = 2 };

/* bb.c: the transform-feedback varyings of every pass that writes points
 * (bb_point_t's layout). */
extern const char *const bb_tf_varyings[];
/* bb.c: the wind's uniforms, objects per collide pass (the shaders'
 * BB_MAX_CUBES), billboards in draw ranges (work counters), and the merge
 * of f->ranges[0..count) adjacent in the buffer into f->firsts /
 * f->counts_gl (returns how many). */
void bb_set_wind(GLuint prog, const bb_wind_desc_t *w);
int bb_pass_objects(const bb_field_t *f);
double bb_range_total(const GLsizei *size, int n);
int bb_merge_ranges(bb_field_t *f, int count);

/* bb_draw.c: a render program's uniforms (view, fade bands, wind, cards,
 * slope map, GI) for draw desc dd. */
void bb_render_uniforms(const bb_field_t *f, gfx_program_t p, const bb_draw_desc_t *dd);

/* bb_ring.c: make's ring (window, capacity, program; false when it
 * fails, logged), the follow of a camera (generation of the slots whose
 * cell changed), the draw ranges of the ring's cells dd shows (merged into
 * f->firsts / f->counts_gl, in billboards; returns how many), and the
 * ring's share of bb_field_destroy. */
bool bb_ring_make(bb_field_t *f, int tile);
void bb_ring_follow(bb_field_t *f, const float camera[3]);
int bb_ring_ranges(bb_field_t *f, const bb_draw_desc_t *dd, uint32_t state_mask);
/* bb_ring.c: a field's defines with the world's height function
 * (BB_GROUND_WORLD; its uniforms: gfx_world_height_uniforms) into buf; the
 * held slots in state_mask (BB_NODE_MASK bits) as ranges in f->ranges
 * (COLLIDING alone: at most f->ring_collide_slots), returns how many. */
bool bb_ring_defines(const char *field_defines, char *buf, size_t size);
/* Starts building bb_ring_make's programs for a field's defines
 * (gfx_programs_prefetch). */
void bb_ring_prefetch(const char *field_defines);
int bb_ring_collect(bb_field_t *f, uint32_t state_mask);
void bb_ring_destroy(bb_field_t *f);

/* bb_generate.c: the height grid's uniforms and texture (BB_TEX_HEIGHTS); and
 * make's stages (each false when it fails, logged): the layout textures
 * and clump array; the height grid; mesh terrains' triangle
 * frames (NULL when out of memory; *seeding triangles holding *cells
 * candidates); the generation pass in tiles of tile x tile cells (tris NULL
 * on heightfields); each billboard's bounding sphere read back. */
void bb_set_heights(const bb_field_t *f, gfx_program_t p);
/* bb_generate.c: binds the generation program (f->gen_prog) with the rule's
 * uniforms (u_gen) and the layout maps. */
void bb_set_gen(const bb_field_t *f);
bool bb_upload_layout(bb_field_t *f);
bool bb_upload_heights(bb_field_t *f, const terrain_mesh_t *t);
bb_gen_tri_t *bb_mesh_tris(const terrain_mesh_t *t, float spacing, int *seeding, double *cells);
bool bb_generate(bb_field_t *f, const terrain_mesh_t *t, const bb_gen_tri_t *tris, int tile);
bool bb_read_spheres(bb_field_t *f);

/* bb_batch.c: groups the colliding leaf ranges f->ranges[0..ncol) into
 * f->plan, batches of at most bb_pass_objects(f) objects (need[k] set for
 * every object in a batch); uploads the batches' entries of gpu and runs
 * the collide pass over them. */
bool bb_plan_batches(bb_field_t *f, int ncol, const bb_bound_t *bounds, int count, bool *need);
bool bb_collide_batches(bb_field_t *f, const bb_object_gpu_t *gpu);

/* bb_occlude.c: occlusion culling's state; ranges of leaves in the frustum
 * less those hidden (returns how many are kept, in order; records the
 * leaves to query); the queries after the draw; leaves now hidden. */
bool bb_occlusion_make(bb_field_t *f);
void bb_occlusion_destroy(bb_field_t *f);
int bb_occlusion_filter(bb_field_t *f, bb_range_t *ranges, int n, const float camera[3]);
void bb_occlusion_query(bb_field_t *f, const bb_draw_desc_t *dd);
int bb_occlusion_hidden(const bb_field_t *f);

#endif

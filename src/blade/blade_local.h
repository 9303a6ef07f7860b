/* blade_local: the bodies of the blade module's GPU objects (blade_gpu_t,
 * blade_tiles_t) and the helpers blade.c and blade_tiles.c share. Included
 * by the .c files of src/blade only; everything else goes through blade.h and
 * blade_tiles.h (make, info, stats, the read functions). */
#ifndef MEADOW_BLADE_LOCAL_H
#define MEADOW_BLADE_LOCAL_H

#include "blade/blade.h"
#include "blade/blade_tiles.h"
#include "common/bindings_blade.glsl"
#include "common/bindings_hybrid.glsl"

#define BLADE_GPU_READBACK_SLOTS 3
#define BLADE_TILES_READBACK_SLOTS 4
/* Spheres the physics' sphere buffers hold at make time; a step with more
 * doubles them (blade_sphere_buffer_fit), up to BLADE_MAX_SPHERES. */
#define BLADE_SPHERES_FIRST 512

struct blade_gpu_t {
    blade_gpu_desc_t desc; /* resolved; desc.field is NULL after make */
    uint32_t blade_count, padded_count, patch_count, patch_size;
    uint32_t thinned; /* blade_gpu_info_t.thinned */
    gfx_buffer_t blades, eta, winds, spheres, survivors, command;
    int sphere_capacity; /* spheres the sphere buffer holds (blade_sphere_buffer_fit) */
    int sphere_count;    /* spheres the latest update put in it */
    gfx_buffer_t counters; /* blade_patch.glsl's Counters: per-test counts, patch test, dispatch, buckets */
    gfx_buffer_t patches, patch_boxes, patch_keys; /* the patch test's list, boxes (made once), keys */
    raster_program_t raster; /* made on the first blade_gpu_raster */
    gfx_buffer_t cube_objects; /* BLADE_MAX_CUBES collide_cube_proxy_t */
    gfx_texture_t own_cubes;   /* made by blade_gpu_upload_cubes */
    gfx_readback_t readback;   /* the counters' first 6 words, then the command */
    blade_gpu_stats_t stats;
    gfx_program_t physics, physics_cubes, cull; /* physics_cubes: with cube proxies */
    gfx_program_t patch_cull, patch_list;       /* the patch test (blade_patch_*.comp) */
    gfx_program_t draw, draw_fade;              /* the path's: opaque, and with the hybrid fade */
    GLuint vao;
    bool culled_once;
};

struct blade_tiles_t {
    blade_tiles_desc_t desc; /* resolved; desc.terrain and desc.extent are NULL after make */
    hybrid_grid_t grid;
    float field_min[2], field_size; /* heightfield square */
    int grid_res;
    int tile_offset[2];             /* world tile coordinates of field tile (0, 0) (template hash) */
    bool world;                     /* the ground is a world terrain's function (no ground texture) */
    terrain_world_t world_fn;       /* its parameters (CPU twin of the ground) */
    char defines[64];               /* the programs' #defines: TILES_WORLD on a world */
    uint32_t *slot_epoch;           /* per slot: the owner's epoch when the slot was initialised */
    uint8_t *away_mark;             /* per slot: kept by a tile away from the window (this update) */
    uint32_t *motion_epoch[BLADE_TILES_READBACK_SLOTS]; /* the owners' epochs at copy time */
    float reach;                    /* height_max + width_max / 2 */
    uint32_t template_blades;       /* padded blades per template */
    uint32_t draw_capacity;
    int *slot_owner;                /* tile per slot, -1 free */
    float *tile_motion;             /* per tile, for hybrid */
    uint32_t *scratch;              /* per-frame upload lists */
    blade_order_key_t *order;       /* max_draw_tiles: the drawn tiles, nearest first */
    blade_t *template_cpu;          /* template_count * template_blades, tile-local */
    uint32_t template_real[BLADE_TILES_MAX_TEMPLATES]; /* blades per template, padding excluded */
    int count_word;                 /* the word a draw command counts blades in: 1 instances (pull),
                                       0 patch vertices (tessellate) */
    uint32_t ring_tile_culled[BLADE_TILES_READBACK_SLOTS]; /* stats.tile_culled per draw_ring slot */
    float *ground_cpu;              /* the ground texture: xyz normal, w height per grid vertex */
    int max_draw_tiles;
    blade_env_t env;                /* latest resolved env (gravity, winds) */
    float time;
    gfx_buffer_t templates, pool, eta, motion, winds, spheres, slot_spheres, slot_list, init_list,
        tile_list, drawn, drawn_ids, command;
    int sphere_capacity; /* spheres the sphere buffer holds (blade_sphere_buffer_fit) */
    int sphere_count;    /* spheres the latest update put in it */
    uint32_t *slot_words;    /* slot_spheres' CPU twin: list heads, then the lists (blade_tiles.c) */
    int slot_words_capacity; /* words both hold (grown to each update's need) */
    gfx_readback_t motion_ring, draw_ring; /* BLADE_TILES_READBACK_SLOTS deep */
    int *motion_owner[BLADE_TILES_READBACK_SLOTS]; /* recovering slot owners at copy time, else -1 */
    float *slot_motion;                            /* latest read back, per slot */
    gfx_texture_t ground;
    gfx_texture_t extent; /* R8, id 0 when the desc gave none */
    gfx_buffer_t tile_info; /* per tile: state | slot << 2, for the overlays */
    int overlay;            /* BLADE_TILES_OVERLAY_* */
    gfx_program_t init, physics, cull, draw, draw_fade, handover, resolve;
    raster_program_t raster; /* made on the first blade_tiles_raster */
    bool programs_failed;    /* draw and draw_fade, made on the first blade_tiles_draw, did not build */
    hybrid_slope_grid_t slope_grid;
    gfx_buffer_t slope_map, slope_sums, bb_sums; /* hybrid_slope_cell_t / _sum_t per cell */
    blade_tiles_slope_source_fn source;
    void *source_user;
    GLuint vao;
    blade_tiles_stats_t stats;
    bool culled_once, warned_overflow;
};

/* Seeds g's blades and patch boxes (made, zeroed) from seed on the GPU
 * (blade_seed_gpu.c) and reads back the thinned count; false (logged) when
 * a program or buffer cannot be made. */
bool blade_gpu_seed(blade_gpu_t *g, const blade_gpu_seed_t *seed);

/* Makes *buf (labelled "<label>.spheres", *capacity spheres) hold count
 * spheres: past its capacity it is remade, doubled until they fit (its
 * contents are not kept). False (logged) when the GL cannot make it; *buf
 * and *capacity are then unchanged. */
bool blade_sphere_buffer_fit(gfx_buffer_t *buf, int *capacity, int count, const char *label);

/* The surface of drawn blades (blade_geom.glsl uniforms). */
typedef struct blade_surface_t {
    blade_shape_t shape;
    float displacement, width_correction;
    float width_printed[2]; /* eq. 24 as printed: w_min, w_span px (0: off) */
    int max_level;
    float lod_distance;
} blade_surface_t;
/* Vertices of one pulled strip (blade_geom.glsl blade_strip_uv):
 * S = 2 (max_level + 1), or 2 S + 2 with the eq. 23 displacement (two
 * columns across the width). */
uint32_t blade_strip_vertices(int max_level, float displacement);
/* Sets the surface and shading uniforms (blade_geom.glsl,
 * grass_shade.glsl) of program p (in use); zero sun and albedos take the
 * blade_draw_desc_t defaults. */
void blade_set_surface_uniforms(gfx_program_t p, const blade_surface_t *surf, const blade_draw_desc_t *desc);
/* Rasterizes the blades of
 * `blades` listed in `ids` (id 0: blades[i] directly), as many as the uint
 * at word count_index of `count` (at most count_max); `prog` is made on
 * first use and kept by the caller. */
bool blade_raster_list(raster_t *r, raster_program_t *prog, const blade_surface_t *surf,
                       const blade_draw_desc_t *desc, gfx_buffer_t blades, gfx_buffer_t ids, gfx_buffer_t count,
                       uint32_t count_index, uint32_t count_max);


#endif

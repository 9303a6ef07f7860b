/* admit: resource admission. Before anything of the grass is allocated
 * the program estimates, from the scene and the loaded ground alone, the
 * GPU and host memory a run will hold (render targets, the compute
 * rasterizer's visibility buffer, terrain, the full blade field or the
 * hybrid's tiles, billboards, collision cube arrays) and its per-frame work
 * (blades simulated, billboard candidates), and checks them and the GL's
 * limits (texture size, geometry-shader output, compute dispatch size). A
 * scene that does not fit is refused with one line naming the key and the
 * largest (or smallest) value of it that fits, found by bisecting the same
 * estimate.
 *
 * GL-free: the GL's limits come in as numbers (gfx_limits), the machine's
 * memory from admit_host_bytes (/proc/meminfo, RLIMIT_AS). The estimate
 * follows the allocations of bb_field_make, blade_gpu_make,
 * blade_tiles_make (blade_tiles_estimate_bytes), raster_make,
 * gfx_target_make and ground_make; test_admit compares it with
 * gfx_memory_bytes after start-up. */
#ifndef MEADOW_ADMIT_H
#define MEADOW_ADMIT_H

#include <stdbool.h>
#include <stddef.h>

#include "scene/scene.h"
#include "terrain/terrain.h"

/* The GL's limits (0: unknown, not checked) and the memory a run may use. */
typedef struct admit_limits_t {
    int max_texture_size;     /* GL_MAX_TEXTURE_SIZE */
    int max_renderbuffer_size; /* GL_MAX_RENDERBUFFER_SIZE */
    int max_gs_vertices;      /* GL_MAX_GEOMETRY_OUTPUT_VERTICES */
    int max_gs_components;    /* GL_MAX_GEOMETRY_TOTAL_OUTPUT_COMPONENTS */
    int max_compute_groups;   /* GL_MAX_COMPUTE_WORK_GROUP_COUNT[0]: blade kernels run 256 blades a group */
    double gpu_bytes;         /* the GPU's own memory; 0: it shares host memory (llvmpipe, unknown) */
    double host_bytes;        /* host memory the process may still take */
} admit_limits_t;

/* What the estimate needs beyond the scene: the ground as loaded (mesh
 * terrains: its size; heightfields scale with terrain.size) and which
 * systems this run makes. */
typedef struct admit_world_t {
    const terrain_mesh_t *terrain;
    double terrain_area;   /* m^2 of ground surface at the scene's terrain.size */
    bool billboards;       /* bb field (billboard and hybrid modes) */
    bool tiles;            /* blade tiles: the hybrid's on heightfields, every grass mode's on worlds */
    float tiles_distance;  /* the tiles' blade distance (0: grass.switch_distance) */
    bool full_field;       /* every blade of the field (blade mode, hybrid on a mesh) */
    bool raster;           /* the compute rasterizer's buffers (raster compute or auto) */
    bool size_option;      /* size is --size's: messages name it as the option (--size WxH) */
    int target_samples;    /* samples of the main target (the GL's cap applied) */
    float collider_radius; /* largest collider's bounding radius (grass.cube_texel) */
    int max_texture_size;  /* GL_MAX_TEXTURE_SIZE: caps those cube maps (0: 16384) */
    int objects;           /* colliders and characters that bend grass (--character adds one to none) */
    const int *collider_spheres; /* sphere proxies of each scene collider in the blade physics (NULL: none) */
    const int *character_spheres; /* those of each loaded character (NULL before they are loaded) */
    int characters;               /* entries of character_spheres */
} admit_world_t;

enum {
    ADMIT_FIXED = 0, /* gfx's upload ring, the rasterizer's triangle queues, programs */
    ADMIT_TARGETS,   /* main target and its resolve */
    ADMIT_RASTER,    /* compute rasterizer: visibility buffer, opaque depth */
    ADMIT_TERRAIN,
    ADMIT_BLADES,    /* the full blade field */
    ADMIT_TILES,     /* the hybrid's tiles */
    ADMIT_BILLBOARDS,
    ADMIT_CUBES,     /* collision cube arrays */
    ADMIT_PARTS
};

typedef struct admit_t {
    double gpu[ADMIT_PARTS]; /* bytes of GPU storage by part */
    double gpu_total;            /* held for the run (what gfx_memory_bytes then reports) */
    double transient;            /* held at start-up only: raster auto's calibration targets */
    double raster_vis;           /* bytes of the visibility buffer, the largest single buffer (0: none) */
    double host;                 /* bytes of host memory beyond the GPU's (terrain, seeding) */
    double blades;               /* blades simulated per frame (full field: all; tiles: the pool) */
    double bb_candidates;        /* billboard candidate cells (work of a regeneration) */
} admit_t;

/* RASTER_QUEUE_LAYERS of raster.h (a GL header; world.c asserts they agree). */
#define ADMIT_RASTER_QUEUE_LAYERS 16
/* Host memory set aside for the GL driver when checking before it starts
 * (llvmpipe's threads and code took ~0.5 GB of address space here). */
#define ADMIT_GL_RESERVE (512.0 * 1024.0 * 1024.0)
/* Most billboard candidates a field holds (bb_field_make's limit). */
#define ADMIT_MAX_BB_CANDIDATES (1u << 26)
/* Most colliders and characters together (COLLIDE_MAX_OBJECTS, a collide
 * set's; world.c asserts they agree). */
#define ADMIT_MAX_OBJECTS 128
/* Most sphere proxies of the blade physics in one step (BLADE_MAX_SPHERES,
 * a collide set's; grass.c asserts they agree): a scene whose colliders and
 * characters pack more is refused, naming the key. */
#define ADMIT_MAX_SPHERES 4096
/* Most bytes of one GL buffer: Mesa refuses a larger one with
 * GL_OUT_OF_MEMORY (its resource sizes are 32-bit); the compute
 * rasterizer's visibility buffer is the one that reaches it (16384 x 16384
 * at 4 samples: 8 GiB). */
#define ADMIT_MAX_BUFFER_BYTES 4294967295.0
/* Most blades of a full blade field: 50M x 68 B = 3.4 GB of GPU state. */
#define ADMIT_MAX_FIELD_BLADES 50000000

const char *admit_part_name(int part);
/* False with one line in err when s has a world terrain (terrain.type
 * "world", no vertices) and w asks for grass that still needs the
 * terrain's vertices: the full blade field (the bench's reference) or the
 * GI volumes. Every mode draws streamed grass there: tiles of blades, a
 * ring of billboard cells (docs/WORLD.md). */
bool admit_world_supported(const scene_desc_t *s, const admit_world_t *w, char *err, size_t err_size);
void admit_estimate(const scene_desc_t *s, const admit_world_t *w, admit_t *out);
/* Checks s against the limits; false with one line in err (naming the key
 * and the largest value that fits) when it does not fit; what a world
 * terrain cannot draw yet is refused here (admit_world_supported). */
bool admit_check(const scene_desc_t *s, const admit_world_t *w, const admit_limits_t *lim, char *err,
                     size_t err_size);
/* This process's host memory headroom: 80 % of MemAvailable, and under a
 * finite RLIMIT_AS of the address space left, at most
 * $MEADOW_MEMORY_LIMIT_MB MiB when that is set (a cap where RLIMIT_AS
 * cannot be used: ASan reserves terabytes); 0 when nothing is known. */
double admit_host_bytes(void);
/* False with one line in err when grass.tile_size cuts a heightfield into
 * more than HYBRID_MAX_TILES tiles or holds less than one blade per tile
 * (the hybrid's tiles and templates; a 0.001 m tile had grown to 24 GB,
 * 1e-6 m never finished), naming the smallest value that fits. */
bool admit_tiles_check(const scene_desc_t *s, const terrain_mesh_t *t, char *err, size_t err_size);
/* m^2 of a terrain mesh's surface (admit_world_t.terrain_area). */
double admit_terrain_area(const terrain_mesh_t *t);

#endif

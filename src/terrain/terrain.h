/* terrain: the ground grass grows on. A deterministic procedural heightfield
 * (value-noise fBm from core_hash_u32, seeded by the scene seed), an
 * arbitrary triangle mesh loaded with assimp, or the open world's height
 * function (terrain_world.h: no vertices held), plus ground-height queries
 * (exact barycentric lookup on the heightfield grid; downward ray cast through
 * a uniform 2D grid of triangles for meshes; the function itself for worlds).
 * GL-free. */
#ifndef MEADOW_TERRAIN_H
#define MEADOW_TERRAIN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <cglm/cglm.h>

#include "terrain/terrain_world.h"

#define TERRAIN_PATH_MAX 256 /* bytes of a mesh path, including the NUL */

/* Keys terrain.size, resolution, height and scale. */
#define TERRAIN_DEFAULT_SIZE 40.0f
#define TERRAIN_DEFAULT_RESOLUTION 64
#define TERRAIN_DEFAULT_HEIGHT 1.5f
#define TERRAIN_DEFAULT_SCALE 1.0f
#define TERRAIN_RESOLUTION_MAX 4096 /* also terrain_make_heightfield's limit */

typedef enum terrain_type_t {
    TERRAIN_HEIGHTFIELD = 0, /* default */
    TERRAIN_MESH,
    TERRAIN_WORLD, /* terrain_world_t: a height function, drawn as a clipmap */
} terrain_type_t;

/* Zero means default: the TERRAIN_DEFAULT_* below (the scene keys'
 * defaults too, scene/scene_fields.c). resolution is at most
 * TERRAIN_RESOLUTION_MAX (4096; the key's range too). */
typedef struct terrain_desc_t {
    terrain_type_t type;         /* default heightfield */
    float size;                  /* heightfield or world side, metres, square; default 40
                                    (at most TERRAIN_WORLD_SIZE_MAX for worlds) */
    int resolution;              /* heightfield grid cells per side; default 64 */
    float height;                /* heightfield or world amplitude: heights in [-height, height]; default 1.5 */
    char mesh[TERRAIN_PATH_MAX]; /* mesh file (repository-relative or absolute), type mesh */
    float scale;                 /* uniform scale applied to the mesh; default 1 */
} terrain_desc_t;

/* Returns d with the zero fields resolved to the defaults above. */
terrain_desc_t terrain_desc_defaults(const terrain_desc_t *d);

/* A world terrain (type TERRAIN_WORLD) holds no vertices, indices or grid:
 * vertex_count, index_count, grid_res and cells_x are 0 and the arrays NULL;
 * aabb is the world square and [-height, height]. */
typedef struct terrain_mesh_t {
    terrain_type_t type;
    terrain_world_t world; /* type TERRAIN_WORLD: the height function's parameters */
    float *positions; /* xyz per vertex */
    float *normals;   /* xyz per vertex, unit */
    float *uvs;       /* uv per vertex: [0,1] across the heightfield; the file's
                         first UV set for meshes, else planar xz over the AABB */
    uint32_t *indices; /* 3 per triangle, counter-clockwise seen from outside/above */
    uint32_t vertex_count, index_count;
    vec3 aabb_min, aabb_max;

    /* heightfield layout (grid_res > 0): vertex (i, j) at index j*(res+1)+i,
     * x = -size/2 + i*size/res, z = -size/2 + j*size/res. */
    int grid_res;
    float grid_size;

    /* 2D triangle grid over xz for ray casts (terrain_build_grid). */
    int cells_x, cells_z;
    float cell_w, cell_d;        /* cell width (x) and depth (z), metres */
    uint32_t *cell_start;        /* cells_x*cells_z + 1 offsets into cell_tris */
    uint32_t *cell_tris;         /* triangle indices per cell */
} terrain_mesh_t;

/* Procedural heightfield centred on the origin, y up: 4 octaves of value
 * noise, base wavelength 16 m, gain 0.5, lacunarity 2, normalised to
 * [-height, height]. Same desc and seed give bit-identical meshes. Vertex
 * normals are area-weighted face normals. A desc of type TERRAIN_WORLD makes
 * a world terrain instead (terrain_make_world). Returns false (logged) when
 * out of memory or the desc is invalid. */
bool terrain_make_heightfield(terrain_mesh_t *mesh, const terrain_desc_t *desc, uint64_t seed);

/* World terrain (terrain_world_make of desc and seed): no allocation, a
 * few dozen bytes whatever desc->size. Returns false (logged) when the size
 * exceeds TERRAIN_WORLD_SIZE_MAX. */
bool terrain_make_world(terrain_mesh_t *mesh, const terrain_desc_t *desc, uint64_t seed);

/* Loads every mesh of a file with assimp (triangulate, generate smooth
 * normals, join identical vertices, pre-transform node matrices), merges them
 * into one, scales by `scale` (0 = 1) and builds the ray-cast grid. Rejects
 * files without triangles and NaN/infinite data with a message in err. */
bool terrain_load_mesh(terrain_mesh_t *mesh, const char *path, float scale, char *err,
                       size_t err_size);

/* Builds the uniform 2D grid of triangles used by terrain_height_at for
 * non-heightfield meshes (about 4 triangles per cell, at most 512 cells per
 * side). Called by terrain_load_mesh; call it yourself after filling a mesh
 * by hand. Returns false when out of memory. */
bool terrain_build_grid(terrain_mesh_t *mesh);

/* Ground height under (x, z) and the unit face normal there (normal_out may be
 * NULL). Heightfield: exact barycentric interpolation on the grid triangle,
 * (x, z) clamped to the terrain square. Mesh: the highest surface hit by a
 * vertical ray; -FLT_MAX and normal (0,1,0) when nothing lies under (x, z).
 * World: terrain_world_height (analytic normal), not clamped. */
float terrain_height_at(const terrain_mesh_t *mesh, float x, float z, vec3 normal_out);

/* Hash of positions, normals, uvs and indices, and of the type and world
 * parameters (determinism tests). */
uint64_t terrain_hash(const terrain_mesh_t *mesh);

void terrain_free(terrain_mesh_t *mesh);

#endif

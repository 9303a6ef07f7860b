/* blade_seed: places Bézier grass blades (Jahrmann & Wimmer 2017, sec. 4)
 * on any triangle mesh and groups them into spatially ordered patches.
 * GL-free, deterministic from desc.seed (core_rng_t).
 *
 * Every blade: up = interpolated vertex normal (face normal when normals is
 * NULL or the interpolation degenerates), height/width/stiffness/direction
 * angle uniform in their ranges, rest pose v1 = v2 = v0 + up * height.
 *
 * Patches: all blades are sorted by the 63-bit Morton code (21 bits per
 * axis) of their root, quantized in the cube that bounds the mesh, ties
 * broken by creation order; consecutive runs of patch_size blades form the
 * patches, so blades inside a patch are in Morton order and patches follow
 * the Morton curve. The last patch is padded with copies of its last blade
 * at height 0 and width 0 (v1 = v2 = v0): the simulation and the culling
 * skip blades of height <= 0. A patch AABB bounds the roots grown by the
 * patch's max(height + width/2) on every side: the whole blade, whatever the
 * forces, stays within its height of the root (curve length = height) plus
 * half its width. */
#ifndef MEADOW_BLADE_SEED_H
#define MEADOW_BLADE_SEED_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "blade/blade_ref.h"

/* Input mesh, borrowed. */
typedef struct blade_mesh_t {
    const float *positions; /* xyz per vertex */
    const float *normals;   /* xyz per vertex, or NULL for face normals */
    size_t vertex_count;
    const uint32_t *indices; /* 3 per triangle */
    size_t index_count;
} blade_mesh_t;

/* Seeding modes:
 *   BLADE_SEED_UNIFORM: N = round(density * area) roots, each on a triangle
 *     picked with probability proportional to its area, uniform inside it.
 *   BLADE_SEED_TUFTS: tuft centres by dart throwing (uniform candidates as
 *     above, rejected when closer than tuft_min_distance to an accepted one)
 *     until round(density * area / tuft_blades) centres or
 *     tuft_attempts_per_centre * target candidates were tried (a warning is
 *     logged when the target is not reached); then tuft_blades roots around
 *     each centre, uniform in a disc of tuft_radius on the plane of the
 *     centre's triangle. An offset that leaves the triangle is redrawn up to 8
 *     times, then replaced by the closest point of the triangle, so every
 *     root lies on the mesh. */
enum { BLADE_SEED_UNIFORM = 0, BLADE_SEED_TUFTS = 1 };

/* Zero means default:
 *   population       density, height, width, stiffness: blade_population.h
 *                    (the program's; shape, albedo and gravity are not used
 *                    by the seeding); angle [0, 2 pi) (both 0 means the full
 *                    circle);
 *   tuft_min_distance 0.25 m; tuft_blades 8; tuft_radius 0.06 m;
 *   tuft_attempts_per_centre 30; max_blades 4,194,304 (seeding fails with a
 *   logged error when the count, before padding, would exceed it);
 *   patch_size 256. seed 0 is a valid seed. */
typedef struct blade_seed_desc_t {
    uint64_t seed;
    int mode;
    blade_population_t population;
    float angle_min, angle_max;
    float tuft_min_distance;
    int tuft_blades;
    float tuft_radius;
    int tuft_attempts_per_centre;
    size_t max_blades;
    int patch_size;
} blade_seed_desc_t;

typedef struct blade_aabb_t {
    float min[3], max[3];
} blade_aabb_t;

/* A drawn group (patch, tile) and its squared distance to the camera. */
typedef struct blade_order_key_t {
    float dist2;
    uint32_t id;
} blade_order_key_t;

/* Sorts keys nearest first, ties by id (the same order on every run).
 * The draws append blades in this order, so the depth test rejects more of
 * the hidden ones (docs/PERFORMANCE.md, "Opaque blades tested before
 * shading, drawn nearest first"). */
void blade_order_sort(blade_order_key_t *keys, size_t n);

typedef struct blade_field_t {
    blade_t *blades;        /* padded_count blades, patch after patch */
    float *eta;             /* padded_count collision strengths, all 0 */
    blade_aabb_t *patch_aabbs; /* patch_count */
    size_t blade_count;     /* real blades (the first blade_count entries) */
    size_t padded_count;    /* patch_count * patch_size */
    size_t patch_count;
    int patch_size;
    float morton_origin[3]; /* Morton quantization: cell = (p - origin) * scale */
    float morton_scale;     /* cells per metre (2^21 cells over the cube) */
} blade_field_t;

blade_seed_desc_t blade_seed_desc_defaults(const blade_seed_desc_t *desc);

/* Seeds a field on mesh. Returns false (one logged error, *out zeroed) on
 * an invalid mesh or a count above max_blades. An empty result (zero area
 * or zero blades) is a success with all counts 0. */
bool blade_seed_mesh(const blade_mesh_t *mesh, const blade_seed_desc_t *desc, blade_field_t *out);

void blade_field_free(blade_field_t *field);

/* Sets field's Morton quantization (morton_origin, morton_scale) to the
 * cube that bounds the mesh's indexed vertices (2^21 cells a side). */
void blade_seed_frame(const blade_mesh_t *mesh, blade_field_t *field);
/* A Morton code and what it orders (blade_seed_sort). */
typedef struct blade_seed_key_t {
    uint64_t code;
    uint32_t index;
} blade_seed_key_t;
/* Sorts keys by code, ties by index (a stable LSD radix sort: 6.5x faster
 * than qsort on 12M blades); tmp holds n keys. */
void blade_seed_sort(blade_seed_key_t *keys, blade_seed_key_t *tmp, size_t n);

/* The point of triangle tri at barycentrics bary, and the unit up there:
 * the interpolated vertex normal, else (no normals, or they cancel) the
 * face normal, else +Y (a degenerate triangle). */
void blade_seed_point(const blade_mesh_t *mesh, size_t tri, const float bary[3], float p[3]);
void blade_seed_normal(const blade_mesh_t *mesh, size_t tri, const float bary[3], float n[3]);
/* Writes the rest pose v1 = v2 = v0 + up * height and the blade's
 * attributes (blade_t's w components). */
void blade_seed_rest(blade_t *b, const float v0[3], const float up[3], float height, float width, float stiffness,
                     float angle);
/* Recomputes field->patch_aabbs from its blades (the banner's boxes). */
void blade_seed_patch_boxes(blade_field_t *field);

/* 63-bit Morton code of a root as used for the ordering. */
uint64_t blade_seed_morton(const blade_field_t *field, const float p[3]);

#endif

/* blade_seed_plan: stratified seeding of Bézier blades (Jahrmann & Wimmer
 * 2017, sec. 4) in which every blade is a function of its index, so the
 * GPU seeds a field of millions in one dispatch (blade_seed.comp, the GLSL
 * twin of blade_seed_plan_blade) and the CPU reproduces any blade of it.
 * GL-free.
 *
 * The plan (CPU, per triangle, no per-blade work): the mesh's triangles in
 * Morton order of their centroids (63-bit codes as blade_seed_morton, ties
 * by index); triangle k of that order holds blades
 * [offsets[k], offsets[k+1]) with offsets[k] = round(density * A_k), A_k
 * the area of the triangles before it. Counts are thus stratified: each
 * triangle takes its area's share to within one blade and the field
 * round(density * area) in all. Consecutive runs of patch_size blades form
 * the patches (blade_seed.h), so blades follow the triangles' Morton curve.
 *
 * Blade i of ordered triangle k (mesh triangle t = order[k], j = i -
 * offsets[k]): the stream s = hash(hash(key ^ hash(t)) + j) (core_hash_u32,
 * key from the desc's seed) gives u_n = hash_float(s + n * 0x9e3779b9) for
 * n = 0..5; barycentrics (1 - sqrt u0, sqrt u0 (1 - u1), sqrt u0 u1), the
 * root and up as blade_seed.h's (interpolated normal, else the face
 * normal), then height u2, width u3, stiffness u4 and direction angle u5
 * uniform in the desc's ranges, rest pose v1 = v2 = v0 + up height.
 * Padding blades (i >= blade_count) copy blade blade_count - 1 at height
 * and width 0 with v1 = v2 = v0.
 *
 * An extent map (bb_layout.h: where grass grows, 0..255 per texel) thins
 * the field: blade i keeps its height where hash(i ^ hash(key' ^
 * 0x5bd1e995)) mod 255 < e, e the texel under its root (extent.glsl's
 * wrap); a thinned blade has height and width 0 and stays in its patch.
 * Patch boxes are computed after the thinning. */
#ifndef MEADOW_BLADE_SEED_PLAN_H
#define MEADOW_BLADE_SEED_PLAN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "blade/blade_seed.h"

/* The extent map that thins a field (borrowed). px NULL: no thinning. */
typedef struct blade_seed_extent_t {
    const uint8_t *px; /* w * h texels, row z, column x */
    int w, h;
    float origin[2];   /* xz of texel (0, 0)'s corner */
    float spacing;     /* metres per texel */
    uint32_t key;      /* the thinning's hash key (the placement seed) */
} blade_seed_extent_t;

typedef struct blade_seed_plan_t {
    blade_seed_desc_t desc;  /* resolved; mode is not read (stratified) */
    uint32_t key;            /* the blades' hash key, from desc.seed */
    uint32_t *order;         /* tri_count mesh triangles, Morton order */
    uint32_t *offsets;       /* tri_count + 1 first blades */
    size_t tri_count;
    size_t blade_count, padded_count, patch_count;
    int patch_size;
    float morton_origin[3], morton_scale; /* as blade_field_t's */
} blade_seed_plan_t;

/* Plans a field on mesh (validated as blade_seed_mesh validates it). False
 * (one logged error, *out zeroed) on an invalid mesh or a count above
 * desc->max_blades; zero area gives an empty plan. */
bool blade_seed_plan_make(const blade_mesh_t *mesh, const blade_seed_desc_t *desc, blade_seed_plan_t *out);
void blade_seed_plan_free(blade_seed_plan_t *plan);

/* Blade i (0 .. padded_count - 1) of the plan on mesh, before thinning:
 * the CPU twin of blade_seed.comp. */
void blade_seed_plan_blade(const blade_seed_plan_t *plan, const blade_mesh_t *mesh, size_t i, blade_t *out);

/* Whether the extent keeps blade i rooted at v0 (true without a map). */
bool blade_seed_extent_keeps(const blade_seed_extent_t *extent, uint32_t i, const float v0[3]);

/* The whole field on the CPU: every blade, thinned by extent (NULL: none;
 * *thinned counts the real blades it removed, NULL: not reported), eta 0,
 * the patch boxes of blade_seed.h over the thinned blades. False (logged)
 * when out of memory. The reference of the GPU seeding (test_blade_gpu_seed). */
bool blade_seed_plan_field(const blade_seed_plan_t *plan, const blade_mesh_t *mesh,
                           const blade_seed_extent_t *extent, blade_field_t *out, size_t *thinned);

#endif

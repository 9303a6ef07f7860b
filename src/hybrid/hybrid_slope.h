/* hybrid_slope: the hand-over of deformation between the two grass models
 * at a representation switch (after Qiu et al.: the average slope of the
 * blades of a tile becomes the slope of its billboards, and a deformed
 * billboard's slope seeds the blades). GL-free reference and the layout
 * the shaders share (shaders/common/slope.glsl twins every function).
 *
 * A grid of square cells covers the field (cells_per_tile per tile side).
 * An element's tilt offset is o = d.xz - d_p.xz, the horizontal change of
 * its unit direction d against its wind pose d_p. A cell stores the mean
 * offset T, the mean magnitude M = mean |o|, the blades' mean eta and the
 * time tau it was written, from fixed-point sums (HYBRID_SLOPE_FIXED per
 * unit; integer atomics on the GPU), so GPU and CPU agree exactly. An
 * element with horizontal facing f takes o' = w (T + f (M - |T|)),
 * w = (1 - clamp((now - tau) / R, 0, 1))^3 (Orthmann's eq. 8 weight over
 * the billboards' recover time R). The reasoning, the new direction and
 * the measurements: docs/HYBRID.md ("Simulation, hand-over, overlays"). */
#ifndef MEADOW_HYBRID_SLOPE_H
#define MEADOW_HYBRID_SLOPE_H

#include <stdbool.h>
#include <stdint.h>

#define HYBRID_SLOPE_FIXED 16384.0f /* fixed-point units per unit offset */
#define HYBRID_SLOPE_MAX_TILT 0.999f
/* Elements one cell can sum without int32 overflow: |o| <= 2, so each adds
 * at most 2 * HYBRID_SLOPE_FIXED to a sum. */
#define HYBRID_SLOPE_MAX_PER_CELL 65000

typedef struct hybrid_slope_grid_t {
    float origin[2]; /* xz of the corner of cell 0 */
    float cell;      /* cell side (m) */
    int nx, nz;
} hybrid_slope_grid_t;

/* One cell as stored on the GPU (std430: two vec4). */
typedef struct hybrid_slope_cell_t {
    float t[2];  /* mean offset T */
    float m;     /* mean magnitude M */
    float eta;   /* mean collision strength */
    float tau;   /* time written (s) */
    float count; /* elements in the mean (0: nothing to hand over) */
    float pad[2];
} hybrid_slope_cell_t;

/* Fixed-point sums of one cell (std430 ivec4 + uint count + pad). */
typedef struct hybrid_slope_sum_t {
    int32_t t[2], m, eta;
    uint32_t count;
    uint32_t pad[3];
} hybrid_slope_sum_t;

/* cells_per_tile cells per side of each tile of a square field of
 * tiles x tiles tiles. */
hybrid_slope_grid_t hybrid_slope_grid(float min_x, float min_z, float tile_size, int tiles_x, int tiles_z,
                                      int cells_per_tile);
/* Cell index of (x, z), -1 outside. */
int hybrid_slope_cell_at(const hybrid_slope_grid_t *g, float x, float z);
/* Tilt offset o of a deformed direction against the pose direction (both
 * unit). */
void hybrid_slope_offset(const float dir[3], const float pose_dir[3], float out[2]);
/* Adds one element's offset and eta to a cell sum (fixed point, rounded to
 * nearest as the shader's int(round(x * FIXED))). */
void hybrid_slope_add(hybrid_slope_sum_t *s, const float o[2], float eta);
/* Mean of a sum, written at time tau. count 0 gives a zero cell. */
hybrid_slope_cell_t hybrid_slope_resolve(const hybrid_slope_sum_t *s, float tau);
/* Eq. 8's weight (1 - clamp(age / recover, 0, 1))^3. */
float hybrid_slope_weight(float age, float recover);
/* The new unit direction of an element (docs/HYBRID.md); w the weight. */
void hybrid_slope_apply(const float pose_dir[3], const float fallback[2], const hybrid_slope_cell_t *c, float w,
                        float out_dir[3]);

#endif

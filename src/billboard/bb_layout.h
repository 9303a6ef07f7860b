/* bb_layout: procedural content for the billboard grass of Orthmann et al.
 * 2009 (sec. 3, "layout textures"): the extent map (where grass grows), the
 * direction map (growth direction), the messiness map, the grass-clump
 * texture array drawn on the billboards, and the CPU twin of the generation
 * rule that turns a candidate grid cell into a bb_point_t. The GLSL twin is
 * bb_generate() in shaders/common/bb.glsl; both use core_hash_u32 /
 * hash_u32 so the accept decision, layer and seed match bit for bit. */
#ifndef MEADOW_BB_LAYOUT_H
#define MEADOW_BB_LAYOUT_H

#include "billboard/bb_ref.h"
#include "core/core.h"

#include <stdbool.h>
#include <stdint.h>

typedef struct bb_layout_desc_t {
    uint32_t seed;     /* any value (0 included) */
    int size;          /* layout texture side in texels, default 256 */
    int clump_size;    /* clump texture side, default 128 */
    int clump_layers;  /* clump texture array layers, default 4 */
    int blades;        /* blades per clump, default 48 */
} bb_layout_desc_t;
bb_layout_desc_t bb_layout_desc_defaults(const bb_layout_desc_t *desc);

/* All images have row 0 at the top; texel (x, y) covers layout cell x along
 * world +x and y along world +z. The layout textures tile seamlessly. */
typedef struct bb_layout_t {
    core_image_t extent;     /* 1 channel: grass coverage (fBm with clearings) */
    core_image_t direction;  /* 3 channels: 0.5 + 0.5 * growth dir (mostly +y) */
    core_image_t messiness;  /* 1 channel */
    int clump_layers;
    core_image_t *clumps;    /* clump_layers RGBA images, straight alpha; fully
                                transparent texels hold the layer's mean blade
                                colour so mipmaps do not darken the edges */
} bb_layout_t;

/* Deterministic from desc->seed. Returns false (and logs) on allocation failure. */
bool bb_layout_generate(bb_layout_t *layout, const bb_layout_desc_t *desc);
void bb_layout_free(bb_layout_t *layout);
/* Writes extent.png, direction.png, messiness.png, clump_<k>.png into dir
 * (created if needed). */
bool bb_layout_write_pngs(const bb_layout_t *layout, const char *dir);

/* ---- generation rule --------------------------------------------------------
 * Candidates form a grid of `spacing` metres; cell (ix, iz) (any ints) is
 * decided by, with hash = core_hash_u32, hf(x) = core_hash_float(x):
 *   h      = hash(uint(ix) * 0x8da6b343u ^ hash(uint(iz) ^ hash(seed)))
 *   texel  (tx, tz) = (floor(ix / cells_per_texel) mod W, same for iz mod H)
 *   E      = extent byte at (tx, tz)
 *   accept iff hash(h ^ 0x5bd1e995u) % 255u < E
 *   position = (origin.x + (ix + hf(h+1)) * spacing, 0,
 *               origin.z + (iz + hf(h+2)) * spacing)   (y: caller adds terrain)
 *   size   = (width * (0.8 + 0.4 hf(h+3)),
 *             height * (0.6 + 0.8 hf(h+4)) * (0.5 + 0.5 E/255))
 *   angle  = 6.2831853 * hf(h+5)
 *   layer  = ((hash(h+6) >> 8) * layers) >> 24
 *   growth = normalize(direction rgb / 255 * 2 - 1), messiness = byte / 255
 *   seed   = h, state = BB_STATE_IDLE, recover_time = 0
 * Integer steps are exact on both sides; float results agree to rounding
 * (a GLSL compiler may contract a*b+c into an fma). */
typedef struct bb_gen_desc_t {
    float spacing;        /* candidate spacing in metres, default 0.25 */
    float origin[2];      /* world xz of the corner of cell (0,0), default (0,0) */
    int cells_per_texel;  /* candidate cells per layout texel, default 1 */
    float width;          /* base billboard width, default 0.5 m */
    float height;         /* base billboard height, default 0.4 m */
    uint32_t seed;        /* any value (0 included) */
    uint32_t layers;      /* clump layers to pick from, default 4, at most 256 */
} bb_gen_desc_t;
bb_gen_desc_t bb_gen_desc_defaults(const bb_gen_desc_t *desc);

/* Applies the rule to cell (ix, iz). Returns true and fills *out when the
 * candidate gets a billboard; false otherwise (out untouched). */
bool bb_layout_sample(const bb_layout_t *layout, const bb_gen_desc_t *desc, int ix, int iz,
                      bb_point_t *out);

#endif

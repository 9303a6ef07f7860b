/* bb_layout: procedural content for the billboard grass of Orthmann et al.
 * 2009 (sec. 3, "layout textures"): the extent map (where grass grows), the
 * direction map (growth direction), the messiness map, the grass-clump
 * texture array drawn on the billboards (baked by blade_clump), and the CPU
 * twin of the generation rule that turns a candidate grid cell into a
 * bb_point_t. The GLSL twin is bb_generate() in shaders/common/bb.glsl;
 * both use core_hash_u32 / hash_u32 so the accept decision, layer and seed
 * match bit for bit.
 *
 * The clump layers are the blade model's, baked by blade_clump
 * (blade/blade_clump.h) from the scene's blade population, once per view
 * with the views on (bb_view.h); this module allocates the images, picks
 * the views and leaves the baking to it. */
#ifndef MEADOW_BB_LAYOUT_H
#define MEADOW_BB_LAYOUT_H

#include "billboard/bb_ref.h"
#include "billboard/bb_view.h"
#include "blade/blade_clump.h"
#include "core/core.h"

#include <stdbool.h>
#include <stdint.h>

/* The extent map's clearings (bb_layout.c, bb_layout_extent). */
typedef enum bb_clearings_t {
    BB_CLEARINGS_NOISE = 0, /* bare blobs where a tileable fBm field dips (default) */
    BB_CLEARINGS_NONE,      /* none: 255 everywhere */
    BB_CLEARINGS_IMAGE,     /* the first channel of `image`, bilinear, clamped to its edges */
} bb_clearings_t;

/* Zero means default. */
typedef struct bb_extent_desc_t {
    bb_clearings_t clearings; /* default noise */
    float fraction;           /* noise: share of texels whose clearing mask is below one half (bare:
                                 extent below about 0.5 x 255), in (0, 1]; default 0: the mask's
                                 fixed threshold, whose share varies with the seed (0.07 to
                                 0.65 below 128 for seeds 0-19 at 112 texels) */
    float feature;            /* noise: texels per cell of the clearing field's coarsest octave,
                                 rounded so a whole number of cells (1 to size / 2) spans the map;
                                 default 0: size / 4 */
    const core_image_t *image; /* image: required, not owned; row 0 maps to texel row 0 */
    float image_texels[2];    /* image: texels the image spans along x and along z from texel
                                 (0, 0); default (size, size) */
} bb_extent_desc_t;

typedef struct bb_layout_desc_t {
    uint32_t seed;     /* any value (0 included) */
    int size;          /* layout texture side in texels, default 256 */
    int clump_size;    /* clump texture side, default 128 */
    int clump_layers;  /* clump layers a billboard picks from, default 4; each is baked
                          once per view */
    int blades;        /* blades per clump layer before the coverage calibration (the
                          layer adds blades until its union covers as much as these
                          do counted with their overlaps; blade_clump.c), default
                          bb_clump_blades(clump.population.density, 6): 52 at the
                          scene's default densities */
    blade_clump_desc_t clump;
    bb_extent_desc_t extent;
    bb_view_desc_t views; /* the views each clump layer is baked for (bb_view.h) */
    bool extent_only;     /* only the extent map (the blade tiles' clearings): direction and
                             messiness are not made (empty images; no bb_layout_sample on
                             it); default false */
} bb_layout_desc_t;
bb_layout_desc_t bb_layout_desc_defaults(const bb_layout_desc_t *desc);

/* Blades per clump layer for a blade field of `blade_density` blades per m^2
 * shown by billboards of `billboard_density` candidates per m^2 (both
 * thinned alike by the extent map): (pi / 2) blade_density /
 * billboard_density, rounded, at least 1. Per billboard as many blades as
 * the blade field grows per billboard, times pi / 2 because a billboard
 * seen at an angle theta foreshortens its blades by |cos theta| once more
 * (mean 2 / pi) than the blades of the field, which are seen at their own
 * angle only: so a ray through the billboard field meets as much blade
 * surface as one through the blade field. */
int bb_clump_blades(float blade_density, float billboard_density);


/* All images have row 0 at the top; texel (x, y) covers layout cell x along
 * world +x and y along world +z. The layout textures tile seamlessly. */
typedef struct bb_layout_t {
    core_image_t extent;     /* 1 channel: grass coverage (bb_extent_desc_t: fBm with clearings) */
    core_image_t direction;  /* 3 channels: 0.5 + 0.5 * growth dir (mostly +y) */
    core_image_t messiness;  /* 1 channel */
    int clump_layers;        /* L, the layers a billboard picks from */
    bb_view_desc_t views;    /* resolved; V = elevations x azimuths views */
    core_image_t *clumps;    /* V L RGBA images, view v of layer k at v L + k: blade
                                albedo, coverage as straight alpha; fully transparent
                                texels hold the view's mean albedo so mipmaps do not
                                darken edges */
    core_image_t *clump_light; /* V L RGBA images beside clumps: the covered samples'
                                mean colour lit as blade_shade lights it before fog
                                (blade_clump.c), linear, alpha 255 */
    blade_clump_stats_t *clump_stats; /* per image: the coverage calibration */
} bb_layout_t;

/* Deterministic from desc->seed. Returns false (and logs) on allocation failure. */
bool bb_layout_generate(bb_layout_t *layout, const bb_layout_desc_t *desc);
void bb_layout_free(bb_layout_t *layout);
/* Writes extent.png, direction.png, messiness.png, clump_<k>.png (view 0),
 * clump_<k>_view<v>.png and clump_<k>_view<v>_light.png into dir (created
 * if needed). */
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

/* ---- generation rule on a mesh triangle ---------------------------------------
 * Mesh terrains (not heightfields) seed billboards per triangle, by its true
 * area, so a steep face gets as many candidates per m^2 as the floor (the
 * grid above sees a face only through its plan area, about cos angle, and
 * a vertical face not at all). A triangle (a, b, c), rotated so that a b is
 * its longest edge, spans the plane frame u = (b - a) / |b - a| and v, the
 * unit in-plane direction perpendicular to u towards c; in that frame the
 * corners are (0, 0), (length, 0) and (foot, height), foot in [0, length].
 * Its candidates form a grid of `spacing` metres over [0, length] x
 * [0, height]: cell (i, j), 0 <= i < cells[0], 0 <= j < cells[1], of
 * triangle index t (any number naming it, the mesh's triangle index in bb_generate.c)
 * is decided by
 *   h      = hash(uint(i) * 0x8da6b343u ^ hash(uint(j) ^ hash(t ^ hash(seed))))
 *   (pu, pv) = ((i + hf(h+1)) * spacing, (j + hf(h+2)) * spacing)
 *   inside iff height * pu >= foot * pv and
 *              height * (length - pu) >= (length - foot) * pv
 *   position = a + pu u + pv v        (on the triangle: no height lookup)
 *   texel  the layout texel of the grid rule's cell under the position,
 *          projected along the largest component of the face normal:
 *          plane 1 (normal mostly y): (x - origin.x, z - origin.z),
 *          plane 0 (mostly x): (z - origin.z, y), plane 2 (mostly z):
 *          (x - origin.x, y); each coordinate c -> floor(floor(c / spacing)
 *          / cells_per_texel) mod the texture side
 *   then the accept test and every other field exactly as the grid rule
 *   (extent E of that texel; growth from the direction map: billboards
 *   stand up from a face as from the floor).
 * Every cell of the box [0, length] x [0, height] holds its share of the
 * triangle's area, so a triangle gets area / spacing^2 candidates in
 * expectation, jittered-grid stratified inside it. Float results agree with
 * the GLSL twin (bb_generate_tri) to rounding; a root within rounding of a
 * texel edge could read the neighbouring texel. */
typedef struct bb_gen_tri_t {  /* std430 twin: struct bb_gen_tri in shaders/common/bb.glsl */
    float a[3];
    float length;              /* |b - a|, the longest edge */
    float u[3];                /* unit (b - a) */
    float height;              /* distance of c from the line a b */
    float v[3];                /* unit, in the plane, perpendicular to u, towards c */
    float foot;                /* (c - a) . u */
    int32_t cells[2];          /* ceil(length / spacing), ceil(height / spacing) */
    int32_t plane;             /* layout projection (above) */
    int32_t pad;
} bb_gen_tri_t;

/* Faces whose unit normal ((b - a) x (c - a), counter-clockwise seen from
 * outside as terrain_mesh_t winds them) has a y component below this get no
 * billboards: they grow up, into the solid above an overhang. Vertical
 * faces (y 0 up to rounding) keep theirs. */
#define BB_GEN_TRI_MIN_UP (-1e-3f)

/* The frame of triangle (a, b, c) for candidates `spacing` apart. Returns
 * false (out zeroed) when the triangle is degenerate (area below 1e-12 m^2)
 * or faces down (BB_GEN_TRI_MIN_UP). */
bool bb_gen_tri_make(const float a[3], const float b[3], const float c[3], float spacing, bb_gen_tri_t *out);

/* Applies the triangle rule to cell (i, j) of triangle `tri` named t (see
 * above). Returns true and fills *out when the candidate lies inside the
 * triangle and gets a billboard; false otherwise (out untouched). */
bool bb_layout_sample_tri(const bb_layout_t *layout, const bb_gen_desc_t *desc, const bb_gen_tri_t *tri,
                          uint32_t t, int i, int j, bb_point_t *out);

#endif

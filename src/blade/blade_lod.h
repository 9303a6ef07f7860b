/* blade_lod: coverage-preserving thinning of blades with distance (the
 * far field as fewer, wider blades: Cook, Halstead, Planck and Ryu 2007,
 * "Stochastic simplification of aggregate detail"; Jahrmann & Wimmer 2017
 * eq. 19-20 as variants). GL-free; the GLSL twin is shaders/common/lod.glsl
 * (same names, lod_ for blade_lod_), statement for statement.
 *
 * Every blade has a rank r in [0, 1): the bit-reversed low 8 bits of its
 * index (patches and tile templates are Morton ordered, so the blades of
 * a low rank are spread evenly over the ground) plus a hash of the index,
 * over 256. At distance d the rule gives the kept fraction u(d); a blade
 * is drawn with the weight w = clamp((u (1 + s) - r) / s, 0, 1) of a
 * shrink window s in rank units (s = 0: w = r < u): as u falls, a blade
 * narrows to nothing before it is culled, and nothing pops. The blades
 * kept cover the area A(u, s) = integral of w over r; with compensation a
 * kept blade is drawn 1 / A times as wide (at most max_scale), so the
 * thinned field covers the ground as the full one. What is still missing,
 * coverage 1 - A * scale (past the widest widening, or without
 * compensation), is what the grass-shaded ground stands in for
 * (blade_lod_ground).
 *
 * Rules (blade_lod_t.rule):
 *   BLADE_LOD_WIDTH (default): u = 1 nearer than D = max(start,
 *     width * focal_px / width_px), D / d beyond: a blade keeps about
 *     width_px pixels of drawn width per blade's place on screen, whatever
 *     the distance (the thinning the projected width asks for).
 *   BLADE_LOD_LEVELS: eq. 19-20 as the paper's text states it: n =
 *     levels, level = floor(n (1 - d / level_distance)) clamped to
 *     [0, n - 1] (1 in n from level_distance to the cull), kept when
 *     (index mod n) <= level: steps of 1 / n, no shrink window; widened
 *     by n / (level + 1) with compensation.
 *   BLADE_LOD_PRINTED: eq. 20 as printed: kept when (index mod n) >=
 *     level (1 blade in n near the camera, all far); no widening.
 *   BLADE_LOD_OFF: u = 1.
 * In every rule the blades shrink over the last `fade` metres before the
 * cull distance (width times (cull - d) / fade), so the end of the grass
 * does not pop either. */
#ifndef MEADOW_BLADE_LOD_H
#define MEADOW_BLADE_LOD_H

#include <stdbool.h>
#include <stdint.h>

typedef enum blade_lod_rule_t {
    BLADE_LOD_WIDTH = 0,
    BLADE_LOD_LEVELS = 1,
    BLADE_LOD_PRINTED = 2,
    BLADE_LOD_OFF = 3,
} blade_lod_rule_t;

/* Zero means default:
 *   rule            BLADE_LOD_WIDTH
 *   start           BLADE_LOD_START_DEFAULT (10 m): nothing thinned nearer
 *   width_px        BLADE_LOD_WIDTH_PX_DEFAULT (1.5 px): WIDTH's projected
 *                   width where thinning starts
 *   levels          8 (LEVELS, PRINTED)
 *   level_distance  the cull distance (LEVELS, PRINTED; 0 stays 0 in the
 *                   resolved copy and means the cull distance)
 *   max_scale       8: the widest a kept blade is drawn (>= 1)
 *   shrink          0.1 rank units (WIDTH); no_shrink: 0 (blades pop)
 *   fade            4 m before the cull distance; no_fade: 0 (hard cut)
 *   no_compensation false: kept blades are widened by 1 / A
 *   no_ground       false: blade_lod_ground gives the coverage thinning
 *                   removed (true: 0, the ground keeps its soil colour) */
typedef struct blade_lod_t {
    blade_lod_rule_t rule;
    float start;
    float width_px;
    int levels;
    float level_distance;
    float max_scale;
    float shrink;
    float fade;
    bool no_shrink, no_fade, no_compensation, no_ground;
} blade_lod_t;

#define BLADE_LOD_START_DEFAULT 10.0f
#define BLADE_LOD_WIDTH_PX_DEFAULT 1.5f

/* Per blade and frame: what the thinning makes of it. */
typedef struct blade_lod_draw_t {
    float weight; /* 0: culled; else drawn at width * weight * scale */
    float scale;  /* compensation widening, 1 without */
} blade_lod_draw_t;

blade_lod_t blade_lod_defaults(const blade_lod_t *lod);

/* Pixels per unit of tangent at the view: viewport height / (2 tan(fovy / 2)),
 * from a perspective view-projection (column-major) and the height in pixels. */
float blade_lod_focal(const float viewproj[16], int height_px);

/* Rank of blade `index` in [0, 1). */
float blade_lod_rank(uint32_t index);

/* Kept fraction u at distance d of a blade of width `width` (m); cull is
 * the cull distance (level_distance's default). lod resolved. */
float blade_lod_kept(const blade_lod_t *lod, float d, float width, float focal_px, float cull);

/* Area the kept blades cover, as a fraction of the full field's, before
 * widening: integral over r in [0, 1) of the weight at u, window s. */
float blade_lod_area(float u, float s);

/* The blade's weight and scale (weight 0: culled) at distance d. */
blade_lod_draw_t blade_lod_blade(const blade_lod_t *lod, uint32_t index, float d, float width, float focal_px,
                                 float cull);

/* Fraction of the full field's coverage that the thinned blades keep at
 * distance d for blades of width `width` (the population's mean):
 * A(u) * scale times the end fade, in [0, 1]. */
float blade_lod_coverage(const blade_lod_t *lod, float d, float width, float focal_px, float cull);

/* How much of the grass-shaded ground shows through at d: 1 - coverage
 * (0 with no_ground). */
float blade_lod_ground(const blade_lod_t *lod, float d, float width, float focal_px, float cull);

#endif

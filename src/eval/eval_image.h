/* eval_image: a placement-invariant image error for grass renderings
 * (docs/METRICS.md, "Image error"). Both images are cut into square blocks
 * (default side: the image height / 8, then twice that); per block it
 * compares three statistics that do not depend on where individual blades
 * stand, only on what a viewer sees at that scale:
 *   colour     CIE76 Delta E of the block means, averaged in linear light
 *              (the colour the block blurs to) and converted to CIELAB;
 *   coverage   |difference| of the fraction of grass pixels, a pixel being
 *              grass where it differs from a grass-free render of the same
 *              view (the background);
 *   structure  L1 distance of the gradient-orientation histograms of CIE L*
 *              (magnitude-weighted, 8 unsigned orientations) over the sum of
 *              both histograms' energy: 0 same, 1 disjoint.
 * Each term is averaged over blocks (pixel-weighted) and block sizes, and
 * divided by a scale at which it is clearly visible; the score is the
 * largest scaled term (the most visible difference).
 * eval_image_seam measures, in the same units, the step in colour and
 * coverage across the blade/billboard switch band of a hybrid frame
 * (docs/METRICS.md, "Hybrid seam"). GL-free. */
#ifndef MEADOW_EVAL_IMAGE_H
#define MEADOW_EVAL_IMAGE_H

#include <stdbool.h>

#include "core/core.h"

/* Zero = default. */
typedef struct eval_image_desc_t {
    int block;                      /* finest block side, px; default image height / 8 */
    int levels;                     /* block sizes block, 2 block, 4 block ...; default 2 */
    const core_image_t *background; /* grass-free render of the same view (same size as
                                       both images); NULL: no coverage term */
    int grass_threshold;            /* a pixel is grass when a channel differs from the
                                       background by more (0..255); default 8 */
    double colour_scale;            /* Delta E that scores 1; default 2.3 (CIE76 JND) */
    double coverage_scale;          /* coverage difference that scores 1; default 0.05 */
    double structure_scale;         /* structure distance that scores 1; default 0.2 */
} eval_image_desc_t;

eval_image_desc_t eval_image_desc_defaults(const eval_image_desc_t *d);

typedef struct eval_image_error_t {
    double score;     /* max of the scaled terms below; 0 = indistinguishable */
    double colour;    /* mean block Delta E (CIE76) */
    double coverage;  /* mean block |grass fraction difference|, 0..1; 0 without background */
    double structure; /* mean block orientation-histogram distance, 0..1 */
} eval_image_error_t;

/* Error of `img` against `ref` (RGB or RGBA, 8 bits, sRGB encoded, same
 * size). Returns false (out zeroed) when the sizes differ, an image has
 * fewer than 3 channels, or memory runs out. */
bool eval_image_error(const core_image_t *img, const core_image_t *ref, const eval_image_desc_t *desc,
                      eval_image_error_t *out);

/* The conversions of the colour term: an 8-bit sRGB value to linear light,
 * and linear sRGB (D65) to CIELAB. */
double eval_srgb_to_linear(int v);
void eval_linear_to_lab(const double rgb[3], double lab[3]);

/* ---- hybrid seam ---------------------------------------------------------------
 * The step of the grass's look across the switch distance s of a hybrid
 * frame. Two windows of `window` metres flank the cross-fade band
 * [s - fade, s + fade]: near [s - fade - window, s - fade) (blades) and
 * far (s + fade, s + fade + window] (billboards). Per window, over the
 * counted pixels (cls GROUND or GRASS) whose visible surface lies at that
 * distance: the mean colour of the GRASS pixels in linear light, converted
 * to CIELAB as in eval_image's colour term, and the grass fraction
 * GRASS / (GROUND + GRASS) (eval_image's coverage). The step of a frame is
 * far minus near. A frame's own step also holds what changes with distance
 * in any rendering (fog, viewing angle, terrain, clearings), so the seam is
 * the step of the frame minus the step of a reference: the same view drawn
 * without a switch (e.g. billboards only), whose windows show one
 * representation:
 *   v        = (Lab far - Lab near)(frame) - (Lab far - Lab near)(ref)
 *   delta_e  = |v| (CIE76), delta_l = v.L*
 *   coverage = |(g far - g near)(frame) - (g far - g near)(ref)|
 *   score    = max(delta_e / colour_scale, coverage / coverage_scale),
 * in eval_image's units (1 = clearly visible). Without a reference the
 * frame's own step is reported (a reference that does not change). */
enum { EVAL_SEAM_SKIP = 0, EVAL_SEAM_GROUND = 1, EVAL_SEAM_GRASS = 2 };

/* One frame: colour (RGB or RGBA, 8 bits, sRGB encoded), distance from the
 * camera to the visible surface (m) and class (EVAL_SEAM_*) per pixel, all
 * with row 0 at the top. */
typedef struct eval_seam_frame_t {
    const core_image_t *img;
    const float *dist;
    const uint8_t *cls;
} eval_seam_frame_t;

/* Zero = default. */
typedef struct eval_seam_desc_t {
    float switch_distance; /* s, m; required (> 0) */
    float fade;            /* half width of the cross-fade band, m; default 1 */
    float window;          /* depth of each window beyond the band, m; default 3 */
    double colour_scale;   /* Delta E that scores 1; default 2.3 (eval_image's) */
    double coverage_scale; /* grass fraction step that scores 1; default 0.05 (eval_image's) */
} eval_seam_desc_t;

eval_seam_desc_t eval_seam_desc_defaults(const eval_seam_desc_t *d);

typedef struct eval_seam_t {
    double score;        /* max of the scaled terms; 0 = no seam */
    double delta_e;      /* CIE76 length of v */
    double delta_l;      /* L* of v (negative: the far side darker than the reference says) */
    double coverage;     /* |grass fraction step - the reference's|, 0..1 */
    double lab[2][2][3]; /* [frame, ref][near, far] grass colour in CIELAB */
    /* The same v over every counted pixel, grass and ground (the mean the
     * eye sees, gaps included, as the image error's colour term takes it) */
    double delta_e_all, delta_l_all;
    double lab_all[2][2][3]; /* [frame, ref][near, far] mean colour of the counted pixels in CIELAB */
    double grass[2][2];  /* [frame, ref][near, far] grass fractions */
    long pixels[2][2];   /* [frame, ref][near, far] counted pixels */
} eval_seam_t;

/* Seam of `frame` against `ref` (NULL: none; same size). Returns false (out
 * zeroed) when the sizes differ, an image has fewer than 3 channels, or a
 * window of a frame holds no grass pixel. */
bool eval_image_seam(const eval_seam_frame_t *frame, const eval_seam_frame_t *ref, const eval_seam_desc_t *desc,
                     eval_seam_t *out);

#endif

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
 * largest scaled term (the most visible difference). GL-free. */
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

#endif

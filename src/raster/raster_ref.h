/* raster_ref: the CPU reference of the compute rasterizer's scan
 * (shaders/raster/raster.glsl): near-plane clipping, the row scan of each
 * sample lattice (1 sample: pixel centres; 4: the 4x MSAA pattern), window
 * depth interpolated in screen space, and
 * the visibility buffer's rule (nearest depth wins; ties keep the smaller
 * colour word, as atomicMin on depth << 32 | colour does). GL-free, for
 * tests: same inputs, same samples up to float rounding at edges. */
#ifndef MEADOW_RASTER_REF_H
#define MEADOW_RASTER_REF_H

#include <stdbool.h>
#include <stdint.h>

/* Samples laid out as raster.glsl's: sample k of pixel p at p n + k,
 * pixels row by row. */
typedef struct raster_ref_t {
    int w, h, samples;  /* pixels, samples per pixel (1 or 4) */
    uint32_t *colour;   /* per sample; 0 = no grass */
    uint32_t *depth;    /* per sample, float bits of the window depth */
} raster_ref_t;

/* Allocates and fills every sample with `depth` and colour 0; false when
 * out of memory. */
bool raster_ref_init(raster_ref_t *r, int w, int h, int samples, float depth);
void raster_ref_free(raster_ref_t *r);
/* Offset of sample k from the pixel centre, in pixels. */
void raster_ref_sample_offset(int samples, int k, float out[2]);
/* Draws a flat-coloured triangle given in clip space. */
void raster_ref_triangle(raster_ref_t *r, const float c0[4], const float c1[4], const float c2[4], uint32_t rgba);

#endif

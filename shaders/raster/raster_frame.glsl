/* raster_frame.glsl: what every compute-rasterizer shader shares (mirrored
 * in src/raster/raster.c): the buffer bindings (common/bindings_raster.glsl)
 * and the frame's size uniforms. The visibility buffer is declared by each user, typed as it
 * needs it (raster.glsl: one 64-bit word or two uints per sample; the
 * start and the composite: uints, colour word first). */
#ifndef RASTER_FRAME_GLSL
#define RASTER_FRAME_GLSL

#include "common/bindings_raster.glsl"

uniform ivec2 u_raster_pixels; /* target size in pixels */
uniform int u_raster_samples;  /* per pixel: 1 or 4 */

#endif

/* bindings_raster.glsl: the compute rasterizer's binding numbers (C and
 * GLSL both include this file; only #define lines and comments, see
 * docs/DESIGN.md "Layout"). The visibility buffer and the queue sit at 20
 * and 21, above every slot a grass raster shader (bb_raster.comp,
 * blade_raster.comp) binds its own buffers on; the other slots belong to
 * the rasterizer's own passes (raster.c, app_floor.c). */
#ifndef BINDINGS_RASTER_GLSL
#define BINDINGS_RASTER_GLSL

/* raster.glsl, raster_init.comp, raster_resolve.glsl */
#define RASTER_BIND_VIS 20
#define RASTER_BIND_QUEUE 21
/* raster_init.comp: the target's depth in, the farthest opaque depth out */
#define RASTER_TEX_DEPTH 0
#define RASTER_IMG_OPAQUE 0
/* raster_composite.comp: the target's colour, read and written */
#define RASTER_IMG_TARGET 0
/* raster_args.comp: a GPU count in, dispatch arguments out */
#define RASTER_BIND_ARGS_SRC 0
#define RASTER_BIND_ARGS 1
/* raster_floor.comp: the compute floor's clip-space triangles */
#define RASTER_BIND_FLOOR_TRIS 0

#endif

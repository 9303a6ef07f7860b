/* bindings_hybrid.glsl: the binding numbers of the blade <-> billboard
 * hand-over buffers (common/slope.glsl, hybrid_slope.h), bound by both
 * grass modules: bb_draw.c and blade_tiles.c include this file, as the
 * shaders do through slope.glsl. Only #define lines and comments, so
 * valid C and GLSL (docs/DESIGN.md "Layout"). Slots above every
 * module-owned storage binding, below the rasterizer's. */
#ifndef BINDINGS_HYBRID_GLSL
#define BINDINGS_HYBRID_GLSL

#define HYBRID_BIND_SLOPE_MAP 13     /* the cells the blades' deformation wrote */
#define HYBRID_BIND_SLOPE_SUMS 14    /* fixed-point sums of one resolve */
#define HYBRID_BIND_SLOPE_BB_SUMS 15 /* the billboards' sums read when tiles start */

#endif

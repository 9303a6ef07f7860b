/* bindings_gfx.glsl: the binding numbers of gfx's own programs, for C
 * (gfx_depth.c) and GLSL (depth_nearest.comp) alike; only #define lines and
 * comments, so both compilers read it (docs/DESIGN.md "Layout"). */
#ifndef BINDINGS_GFX_GLSL
#define BINDINGS_GFX_GLSL

/* depth_nearest.comp: a multisampled depth texture in, a float a pixel out */
#define GFX_TEX_DEPTH 0
#define GFX_BIND_NEAREST 0

#endif

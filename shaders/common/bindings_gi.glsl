/* bindings_gi.glsl: the gi module's binding numbers, one #define each,
 * shared by GLSL (#include "common/bindings_gi.glsl") and C (the same
 * line: shaders/ is on the include path). Only #define lines and comments,
 * so the file is valid in both languages (docs/DESIGN.md "Layout").
 * The volumes read by common/gi.glsl and bound by gi_set_uniforms; the
 * irradiance's three units are consecutive and above every other module's. */
#ifndef BINDINGS_GI_GLSL
#define BINDINGS_GI_GLSL

#define GI_TEX_AO 12
#define GI_TEX_IRR0 13 /* a.rgb, Bx.r */
#define GI_TEX_IRR1 14 /* Bx.gb, By.rg */
#define GI_TEX_IRR2 15 /* By.b, Bz.rgb */

#endif

/* bindings_app.glsl: the binding numbers of the program's own shaders
 * (shaders/app), included as they are by app_terrain.c and terrain.frag;
 * only #define lines and comments, so valid C and GLSL
 * (docs/DESIGN.md "Layout"). */
#ifndef BINDINGS_APP_GLSL
#define BINDINGS_APP_GLSL

/* terrain.frag: the grass extent map that thins the ground canopy */
#define APP_TEX_EXTENT 0

#endif

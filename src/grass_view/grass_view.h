/* grass_view: the one view type of meadow, from the host's grass_draw
 * down to every driver (billboards, blades, tiles, ground) and their CPU
 * references: the host's view and projection, and what grass_view_make
 * (grass.h) derives from them. A module of this header alone, below the
 * drivers and the library; installed beside grass.h (grass.h includes
 * it); no other dependency. */
#ifndef MEADOW_GRASS_VIEW_H
#define MEADOW_GRASS_VIEW_H

#include <stdbool.h>

/* Towards the sun (normalised where used); the clump bakes light with it. */
#define GRASS_SUN_DIR {0.45f, 0.8f, 0.35f}

/* One draw's view: view and proj in, the rest filled by grass_view_make.
 * Two views may be drawn in one frame. */
typedef struct grass_view_t {
    _Alignas(16) float view[16]; /* 16-byte aligned, as SIMD matrix libraries (cglm) read them */
    _Alignas(16) float proj[16];
    _Alignas(16) float viewproj[16];
    _Alignas(16) float inv_viewproj[16];
    _Alignas(16) float planes[6][4]; /* frustum, inside when a*x+b*y+c*z+d >= 0 */
    float camera[3];    /* the eye (m) */
    float sun[3];       /* unit, towards the sun (GRASS_SUN_DIR) */
    float far;          /* the far plane (m) */
    int width, height;  /* the target's pixels */
    float time, dt;     /* simulated time of the draw (s), the frame's step */
    int overlay;        /* debug: 0 off, 1 tile and leaf state, 2 LOD, 3 collision strength */
    bool wireframe;     /* debug: the grass as lines, on the hardware path */
} grass_view_t;

#endif

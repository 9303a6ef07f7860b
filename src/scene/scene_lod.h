/* scene_lod: the hybrid's chain chosen by measurement. `meadow bench
 * --chart hybrid_canopy_distance` writes lod.json: per rasterizer path, of
 * the hybrid configurations it measured (switch and canopy distance, with
 * or without billboards), the one of least wall time whose image error
 * against the all-blade reference and GPU memory stay within the bench's
 * budgets (docs/HYBRID.md, "Switch distances by measurement"). A scene
 * names such a
 * table (grass.lod_table); the program reads it here and takes its choice
 * for the path it draws with, or with raster auto the cheaper path's, when
 * the table was measured on the same GL renderer (GL-free: the caller
 * passes the renderer string).
 *
 * lod.json: {"renderer": S, "scene": S, "budget": "...", "paths": {"hw": P,
 * "compute": P}} with P = {"switch_distance": m, "canopy_distance": m,
 * "gpu_ms": ms, "image_error": e, "budget": e, "met": bool, "label": S,
 * "candidates": n, "billboards": "ring" | "none", "wall_ms": ms}: the
 * chain of that path (blades to switch_distance, then billboards to
 * canopy_distance or, with "none", the canopy from the switch). */
#ifndef MEADOW_SCENE_LOD_H
#define MEADOW_SCENE_LOD_H

#include <stdbool.h>
#include <stddef.h>

#include "scene/scene.h"

typedef struct scene_lod_pick_t {
    bool present;                 /* the table has this path */
    float switch_distance;        /* m */
    float canopy_distance;        /* m */
    scene_hybrid_billboards_t billboards; /* "billboards": "ring" or "none" (absent: ring) */
    double wall_ms;               /* measured wall time per frame (absent: gpu_ms) */
    double gpu_ms, image_error;   /* measured at these distances */
    double budget;                /* the image error allowed (bench: BENCH_LOD_ERROR) */
    bool met;                     /* image_error <= budget (else: the least error within the memory) */
    int candidates;               /* hybrid configurations compared */
    char label[48];
} scene_lod_pick_t;

typedef struct scene_lod_t {
    char renderer[256];
    scene_lod_pick_t path[2]; /* 0 hardware, 1 compute */
} scene_lod_t;

/* Reads a lod.json. False with a message in err (file:line: what). */
bool scene_lod_read(scene_lod_t *t, const char *path, char *err, size_t err_size);

/* The pick for a GL renderer and path (0 hw, 1 compute, -1 auto: the
 * cheaper present path): NULL when the table was measured on another
 * renderer or lacks the path. *compute: the path taken. */
const scene_lod_pick_t *scene_lod_choose(const scene_lod_t *t, const char *renderer, int path, bool *compute);

/* grass.lod_table of s for GL renderer `renderer`: the switch and canopy
 * distances the bench measured for it and the path (*compute; with raster
 * auto the table's cheaper path, written back) replace the scene's before
 * anything is built. A table of another renderer, or one that cannot be
 * read, leaves the scene's with a warning. note gets what was chosen and
 * why (summary.txt). True when the table's distances were taken. */
bool scene_lod_apply(scene_desc_t *s, const char *renderer, bool *compute, char *note, size_t note_size);

#endif

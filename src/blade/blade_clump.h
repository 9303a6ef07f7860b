/* blade_clump: grass-clump images for the billboards of Orthmann et al.
 * 2009, drawn from the blade model of Jahrmann & Wimmer 2017, not
 * painted: each layer is a patch of the blade field seen from the front
 * (orthographic), its blades seeded as blade_seed seeds them (height,
 * width, stiffness and direction angle uniform in the scene's ranges),
 * settled under the program's gravity by the blade physics (blade_ref_step,
 * eq. 3-13, no wind: the billboards sway on their own) and rasterised on
 * the CPU from the C twin of blade_geom.glsl (blade_ref_surface, eq. 21 and
 * the scene's shape). A texel holds the blades' albedo, the root-to-tip mix
 * of blade_shade (unlit: bb_shade lights it), and their coverage as
 * straight alpha; see blade_clump.c for the rasteriser. With the views on
 * (bb_view.h, beyond the paper) each layer is baked once per view, its
 * blades bent by the scene's mean wind, and every view also holds its
 * blades' mean lit colour. GL-free: the billboards (bb_layout) allocate
 * the images, pick the views and upload the result. */
#ifndef MEADOW_BLADE_CLUMP_H
#define MEADOW_BLADE_CLUMP_H

#include <stdbool.h>
#include <stdint.h>

#include "blade/blade_population.h"
#include "core/core.h"

/* Clump rasteriser (blade_clump.c): samples per texel side, quads along a
 * blade, physics steps of BLADE_SETTLE_DT that settle a blade under
 * gravity (1.5 s: the slowest stiffness, 8, leaves e^-12 of the start),
 * texels kept clear at the layer's sides, the most blades a layer takes
 * (it logs a warning when it caps) and the program's sun. */
#define BLADE_CLUMP_SS 4
#define BLADE_CLUMP_SEGMENTS 16
#define BLADE_CLUMP_SETTLE_STEPS 90
#define BLADE_CLUMP_MARGIN 1.5f
#define BLADE_CLUMP_MAX_BLADES 4096
#define BLADE_CLUMP_SUN {0.45f, 0.8f, 0.35f}
/* Defaults the scene shares (SCENE_DEFAULT_BILLBOARD_* of
 * scene/scene_fields.h equal these; test_scene_defaults checks): a layer's
 * size (m, grass.billboard_size) and the cards per m^2 its depth assumes
 * (grass.billboard_density). */
#define BLADE_CLUMP_DEFAULT_WIDTH 1.0f
#define BLADE_CLUMP_DEFAULT_HEIGHT 0.6f
#define BLADE_CLUMP_DEFAULT_CARD_DENSITY 6.0f

/* The blades of the clump layers. Zero means default; defaults marked
 * (scene) are BLADE_CLUMP_DEFAULT_* above (scene key in brackets). */
typedef struct blade_clump_desc_t {
    float size[2];         /* metres a layer spans across and up: the billboard's base
                              size, default 1.0 x 0.6 (scene, grass.billboard_size).
                              Blades are drawn at their size in metres; when the
                              tallest settled blade of a layer reaches above 0.98 x
                              size[1], the layer's vertical scale shrinks so it fits */
    /* The blades (blade_population.h; the scene's): ranges, shape, albedo,
     * the gravity they settle under; the density sets bb_layout_desc_t.blades
     * when that is 0. */
    blade_population_t population;
    float wind;            /* strength of the scene's wind wave (blade_wind_wave); the blades
                              settle under its mean, half of it, default 0 (no wind: the
                              azimuth views differ only by the blades' turn) */
    float wind_dir[2];     /* the wind's xz direction in the world, default (1, 0) */
    float sun[3];          /* direction to the sun in the world (any length), default
                              BLADE_CLUMP_SUN, the program's sun (world.c) */
    float depth;           /* metres of field behind a card that its elevated views show (the
                              mean free path between cards, pi / (2 size[0] billboard
                              density)), default pi / (2 size[0] BLADE_CLUMP_DEFAULT_CARD_DENSITY) */
} blade_clump_desc_t;
blade_clump_desc_t blade_clump_desc_defaults(const blade_clump_desc_t *desc);

/* A clump layer's coverage calibration (blade_clump.c, "Coverage,
 * calibrated"): the blades it took (bake.blades, then more until its mean
 * alpha reaches the target), its mean alpha (covered samples) and the
 * target (mean over sample rows of min(T_row, 1), T the overlap count of
 * bake.blades blades). */
typedef struct blade_clump_stats_t {
    int blades;
    float alpha, target;
} blade_clump_stats_t;

/* One clump layer, baked for every view. Its blades come from the stream
 * (seed, 100 + layer) of core_rng; `blades` is the count before the
 * coverage calibration. views_on false: Orthmann's card, one front view
 * (angles (0, 0)) of blades whose roots spread over the layer's width in
 * depth, no wind; true: roots in [-depth, 0], bent by the wind. View v
 * (elevation angles[v][0], azimuth angles[v][1], radians, as bb_view
 * spreads them) goes to albedo[v stride], light[v stride] (allocated RGBA
 * images, all of one size) and stats[v stride]. */
typedef struct blade_clump_bake_t {
    uint32_t seed;
    int layer;
    int blades;
    bool views_on;
    int views;
    const float (*angles)[2];
    core_image_t *albedo, *light;
    blade_clump_stats_t *stats;
    int stride;
} blade_clump_bake_t;

/* Bakes the layer as the banner says (desc resolved here). False when out
 * of memory. */
bool blade_clump_bake(const blade_clump_desc_t *desc, const blade_clump_bake_t *bake);

#endif

/* blade_population: the one description of a population of Bezier blades
 * (Jahrmann & Wimmer 2017): how many per m^2, the uniform ranges their
 * height, width and stiffness are drawn from, the shape function of eq. 21
 * (sec. 6.3), their albedo from root to tip and the gravity they settle
 * under. The scene's "grass" keys fill one (scene_grass_desc_t.population);
 * the seeder (blade_seed), the tiled field (blade_tiles), the ground canopy
 * (blade_canopy) and the billboards' clump layers (blade_clump_desc_t) each
 * take it whole, so the two grass models draw the same blades.
 *
 * The BLADE_DEFAULT_* values are the program's: the scene keys' defaults
 * (scene_fields.c) and what a zero field resolves to. GL-free, no
 * includes. */
#ifndef MEADOW_BLADE_POPULATION_H
#define MEADOW_BLADE_POPULATION_H

/* Keys grass.density, grass.height, grass.width, grass.stiffness. */
#define BLADE_DEFAULT_DENSITY 200.0f
#define BLADE_DEFAULT_HEIGHT_MIN 0.35f
#define BLADE_DEFAULT_HEIGHT_MAX 0.7f
#define BLADE_DEFAULT_WIDTH_MIN 0.02f
#define BLADE_DEFAULT_WIDTH_MAX 0.05f
#define BLADE_DEFAULT_STIFFNESS_MIN 8.0f
#define BLADE_DEFAULT_STIFFNESS_MAX 12.0f
/* Not scene keys: the albedo at the root and at the tip (blade_shade, the
 * clump layers, the ground canopy), and the gravity of the program's blade
 * physics (m/s: the paper's forces are displacement rates; 1 m/s with
 * stiffness 8-12 bends a 0.5 m blade by ~0.1 m). */
#define BLADE_DEFAULT_ALBEDO_ROOT {0.10f, 0.25f, 0.05f}
#define BLADE_DEFAULT_ALBEDO_TIP {0.45f, 0.65f, 0.20f}
#define BLADE_DEFAULT_GRAVITY 1.0f

/* Blade shape functions of sec. 6.3 (key grass.shape): the width profile
 * f(v) of blade_ref_profile, and the GLSL's SHAPE_*. */
typedef enum blade_shape_t {
    BLADE_SHAPE_QUADRATIC = 0, /* "quadratic" (default) */
    BLADE_SHAPE_QUAD,          /* "quad" */
    BLADE_SHAPE_TRIANGLE,      /* "triangle" */
    BLADE_SHAPE_TRIANGLE_TIP,  /* "triangle_tip" */
    BLADE_SHAPE_DANDELION,     /* "dandelion" */
} blade_shape_t;

/* Zero means default (the BLADE_DEFAULT_* above):
 *   density      blades per m^2, 200 (a negative density is left as it is:
 *                the seeder refuses it)
 *   height       [min, max] m, [0.35, 0.7]; [0, 0] is the default
 *   width        [min, max] m, [0.02, 0.05]; [0, 0] is the default
 *   stiffness    [min, max] (1/s: recovery speed per metre of deflection,
 *                eq. 3), [8, 12]; [0, 0] is the default
 *   shape        quadratic (the enum's 0)
 *   albedo_root  (0, 0, 0): (0.10, 0.25, 0.05)
 *   albedo_tip   (0, 0, 0): (0.45, 0.65, 0.20)
 *   gravity      <= 0: 1 m/s */
typedef struct blade_population_t {
    float density;
    float height[2];
    float width[2];
    float stiffness[2];
    blade_shape_t shape;
    float albedo_root[3], albedo_tip[3];
    float gravity;
} blade_population_t;

/* *p with its zero fields resolved; p NULL: all defaults. */
blade_population_t blade_population_defaults(const blade_population_t *p);

#endif

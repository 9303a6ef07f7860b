/* bb_defaults: the billboard field's defaults (GL-free): what a zero field
 * of bb_field_desc_t takes, and what the scene file's billboard keys
 * default to (scene/scene_fields.h takes them from here). */
#ifndef MEADOW_BB_DEFAULTS_H
#define MEADOW_BB_DEFAULTS_H

#define BB_DEFAULT_DENSITY 6.0f        /* cards per m^2 (grass.billboard_density) */
#define BB_DEFAULT_WIDTH 1.0f          /* m (grass.billboard_size) */
#define BB_DEFAULT_HEIGHT 0.6f
#define BB_DEFAULT_SUBDIV 4            /* mesh cells per side (grass.subdiv) */
#define BB_SUBDIV_MIN 2                /* the geometry shader's output limits */
#define BB_SUBDIV_MAX 8
#define BB_DEFAULT_SPRING_ITERATIONS 2 /* grass.spring_iterations */
#define BB_DEFAULT_DEFORMED_POOL 4096  /* grass.deformed_pool */
#define BB_DEFAULT_CUBE_RESOLUTION 32  /* collision cube-map side (grass.cube_resolution) */
#define BB_DEFAULT_RECOVER_TIME 3.0f   /* s (grass.recover_time) */

#endif

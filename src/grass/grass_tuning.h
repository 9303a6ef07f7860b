/* grass_tuning: the knobs of a field that are not scene keys (the bench's
 * sweeps, the stability suite's paper variant), for in-tree hosts
 * (grass_host_t.tuning, world_setup_t.tuning). GL-free, no driver types. */
#ifndef MEADOW_GRASS_TUNING_H
#define MEADOW_GRASS_TUNING_H

#include <stdbool.h>
#include <stdint.h>

/* Knobs that are not scene-file fields (bench sweeps). Zero = default. */
typedef struct grass_tuning_t {
    int tess_max;            /* blade tessellation level cap; default the blade module's */
    unsigned cull_disable;   /* BLADE_CULL_* tests to skip */
    bool blade_cube_proxies; /* blades collide against depth cube maps instead of
                                sphere proxies (the set's cube proxies; not the tiles) */
    uint32_t placement_seed; /* seeds where grass stands instead of the scene seed: full-field
                                blades (blade_seed and the clearing thinning's draw) and
                                billboards (bb_field_desc_t.placement_seed); terrain,
                                clearings and clump textures keep the scene seed (not the
                                hybrid tiles). The image error's noise floor (docs/METRICS.md) */
    bool view_cards;         /* billboards' view-dependent clump cards (bb_view_desc_t.on) */
    bool paper;              /* both papers' methods as printed (the stability suite's paper
                                variant): blade_env_t.paper with eq. 12's length and the
                                paper's eta gain k = 1, bb_field_desc_t.paper, and no swept
                                colliders (the collide set's objects do not sweep) */
} grass_tuning_t;

#endif

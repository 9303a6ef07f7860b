/* gi_test_util: volumes for the global illumination render tests
 * (test_bb_gpu_gi, test_blade_render): a sky of one colour over open
 * ground below the box, uploaded (gi.h). A sky AMBIENT_UP with bounce
 * AMBIENT_DOWN is shade()'s hemispheric ambient exactly (a neutral
 * volume); a black one takes the ambient away. */
#ifndef MEADOW_GI_TEST_UTIL_H
#define MEADOW_GI_TEST_UTIL_H

#include "gi/gi.h"

#include <string.h>

static inline bool test_gi_sky(gi_gpu_t *g, const float lo[3], const float hi[3], const float sky[3],
                               const float bounce[3])
{
    gi_volume_desc_t d = {.res = {8, 4, 8}};
    memcpy(d.lo, lo, sizeof d.lo);
    memcpy(d.hi, hi, sizeof d.hi);
    memcpy(d.sky_zenith, sky, sizeof d.sky_zenith);
    memcpy(d.sky_horizon, sky, sizeof d.sky_horizon);
    memcpy(d.bounce, bounce, sizeof d.bounce);
    gi_volume_t v;
    if (!gi_volume_make(&v, &d, &(gi_scene_t){0})) return false;
    bool ok = gi_gpu_make(g, &v);
    gi_volume_free(&v);
    return ok;
}

#endif

/* collide_test_util: collide sets for the grass tests. */
#ifndef MEADOW_COLLIDE_TEST_UTIL_H
#define MEADOW_COLLIDE_TEST_UTIL_H

#include <string.h>

#include "collide/collide_set.h"

/* A collide set of resting spheres only (xyz centre, radius; zero sweep;
 * one static set, rebuilt by every call). */
static inline const collide_set_t *test_sphere_set(const float (*spheres)[4], int n)
{
    static collide_set_t set;
    collide_begin_set(&set);
    set.sphere_count = n;
    for (int i = 0; i < n; i++)
        set.spheres[i] =
            (collide_sphere_t){.centre_radius = {spheres[i][0], spheres[i][1], spheres[i][2], spheres[i][3]}};
    return &set;
}

/* The same with each sphere's sweep (xyz previous centre - centre). */
static inline const collide_set_t *test_swept_set(const float (*spheres)[4], const float (*sweeps)[3], int n)
{
    const collide_set_t *c = test_sphere_set(spheres, n);
    collide_set_t *set = (collide_set_t *)c;
    for (int i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) set->spheres[i].sweep[k] = sweeps[i][k];
    return c;
}

#endif

/* collide_test_util: collide sets for the grass tests. */
#ifndef MEADOW_COLLIDE_TEST_UTIL_H
#define MEADOW_COLLIDE_TEST_UTIL_H

#include <string.h>

#include "collide/collide_set.h"

/* A collide set of spheres only (xyz centre, radius; one static set,
 * rebuilt by every call). */
static inline const collide_set_t *test_sphere_set(const float (*spheres)[4], int n)
{
    static collide_set_t set;
    collide_begin_set(&set);
    set.sphere_count = n;
    memcpy(set.spheres, spheres, (size_t)n * sizeof set.spheres[0]);
    return &set;
}

#endif

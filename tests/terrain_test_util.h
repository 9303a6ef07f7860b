/* terrain_test_util: terrain meshes for the grass tests. */
#ifndef MEADOW_TERRAIN_TEST_UTIL_H
#define MEADOW_TERRAIN_TEST_UTIL_H

#include "terrain/terrain.h"

/* Flattens a heightfield made by terrain_make_heightfield to y = 0, normals
 * up, its box with it (the grid and the triangles kept). */
static inline void test_terrain_flatten(terrain_mesh_t *m)
{
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        m->positions[3 * v + 1] = 0.0f;
        m->normals[3 * v + 0] = m->normals[3 * v + 2] = 0.0f;
        m->normals[3 * v + 1] = 1.0f;
    }
    m->aabb_min[1] = m->aabb_max[1] = 0.0f;
}

#endif

/* collide_shape: what the grass models know of the scene's analytic
 * colliders (sphere, capsule, box; scene_collider_t): triangle meshes for
 * drawing them and rendering them into GPU cube maps, CPU cube maps
 * (collide_cube.h), sphere proxies for the blade physics (Jahrmann & Wimmer
 * 2017 collide with spheres only), bounding spheres, and the exact signed
 * distance for accuracy metrics. Every function takes the collider at the
 * origin of its object space (its centre); the scene places it. GL-free. */
#ifndef MEADOW_COLLIDE_SHAPE_H
#define MEADOW_COLLIDE_SHAPE_H

#include <stdbool.h>
#include <stdint.h>

#include "collide/collide_cube.h"
#include "scene/scene.h"

typedef struct collide_mesh_t {
    float *positions; /* xyz, object space (centred on the origin) */
    float *normals;   /* xyz, unit */
    uint32_t *indices;
    uint32_t vertex_count, index_count;
} collide_mesh_t;

/* Mesh of a collider at the origin: sphere (UV sphere, 24x16), capsule
 * (vertical, hemispherical caps), box (24 vertices, flat normals). */
bool collide_make_mesh(collide_mesh_t *m, const scene_collider_t *c);
void collide_free_mesh(collide_mesh_t *m);

/* Exact signed distance from p (object space, relative to the centre) to
 * the collider surface: negative inside. */
float collide_signed_distance(const scene_collider_t *c, const float p[3]);
/* Radius of the bounding sphere around the centre. */
float collide_bounding_radius(const scene_collider_t *c);

/* Rasterises the collider, centred on the cube-space origin, into cube
 * (collide_render_sphere / _capsule / _box; depth-tested like them). */
void collide_render_shape(collide_cubemap_t *cube, const scene_collider_t *c);

/* Sphere proxies (xyz centre, radius) of the collider centred at `position`
 * (world): a sphere exactly; a capsule as 1 + ceil(length / radius)
 * spheres of its radius evenly along the axis (ends on the cap centres,
 * overlapping; one sphere when length is 0, at most
 * 1 + COLLIDE_PACK_SATURATED, which a radius of 0 takes); a box by its
 * bounding sphere (conservative). Writes at most max and returns the number
 * needed. */
#define COLLIDE_PACK_SATURATED 1000000000

int collide_pack_spheres(const scene_collider_t *c, const float position[3], float (*out)[4], int max);

#endif

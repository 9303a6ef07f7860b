/* collide_shape: what the grass models know of an analytic collider
 * (sphere, capsule, box; collide_shape_t, which the scene's colliders and
 * the library's host colliders are turned into): triangle meshes for
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

typedef enum collide_shape_type_t {
    COLLIDE_SHAPE_SPHERE = 0, /* radius */
    COLLIDE_SHAPE_CAPSULE,    /* radius, length: a vertical segment */
    COLLIDE_SHAPE_BOX,        /* half_extents, axis aligned */
} collide_shape_type_t;

/* A collider's shape, its centre at the origin; sizes in metres, as given
 * (no defaults: scene_collider_shape passes the scene's resolved ones). */
typedef struct collide_shape_t {
    collide_shape_type_t type;
    float radius;
    float length;
    float half_extents[3];
} collide_shape_t;

typedef struct collide_mesh_t {
    float *positions; /* xyz, object space (centred on the origin) */
    float *normals;   /* xyz, unit */
    uint32_t *indices;
    uint32_t vertex_count, index_count;
} collide_mesh_t;

/* Mesh of a collider at the origin: sphere (UV sphere, 24x16), capsule
 * (vertical, hemispherical caps), box (24 vertices, flat normals). */
bool collide_make_mesh(collide_mesh_t *m, const collide_shape_t *c);
void collide_free_mesh(collide_mesh_t *m);

/* Exact signed distance from p (object space, relative to the centre) to
 * the collider surface: negative inside. */
float collide_signed_distance(const collide_shape_t *c, const float p[3]);
/* Radius of the bounding sphere around the centre. */
float collide_bounding_radius(const collide_shape_t *c);

/* Rasterises the collider, centred on the cube-space origin, into cube
 * (collide_render_sphere / _capsule / _box; depth-tested like them). */
void collide_render_shape(collide_cubemap_t *cube, const collide_shape_t *c);

/* Sphere proxies (xyz centre, radius) of the collider centred at `position`
 * (world): a sphere exactly; a capsule as 1 + ceil(length / radius)
 * spheres of its radius evenly along the axis (ends on the cap centres,
 * overlapping; one sphere when length is 0, at most
 * 1 + COLLIDE_PACK_SATURATED, which a radius of 0 takes); a box by its
 * bounding sphere (conservative). Writes at most max and returns the number
 * needed. */
#define COLLIDE_PACK_SATURATED 1000000000

int collide_pack_spheres(const collide_shape_t *c, const float position[3], float (*out)[4], int max);

#endif

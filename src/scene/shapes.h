/* shapes: triangle meshes of the analytic colliders (sphere, capsule, box)
 * for drawing them and rendering them into collision cube maps, and their
 * exact signed distance for accuracy metrics. GL-free. */
#ifndef MEADOW_SCENE_SHAPES_H
#define MEADOW_SCENE_SHAPES_H

#include <stdbool.h>
#include <stdint.h>

#include "scene/scene.h"

typedef struct shape_mesh_t {
    float *positions; /* xyz, object space (centred on the origin) */
    float *normals;   /* xyz, unit */
    uint32_t *indices;
    uint32_t vertex_count, index_count;
} shape_mesh_t;

/* Mesh of a collider at the origin: sphere (UV sphere, 24x16), capsule
 * (vertical, hemispherical caps), box (24 vertices, flat normals). */
bool shape_mesh_make(shape_mesh_t *m, const scene_collider_t *c);
void shape_mesh_free(shape_mesh_t *m);

/* Exact signed distance from p (object space, relative to the centre) to
 * the collider surface: negative inside. */
float shape_signed_distance(const scene_collider_t *c, const float p[3]);
/* Radius of the bounding sphere around the centre. */
float shape_bounding_radius(const scene_collider_t *c);

#endif

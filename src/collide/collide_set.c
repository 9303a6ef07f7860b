/* collide_set: building the per-step collide set (see collide_set.h). */
#include "collide/collide_set.h"

#include <string.h>

void collide_begin_set(collide_set_t *set)
{
    set->prev_count = set->object_count;
    set->object_count = 0;
    set->sphere_count = 0;
    set->cube_count = 0;
    set->cube_texture = 0;
    set->cube_res = 0;
    set->cube_maps = NULL;
}

collide_object_t *collide_add_object(collide_set_t *set, const collide_object_t *obj, float dt)
{
    if (set->object_count == COLLIDE_MAX_OBJECTS) return NULL;
    int k = set->object_count++;
    collide_object_t *o = &set->objects[k];
    vec3 prev;
    glm_vec3_copy(o->position, prev);
    bool moved = k < set->prev_count && dt > 0.0f;
    *o = *obj;
    mat4 model;
    memcpy(model, o->model, sizeof model);
    glm_mat4_mulv3(model, o->centre, 1.0f, o->position);
    glm_vec3_copy(moved ? prev : o->position, o->prev_position);
    for (int i = 0; i < 3; i++) o->velocity[i] = moved ? (o->position[i] - prev[i]) / dt : 0.0f;
    return o;
}

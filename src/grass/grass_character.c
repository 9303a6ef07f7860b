/* grass_character: the library's walking characters (grass_character.h)
 * over src/character's set of one, in the field's gfx context; and the
 * collider any character instance is to the grass (also the world's). */
#include "grass/grass_character.h"

#include "grass/grass_local.h"

#include <stdlib.h>
#include <string.h>

#include "character/character.h"
#include "scene/scene_fields.h"

struct grass_character_t {
    grass_t *grass;
    scene_character_t desc;
    character_set_t set;
};

grass_collider_t grass_character_collider_of(const character_instance_t *inst)
{
    character_object_t co;
    character_bb_object(inst, &co);
    grass_collider_t c = {.shape = GRASS_SHAPE_SPHERES, .spheres = (const float (*)[4])inst->spheres,
                          .sphere_count = inst->sphere_count, .bound_radius = inst->radius, .vao = co.vao,
                          .index_type = co.index_type, .index_count = co.index_count};
    memcpy(c.position, inst->centre, sizeof c.position);
    memcpy(c.model, co.model, sizeof c.model);
    /* the collider's centre is in the model's space, the character's in the world */
    mat4 model, inv;
    memcpy(model, co.model, sizeof model);
    glm_mat4_inv(model, inv);
    glm_mat4_mulv3(inv, co.centre, 1.0f, c.centre);
    return c;
}

grass_character_t *grass_character_make(grass_t *g, const grass_character_desc_t *d)
{
    if (!d->model || !d->model[0] || d->waypoint_count < 0 || d->waypoint_count > SCENE_MAX_PATH_KEYS) {
        core_log_error("grass_character_make: %s", !d->model || !d->model[0] ? "no model" : "too many waypoints");
        return NULL;
    }
    grass_character_t *c = calloc(1, sizeof *c);
    if (!c) return NULL;
    c->grass = g;
    scene_character_t *s = &c->desc;
    if (!core_fs_resolve(d->model, s->model, sizeof s->model)) snprintf(s->model, sizeof s->model, "%s", d->model);
    if (d->clip) snprintf(s->clip_name, sizeof s->clip_name, "%s", d->clip);
    s->clip_index = d->clip ? -1 : 0;
    s->speed = d->speed > 0.0f ? d->speed : SCENE_DEFAULT_WALK_SPEED;
    s->scale = SCENE_DEFAULT_CHARACTER_SCALE;
    s->height = d->height;
    s->waypoint_count = d->waypoint_count;
    for (int i = 0; i < d->waypoint_count; i++) memcpy(s->waypoints[i], d->waypoints[i], sizeof s->waypoints[i]);
    s->loop = d->loop;
    gfx_ctx_t *prev = grass_enter(g);
    bool ok = character_set_make(&c->set, &(character_set_desc_t){.characters = s, .count = 1,
                                                                   .terrain = g->terrain, .capsules = 8});
    grass_leave(prev);
    if (!ok) {
        free(c);
        return NULL;
    }
    return c;
}

void grass_character_update(grass_character_t *c, float t, float dt)
{
    gfx_ctx_t *prev = grass_enter(c->grass);
    character_set_update(&c->set, t, dt);
    grass_leave(prev);
}

grass_collider_t grass_character_collider(const grass_character_t *c)
{
    return grass_character_collider_of(&c->set.items[0]);
}

void grass_character_draw(const grass_character_t *c, const grass_view_t *v)
{
    gfx_ctx_t *prev = grass_enter(c->grass);
    character_set_draw(&c->set, v->viewproj, v->camera, v->sun);
    grass_leave(prev);
}

void grass_character_destroy(grass_character_t *c)
{
    if (!c) return;
    gfx_ctx_t *prev = grass_enter(c->grass);
    character_set_destroy(&c->set);
    grass_leave(prev);
    free(c);
}

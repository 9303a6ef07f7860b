/* grass_update: one step of the grass. The host's colliders become the
 * step's collide set (objects for the billboards' cube maps, the first
 * GRASS_MAX_COLLIDERS, with a warning past them; sphere proxies for the
 * blades), then every grass system takes it: the billboards, the blade
 * field or its tiles. */
#include "grass/grass_local.h"

#include <string.h>

#include "collide/collide_shape.h"
#include "platform/plat.h"

/* The analytic shape of a collider (no path: it stands at its position). */
static collide_shape_t shape_of(const grass_collider_t *c)
{
    static const collide_shape_type_t types[] = {[GRASS_SHAPE_SPHERE] = COLLIDE_SHAPE_SPHERE,
                                                 [GRASS_SHAPE_CAPSULE] = COLLIDE_SHAPE_CAPSULE,
                                                 [GRASS_SHAPE_BOX] = COLLIDE_SHAPE_BOX};
    collide_shape_t s = {.type = types[c->shape], .radius = c->radius, .length = c->length};
    memcpy(s.half_extents, c->half_extents, sizeof s.half_extents);
    return s;
}

static float bound_radius(const grass_collider_t *c)
{
    if (c->shape == GRASS_SHAPE_SPHERES) return c->bound_radius;
    collide_shape_t s = shape_of(c);
    return collide_bounding_radius(&s);
}

/* The step's objects: each collider with its mesh (vao 0: none, the blades
 * alone take it), the first GRASS_MAX_COLLIDERS. The set keeps the
 * previous step's at the same index for the sweep. */
static void add_objects(grass_t *g, const grass_collider_t *c, int count, float dt)
{
    collide_set_t *set = &g->collide;
    for (int i = 0; i < count && i < GRASS_MAX_COLLIDERS; i++) {
        collide_object_t o = {.radius = bound_radius(&c[i]), .vao = c[i].vao, .index_count = c[i].index_count,
                              .index_type = c[i].index_type};
        if (c[i].vao) {
            memcpy(o.model, c[i].model, sizeof o.model);
            memcpy(o.centre, c[i].centre, sizeof o.centre);
        } else {
            mat4 m;
            glm_translate_make(m, (float *)c[i].position);
            memcpy(o.model, m, sizeof o.model);
        }
        collide_add_object(set, &o, dt);
    }
}

/* Colliders past the collide set: warned once per count past it (a host
 * that keeps giving 130 hears it once, again when it gives 131). */
static void report_over(grass_t *g, int count)
{
    if (count <= GRASS_MAX_COLLIDERS) {
        g->colliders_warned = 0;
        return;
    }
    if (count == g->colliders_warned) return;
    g->colliders_warned = count;
    core_log_warn("grass_update: %d colliders given, the collide set holds %d (GRASS_MAX_COLLIDERS); colliders "
                  "%d..%d bend blades only (sphere proxies without a sweep), not billboards",
                  count, GRASS_MAX_COLLIDERS, GRASS_MAX_COLLIDERS + 1, count);
}

/* Within reach of the camera (horizontally; reach 0: everywhere)? */
static bool near_camera(const grass_t *g, const grass_collider_t *c, float reach)
{
    if (reach <= 0.0f) return true;
    float dx = c->position[0] - g->camera[0], dz = c->position[2] - g->camera[2], r = reach + c->bound_radius;
    return dx * dx + dz * dz <= r * r;
}

/* A sphere set's spheres into out (at most room of them), unswept; how
 * many went in. */
static int copy_spheres(const grass_collider_t *c, collide_sphere_t *out, int room)
{
    int got = c->sphere_count < room ? c->sphere_count : room;
    for (int k = 0; k < got; k++)
        out[k] = (collide_sphere_t){
            .centre_radius = {c->spheres[k][0], c->spheres[k][1], c->spheres[k][2], c->spheres[k][3]}};
    return got;
}

/* The step's travel of object o backwards (previous - current centre; no
 * object: none). */
static void object_sweep(const collide_object_t *o, float sweep[4])
{
    for (int a = 0; a < 3; a++) sweep[a] = o ? o->prev_position[a] - o->position[a] : 0.0f;
    sweep[3] = 0.0f;
}

/* Sphere proxies for the blade physics: each shape packed by
 * collide_pack_spheres with its object's sweep, each sphere set within
 * reach of the camera as it is. Admission (grass_admit) keeps a scene's
 * within BLADE_MAX_SPHERES; past them (a world's characters, which it
 * cannot count: only those near the camera are packed) the rest is
 * counted in *dropped. */
static int blade_spheres(grass_t *g, const grass_collider_t *c, int count, collide_sphere_t *out, int max,
                         int *dropped)
{
    static float packed[BLADE_MAX_SPHERES][4];
    float reach = grass_collider_reach(g);
    int n = 0;
    for (int i = 0; i < count; i++) {
        if (c[i].shape == GRASS_SHAPE_SPHERES) {
            if (!near_camera(g, &c[i], reach)) continue;
            int got = copy_spheres(&c[i], out + n, max - n);
            n += got;
            *dropped += c[i].sphere_count - got;
            continue;
        }
        collide_shape_t s = shape_of(&c[i]);
        int want = collide_pack_spheres(&s, c[i].position, packed, max - n);
        int got = want < max - n ? want : max - n;
        const collide_object_t *o = i < g->collide.object_count ? &g->collide.objects[i] : NULL;
        for (int k = 0; k < got; k++) {
            memcpy(out[n + k].centre_radius, packed[k], sizeof packed[k]);
            object_sweep(o, out[n + k].sweep);
        }
        n += got;
        *dropped += want - got;
    }
    return n;
}

/* Sphere proxies that did not fit this step: counted
 * ("grass.spheres_dropped", summary.txt's counts) and warned at every
 * step that drops some. */
static void report_dropped(int dropped, int kept)
{
    if (dropped <= 0) return;
    gfx_count_add("grass.spheres_dropped", dropped);
    core_log_warn("grass: %d of %d sphere proxies left out of this step's blade physics (it takes at most %d, "
                  "BLADE_MAX_SPHERES): the colliders or characters near the camera beyond them bend no blades",
                  dropped, dropped + kept, BLADE_MAX_SPHERES);
}

/* Cube-map proxies of the blade physics (tuning.blade_cube_proxies; beyond
 * both papers), into the collide set. With the billboard field: its cube
 * maps of the set's objects as rendered by this step's bb_field_update
 * (bb_field_lend_cubes). Blade mode (no field): the shape colliders
 * rasterised once on the CPU (collide_render_shape) at the cube
 * resolution, the first BLADE_MAX_CUBES of them; further colliders by
 * their bounding sphere and sphere sets as they are. */
static void blade_cube_proxies(grass_t *g, const grass_collider_t *c, int count, int *dropped)
{
    collide_set_t *set = &g->collide;
    if (g->bb) {
        bb_field_lend_cubes(g->bb, set);
        return;
    }
    int nc = 0;
    while (nc < count && nc < BLADE_MAX_CUBES && c[nc].shape != GRASS_SHAPE_SPHERES) nc++;
    if (nc > 0 && !g->blade_cubes) {
        collide_cubemap_t cubes[BLADE_MAX_CUBES];
        int made = 0;
        for (; made < nc; made++) {
            collide_shape_t s = shape_of(&c[made]);
            if (!collide_init_cubemap(&cubes[made], g->cube_res, (vec3){0, 0, 0}, bound_radius(&c[made]))) break;
            collide_render_shape(&cubes[made], &s);
        }
        if (made == nc) g->blade_cubes = blade_gpu_upload_cubes(g->blades, cubes, nc);
        for (int k = 0; k < made; k++) collide_free_cubemap(&cubes[k]);
    }
    if (!g->blade_cubes) nc = 0;
    for (int k = 0; k < nc; k++) {
        mat4 model;
        glm_translate_make(model, (float *)c[k].position);
        collide_make_cube_proxy((const float *)model, (vec3){0, 0, 0}, bound_radius(&c[k]),
                                &set->cubes[set->cube_count++]);
    }
    set->cube_texture = g->blade_cubes;
    set->cube_res = g->cube_res;
    for (int k = nc; k < count; k++) {
        if (c[k].shape == GRASS_SHAPE_SPHERES) {
            int got = copy_spheres(&c[k], set->spheres + set->sphere_count, BLADE_MAX_SPHERES - set->sphere_count);
            set->sphere_count += got;
            *dropped += c[k].sphere_count - got;
            continue;
        }
        if (set->sphere_count == BLADE_MAX_SPHERES) {
            ++*dropped;
            continue;
        }
        collide_sphere_t *s = &set->spheres[set->sphere_count++];
        *s = (collide_sphere_t){.centre_radius = {c[k].position[0], c[k].position[1], c[k].position[2],
                                                  bound_radius(&c[k])}};
        object_sweep(k < set->object_count ? &set->objects[k] : NULL, s->sweep);
    }
}

void grass_prime_colliders(grass_t *g, const grass_collider_t *colliders, int count)
{
    collide_begin_set(&g->collide);
    add_objects(g, colliders, count, 0.0f);
    g->stepped = true;
}

/* Adds the CPU ms since *mark to update part k and restarts the mark. */
static void update_part(grass_t *g, int k, double *mark)
{
    double now = plat_time();
    g->update_ms[k] = (now - *mark) * 1e3;
    *mark = now;
}

void grass_update(grass_t *g, const grass_collider_t *colliders, int count, float t, float dt)
{
    gfx_ctx_t *prev = grass_enter(g);
    double mark = plat_time();
    if (g->views > 0) {
        for (int k = 0; k < 3; k++) g->camera[k] = g->view_camera[k];
        g->views = 0;
    }
    collide_set_t *set = &g->collide;
    collide_begin_set(set);
    add_objects(g, colliders, count, dt);
    report_over(g, count);
    g->stepped = true;
    /* The papers' colliders stand where they are at each step (no sweep). */
    for (int i = 0; i < set->object_count && g->tuning.paper; i++)
        memcpy(set->objects[i].prev_position, set->objects[i].position, sizeof set->objects[i].prev_position);
    if (g->bb) {
        /* The hybrid draws no billboard nearer than its fade band: objects
         * there bend the blades alone (unless the blades borrow the
         * billboards' cube maps). */
        bool hide = g->mode == SCENE_MODE_HYBRID && !g->reference && g->drawn && !g->tuning.blade_cube_proxies;
        bb_field_set_hidden(g->bb, g->camera, hide ? g->scene->grass.switch_distance - GRASS_SWITCH_FADE : 0.0f);
        bb_field_update(g->bb, set, t, dt);
    }
    update_part(g, 0, &mark);
    if (g->have_blades || g->have_tiles) {
        blade_env_t *env = &g->blade_env;
        env->dt = dt;
        env->time = t;
        int dropped = 0;
        if (g->tuning.blade_cube_proxies && g->have_blades) blade_cube_proxies(g, colliders, count, &dropped);
        else set->sphere_count = blade_spheres(g, colliders, count, set->spheres, BLADE_MAX_SPHERES, &dropped);
        report_dropped(dropped, set->sphere_count);
        update_part(g, 1, &mark);
        if (g->have_blades) blade_gpu_update(g->blades, env, set);
        if (g->have_tiles) blade_tiles_update(g->tiles, g->camera, set, env);
    }
    update_part(g, 2, &mark);
    grass_leave(prev);
}

void grass_update_spheres(grass_t *g, const collide_sphere_t *spheres, int count, float t, float dt)
{
    blade_env_t *env = &g->blade_env;
    env->dt = dt;
    env->time = t;
    collide_begin_set(&g->collide);
    g->collide.sphere_count = count < BLADE_MAX_SPHERES ? count : BLADE_MAX_SPHERES;
    report_dropped(count - g->collide.sphere_count, g->collide.sphere_count);
    memcpy(g->collide.spheres, spheres, (size_t)g->collide.sphere_count * sizeof *spheres);
    blade_gpu_update(g->blades, env, &g->collide);
}

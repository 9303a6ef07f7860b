/* scene: strict JSON -> scene_desc_t with file:line:field errors (see
 * scene.h), defaults, and the initial camera. */
#include "scene/scene.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "scene/scene_json.h"

typedef scene_json_t json_t;

static const char *const mode_names[] = {"hybrid", "billboard", "blade"};
static const char *const raster_names[] = {"hw", "compute", "auto"};
static const char *const shape_names[] = {"quadratic", "quad", "triangle", "triangle_tip",
                                          "dandelion"};
static const char *const terrain_names[] = {"heightfield", "mesh"};
static const char *const wind_names[] = {"directional", "point"};
static const char *const collider_names[] = {"sphere", "capsule", "box"};

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))

/* ---- defaults ------------------------------------------------------------ */

static void pair_default(float *v, float lo, float hi)
{
    if (v[0] == 0 && v[1] == 0) {
        v[0] = lo;
        v[1] = hi;
    }
}

void scene_desc_defaults(scene_desc_t *d)
{
    if (d->frames <= 0) d->frames = 300;
    if (d->dt <= 0) d->dt = 1.0f / 60.0f;
    if (d->size[0] <= 0) d->size[0] = 1280;
    if (d->size[1] <= 0) d->size[1] = 720;
    if (d->msaa <= 0) d->msaa = 4;
    d->terrain = terrain_desc_defaults(&d->terrain);

    scene_grass_desc_t *g = &d->grass;
    if (g->density <= 0) g->density = 200.0f;
    pair_default(g->height, 0.35f, 0.7f);
    pair_default(g->width, 0.02f, 0.05f);
    pair_default(g->stiffness, 8.0f, 12.0f);
    if (g->billboard_density <= 0) g->billboard_density = 6.0f;
    if (g->billboard_size[0] <= 0) g->billboard_size[0] = 1.0f;
    if (g->billboard_size[1] <= 0) g->billboard_size[1] = 0.6f;
    if (g->switch_distance <= 0) g->switch_distance = 12.0f;
    if (g->tile_size <= 0) g->tile_size = 4.0f;
    if (g->subdiv[0] <= 0) g->subdiv[0] = 4;
    if (g->subdiv[1] <= 0) g->subdiv[1] = 4;
    if (g->spring_iterations <= 0) g->spring_iterations = 2;
    if (g->cube_resolution <= 0) g->cube_resolution = 32;
    if (g->recover_time <= 0) g->recover_time = 3.0f;

    scene_camera_desc_t *c = &d->camera;
    if (c->fov <= 0) c->fov = 60.0f;
    if (c->near <= 0) c->near = 0.1f;
    if (c->far <= 0) c->far = 200.0f;
    if (glm_vec3_eq(c->position, 0.0f) && glm_vec3_eq(c->target, 0.0f)) {
        c->position[1] = 8.0f;
        c->position[2] = 24.0f;
    }

    for (int i = 0; i < d->wind_count; i++) {
        scene_wind_t *w = &d->wind[i];
        if (w->strength <= 0) w->strength = 1.0f;
        if (w->type == SCENE_WIND_DIRECTIONAL) {
            float len = hypotf(w->direction[0], w->direction[1]);
            if (len > 0) {
                w->direction[0] /= len;
                w->direction[1] /= len;
            } else {
                w->direction[0] = 1.0f;
                w->direction[1] = 0.0f;
            }
            if (w->wavelength <= 0) w->wavelength = 10.0f;
            if (w->speed <= 0) w->speed = 2.0f;
        } else if (w->radius <= 0) {
            w->radius = 5.0f;
        }
    }
    for (int i = 0; i < d->collider_count; i++) {
        scene_collider_t *c2 = &d->colliders[i];
        if (c2->radius <= 0) c2->radius = c2->type == SCENE_COLLIDER_CAPSULE ? 0.3f : 0.5f;
        if (c2->length <= 0) c2->length = 1.0f;
        for (int k = 0; k < 3; k++)
            if (c2->half_extents[k] <= 0) c2->half_extents[k] = 0.5f;
    }
    for (int i = 0; i < d->character_count; i++) {
        scene_character_t *ch = &d->characters[i];
        if (ch->speed <= 0) ch->speed = 1.2f;
        if (ch->scale <= 0) ch->scale = 1.0f;
    }
}

void scene_free(scene_desc_t *d) { memset(d, 0, sizeof *d); }

void scene_camera_init(const scene_desc_t *d, cam_t *cam)
{
    *cam = (cam_t){
        .fov = d->camera.fov,
        .near = d->camera.near,
        .far = d->camera.far,
        .aspect = d->size[1] > 0 ? (float)d->size[0] / (float)d->size[1] : 0.0f,
    };
    glm_vec3_copy((float *)d->camera.position, cam->position);
    glm_vec3_copy((float *)d->camera.target, cam->target);
    cam_path_eval(&d->camera.path, 0.0f, cam);
    cam_defaults(cam);
}

const char *scene_mode_name(scene_mode_t mode) { return mode_names[mode]; }
const char *scene_raster_name(scene_raster_t raster) { return raster_names[raster]; }

bool scene_raster_parse(const char *name, scene_raster_t *out)
{
    for (int i = 0; i < (int)COUNT(raster_names); i++)
        if (strcmp(name, raster_names[i]) == 0) {
            *out = (scene_raster_t)i;
            return true;
        }
    return false;
}
const char *scene_blade_shape_name(scene_blade_shape_t shape) { return shape_names[shape]; }

/* ---- parse helpers --------------------------------------------------------
 * Every helper takes the dotted field path for messages and returns false
 * after writing the first error. */

typedef struct sp_t {
    const char *name;
    char *err;
    size_t err_size;
} sp_t;

__attribute__((format(printf, 4, 5))) static bool sp_fail(sp_t *sp, int line, const char *field,
                                                          const char *fmt, ...)
{
    if (!sp->err || !sp->err_size) return false;
    int n = snprintf(sp->err, sp->err_size, "%s:%d: field \"%s\": ", sp->name, line, field);
    if (n < 0 || (size_t)n >= sp->err_size) return false;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(sp->err + n, sp->err_size - (size_t)n, fmt, ap);
    va_end(ap);
    return false;
}

/* parent.key, or parent[index] when key is NULL. Field paths longer than
 * the buffer are cut (they only label messages). */
static const char *field_join(char *buf, size_t size, const char *parent, const char *key, int index)
{
    int n;
    if (!key) n = snprintf(buf, size, "%s[%d]", parent, index);
    else if (parent[0]) n = snprintf(buf, size, "%s.%s", parent, key);
    else n = snprintf(buf, size, "%s", key);
    if (n < 0 || (size_t)n >= size) buf[size - 1] = 0;
    return buf;
}

static bool want(sp_t *sp, const json_t *v, const char *field, scene_json_type_t type)
{
    if (v->type == type) return true;
    return sp_fail(sp, v->line, field, "expected %s, got %s", scene_json_type_name(type),
                   scene_json_type_name(v->type));
}

static bool get_double(sp_t *sp, const json_t *v, const char *field, double lo, double hi,
                       bool integer, double *out)
{
    if (!want(sp, v, field, SCENE_JSON_NUMBER)) return false;
    if (integer && v->number != floor(v->number))
        return sp_fail(sp, v->line, field, "expected an integer, got %g", v->number);
    if (v->number < lo || v->number > hi)
        return sp_fail(sp, v->line, field, "%g is out of range [%g, %g]", v->number, lo, hi);
    *out = v->number;
    return true;
}

static bool get_float(sp_t *sp, const json_t *v, const char *field, double lo, double hi, float *out)
{
    double d = 0;
    if (!get_double(sp, v, field, lo, hi, false, &d)) return false;
    *out = (float)d;
    return true;
}

static bool get_int(sp_t *sp, const json_t *v, const char *field, double lo, double hi, int *out)
{
    double d = 0;
    if (!get_double(sp, v, field, lo, hi, true, &d)) return false;
    *out = (int)d;
    return true;
}

static bool get_bool(sp_t *sp, const json_t *v, const char *field, bool *out)
{
    if (!want(sp, v, field, SCENE_JSON_BOOL)) return false;
    *out = v->boolean;
    return true;
}

/* Array of exactly n numbers in [lo, hi]; integers when ints != NULL. */
static bool get_vec(sp_t *sp, const json_t *v, const char *field, int n, double lo, double hi,
                    float *floats, int *ints)
{
    if (!want(sp, v, field, SCENE_JSON_ARRAY)) return false;
    if (v->count != n)
        return sp_fail(sp, v->line, field, "expected an array of %d numbers, got %d element%s", n,
                       v->count, v->count == 1 ? "" : "s");
    int i = 0;
    for (const json_t *e = v->child; e; e = e->next, i++) {
        char f[160];
        field_join(f, sizeof f, field, NULL, i);
        double d = 0;
        if (!get_double(sp, e, f, lo, hi, ints != NULL, &d)) return false;
        if (ints) ints[i] = (int)d;
        else floats[i] = (float)d;
    }
    return true;
}

/* [min, max] pair, min <= max. */
static bool get_pair(sp_t *sp, const json_t *v, const char *field, double lo, double hi, float *out)
{
    if (!get_vec(sp, v, field, 2, lo, hi, out, NULL)) return false;
    if (out[0] > out[1])
        return sp_fail(sp, v->line, field, "min %g is greater than max %g", (double)out[0],
                       (double)out[1]);
    return true;
}

static bool get_string(sp_t *sp, const json_t *v, const char *field, char *out, size_t cap)
{
    if (!want(sp, v, field, SCENE_JSON_STRING)) return false;
    if (v->string_len >= cap)
        return sp_fail(sp, v->line, field, "string of %zu bytes is longer than the maximum %zu",
                       v->string_len, cap - 1);
    memcpy(out, v->string, v->string_len + 1);
    return true;
}

static void list_names(char *buf, size_t size, const char *const *names, int n)
{
    size_t used = 0;
    buf[0] = 0;
    for (int i = 0; i < n && used < size; i++) {
        int w = snprintf(buf + used, size - used, "%s%s", i ? ", " : "", names[i]);
        if (w < 0) break;
        used += (size_t)w;
    }
}

static bool get_enum(sp_t *sp, const json_t *v, const char *field, const char *const *names, int n,
                     int *out)
{
    if (!want(sp, v, field, SCENE_JSON_STRING)) return false;
    for (int i = 0; i < n; i++) {
        if (strcmp(v->string, names[i]) == 0) {
            *out = i;
            return true;
        }
    }
    char list[256];
    list_names(list, sizeof list, names, n);
    return sp_fail(sp, v->line, field, "unknown value \"%s\" (expected one of: %s)", v->string, list);
}

/* Object whose keys all appear in `keys`; `what` qualifies the message. */
static bool check_object(sp_t *sp, const json_t *v, const char *field, const char *const *keys, int n,
                         const char *what)
{
    if (!want(sp, v, field[0] ? field : "(top level)", SCENE_JSON_OBJECT)) return false;
    for (const json_t *m = v->child; m; m = m->next) {
        bool known = false;
        for (int i = 0; i < n && !known; i++) known = strcmp(m->key, keys[i]) == 0;
        if (known) continue;
        char f[160], list[512];
        field_join(f, sizeof f, field, m->key, 0);
        list_names(list, sizeof list, keys, n);
        return sp_fail(sp, m->key_line, f, "unknown key \"%s\"%s (expected one of: %s)", m->key, what,
                       list);
    }
    return true;
}

/* Array with at most max entries. */
static bool get_array(sp_t *sp, const json_t *v, const char *field, int max, const char *max_name,
                      int *count)
{
    if (!want(sp, v, field, SCENE_JSON_ARRAY)) return false;
    if (v->count > max)
        return sp_fail(sp, v->line, field, "%d entries, more than the maximum %d (%s)", v->count, max,
                       max_name);
    *count = v->count;
    return true;
}

/* Looks up key in obj; on hit writes the member's field path into f. */
static const json_t *member(const json_t *obj, const char *parent, const char *key, char *f, size_t fs)
{
    const json_t *m = scene_json_get(obj, key);
    if (m) field_join(f, fs, parent, key, 0);
    return m;
}

#define F_SIZE 160
#define MEMBER(obj, parent, key) member((obj), (parent), (key), f, sizeof f)

/* Key times strictly increasing. */
static bool check_time_order(sp_t *sp, const json_t *v, const char *field, float prev, float t, int i)
{
    if (i > 0 && !(t > prev))
        return sp_fail(sp, v->line, field,
                       "%g is not greater than the previous key's t %g (keys must be strictly "
                       "increasing in t)",
                       (double)t, (double)prev);
    return true;
}

/* ---- sections ------------------------------------------------------------ */

static bool parse_terrain(sp_t *sp, const json_t *o, terrain_desc_t *t)
{
    static const char *const keys[] = {"type", "size", "resolution", "height", "mesh", "scale"};
    const char *p = "terrain";
    char f[F_SIZE];
    const json_t *v;
    if (!check_object(sp, o, p, keys, COUNT(keys), "")) return false;
    int type = 0;
    if ((v = MEMBER(o, p, "type")) && !get_enum(sp, v, f, terrain_names, COUNT(terrain_names), &type))
        return false;
    t->type = (terrain_type_t)type;
    if ((v = MEMBER(o, p, "size")) && !get_float(sp, v, f, 0, 10000, &t->size)) return false;
    if ((v = MEMBER(o, p, "resolution")) && !get_int(sp, v, f, 0, 4096, &t->resolution)) return false;
    if ((v = MEMBER(o, p, "height")) && !get_float(sp, v, f, 0, 1000, &t->height)) return false;
    if ((v = MEMBER(o, p, "mesh")) && !get_string(sp, v, f, t->mesh, sizeof t->mesh)) return false;
    if ((v = MEMBER(o, p, "scale")) && !get_float(sp, v, f, 0, 1e6, &t->scale)) return false;
    if (t->type == TERRAIN_MESH && !t->mesh[0])
        return sp_fail(sp, o->line, "terrain.mesh", "required when terrain.type is \"mesh\"");
    return true;
}

static bool parse_grass(sp_t *sp, const json_t *o, scene_grass_desc_t *g)
{
    static const char *const keys[] = {
        "density",         "height",    "width", "stiffness", "billboard_density",
        "billboard_size",  "switch_distance", "tile_size", "shape", "subdiv",
        "spring_iterations", "cube_resolution", "recover_time"};
    const char *p = "grass";
    char f[F_SIZE];
    const json_t *v;
    if (!check_object(sp, o, p, keys, COUNT(keys), "")) return false;
    if ((v = MEMBER(o, p, "density")) && !get_float(sp, v, f, 0, 10000, &g->density)) return false;
    if ((v = MEMBER(o, p, "height")) && !get_pair(sp, v, f, 0, 10, g->height)) return false;
    if ((v = MEMBER(o, p, "width")) && !get_pair(sp, v, f, 0, 1, g->width)) return false;
    if ((v = MEMBER(o, p, "stiffness")) && !get_pair(sp, v, f, 0, 100, g->stiffness)) return false;
    if (v && !(g->stiffness[0] > 0))
        return sp_fail(sp, v->line, f, "%g is out of range (0, 100]: a blade of stiffness 0 never stands up (eq. 1)",
                       (double)g->stiffness[0]);
    if ((v = MEMBER(o, p, "billboard_density")) && !get_float(sp, v, f, 0, 1000, &g->billboard_density))
        return false;
    if ((v = MEMBER(o, p, "billboard_size")) && !get_vec(sp, v, f, 2, 0, 20, g->billboard_size, NULL))
        return false;
    if ((v = MEMBER(o, p, "switch_distance")) && !get_float(sp, v, f, 0, 1000, &g->switch_distance))
        return false;
    if ((v = MEMBER(o, p, "tile_size")) && !get_float(sp, v, f, 0, 1000, &g->tile_size)) return false;
    int shape = 0;
    if ((v = MEMBER(o, p, "shape")) && !get_enum(sp, v, f, shape_names, COUNT(shape_names), &shape))
        return false;
    g->shape = (scene_blade_shape_t)shape;
    if ((v = MEMBER(o, p, "subdiv")) && !get_vec(sp, v, f, 2, 0, 64, NULL, g->subdiv)) return false;
    if ((v = MEMBER(o, p, "spring_iterations")) && !get_int(sp, v, f, 0, 64, &g->spring_iterations))
        return false;
    if ((v = MEMBER(o, p, "cube_resolution")) && !get_int(sp, v, f, 0, 4096, &g->cube_resolution))
        return false;
    if ((v = MEMBER(o, p, "recover_time")) && !get_float(sp, v, f, 0, 3600, &g->recover_time))
        return false;
    return true;
}

static bool parse_camera(sp_t *sp, const json_t *o, scene_camera_desc_t *c)
{
    static const char *const keys[] = {"position", "target", "fov", "near", "far", "path"};
    static const char *const key_keys[] = {"t", "position", "target"};
    const char *p = "camera";
    char f[F_SIZE];
    const json_t *v;
    if (!check_object(sp, o, p, keys, COUNT(keys), "")) return false;
    if ((v = MEMBER(o, p, "position")) && !get_vec(sp, v, f, 3, -1e6, 1e6, c->position, NULL))
        return false;
    if ((v = MEMBER(o, p, "target")) && !get_vec(sp, v, f, 3, -1e6, 1e6, c->target, NULL)) return false;
    if ((v = MEMBER(o, p, "fov")) && !get_float(sp, v, f, 0, 179, &c->fov)) return false;
    if ((v = MEMBER(o, p, "near")) && !get_float(sp, v, f, 0, 1e4, &c->near)) return false;
    if ((v = MEMBER(o, p, "far")) && !get_float(sp, v, f, 0, 1e6, &c->far)) return false;
    float near = c->near > 0 ? c->near : 0.1f, far = c->far > 0 ? c->far : 200.0f;
    if (far <= near) {
        const json_t *at = v ? v : scene_json_get(o, "near");
        return sp_fail(sp, at->line, "camera.far", "far %g must be greater than near %g", (double)far,
                       (double)near);
    }
    if (!(v = MEMBER(o, p, "path"))) return true;
    if (!get_array(sp, v, f, SCENE_MAX_PATH_KEYS, "SCENE_MAX_PATH_KEYS", &c->path.count)) return false;
    int i = 0;
    for (const json_t *e = v->child; e; e = e->next, i++) {
        char ef[F_SIZE], kf[F_SIZE];
        cam_path_key_t *k = &c->path.keys[i];
        field_join(ef, sizeof ef, "camera.path", NULL, i);
        if (!check_object(sp, e, ef, key_keys, COUNT(key_keys), "")) return false;
        for (int r = 0; r < COUNT(key_keys); r++) {
            if (!scene_json_get(e, key_keys[r]))
                return sp_fail(sp, e->line, field_join(kf, sizeof kf, ef, key_keys[r], 0),
                               "required but missing");
        }
        const json_t *t = member(e, ef, "t", kf, sizeof kf);
        if (!get_float(sp, t, kf, -1e6, 1e6, &k->t)) return false;
        if (!check_time_order(sp, t, kf, i ? c->path.keys[i - 1].t : 0, k->t, i)) return false;
        if (!get_vec(sp, member(e, ef, "position", kf, sizeof kf), kf, 3, -1e6, 1e6, k->position, NULL))
            return false;
        if (!get_vec(sp, member(e, ef, "target", kf, sizeof kf), kf, 3, -1e6, 1e6, k->target, NULL))
            return false;
    }
    return true;
}

static bool parse_wind(sp_t *sp, const json_t *arr, scene_desc_t *d)
{
    static const char *const dir_keys[] = {"type", "direction", "strength", "wavelength", "speed"};
    static const char *const point_keys[] = {"type", "position", "strength", "radius"};
    if (!get_array(sp, arr, "wind", SCENE_MAX_WIND, "SCENE_MAX_WIND", &d->wind_count)) return false;
    int i = 0;
    for (const json_t *e = arr->child; e; e = e->next, i++) {
        char p[F_SIZE], f[F_SIZE];
        scene_wind_t *w = &d->wind[i];
        const json_t *v;
        field_join(p, sizeof p, "wind", NULL, i);
        if (!want(sp, e, p, SCENE_JSON_OBJECT)) return false;
        int type = 0;
        if ((v = MEMBER(e, p, "type")) && !get_enum(sp, v, f, wind_names, COUNT(wind_names), &type))
            return false;
        w->type = (scene_wind_type_t)type;
        if (w->type == SCENE_WIND_DIRECTIONAL) {
            if (!check_object(sp, e, p, dir_keys, COUNT(dir_keys), " for wind type \"directional\""))
                return false;
            if ((v = MEMBER(e, p, "direction")) && !get_vec(sp, v, f, 2, -1e6, 1e6, w->direction, NULL))
                return false;
            if ((v = MEMBER(e, p, "wavelength")) && !get_float(sp, v, f, 0, 1e4, &w->wavelength))
                return false;
            if ((v = MEMBER(e, p, "speed")) && !get_float(sp, v, f, 0, 1000, &w->speed)) return false;
        } else {
            if (!check_object(sp, e, p, point_keys, COUNT(point_keys), " for wind type \"point\""))
                return false;
            if ((v = MEMBER(e, p, "position")) && !get_vec(sp, v, f, 3, -1e6, 1e6, w->position, NULL))
                return false;
            if ((v = MEMBER(e, p, "radius")) && !get_float(sp, v, f, 0, 1e4, &w->radius)) return false;
        }
        if ((v = MEMBER(e, p, "strength")) && !get_float(sp, v, f, 0, 100, &w->strength)) return false;
    }
    return true;
}

static bool parse_key_path(sp_t *sp, const json_t *arr, const char *field, scene_path_t *path)
{
    static const char *const key_keys[] = {"t", "position"};
    if (!get_array(sp, arr, field, SCENE_MAX_PATH_KEYS, "SCENE_MAX_PATH_KEYS", &path->count))
        return false;
    int i = 0;
    for (const json_t *e = arr->child; e; e = e->next, i++) {
        char ef[F_SIZE], kf[F_SIZE];
        scene_path_key_t *k = &path->keys[i];
        field_join(ef, sizeof ef, field, NULL, i);
        if (!check_object(sp, e, ef, key_keys, COUNT(key_keys), "")) return false;
        for (int r = 0; r < COUNT(key_keys); r++) {
            if (!scene_json_get(e, key_keys[r]))
                return sp_fail(sp, e->line, field_join(kf, sizeof kf, ef, key_keys[r], 0),
                               "required but missing");
        }
        const json_t *t = member(e, ef, "t", kf, sizeof kf);
        if (!get_float(sp, t, kf, -1e6, 1e6, &k->t)) return false;
        if (!check_time_order(sp, t, kf, i ? path->keys[i - 1].t : 0, k->t, i)) return false;
        if (!get_vec(sp, member(e, ef, "position", kf, sizeof kf), kf, 3, -1e6, 1e6, k->position, NULL))
            return false;
    }
    return true;
}

static bool parse_colliders(sp_t *sp, const json_t *arr, scene_desc_t *d)
{
    static const char *const sphere_keys[] = {"type", "position", "path", "loop", "radius"};
    static const char *const capsule_keys[] = {"type", "position", "path", "loop", "radius", "length"};
    static const char *const box_keys[] = {"type", "position", "path", "loop", "half_extents"};
    if (!get_array(sp, arr, "colliders", SCENE_MAX_COLLIDERS, "SCENE_MAX_COLLIDERS",
                   &d->collider_count))
        return false;
    int i = 0;
    for (const json_t *e = arr->child; e; e = e->next, i++) {
        char p[F_SIZE], f[F_SIZE];
        scene_collider_t *c = &d->colliders[i];
        const json_t *v;
        field_join(p, sizeof p, "colliders", NULL, i);
        if (!want(sp, e, p, SCENE_JSON_OBJECT)) return false;
        int type = 0;
        if ((v = MEMBER(e, p, "type")) &&
            !get_enum(sp, v, f, collider_names, COUNT(collider_names), &type))
            return false;
        c->type = (scene_collider_type_t)type;
        bool ok = c->type == SCENE_COLLIDER_SPHERE
                      ? check_object(sp, e, p, sphere_keys, COUNT(sphere_keys),
                                     " for collider type \"sphere\"")
                  : c->type == SCENE_COLLIDER_CAPSULE
                      ? check_object(sp, e, p, capsule_keys, COUNT(capsule_keys),
                                     " for collider type \"capsule\"")
                      : check_object(sp, e, p, box_keys, COUNT(box_keys), " for collider type \"box\"");
        if (!ok) return false;
        if ((v = MEMBER(e, p, "radius")) && !get_float(sp, v, f, 0, 100, &c->radius)) return false;
        if ((v = MEMBER(e, p, "length")) && !get_float(sp, v, f, 0, 100, &c->length)) return false;
        if ((v = MEMBER(e, p, "half_extents")) && !get_vec(sp, v, f, 3, 0, 100, c->half_extents, NULL))
            return false;
        if ((v = MEMBER(e, p, "loop")) && !get_bool(sp, v, f, &c->loop)) return false;
        const json_t *pos = scene_json_get(e, "position");
        if ((v = MEMBER(e, p, "path"))) {
            if (pos) return sp_fail(sp, pos->key_line, p, "give either \"position\" or \"path\", not both");
            if (!parse_key_path(sp, v, f, &c->path)) return false;
        } else if ((v = MEMBER(e, p, "position"))) {
            if (!get_vec(sp, v, f, 3, -1e6, 1e6, c->path.keys[0].position, NULL)) return false;
            c->path.count = 1;
        }
    }
    return true;
}

static bool parse_characters(sp_t *sp, const json_t *arr, scene_desc_t *d)
{
    static const char *const keys[] = {"model", "clip", "speed", "scale", "path", "loop"};
    if (!get_array(sp, arr, "characters", SCENE_MAX_CHARACTERS, "SCENE_MAX_CHARACTERS",
                   &d->character_count))
        return false;
    int i = 0;
    for (const json_t *e = arr->child; e; e = e->next, i++) {
        char p[F_SIZE], f[F_SIZE];
        scene_character_t *c = &d->characters[i];
        const json_t *v;
        field_join(p, sizeof p, "characters", NULL, i);
        if (!check_object(sp, e, p, keys, COUNT(keys), "")) return false;
        if (!(v = MEMBER(e, p, "model")))
            return sp_fail(sp, e->line, field_join(f, sizeof f, p, "model", 0), "required but missing");
        if (!get_string(sp, v, f, c->model, sizeof c->model)) return false;
        if (!c->model[0]) return sp_fail(sp, v->line, f, "must not be empty");
        if ((v = MEMBER(e, p, "clip"))) {
            if (v->type == SCENE_JSON_STRING) {
                if (!get_string(sp, v, f, c->clip_name, sizeof c->clip_name)) return false;
                c->clip_index = -1;
            } else if (v->type == SCENE_JSON_NUMBER) {
                if (!get_int(sp, v, f, 0, 1000, &c->clip_index)) return false;
            } else {
                return sp_fail(sp, v->line, f, "expected string or number, got %s",
                               scene_json_type_name(v->type));
            }
        }
        if ((v = MEMBER(e, p, "speed")) && !get_float(sp, v, f, 0, 100, &c->speed)) return false;
        if ((v = MEMBER(e, p, "scale")) && !get_float(sp, v, f, 0, 1000, &c->scale)) return false;
        if ((v = MEMBER(e, p, "loop")) && !get_bool(sp, v, f, &c->loop)) return false;
        if ((v = MEMBER(e, p, "path"))) {
            if (!get_array(sp, v, f, SCENE_MAX_PATH_KEYS, "SCENE_MAX_PATH_KEYS", &c->waypoint_count))
                return false;
            int k = 0;
            for (const json_t *w = v->child; w; w = w->next, k++) {
                char wf[F_SIZE];
                field_join(wf, sizeof wf, f, NULL, k);
                if (!get_vec(sp, w, wf, 2, -1e6, 1e6, c->waypoints[k], NULL)) return false;
            }
        }
    }
    return true;
}

static bool parse_root(sp_t *sp, const json_t *o, scene_desc_t *d)
{
    static const char *const keys[] = {"seed",    "frames", "dt",     "size", "msaa",      "mode",      "raster",
                                       "terrain", "grass",  "camera", "wind", "colliders", "characters"};
    const char *p = "";
    char f[F_SIZE];
    const json_t *v;
    if (!check_object(sp, o, p, keys, COUNT(keys), "")) return false;
    double seed;
    if ((v = MEMBER(o, p, "seed"))) {
        if (!get_double(sp, v, f, 0, 4294967295.0, true, &seed)) return false;
        d->seed = (uint32_t)seed;
    }
    if ((v = MEMBER(o, p, "frames")) && !get_int(sp, v, f, 0, 1e7, &d->frames)) return false;
    if ((v = MEMBER(o, p, "dt")) && !get_float(sp, v, f, 0, 1, &d->dt)) return false;
    if ((v = MEMBER(o, p, "size")) && !get_vec(sp, v, f, 2, 0, 16384, NULL, d->size)) return false;
    if ((v = MEMBER(o, p, "msaa"))) {
        if (!get_int(sp, v, f, 0, 16, &d->msaa)) return false;
        if (d->msaa & (d->msaa - 1))
            return sp_fail(sp, v->line, f, "%d is not one of 0, 1, 2, 4, 8, 16", d->msaa);
    }
    int mode = 0;
    if ((v = MEMBER(o, p, "mode")) && !get_enum(sp, v, f, mode_names, COUNT(mode_names), &mode))
        return false;
    d->mode = (scene_mode_t)mode;
    int raster = 0;
    if ((v = MEMBER(o, p, "raster")) && !get_enum(sp, v, f, raster_names, COUNT(raster_names), &raster))
        return false;
    d->raster = (scene_raster_t)raster;
    if ((v = scene_json_get(o, "terrain")) && !parse_terrain(sp, v, &d->terrain)) return false;
    if ((v = scene_json_get(o, "grass")) && !parse_grass(sp, v, &d->grass)) return false;
    if ((v = scene_json_get(o, "camera")) && !parse_camera(sp, v, &d->camera)) return false;
    if ((v = scene_json_get(o, "wind")) && !parse_wind(sp, v, d)) return false;
    if ((v = scene_json_get(o, "colliders")) && !parse_colliders(sp, v, d)) return false;
    if ((v = scene_json_get(o, "characters")) && !parse_characters(sp, v, d)) return false;
    return true;
}

bool scene_parse(scene_desc_t *out, const char *text, const char *name_for_errors, char *err,
                 size_t err_size)
{
    memset(out, 0, sizeof *out);
    if (err && err_size) err[0] = 0;
    scene_json_doc_t doc;
    bool ok = scene_json_parse(&doc, text, name_for_errors, err, err_size);
    if (ok) {
        sp_t sp = {.name = name_for_errors, .err = err, .err_size = err_size};
        ok = parse_root(&sp, doc.root, out);
        scene_json_free(&doc);
    }
    if (!ok) {
        memset(out, 0, sizeof *out);
        core_log_error("%s", err && err_size ? err : "scene parse failed");
        return false;
    }
    scene_desc_defaults(out);
    return true;
}

bool scene_load(scene_desc_t *out, const char *path, char *err, size_t err_size)
{
    char why[256];
    char *text = core_fs_read(path, NULL, why, sizeof why);
    if (!text) {
        memset(out, 0, sizeof *out);
        if (err && err_size) snprintf(err, err_size, "%s: cannot read: %s", path, why);
        core_log_error("%s: cannot read: %s", path, why);
        return false;
    }
    bool ok = scene_parse(out, text, path, err, err_size);
    free(text);
    return ok;
}

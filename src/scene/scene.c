/* scene: strict JSON -> scene_desc_t with file:line:field errors (see
 * scene.h), defaults, and the initial camera. */
#include "scene/scene.h"

#include <assert.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "scene/scene_fields.h"
#include "scene/scene_json.h"

typedef scene_json_t json_t;

static_assert(sizeof(scene_mode_t) == sizeof(int) && sizeof(scene_raster_t) == sizeof(int) &&
                  sizeof(blade_shape_t) == sizeof(int) && sizeof(terrain_type_t) == sizeof(int) &&
                  sizeof(scene_wind_type_t) == sizeof(int) && sizeof(scene_collider_type_t) == sizeof(int) &&
                  sizeof(scene_clearings_type_t) == sizeof(int),
              "SCENE_FIELD_ENUM members are stored as int");

/* The accepted strings of an enum key (NULL-terminated). */
static const char *const *names_of(scene_section_t section, const char *key)
{
    return scene_field_find(section, key)->names;
}

/* ---- defaults ------------------------------------------------------------
 * The table's defaults (scene_fields.c) fill every zero field of a section,
 * whatever the entry's type; the few rules a row cannot say are below. */

static void fill_defaults(scene_section_t section, void *base)
{
    for (int i = 0; i < scene_field_count; i++) {
        const scene_field_t *f = &scene_fields[i];
        if (f->section != section || (f->flags & SCENE_FIELD_NO_DEFAULT)) continue;
        char *at = (char *)base + f->offset;
        int *ints = (int *)at;
        float *floats = (float *)at;
        switch (f->type) {
        case SCENE_FIELD_INT:
            if (ints[0] <= 0) ints[0] = (int)f->def[0];
            break;
        case SCENE_FIELD_FLOAT:
            if (floats[0] <= 0) floats[0] = f->def[0];
            break;
        case SCENE_FIELD_INTS:
            for (int k = 0; k < f->n; k++)
                if (ints[k] <= 0) ints[k] = (int)f->def[k];
            break;
        case SCENE_FIELD_FLOATS:
            for (int k = 0; k < f->n; k++)
                if (floats[k] <= 0) floats[k] = f->def[k];
            break;
        case SCENE_FIELD_RANGE:
            if (floats[0] == 0 && floats[1] == 0) {
                floats[0] = f->def[0];
                floats[1] = f->def[1];
            }
            break;
        default: break;
        }
    }
}

void scene_desc_defaults(scene_desc_t *d)
{
    fill_defaults(SCENE_SEC_ROOT, d);
    fill_defaults(SCENE_SEC_TERRAIN, &d->terrain);
    fill_defaults(SCENE_SEC_GRASS, &d->grass);
    fill_defaults(SCENE_SEC_CLEARINGS, &d->grass.clearings);
    fill_defaults(SCENE_SEC_LOD, &d->grass.lod);
    scene_camera_desc_t *c = &d->camera;
    fill_defaults(SCENE_SEC_CAMERA, c);
    if (glm_vec3_eq(c->position, 0.0f) && glm_vec3_eq(c->target, 0.0f)) {
        c->position[1] = SCENE_DEFAULT_CAMERA_Y;
        c->position[2] = SCENE_DEFAULT_CAMERA_Z;
    }
    for (int i = 0; i < d->wind_count; i++) {
        scene_wind_t *w = &d->wind[i];
        if (w->type == SCENE_WIND_DIRECTIONAL) {
            float len = hypotf(w->direction[0], w->direction[1]);
            if (len > 0) {
                w->direction[0] /= len;
                w->direction[1] /= len;
            } else {
                w->direction[0] = 1.0f;
                w->direction[1] = 0.0f;
            }
        }
        fill_defaults(SCENE_SEC_WIND, w);
    }
    for (int i = 0; i < d->collider_count; i++) {
        scene_collider_t *c2 = &d->colliders[i];
        if (c2->radius <= 0 && c2->type == SCENE_COLLIDER_CAPSULE) c2->radius = SCENE_DEFAULT_CAPSULE_RADIUS;
        fill_defaults(SCENE_SEC_COLLIDER, c2);
    }
    for (int i = 0; i < d->character_count; i++) fill_defaults(SCENE_SEC_CHARACTER, &d->characters[i]);
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

float scene_blade_distance(const scene_grass_desc_t *g, const float cam_pos[3], float far, const float field_min[3],
                           const float field_max[3])
{
    if (g->blade_distance > 0.0f) return g->blade_distance;
    float d2 = 0.0f;
    for (int k = 0; k < 3; k++) {
        float e = fmaxf(fabsf(field_min[k] - cam_pos[k]), fabsf(field_max[k] - cam_pos[k]));
        d2 += e * e;
    }
    return fminf(sqrtf(d2), far);
}

float scene_focal(const scene_desc_t *s)
{
    float fov = s->camera.fov > 0.0f ? s->camera.fov : SCENE_DEFAULT_FOV;
    int h = s->size[1] > 0 ? s->size[1] : SCENE_DEFAULT_HEIGHT;
    return 0.5f * (float)h / tanf(glm_rad(0.5f * fov));
}

const char *scene_mode_name(scene_mode_t mode) { return names_of(SCENE_SEC_ROOT, "mode")[mode]; }
const char *scene_raster_name(scene_raster_t raster) { return names_of(SCENE_SEC_ROOT, "raster")[raster]; }

bool scene_raster_parse(const char *name, scene_raster_t *out)
{
    const char *const *names = names_of(SCENE_SEC_ROOT, "raster");
    for (int i = 0; names[i]; i++)
        if (strcmp(name, names[i]) == 0) {
            *out = (scene_raster_t)i;
            return true;
        }
    return false;
}

collide_shape_t scene_collider_shape(const scene_collider_t *c)
{
    static const collide_shape_type_t types[] = {[SCENE_COLLIDER_SPHERE] = COLLIDE_SHAPE_SPHERE,
                                                 [SCENE_COLLIDER_CAPSULE] = COLLIDE_SHAPE_CAPSULE,
                                                 [SCENE_COLLIDER_BOX] = COLLIDE_SHAPE_BOX};
    collide_shape_t s = {.type = types[c->type], .radius = c->radius, .length = c->length};
    memcpy(s.half_extents, c->half_extents, sizeof s.half_extents);
    return s;
}

const char *scene_blade_shape_name(blade_shape_t shape)
{
    return names_of(SCENE_SEC_GRASS, "shape")[shape];
}

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

/* A number of row f: integral when `integer`, in [f->lo, f->hi] (or 0 with
 * SCENE_FIELD_ZERO_OK, or a power of two with SCENE_FIELD_POW2). */
static bool get_number(sp_t *sp, const json_t *v, const char *field, const scene_field_t *f, bool integer,
                       double *out)
{
    if (!want(sp, v, field, SCENE_JSON_NUMBER)) return false;
    double x = v->number;
    if (integer && x != floor(x)) return sp_fail(sp, v->line, field, "expected an integer, got %g", x);
    char why[160];
    if (!scene_field_accepts(f, x, why, sizeof why)) return sp_fail(sp, v->line, field, "%s", why);
    *out = x;
    return true;
}

/* Array of exactly f->n numbers (2 for a range) of row f; integers when ints
 * != NULL. */
static bool get_numbers(sp_t *sp, const json_t *v, const char *field, const scene_field_t *f, float *floats,
                        int *ints)
{
    int n = f->type == SCENE_FIELD_RANGE ? 2 : f->n;
    if (!want(sp, v, field, SCENE_JSON_ARRAY)) return false;
    if (v->count != n)
        return sp_fail(sp, v->line, field, "expected an array of %d numbers, got %d element%s", n, v->count,
                       v->count == 1 ? "" : "s");
    int i = 0;
    for (const json_t *e = v->child; e; e = e->next, i++) {
        char ef[160];
        field_join(ef, sizeof ef, field, NULL, i);
        double d = 0;
        if (!get_number(sp, e, ef, f, ints != NULL, &d)) return false;
        if (ints) ints[i] = (int)d;
        else floats[i] = (float)d;
    }
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

static bool get_enum(sp_t *sp, const json_t *v, const char *field, const char *const *names, int *out)
{
    if (!want(sp, v, field, SCENE_JSON_STRING)) return false;
    int n = 0;
    for (; names[n]; n++) {
        if (strcmp(v->string, names[n]) == 0) {
            *out = n;
            return true;
        }
    }
    char list[256];
    list_names(list, sizeof list, names, n);
    return sp_fail(sp, v->line, field, "unknown value \"%s\" (expected one of: %s)", v->string, list);
}

/* Array of at most row f's f->hi entries. */
static bool get_array(sp_t *sp, const json_t *v, const char *field, const scene_field_t *f, int *count)
{
    if (!want(sp, v, field, SCENE_JSON_ARRAY)) return false;
    if (v->count > (int)f->hi)
        return sp_fail(sp, v->line, field, "%d entries, more than the maximum %d (%s)", v->count, (int)f->hi,
                       f->limit);
    *count = v->count;
    return true;
}

/* The value v of row f into `at` (the member in the section's struct).
 * Objects, arrays and custom rows are left to the section parsers. */
static bool get_field(sp_t *sp, const json_t *v, const char *field, const scene_field_t *f, void *at)
{
    double d = 0;
    switch (f->type) {
    case SCENE_FIELD_INT:
        if (!get_number(sp, v, field, f, true, &d)) return false;
        *(int *)at = (int)d;
        return true;
    case SCENE_FIELD_U32:
        if (!get_number(sp, v, field, f, true, &d)) return false;
        *(uint32_t *)at = (uint32_t)d;
        return true;
    case SCENE_FIELD_FLOAT:
        if (!get_number(sp, v, field, f, false, &d)) return false;
        *(float *)at = (float)d;
        return true;
    case SCENE_FIELD_INTS: return get_numbers(sp, v, field, f, NULL, at);
    case SCENE_FIELD_FLOATS: return get_numbers(sp, v, field, f, at, NULL);
    case SCENE_FIELD_RANGE: {
        float *r = at;
        if (!get_numbers(sp, v, field, f, r, NULL)) return false;
        if (r[0] > r[1])
            return sp_fail(sp, v->line, field, "min %g is greater than max %g", (double)r[0], (double)r[1]);
        return true;
    }
    case SCENE_FIELD_ENUM: return get_enum(sp, v, field, f->names, at);
    case SCENE_FIELD_BOOL:
        if (!want(sp, v, field, SCENE_JSON_BOOL)) return false;
        *(bool *)at = v->boolean;
        return true;
    case SCENE_FIELD_STRING: return get_string(sp, v, field, at, f->size);
    default: return true;
    }
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

static bool accepts(const scene_field_t *f, scene_section_t section, unsigned variant)
{
    return f->section == section && (!f->variants || !variant || (f->variants & variant));
}

/* v is an object whose keys are all rows of `section` that accept `variant`
 * (an entry-type bit; 0: every row); `what` qualifies the message. */
static bool check_members(sp_t *sp, const json_t *v, const char *field, scene_section_t section, unsigned variant,
                          const char *what)
{
    if (!want(sp, v, field[0] ? field : "(top level)", SCENE_JSON_OBJECT)) return false;
    for (const json_t *m = v->child; m; m = m->next) {
        const scene_field_t *row = scene_field_find(section, m->key);
        if (row && accepts(row, section, variant)) continue;
        const char *keys[64];
        int n = 0;
        for (int i = 0; i < scene_field_count && n < (int)(sizeof keys / sizeof keys[0]); i++)
            if (accepts(&scene_fields[i], section, variant)) keys[n++] = scene_fields[i].key;
        char f[F_SIZE], list[512];
        field_join(f, sizeof f, field, m->key, 0);
        list_names(list, sizeof list, keys, n);
        return sp_fail(sp, m->key_line, f, "unknown key \"%s\"%s (expected one of: %s)", m->key, what, list);
    }
    return true;
}

/* Every table row of `section` accepting `variant` from object o (field path
 * parent) into the struct at base; missing required keys are errors. */
static bool get_members(sp_t *sp, const json_t *o, const char *parent, scene_section_t section, unsigned variant,
                        void *base)
{
    char f[F_SIZE];
    for (int i = 0; i < scene_field_count; i++) {
        const scene_field_t *row = &scene_fields[i];
        if (!accepts(row, section, variant)) continue;
        const json_t *v = MEMBER(o, parent, row->key);
        if (!v) {
            if (row->flags & SCENE_FIELD_REQUIRED)
                return sp_fail(sp, o->line, field_join(f, sizeof f, parent, row->key, 0), "required but missing");
            continue;
        }
        if (!get_field(sp, v, f, row, (char *)base + row->offset)) return false;
    }
    return true;
}

/* An object entry of a typed array (wind, colliders): its "type" first,
 * then its keys for that type. */
static bool get_typed_entry(sp_t *sp, const json_t *e, const char *p, scene_section_t section, const char *kind,
                            int *type, void *base)
{
    char f[F_SIZE], what[64];
    const json_t *v;
    const scene_field_t *row = scene_field_find(section, "type");
    if (!want(sp, e, p, SCENE_JSON_OBJECT)) return false;
    if ((v = MEMBER(e, p, "type")) && !get_enum(sp, v, f, row->names, type)) return false;
    snprintf(what, sizeof what, " for %s type \"%s\"", kind, row->names[*type]);
    unsigned variant = 1u << *type;
    return check_members(sp, e, p, section, variant, what) && get_members(sp, e, p, section, variant, base);
}

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
    int type = 0;
    if (!get_typed_entry(sp, o, "terrain", SCENE_SEC_TERRAIN, "terrain", &type, t)) return false;
    t->type = (terrain_type_t)type;
    if (t->type == TERRAIN_MESH && !t->mesh[0])
        return sp_fail(sp, o->line, "terrain.mesh", "required when terrain.type is \"mesh\"");
    if (t->type == TERRAIN_WORLD && t->size > TERRAIN_WORLD_SIZE_MAX)
        return sp_fail(sp, o->line, "terrain.size", "%g is above %g, the largest world (TERRAIN_WORLD_SIZE_MAX)",
                       (double)t->size, (double)TERRAIN_WORLD_SIZE_MAX);
    return true;
}

static bool parse_grass(sp_t *sp, const json_t *o, scene_grass_desc_t *g)
{
    if (!check_members(sp, o, "grass", SCENE_SEC_GRASS, 0, "")) return false;
    if (!get_members(sp, o, "grass", SCENE_SEC_GRASS, 0, g)) return false;
    const json_t *v = scene_json_get(o, "lod");
    if (v && !(check_members(sp, v, "grass.lod", SCENE_SEC_LOD, 0, "") &&
               get_members(sp, v, "grass.lod", SCENE_SEC_LOD, 0, &g->lod)))
        return false;
    v = scene_json_get(o, "clearings");
    if (!v) return true;
    int type = 0;
    if (!get_typed_entry(sp, v, "grass.clearings", SCENE_SEC_CLEARINGS, "clearings", &type, &g->clearings))
        return false;
    g->clearings.type = (scene_clearings_type_t)type;
    if (type == SCENE_CLEARINGS_IMAGE && !g->clearings.image[0])
        return sp_fail(sp, scene_json_get(v, "image")->line, "grass.clearings.image", "must not be empty");
    return true;
}

/* "path" of an object: entries of `section` (camera or collider keys, each
 * struct `stride` bytes from keys), t strictly increasing. */
static bool parse_keys(sp_t *sp, const json_t *arr, const char *field, const scene_field_t *row,
                       scene_section_t section, void *keys, size_t stride, int *count)
{
    if (!get_array(sp, arr, field, row, count)) return false;
    int i = 0;
    for (const json_t *e = arr->child; e; e = e->next, i++) {
        char ef[F_SIZE], kf[F_SIZE];
        char *key = (char *)keys + (size_t)i * stride;
        field_join(ef, sizeof ef, field, NULL, i);
        if (!check_members(sp, e, ef, section, 0, "")) return false;
        if (!get_members(sp, e, ef, section, 0, key)) return false;
        const scene_field_t *t = scene_field_find(section, "t");
        float prev = i ? *(const float *)(key - stride + t->offset) : 0;
        if (!check_time_order(sp, member(e, ef, "t", kf, sizeof kf), kf, prev, *(const float *)(key + t->offset), i))
            return false;
    }
    return true;
}

/* A camera (or camera path key) object o looks from position at target:
 * the two must differ, or the camera has no direction. */
static bool look_ok(sp_t *sp, const json_t *o, const char *field, const float position[3], const float target[3])
{
    if (glm_vec3_distance((float *)position, (float *)target) > 1e-6f) return true;
    const json_t *at = scene_json_get(o, "target") ? scene_json_get(o, "target") : scene_json_get(o, "position");
    char f[F_SIZE];
    return sp_fail(sp, at ? at->line : o->line, field_join(f, sizeof f, field, "target", 0),
                   "[%g, %g, %g] is %s.position: a camera must look at a point other than where it stands",
                   (double)target[0], (double)target[1], (double)target[2], field);
}

static bool parse_camera(sp_t *sp, const json_t *o, scene_camera_desc_t *c)
{
    const char *p = "camera";
    char f[F_SIZE];
    const json_t *v;
    if (!check_members(sp, o, p, SCENE_SEC_CAMERA, 0, "")) return false;
    if (!get_members(sp, o, p, SCENE_SEC_CAMERA, 0, c)) return false;
    float near = c->near > 0 ? c->near : SCENE_DEFAULT_NEAR, far = c->far > 0 ? c->far : SCENE_DEFAULT_FAR;
    if (far <= near) {
        const json_t *at = (v = scene_json_get(o, "far")) ? v : scene_json_get(o, "near");
        return sp_fail(sp, at->line, "camera.far", "far %g must be greater than near %g", (double)far,
                       (double)near);
    }
    bool given = !glm_vec3_eq(c->position, 0.0f) || !glm_vec3_eq(c->target, 0.0f); /* both 0: the default */
    if (given && !look_ok(sp, o, "camera", c->position, c->target)) return false;
    if (!(v = MEMBER(o, p, "path"))) return true;
    if (!parse_keys(sp, v, f, scene_field_find(SCENE_SEC_CAMERA, "path"), SCENE_SEC_CAMERA_KEY, c->path.keys,
                    sizeof c->path.keys[0], &c->path.count))
        return false;
    int i = 0;
    for (const json_t *e = v->child; e; e = e->next, i++) {
        char kf[F_SIZE];
        if (!look_ok(sp, e, field_join(kf, sizeof kf, "camera.path", NULL, i), c->path.keys[i].position,
                     c->path.keys[i].target))
            return false;
    }
    return true;
}

static bool parse_wind(sp_t *sp, const json_t *arr, scene_desc_t *d)
{
    if (!get_array(sp, arr, "wind", scene_field_find(SCENE_SEC_ROOT, "wind"), &d->wind_count)) return false;
    int i = 0;
    for (const json_t *e = arr->child; e; e = e->next, i++) {
        char p[F_SIZE];
        scene_wind_t *w = &d->wind[i];
        int type = 0;
        field_join(p, sizeof p, "wind", NULL, i);
        if (!get_typed_entry(sp, e, p, SCENE_SEC_WIND, "wind", &type, w)) return false;
        w->type = (scene_wind_type_t)type;
    }
    return true;
}

static bool parse_colliders(sp_t *sp, const json_t *arr, scene_desc_t *d)
{
    if (!get_array(sp, arr, "colliders", scene_field_find(SCENE_SEC_ROOT, "colliders"), &d->collider_count))
        return false;
    int i = 0;
    for (const json_t *e = arr->child; e; e = e->next, i++) {
        char p[F_SIZE], f[F_SIZE];
        scene_collider_t *c = &d->colliders[i];
        const json_t *v;
        int type = 0;
        field_join(p, sizeof p, "colliders", NULL, i);
        if (!get_typed_entry(sp, e, p, SCENE_SEC_COLLIDER, "collider", &type, c)) return false;
        c->type = (scene_collider_type_t)type;
        const json_t *pos = scene_json_get(e, "position");
        if ((v = MEMBER(e, p, "path"))) {
            if (pos) return sp_fail(sp, pos->key_line, p, "give either \"position\" or \"path\", not both");
            if (!parse_keys(sp, v, f, scene_field_find(SCENE_SEC_COLLIDER, "path"), SCENE_SEC_COLLIDER_KEY,
                            c->path.keys, sizeof c->path.keys[0], &c->path.count))
                return false;
        } else if ((v = MEMBER(e, p, "position"))) {
            if (!get_numbers(sp, v, f, scene_field_find(SCENE_SEC_COLLIDER, "position"), c->path.keys[0].position,
                             NULL))
                return false;
            c->path.count = 1;
        }
    }
    return true;
}

/* "clips": {"name": [start, end], ...} into c's named ranges: at most
 * SCENE_MAX_CLIP_RANGES, each name a word (not empty, not an index nor a
 * START:END range), start < end within the row's bounds. */
static bool parse_clip_ranges(sp_t *sp, const json_t *v, const char *field, scene_character_t *c)
{
    const scene_field_t *row = scene_field_find(SCENE_SEC_CHARACTER, "clips");
    const scene_field_t ends = {.type = SCENE_FIELD_FLOATS, .n = 2, .lo = row->lo, .hi = row->hi};
    if (!want(sp, v, field, SCENE_JSON_OBJECT)) return false;
    if (v->count > SCENE_MAX_CLIP_RANGES)
        return sp_fail(sp, v->line, field, "%d names, more than the maximum %d (%s)", v->count, SCENE_MAX_CLIP_RANGES,
                       row->limit);
    for (const json_t *m = v->child; m; m = m->next) {
        char mf[F_SIZE], *end;
        scene_clip_range_t *r = &c->clip_ranges[c->clip_range_count];
        field_join(mf, sizeof mf, field, m->key, 0);
        size_t len = strlen(m->key);
        if (!len) return sp_fail(sp, m->key_line, mf, "a range needs a name");
        if (len >= sizeof r->name)
            return sp_fail(sp, m->key_line, mf, "name of %zu bytes is longer than the maximum %zu", len,
                           sizeof r->name - 1);
        (void)strtol(m->key, &end, 10);
        if (!*end || strchr(m->key, ':'))
            return sp_fail(sp, m->key_line, mf, "\"%s\" reads as a clip %s; name the range with a word", m->key,
                           *end ? "range START:END" : "index");
        if (!get_numbers(sp, m, mf, &ends, r->range, NULL)) return false;
        if (!(r->range[1] > r->range[0]))
            return sp_fail(sp, m->line, mf, "end %g is not after start %g", (double)r->range[1],
                           (double)r->range[0]);
        memcpy(r->name, m->key, len + 1);
        c->clip_range_count++;
    }
    return true;
}

static bool parse_characters(sp_t *sp, const json_t *arr, scene_desc_t *d)
{
    static const scene_field_t waypoint = {.type = SCENE_FIELD_FLOATS, .n = 2, .lo = -SCENE_COORD_MAX,
                                           .hi = SCENE_COORD_MAX};
    if (!get_array(sp, arr, "characters", scene_field_find(SCENE_SEC_ROOT, "characters"), &d->character_count))
        return false;
    int i = 0;
    for (const json_t *e = arr->child; e; e = e->next, i++) {
        char p[F_SIZE], f[F_SIZE];
        scene_character_t *c = &d->characters[i];
        const json_t *v;
        field_join(p, sizeof p, "characters", NULL, i);
        if (!check_members(sp, e, p, SCENE_SEC_CHARACTER, 0, "")) return false;
        if (!get_members(sp, e, p, SCENE_SEC_CHARACTER, 0, c)) return false;
        if (!c->model[0]) return sp_fail(sp, scene_json_get(e, "model")->line, field_join(f, sizeof f, p, "model", 0),
                                         "must not be empty");
        int up = scene_axis_code(c->up), fwd = scene_axis_code(c->forward);
        if (up && fwd && abs(up) == abs(fwd))
            return sp_fail(sp, scene_json_get(e, "forward")->line, field_join(f, sizeof f, p, "forward", 0),
                           "lies along up; choose an axis perpendicular to it");
        if ((v = MEMBER(e, p, "clip"))) {
            if (v->type == SCENE_JSON_STRING) {
                if (!get_string(sp, v, f, c->clip_name, sizeof c->clip_name)) return false;
                c->clip_index = -1;
            } else if (v->type == SCENE_JSON_NUMBER) {
                double x = 0;
                if (!get_number(sp, v, f, scene_field_find(SCENE_SEC_CHARACTER, "clip"), true, &x)) return false;
                c->clip_index = (int)x;
            } else {
                return sp_fail(sp, v->line, f, "expected string or number, got %s", scene_json_type_name(v->type));
            }
        }
        if ((v = MEMBER(e, p, "clips")) && !parse_clip_ranges(sp, v, f, c)) return false;
        if ((v = MEMBER(e, p, "path"))) {
            if (!get_array(sp, v, f, scene_field_find(SCENE_SEC_CHARACTER, "path"), &c->waypoint_count))
                return false;
            int k = 0;
            for (const json_t *w = v->child; w; w = w->next, k++) {
                char wf[F_SIZE];
                field_join(wf, sizeof wf, f, NULL, k);
                if (!get_numbers(sp, w, wf, &waypoint, c->waypoints[k], NULL)) return false;
            }
        }
    }
    return true;
}

static bool parse_root(sp_t *sp, const json_t *o, scene_desc_t *d)
{
    const json_t *v;
    if (!check_members(sp, o, "", SCENE_SEC_ROOT, 0, "")) return false;
    if (!get_members(sp, o, "", SCENE_SEC_ROOT, 0, d)) return false;
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
    size_t size = 0;
    char *text = core_fs_read(path, &size, why, sizeof why);
    const char *nul = text ? memchr(text, 0, size) : NULL;
    if (nul) {
        /* The parser reads a C string: without this a NUL read as the end. */
        int line = 1;
        for (const char *c = text; c < nul; c++) line += *c == '\n';
        snprintf(why, sizeof why, "%d: a NUL byte at offset %zu: a scene file is UTF-8 text", line,
                 (size_t)(nul - text));
        free(text);
        text = NULL;
    }
    if (!text) {
        memset(out, 0, sizeof *out);
        if (err && err_size) snprintf(err, err_size, "%s:%s%s", path, nul ? "" : " cannot read: ", why);
        core_log_error("%s:%s%s", path, nul ? "" : " cannot read: ", why);
        return false;
    }
    bool ok = scene_parse(out, text, path, err, err_size);
    free(text);
    return ok;
}

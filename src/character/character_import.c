/* character_import: units, axes and height of an imported character (see
 * character_import.h). The transform C = [s R | t] is a similarity, so it
 * commutes with a bone's TRS decomposition: C T(t) R(q) S(v) =
 * T(s R t + c) R(q_R q) S(s v). Root bones take it on their bind values and
 * keys; every inverse bind matrix becomes B C^-1, so skinning gives
 * C (old skinned position) for the converted vertex C p. */
#include "character/character_import.h"

#include "character/character_ref.h"
#include "core/core.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int character_axis_parse(const char *s)
{
    int sign = 1;
    if (*s == '+' || *s == '-') sign = *s++ == '-' ? -1 : 1;
    if (!s[0] || s[1]) return 0;
    int a = s[0] == 'x' || s[0] == 'X' ? 1 : s[0] == 'y' || s[0] == 'Y' ? 2 : s[0] == 'z' || s[0] == 'Z' ? 3 : 0;
    return sign * a;
}

const char *character_axis_name(int code)
{
    static const char *const names[] = {"-z", "-y", "-x", "auto", "+x", "+y", "+z"};
    return code >= -3 && code <= 3 ? names[code + 3] : "?";
}

static void axis_vec(int code, float v[3])
{
    v[0] = v[1] = v[2] = 0.0f;
    v[(code < 0 ? -code : code) - 1] = code < 0 ? -1.0f : 1.0f;
}

void character_import_matrix(float scale, int up, int forward, float yaw_deg, float lift, float out[16])
{
    float u[3], f[3], r[3];
    axis_vec(up, u);
    axis_vec(forward, f);
    r[0] = u[1] * f[2] - u[2] * f[1], r[1] = u[2] * f[0] - u[0] * f[2], r[2] = u[0] * f[1] - u[1] * f[0];
    /* rows of the axis change: file right -> +X, up -> +Y, forward -> +Z */
    const float *rows[3] = {r, u, f};
    double yaw = (double)yaw_deg * 3.14159265358979323846 / 180.0;
    float c = (float)cos(yaw), s = (float)sin(yaw);
    const float ry[3][3] = {{c, 0.0f, s}, {0.0f, 1.0f, 0.0f}, {-s, 0.0f, c}};
    memset(out, 0, 16 * sizeof(float));
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) {
            float e = 0.0f;
            for (int k = 0; k < 3; k++) e += ry[i][k] * rows[k][j];
            out[j * 4 + i] = scale * e;
        }
    out[13] = lift;
    out[15] = 1.0f;
}

/* Unit quaternion (x, y, z, w) of the rotation R = m3x3 / scale. */
static void rotation_quat(const float m[16], float scale, float q[4])
{
    float r[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) r[i][j] = m[j * 4 + i] / scale;
    float tr = r[0][0] + r[1][1] + r[2][2];
    if (tr > 0.0f) {
        float s = sqrtf(tr + 1.0f) * 2.0f;
        q[3] = 0.25f * s, q[0] = (r[2][1] - r[1][2]) / s, q[1] = (r[0][2] - r[2][0]) / s, q[2] = (r[1][0] - r[0][1]) / s;
    } else if (r[0][0] > r[1][1] && r[0][0] > r[2][2]) {
        float s = sqrtf(1.0f + r[0][0] - r[1][1] - r[2][2]) * 2.0f;
        q[3] = (r[2][1] - r[1][2]) / s, q[0] = 0.25f * s, q[1] = (r[0][1] + r[1][0]) / s, q[2] = (r[0][2] + r[2][0]) / s;
    } else if (r[1][1] > r[2][2]) {
        float s = sqrtf(1.0f + r[1][1] - r[0][0] - r[2][2]) * 2.0f;
        q[3] = (r[0][2] - r[2][0]) / s, q[0] = (r[0][1] + r[1][0]) / s, q[1] = 0.25f * s, q[2] = (r[1][2] + r[2][1]) / s;
    } else {
        float s = sqrtf(1.0f + r[2][2] - r[0][0] - r[1][1]) * 2.0f;
        q[3] = (r[1][0] - r[0][1]) / s, q[0] = (r[0][2] + r[2][0]) / s, q[1] = (r[1][2] + r[2][1]) / s, q[2] = 0.25f * s;
    }
}

/* out = a * b (Hamilton product, x y z w). */
static void quat_mul(const float a[4], const float b[4], float out[4])
{
    float r[4] = {a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
                  a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
                  a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
                  a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2]};
    memcpy(out, r, sizeof r);
}

static void root_track(character_channel_t *ch, const float c[16], float scale, const float q[4])
{
    for (int k = 0; k < ch->pos.count; k++) character_mat4_point(c, ch->pos.keys[k].v, ch->pos.keys[k].v);
    for (int k = 0; k < ch->rot.count; k++) quat_mul(q, ch->rot.keys[k].v, ch->rot.keys[k].v);
    for (int k = 0; k < ch->scale.count; k++)
        for (int e = 0; e < 3; e++) ch->scale.keys[k].v[e] *= scale;
}

static bool apply(character_model_t *m, const float c[16], float scale)
{
    float inv[16], q[4];
    if (!character_mat4_invert(c, inv)) return false;
    rotation_quat(c, scale, q);
    for (int v = 0; v < m->vertex_count; v++) {
        character_vertex_t *vx = &m->vertices[v];
        character_mat4_point(c, vx->pos, vx->pos);
        float n[3];
        for (int i = 0; i < 3; i++)
            n[i] = (c[i] * vx->normal[0] + c[4 + i] * vx->normal[1] + c[8 + i] * vx->normal[2]) / scale;
        memcpy(vx->normal, n, sizeof n);
    }
    for (int b = 0; b < m->bone_count; b++) {
        character_bone_t *bone = &m->bones[b];
        character_mat4_mul(bone->inverse_bind, inv, bone->inverse_bind);
        if (bone->parent >= 0) continue;
        character_mat4_mul(c, bone->bind_local, bone->bind_local);
        character_mat4_point(c, bone->bind_t, bone->bind_t);
        quat_mul(q, bone->bind_r, bone->bind_r);
        for (int e = 0; e < 3; e++) bone->bind_s[e] *= scale;
        for (int k = 0; k < m->clip_count; k++) root_track(&m->clips[k].channels[b], c, scale, q);
    }
    return true;
}

/* Lowest and highest bind-pose vertex along an axis. */
static void extent(const character_model_t *m, int axis, float *lo, float *hi)
{
    float a[3];
    axis_vec(axis, a);
    *lo = FLT_MAX, *hi = -FLT_MAX;
    for (int v = 0; v < m->vertex_count; v++) {
        const float *p = m->vertices[v].pos;
        float d = a[0] * p[0] + a[1] * p[1] + a[2] * p[2];
        *lo = fminf(*lo, d), *hi = fmaxf(*hi, d);
    }
}

static bool format_is(const char *format, const char *const *list)
{
    for (; *list; list++)
        if (!strcmp(format, *list)) return true;
    return false;
}

/* up and forward (file axes) with where they came from. */
static void choose_axes(const character_model_t *m, const character_import_desc_t *d, character_import_t *o)
{
    static const char *const z_up[] = {"3ds", "ase", "blend", "mdl", "md2", "smd", NULL};
    static const char *const face_x[] = {"mdl", "md2", "md3", "md5mesh", "smd", NULL};
    static const char *const face_neg_y[] = {"3ds", "ase", "blend", NULL};
    const char *fmt = m->file.format;
    if (d->up) o->up = d->up, o->up_from = "scene";
    else if (m->file.up) o->up = m->file.up, o->up_from = "metadata";
    else if (format_is(fmt, z_up)) o->up = 3, o->up_from = "format";
    else o->up = 2, o->up_from = "default";
    if (d->forward) o->forward = d->forward, o->forward_from = "scene";
    else if (m->file.front) o->forward = m->file.front, o->forward_from = "metadata";
    else if (format_is(fmt, face_x)) o->forward = 1, o->forward_from = "format";
    else if (!strcmp(fmt, "b3d")) o->forward = -3, o->forward_from = "format";
    else if (format_is(fmt, face_neg_y)) o->forward = -2, o->forward_from = "format";
    else o->forward = 3, o->forward_from = "default";
    if (abs(o->forward) == abs(o->up) && !d->forward) {
        /* a stated up with a conventional forward along it: the first
         * axis perpendicular to up of +Z, -Y, +X */
        o->forward = abs(o->up) != 3 ? 3 : -2;
        o->forward_from = "default";
    }
}

static float choose_scale(const character_model_t *m, const char *path, const character_import_desc_t *d,
                          character_import_t *o)
{
    float h = o->file_height;
    if (d->height > 0.0f) {
        o->scale_from = "scene";
        return d->height / h;
    }
    if (m->file.unit_metres > 0.0f) {
        o->scale_from = "metadata";
        float metres = h * m->file.unit_metres;
        if (metres < CHARACTER_IMPORT_MIN_HEIGHT || metres > CHARACTER_IMPORT_MAX_HEIGHT)
            core_log_warn("%s: the model is %.3g m tall in the file's units (%g m per unit), far from human size; "
                          "set characters[].height or --character-height to fit it",
                          path, (double)metres, (double)m->file.unit_metres);
        return m->file.unit_metres;
    }
    if (h >= CHARACTER_IMPORT_MIN_HEIGHT && h <= CHARACTER_IMPORT_MAX_HEIGHT) {
        o->scale_from = "file (metres)";
        return 1.0f;
    }
    o->scale_from = "fitted";
    core_log_warn("%s: the model is %.3g units tall and the file states no unit; far from human size, so it is "
                  "fitted to %.2f m (set characters[].height or --character-height to choose)",
                  path, (double)h, (double)CHARACTER_IMPORT_FIT_HEIGHT);
    return CHARACTER_IMPORT_FIT_HEIGHT / h;
}

bool character_import(character_model_t *model, const char *path, const character_import_desc_t *desc,
                      character_import_t *out, char *err, size_t err_size)
{
    character_import_t o = {0};
    if (abs(desc->up) > 3 || abs(desc->forward) > 3) {
        snprintf(err, err_size, "axis codes up %d, forward %d are not in -3..3", desc->up, desc->forward);
        return false;
    }
    if (!(desc->height >= 0.0f && desc->height <= CHARACTER_IMPORT_MAX_FIT)) {
        snprintf(err, err_size, "height %g m is outside 0..%g", (double)desc->height,
                 (double)CHARACTER_IMPORT_MAX_FIT);
        return false;
    }
    if (desc->up && desc->forward && abs(desc->up) == abs(desc->forward)) {
        snprintf(err, err_size, "forward %s lies along up %s", character_axis_name(desc->forward),
                 character_axis_name(desc->up));
        return false;
    }
    choose_axes(model, desc, &o);
    if (abs(o.up) == abs(o.forward)) {
        snprintf(err, err_size, "forward %s lies along the file's up axis %s; choose another forward",
                 character_axis_name(o.forward), character_axis_name(o.up));
        return false;
    }
    float lo, hi;
    extent(model, o.up, &lo, &hi);
    o.file_height = hi - lo;
    if (!(o.file_height > 0.0f) || !isfinite(o.file_height)) {
        snprintf(err, err_size, "the model has no height along its up axis %s", character_axis_name(o.up));
        return false;
    }
    o.scale = choose_scale(model, path, desc, &o);
    o.height = o.file_height * o.scale;
    /* feet on the ground: the bind pose's lowest point goes to y = 0 unless
     * it is already within 1% of the height */
    float lift = fabsf(lo * o.scale) > 0.01f * o.height ? -lo * o.scale : 0.0f;
    float c[16];
    character_import_matrix(o.scale, o.up, o.forward, desc->yaw, lift, c);
    bool identity = true;
    for (int e = 0; e < 16; e++) identity &= c[e] == ((e % 5) == 0 ? 1.0f : 0.0f);
    if (!identity && !apply(model, c, o.scale)) {
        snprintf(err, err_size, "scale %g cannot be inverted", (double)o.scale);
        return false;
    }
    if (out) *out = o;
    return true;
}

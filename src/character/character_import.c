/* character_import: units, axes and height of an imported character (see
 * character_import.h). The transform C = [s R | t] is a similarity, so it
 * commutes with a bone's TRS decomposition: C T(t) R(q) S(v) =
 * T(s R t + c) R(q_R q) S(s v). Root bones take it on their bind values and
 * keys; every inverse bind matrix becomes B C^-1, so skinning gives
 * C (old skinned position) for the converted vertex C p. */
#include "character/character_import.h"

#include "character/character_orient.h"
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
    for (int k = 0; k < m->morph_count; k++)
        for (int v = 0; v < m->morphs[k].count; v++) {
            float *d = m->morphs[k].delta[v], r[6];
            for (int i = 0; i < 3; i++) {
                r[i] = c[i] * d[0] + c[4 + i] * d[1] + c[8 + i] * d[2];
                r[3 + i] = (c[i] * d[3] + c[4 + i] * d[4] + c[8 + i] * d[5]) / scale;
            }
            memcpy(d, r, sizeof r);
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

/* Lowest and highest drawn vertex along an axis. */
static void extent(const character_model_t *m, const float *p, int axis, float *lo, float *hi)
{
    float a[3];
    axis_vec(axis, a);
    *lo = FLT_MAX, *hi = -FLT_MAX;
    for (int v = 0; v < m->vertex_count; v++) {
        const float *q = p + 3 * v;
        float d = a[0] * q[0] + a[1] * q[1] + a[2] * q[2];
        *lo = fminf(*lo, d), *hi = fmaxf(*hi, d);
    }
}

static bool format_is(const char *format, const char *const *list)
{
    for (; *list; list++)
        if (!strcmp(format, *list)) return true;
    return false;
}

/* Confidence of each kind of evidence (summary.txt; below
 * CHARACTER_IMPORT_LOW_CONFIDENCE the import warns). */
float character_import_evidence(const char *from)
{
    static const struct {
        const char *from;
        float c;
    } table[] = {{"scene", 1.0f},           {"skeleton, geometry", 0.95f}, {"metadata, geometry", 0.9f},
                 {"walk", 0.9f},            {"skeleton", 0.8f},            {"geometry", 0.7f},
                 {"metadata", 0.6f},        {"geometry (weak)", 0.5f},     {"geometry (head)", 0.4f},
                 {"format", 0.3f},          {"default", 0.2f}};
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (!strcmp(from, table[i].from)) return table[i].c;
    return 0.0f;
}

/* A geometry margin this large decides the up axis (at twice it, with a
 * high confidence). */
#define GEOMETRY_MARGIN 1.5f

/* up from the drawn pose P (file units) with where it came from. The
 * per-format table (what assimp 5.2 leaves Z-up or turns Y-up) breaks a
 * tie the geometry leaves: the sign along the axis the geometry found, or
 * the axis when the geometry is weak. A flat axis is never up. */
static void choose_up(const character_model_t *m, const character_import_desc_t *d, const character_pose_t *pose,
                      const float *p, character_import_t *o)
{
    static const char *const z_up[] = {"3ds", "ase", "blend", "smd", "csm", NULL};
    static const char *const y_up[] = {"mdl", "md2", "md3", "mdc", "iqm", NULL};
    float cos_sk, margin, lo, hi, size = 0.0f;
    int sk = character_orient_skeleton_up(m, pose, &cos_sk);
    int geo = character_orient_geometry_up(m, p, &margin);
    int meta = m->file.up;
    int fmt = format_is(m->file.format, z_up) ? 3 : format_is(m->file.format, y_up) ? 2 : 0;
    for (int a = 1; a <= 3; a++) extent(m, p, a, &lo, &hi), size = fmaxf(size, hi - lo);
    if (d->up) o->up = d->up, o->up_from = "scene";
    else if (sk) o->up = sk, o->up_from = geo == sk && margin >= GEOMETRY_MARGIN ? "skeleton, geometry" : "skeleton";
    else if (meta) o->up = meta, o->up_from = geo == meta && margin >= GEOMETRY_MARGIN ? "metadata, geometry" : "metadata";
    else if (margin >= 2.0f * GEOMETRY_MARGIN && fmt && abs(geo) == fmt) o->up = fmt, o->up_from = "geometry";
    else if (margin >= 2.0f * GEOMETRY_MARGIN) o->up = geo, o->up_from = "geometry";
    else if (fmt) o->up = fmt, o->up_from = "format";
    else if (margin >= GEOMETRY_MARGIN) o->up = geo, o->up_from = "geometry (weak)";
    else o->up = 2, o->up_from = "default";
    extent(m, p, o->up, &lo, &hi);
    if (!d->up && !(hi - lo > 1e-3f * size)) o->up = geo, o->up_from = "geometry (weak)";
    o->up_confidence = character_import_evidence(o->up_from);
}

/* forward (file axis) perpendicular to up; the walk (character_walk_face)
 * may still turn it. */
static void choose_forward(const character_model_t *m, const character_import_desc_t *d,
                           const character_pose_t *pose, const float *p, character_import_t *o)
{
    static const char *const face_x[] = {"mdl", "md2", "md3", "md5mesh", "smd", "iqm", NULL};
    static const char *const face_neg_z[] = {"b3d", "ms3d", NULL};
    static const char *const face_neg_y[] = {"3ds", "ase", "blend", NULL};
    const char *fmt = m->file.format;
    int sk = character_orient_skeleton_forward(m, pose, o->up);
    int body;
    if (d->forward) o->forward = d->forward, o->forward_from = "scene";
    else if (sk) o->forward = sk, o->forward_from = "skeleton";
    else if (m->file.front && abs(m->file.front) != abs(o->up)) o->forward = m->file.front, o->forward_from = "metadata";
    else if ((body = character_orient_body_forward(m, p, o->up))) o->forward = body, o->forward_from = "geometry (head)";
    else if (format_is(fmt, face_x)) o->forward = 1, o->forward_from = "format";
    else if (format_is(fmt, face_neg_z)) o->forward = -3, o->forward_from = "format";
    else if (format_is(fmt, face_neg_y)) o->forward = -2, o->forward_from = "format";
    else o->forward = 3, o->forward_from = "default";
    if (abs(o->forward) == abs(o->up) && !d->forward) {
        /* a conventional forward along the up found: the first axis
         * perpendicular to up of +Z, -Y, +X */
        o->forward = abs(o->up) != 3 ? 3 : -2;
        o->forward_from = "default";
    }
    o->forward_confidence = character_import_evidence(o->forward_from);
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
    o.pose_clip = character_orient_pose_clip(model);
    character_pose_t pose;
    float *p = malloc(sizeof(float) * 3 * (size_t)model->vertex_count);
    if (!p || !character_pose_init(&pose, model)) {
        free(p);
        snprintf(err, err_size, "out of memory for the drawn pose");
        return false;
    }
    character_orient_pose(model, o.pose_clip, &pose, p);
    choose_up(model, desc, &pose, p, &o);
    choose_forward(model, desc, &pose, p, &o);
    character_pose_free(&pose);
    bool ok = false;
    float lo, hi, c[16];
    if (abs(o.up) == abs(o.forward)) {
        snprintf(err, err_size, "forward %s lies along the file's up axis %s; choose another forward",
                 character_axis_name(o.forward), character_axis_name(o.up));
        goto done;
    }
    extent(model, p, o.up, &lo, &hi);
    o.file_height = hi - lo;
    if (!(o.file_height > 0.0f) || !isfinite(o.file_height)) {
        snprintf(err, err_size, "the model has no height along its up axis %s", character_axis_name(o.up));
        goto done;
    }
    o.scale = choose_scale(model, path, desc, &o);
    o.height = o.file_height * o.scale;
    /* feet on the ground: the drawn pose's lowest point goes to y = 0
     * unless it is there already (within 1% of the height and 1 cm) */
    float lift = fabsf(lo * o.scale) > fminf(0.01f * o.height, 0.01f) ? -lo * o.scale : 0.0f;
    character_import_matrix(o.scale, o.up, o.forward, desc->yaw, lift, c);
    bool identity = true;
    for (int e = 0; e < 16; e++) identity &= c[e] == ((e % 5) == 0 ? 1.0f : 0.0f);
    if (!identity && !apply(model, c, o.scale)) {
        snprintf(err, err_size, "scale %g cannot be inverted", (double)o.scale);
        goto done;
    }
    for (int k = 0; k < 3; k++) o.box_min[k] = FLT_MAX, o.box_max[k] = -FLT_MAX;
    for (int v = 0; v < model->vertex_count; v++) {
        float q[3];
        character_mat4_point(c, p + 3 * v, q);
        for (int k = 0; k < 3; k++) o.box_min[k] = fminf(o.box_min[k], q[k]), o.box_max[k] = fmaxf(o.box_max[k], q[k]);
    }
    ok = true;
done:
    free(p);
    if (!ok) return false;
    if (out) *out = o;
    return true;
}

float character_import_confidence(const character_import_t *o)
{
    return fminf(o->up_confidence, o->forward_confidence);
}

bool character_import_report(const char *path, const character_import_t *o)
{
    if (character_import_confidence(o) >= CHARACTER_IMPORT_LOW_CONFIDENCE) return false;
    core_log_warn("%s: up %s (%s) and forward %s (%s) are a guess (confidence %.2f); set characters[].up, "
                  "characters[].forward or characters[].rotation to choose",
                  path, character_axis_name(o->up), o->up_from, character_axis_name(o->forward), o->forward_from,
                  (double)character_import_confidence(o));
    return true;
}

/* character_ref: GL-free clip sampling, bone hierarchy, linear blend
 * skinning, per-bone capsule fitting and bounds (see character_ref.h).
 * Plain float maths, column-major 4x4 matrices (m[col * 4 + row]). */
#include "character/character_ref.h"

#include "core/core.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- small maths ---------------------------------------------------------- */
void character_mat4_mul(const float a[16], const float b[16], float out[16])
{
    float r[16];
    for (int c = 0; c < 4; c++)
        for (int row = 0; row < 4; row++) {
            float s = 0.0f;
            for (int k = 0; k < 4; k++) s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    memcpy(out, r, sizeof r);
}

bool character_mat4_invert(const float m[16], float out[16])
{
    float inv[16];
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] +
             m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] -
             m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] +
             m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] -
              m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] -
             m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] +
             m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] -
             m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] +
              m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] +
             m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] -
             m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] +
              m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] -
              m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] -
             m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] +
             m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] -
              m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] +
              m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    float det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    if (!(fabsf(det) > 1e-30f)) return false;
    for (int i = 0; i < 16; i++) out[i] = inv[i] / det;
    return true;
}

void character_mat4_point(const float m[16], const float p[3], float out[3])
{
    float r[3];
    for (int k = 0; k < 3; k++) r[k] = m[k] * p[0] + m[4 + k] * p[1] + m[8 + k] * p[2] + m[12 + k];
    memcpy(out, r, sizeof r);
}

void character_trs_matrix(const float t[3], const float r[4], const float s[3], float out[16])
{
    float x = r[0], y = r[1], z = r[2], w = r[3];
    float rot[9] = {
        1 - 2 * (y * y + z * z), 2 * (x * y + z * w),     2 * (x * z - y * w),
        2 * (x * y - z * w),     1 - 2 * (x * x + z * z), 2 * (y * z + x * w),
        2 * (x * z + y * w),     2 * (y * z - x * w),     1 - 2 * (x * x + y * y),
    };
    for (int c = 0; c < 3; c++) {
        for (int row = 0; row < 3; row++) out[c * 4 + row] = rot[c * 3 + row] * s[c];
        out[c * 4 + 3] = 0.0f;
    }
    out[12] = t[0], out[13] = t[1], out[14] = t[2], out[15] = 1.0f;
}

void character_quat_slerp(const float a[4], const float b[4], float t, float out[4])
{
    float bb[4] = {b[0], b[1], b[2], b[3]};
    float d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
    if (d < 0.0f) { /* shortest path: q and -q are the same rotation */
        d = -d;
        for (int k = 0; k < 4; k++) bb[k] = -bb[k];
    }
    float wa, wb;
    if (d > 0.9995f) {
        wa = 1.0f - t, wb = t;
    } else {
        float th = acosf(d), sn = sinf(th);
        wa = sinf((1.0f - t) * th) / sn, wb = sinf(t * th) / sn;
    }
    float len = 0.0f;
    for (int k = 0; k < 4; k++) {
        out[k] = wa * a[k] + wb * bb[k];
        len += out[k] * out[k];
    }
    len = sqrtf(len);
    if (len > 0.0f)
        for (int k = 0; k < 4; k++) out[k] /= len;
}

/* ---- sampling -------------------------------------------------------------- */
void character_track_sample(const character_track_t *track, float time, bool is_rotation, float out[4])
{
    int n = track->count;
    if (n == 0) return;
    const character_key_t *k = track->keys;
    int ncomp = is_rotation ? 4 : 3;
    if (n == 1 || !(time > k[0].time)) {
        memcpy(out, k[0].v, sizeof(float) * (size_t)ncomp);
        return;
    }
    if (time >= k[n - 1].time) {
        memcpy(out, k[n - 1].v, sizeof(float) * (size_t)ncomp);
        return;
    }
    /* last key with time <= t; then k[lo].time <= t < k[lo+1].time */
    int lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        int mid = (lo + hi) / 2;
        if (k[mid].time <= time) lo = mid;
        else hi = mid;
    }
    float f = (time - k[lo].time) / (k[lo + 1].time - k[lo].time);
    if (is_rotation) {
        character_quat_slerp(k[lo].v, k[lo + 1].v, f, out);
    } else {
        for (int c = 0; c < 3; c++) out[c] = k[lo].v[c] + (k[lo + 1].v[c] - k[lo].v[c]) * f;
    }
}

bool character_pose_init(character_pose_t *pose, const character_model_t *model)
{
    memset(pose, 0, sizeof *pose);
    size_t n = (size_t)model->bone_count;
    pose->bone_count = model->bone_count;
    pose->t = calloc(n, sizeof *pose->t);
    pose->r = calloc(n, sizeof *pose->r);
    pose->s = calloc(n, sizeof *pose->s);
    pose->global = calloc(n, sizeof *pose->global);
    pose->skin = calloc(n, sizeof *pose->skin);
    pose->morph_count = model->morph_count;
    pose->morph = calloc((size_t)model->morph_count + 1, sizeof *pose->morph);
    if (!pose->t || !pose->r || !pose->s || !pose->global || !pose->skin || !pose->morph) {
        core_log_error("%s:%d: out of memory for a pose of %d bones", __FILE__, __LINE__, model->bone_count);
        character_pose_free(pose);
        return false;
    }
    character_pose_bind(model, pose);
    character_pose_globals(model, pose);
    return true;
}

void character_pose_free(character_pose_t *pose)
{
    free(pose->t), free(pose->r), free(pose->s), free(pose->global), free(pose->skin), free(pose->morph);
    memset(pose, 0, sizeof *pose);
}

void character_pose_bind(const character_model_t *model, character_pose_t *pose)
{
    assert(pose->bone_count == model->bone_count);
    for (int i = 0; i < model->bone_count; i++) {
        const character_bone_t *b = &model->bones[i];
        memcpy(pose->t[i], b->bind_t, sizeof pose->t[i]);
        memcpy(pose->r[i], b->bind_r, sizeof pose->r[i]);
        memcpy(pose->s[i], b->bind_s, sizeof pose->s[i]);
    }
    assert(pose->morph_count == model->morph_count);
    for (int k = 0; k < model->morph_count; k++) pose->morph[k] = model->morphs[k].weight;
}

void character_sample_clip(const character_model_t *model, int clip, float time, bool loop,
                           character_pose_t *pose)
{
    assert(clip >= 0 && clip < model->clip_count);
    assert(pose->bone_count == model->bone_count);
    const character_clip_t *c = &model->clips[clip];
    float d = c->duration;
    if (loop && d > 0.0f) {
        time = fmodf(time, d);
        if (time < 0.0f) time += d;
    } else {
        time = time < 0.0f ? 0.0f : time > d ? d : time;
    }
    character_pose_bind(model, pose);
    for (int i = 0; i < model->bone_count; i++) {
        const character_channel_t *ch = &c->channels[i];
        float v[4];
        if (ch->pos.count) {
            character_track_sample(&ch->pos, time, false, v);
            memcpy(pose->t[i], v, sizeof pose->t[i]);
        }
        if (ch->rot.count) character_track_sample(&ch->rot, time, true, pose->r[i]);
        if (ch->scale.count) {
            character_track_sample(&ch->scale, time, false, v);
            memcpy(pose->s[i], v, sizeof pose->s[i]);
        }
    }
    for (int k = 0; k < c->morph_count && k < pose->morph_count; k++) {
        float v[4];
        if (!c->morph[k].count) continue;
        character_track_sample(&c->morph[k], time, false, v);
        pose->morph[k] = v[0];
    }
}

void character_pose_globals(const character_model_t *model, character_pose_t *pose)
{
    assert(pose->bone_count == model->bone_count);
    for (int i = 0; i < model->bone_count; i++) {
        float local[16];
        character_trs_matrix(pose->t[i], pose->r[i], pose->s[i], local);
        int p = model->bones[i].parent;
        assert(p < i);
        if (p >= 0) character_mat4_mul(pose->global[p], local, pose->global[i]);
        else memcpy(pose->global[i], local, sizeof local);
        character_mat4_mul(pose->global[i], model->bones[i].inverse_bind, pose->skin[i]);
    }
}

/* ---- skinning --------------------------------------------------------------- */
/* Vertex v with the pose's morph weights: position and normal. */
static void morph_vertex(const character_model_t *model, const character_pose_t *pose, int v, float pos[3],
                         float normal[3])
{
    const character_vertex_t *vx = &model->vertices[v];
    memcpy(pos, vx->pos, sizeof vx->pos);
    memcpy(normal, vx->normal, sizeof vx->normal);
    for (int k = 0; k < model->morph_count; k++) {
        const character_morph_t *mo = &model->morphs[k];
        float w = pose->morph[k];
        if (w == 0.0f || v < mo->first || v >= mo->first + mo->count) continue;
        const float *d = mo->delta[v - mo->first];
        for (int e = 0; e < 3; e++) pos[e] += w * d[e], normal[e] += w * d[3 + e];
    }
}

void character_morph_apply(const character_model_t *model, const character_pose_t *pose, character_vertex_t *out)
{
    for (int v = 0; v < model->vertex_count; v++) {
        out[v] = model->vertices[v];
        morph_vertex(model, pose, v, out[v].pos, out[v].normal);
    }
}

float character_morph_reach(const character_model_t *model, int v)
{
    float r = 0.0f;
    for (int k = 0; k < model->morph_count; k++) {
        const character_morph_t *mo = &model->morphs[k];
        if (v < mo->first || v >= mo->first + mo->count) continue;
        const float *d = mo->delta[v - mo->first];
        r += mo->max_weight * sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    }
    return r;
}

void character_skin_cpu(const character_model_t *model, const character_pose_t *pose, float *out_positions,
                        float *out_normals)
{
    for (int v = 0; v < model->vertex_count; v++) {
        const character_vertex_t *vx = &model->vertices[v];
        float pos[3], normal[3];
        morph_vertex(model, pose, v, pos, normal);
        float m[16] = {0};
        for (int k = 0; k < CHARACTER_MAX_INFLUENCES; k++) {
            float w = vx->weights[k];
            if (w == 0.0f) continue;
            const float *s = pose->skin[vx->joints[k]];
            for (int e = 0; e < 16; e++) m[e] += w * s[e];
        }
        character_mat4_point(m, pos, out_positions + 3 * v);
        if (out_normals) {
            float *n = out_normals + 3 * v, len = 0.0f;
            for (int k = 0; k < 3; k++) {
                n[k] = m[k] * normal[0] + m[4 + k] * normal[1] + m[8 + k] * normal[2];
                len += n[k] * n[k];
            }
            len = sqrtf(len);
            if (len > 0.0f)
                for (int k = 0; k < 3; k++) n[k] /= len;
        }
    }
}

/* ---- capsules ----------------------------------------------------------------- */
static int dominant_bone(const character_vertex_t *v)
{
    int best = 0;
    for (int k = 1; k < CHARACTER_MAX_INFLUENCES; k++)
        if (v->weights[k] > v->weights[best]) best = k;
    return v->joints[best];
}

/* Fits a capsule to the vertices whose dominant bone maps to `group`. */
static void fit_group(const character_model_t *model, const int *group_of, int group, const float *pos,
                      character_capsule_t *c)
{
    double cen[3] = {0}, cov[9] = {0};
    int n = 0;
    for (int v = 0; v < model->vertex_count; v++) {
        if (group_of[dominant_bone(&model->vertices[v])] != group) continue;
        for (int k = 0; k < 3; k++) cen[k] += pos[3 * v + k];
        n++;
    }
    for (int k = 0; k < 3; k++) cen[k] /= n;
    for (int v = 0; v < model->vertex_count; v++) {
        if (group_of[dominant_bone(&model->vertices[v])] != group) continue;
        double d[3] = {pos[3 * v] - cen[0], pos[3 * v + 1] - cen[1], pos[3 * v + 2] - cen[2]};
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 3; j++) cov[i * 3 + j] += d[i] * d[j];
    }
    /* principal axis by power iteration (deterministic start vector) */
    double ax[3] = {0.5773, 0.5774, 0.5775};
    for (int it = 0; it < 64; it++) {
        double nx[3] = {0}, len = 0.0;
        for (int i = 0; i < 3; i++) {
            for (int j = 0; j < 3; j++) nx[i] += cov[i * 3 + j] * ax[j];
            len += nx[i] * nx[i];
        }
        len = sqrt(len);
        if (len < 1e-20) {
            ax[0] = 0, ax[1] = 1, ax[2] = 0;
            break;
        }
        for (int i = 0; i < 3; i++) ax[i] = nx[i] / len;
    }
    /* radius: largest distance from the axis; end points: as far in as
     * keeping every vertex inside allows (see character_ref.h) */
    double r2 = 0.0;
    for (int v = 0; v < model->vertex_count; v++) {
        if (group_of[dominant_bone(&model->vertices[v])] != group) continue;
        double d[3] = {pos[3 * v] - cen[0], pos[3 * v + 1] - cen[1], pos[3 * v + 2] - cen[2]};
        double pr = d[0] * ax[0] + d[1] * ax[1] + d[2] * ax[2];
        double q = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - pr * pr;
        if (q > r2) r2 = q;
    }
    double r = sqrt(r2) * (1.0 + 1e-5) + 1e-6;
    r2 = r * r;
    double lo = INFINITY, hi = -INFINITY;
    for (int v = 0; v < model->vertex_count; v++) {
        if (group_of[dominant_bone(&model->vertices[v])] != group) continue;
        double d[3] = {pos[3 * v] - cen[0], pos[3 * v + 1] - cen[1], pos[3 * v + 2] - cen[2]};
        double pr = d[0] * ax[0] + d[1] * ax[1] + d[2] * ax[2];
        double q = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] - pr * pr;
        double h = sqrt(fmax(0.0, r2 - q));
        if (pr + h < lo) lo = pr + h;
        if (pr - h > hi) hi = pr - h;
    }
    if (lo > hi) lo = hi = 0.5 * (lo + hi);
    for (int k = 0; k < 3; k++) {
        c->a[k] = (float)(cen[k] + ax[k] * lo);
        c->b[k] = (float)(cen[k] + ax[k] * hi);
    }
    c->radius = (float)r;
    c->vertex_count = n;
}

int character_fit_capsules(const character_model_t *model, const character_pose_t *pose,
                           const float *skinned_positions, character_capsule_t *capsules_out, int max)
{
    assert(pose->bone_count == model->bone_count);
    int nb = model->bone_count;
    if (max <= 0 || nb == 0) return 0;
    int *group_of = malloc(sizeof(int) * (size_t)nb);
    int *count = calloc((size_t)nb, sizeof(int));
    double (*sum)[3] = calloc((size_t)nb, sizeof *sum);
    if (!group_of || !count || !sum) {
        core_log_error("%s:%d: out of memory fitting capsules", __FILE__, __LINE__);
        free(group_of), free(count), free(sum);
        return 0;
    }
    for (int b = 0; b < nb; b++) group_of[b] = b;
    for (int v = 0; v < model->vertex_count; v++) {
        int b = dominant_bone(&model->vertices[v]);
        count[b]++;
        for (int k = 0; k < 3; k++) sum[b][k] += skinned_positions[3 * v + k];
    }
    int active = 0;
    for (int b = 0; b < nb; b++) active += count[b] > 0;
    while (active > max) {
        int g = -1;
        for (int b = 0; b < nb; b++)
            if (count[b] > 0 && (g < 0 || count[b] <= count[g])) g = b;
        int target = model->bones[g].parent;
        while (target >= 0 && count[target] == 0) target = model->bones[target].parent;
        if (target < 0) { /* a root: merge into the nearest group by centroid */
            double best = INFINITY;
            for (int b = 0; b < nb; b++) {
                if (b == g || count[b] == 0) continue;
                double d2 = 0.0;
                for (int k = 0; k < 3; k++) {
                    double d = sum[b][k] / count[b] - sum[g][k] / count[g];
                    d2 += d * d;
                }
                if (d2 < best) best = d2, target = b;
            }
        }
        for (int b = 0; b < nb; b++)
            if (group_of[b] == g) group_of[b] = target;
        count[target] += count[g];
        for (int k = 0; k < 3; k++) sum[target][k] += sum[g][k];
        count[g] = 0;
        active--;
    }
    int out = 0;
    for (int b = 0; b < nb; b++) {
        if (count[b] == 0) continue;
        character_capsule_t *c = &capsules_out[out++];
        memset(c, 0, sizeof *c);
        c->bone = b;
        fit_group(model, group_of, b, skinned_positions, c);
        float inv[16];
        if (!character_mat4_invert(pose->global[b], inv)) {
            core_log_warn("character: bone %d has a singular global matrix; capsule local ends = model ends", b);
            memcpy(c->local_a, c->a, sizeof c->a), memcpy(c->local_b, c->b, sizeof c->b);
        } else {
            character_mat4_point(inv, c->a, c->local_a);
            character_mat4_point(inv, c->b, c->local_b);
        }
    }
    free(group_of), free(count), free(sum);
    return out;
}

float character_capsule_distance(const character_capsule_t *c, const float p[3])
{
    float ab[3], ap[3], dd = 0.0f, t = 0.0f;
    for (int k = 0; k < 3; k++) {
        ab[k] = c->b[k] - c->a[k], ap[k] = p[k] - c->a[k];
        dd += ab[k] * ab[k], t += ab[k] * ap[k];
    }
    t = dd > 0.0f ? t / dd : 0.0f;
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    float d2 = 0.0f;
    for (int k = 0; k < 3; k++) {
        float e = ap[k] - ab[k] * t;
        d2 += e * e;
    }
    return sqrtf(d2) - c->radius;
}

/* ---- bounds --------------------------------------------------------------------- */
void character_bounds(const character_model_t *model, const float *pos, character_bounds_t *out)
{
    memset(out, 0, sizeof *out);
    if (model->vertex_count == 0) return;
    for (int k = 0; k < 3; k++) out->min[k] = out->max[k] = pos[k];
    for (int v = 1; v < model->vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            out->min[k] = fminf(out->min[k], pos[3 * v + k]);
            out->max[k] = fmaxf(out->max[k], pos[3 * v + k]);
        }
    for (int k = 0; k < 3; k++) out->center[k] = 0.5f * (out->min[k] + out->max[k]);
    float r2 = 0.0f;
    for (int v = 0; v < model->vertex_count; v++) {
        float d2 = 0.0f;
        for (int k = 0; k < 3; k++) {
            float d = pos[3 * v + k] - out->center[k];
            d2 += d * d;
        }
        r2 = fmaxf(r2, d2);
    }
    out->radius = sqrtf(r2);
}

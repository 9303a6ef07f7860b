/* character_load: assimp -> character_model_t (see character_load.h).
 * Node hierarchy flattened depth-first (parents first), meshes merged,
 * weights limited to the 4 largest and renormalised, clips converted to
 * seconds and repaired by character_clip_fixup. No paper equations. */
#include "character/character_load.h"

#include "character/character_ref.h"
#include "core/core.h"
#include "mesh/mesh_import.h"

#include <assimp/cimport.h>
#include <assimp/material.h>
#include <assimp/metadata.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <unistd.h>

static char *dup_str(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

/* assimp matrices are row-major (a1..a4 is the first row). */
static void mat_from_ai(const struct aiMatrix4x4 *m, float out[16])
{
    const float rows[4][4] = {{m->a1, m->a2, m->a3, m->a4},
                              {m->b1, m->b2, m->b3, m->b4},
                              {m->c1, m->c2, m->c3, m->c4},
                              {m->d1, m->d2, m->d3, m->d4}};
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) out[c * 4 + r] = rows[r][c];
}

static void mat_identity(float m[16])
{
    memset(m, 0, sizeof(float) * 16);
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

/* Normal matrix (inverse transpose of the upper 3x3) applied to n. */
static void transform_normal(const float m[16], const float n[3], float out[3])
{
    float inv[16];
    if (!character_mat4_invert(m, inv)) mat_identity(inv);
    float len = 0.0f;
    for (int k = 0; k < 3; k++) {
        out[k] = inv[k * 4 + 0] * n[0] + inv[k * 4 + 1] * n[1] + inv[k * 4 + 2] * n[2];
        len += out[k] * out[k];
    }
    len = sqrtf(len);
    if (len > 0.0f)
        for (int k = 0; k < 3; k++) out[k] /= len;
}

void character_model_free(character_model_t *model)
{
    if (!model) return;
    for (int i = 0; i < model->bone_count; i++) free(model->bones[i].name);
    for (int c = 0; c < model->clip_count; c++) {
        character_clip_t *clip = &model->clips[c];
        for (int b = 0; clip->channels && b < model->bone_count; b++) {
            free(clip->channels[b].pos.keys);
            free(clip->channels[b].rot.keys);
            free(clip->channels[b].scale.keys);
        }
        free(clip->channels);
        for (int k = 0; clip->morph && k < clip->morph_count; k++) free(clip->morph[k].keys);
        free(clip->morph);
        free(clip->name);
    }
    free(model->clips);
    for (int k = 0; k < model->morph_count; k++) free(model->morphs[k].delta);
    free(model->morphs);
    free(model->bones);
    free(model->vertices);
    free(model->indices);
    free(model->texture_embedded.data);
    memset(model, 0, sizeof *model);
}

int character_bone_find(const character_model_t *model, const char *name)
{
    for (int i = 0; i < model->bone_count; i++)
        if (!strcmp(model->bones[i].name, name)) return i;
    return -1;
}

/* ---- clip repair ------------------------------------------------------------ */
static int key_cmp(const void *a, const void *b)
{
    float ta = ((const character_key_t *)a)->time, tb = ((const character_key_t *)b)->time;
    return (ta > tb) - (ta < tb);
}

typedef struct fix_counts_t {
    int nan, zero_quat, negative, unsorted, unnormalised;
    float max_time;
} fix_counts_t;

static void fix_track(character_track_t *t, bool rot, fix_counts_t *fc)
{
    int n = 0, ncomp = rot ? 4 : 3;
    for (int i = 0; i < t->count; i++) {
        character_key_t k = t->keys[i];
        bool finite = isfinite(k.time);
        for (int c = 0; c < ncomp; c++) finite &= isfinite(k.v[c]);
        if (!finite) {
            fc->nan++;
            continue;
        }
        if (rot) {
            float len = sqrtf(k.v[0] * k.v[0] + k.v[1] * k.v[1] + k.v[2] * k.v[2] + k.v[3] * k.v[3]);
            if (len < 1e-6f) {
                fc->zero_quat++;
                continue;
            }
            if (fabsf(len - 1.0f) > 1e-3f) fc->unnormalised++;
            for (int c = 0; c < 4; c++) k.v[c] /= len;
        }
        if (k.time < 0.0f) {
            fc->negative++;
            k.time = 0.0f;
        }
        t->keys[n++] = k;
    }
    t->count = n;
    for (int i = 1; i < n; i++)
        if (t->keys[i].time < t->keys[i - 1].time) {
            fc->unsorted++;
            qsort(t->keys, (size_t)n, sizeof *t->keys, key_cmp);
            break;
        }
    if (n && t->keys[n - 1].time > fc->max_time) fc->max_time = t->keys[n - 1].time;
}

int character_clip_fixup(character_clip_t *clip, int bone_count, const char *context)
{
    fix_counts_t fc = {0};
    int keys = 0;
    for (int b = 0; b < bone_count; b++) {
        character_channel_t *ch = &clip->channels[b];
        fix_track(&ch->pos, false, &fc);
        fix_track(&ch->rot, true, &fc);
        fix_track(&ch->scale, false, &fc);
        keys += ch->pos.count + ch->rot.count + ch->scale.count;
    }
    for (int k = 0; clip->morph && k < clip->morph_count; k++) {
        fix_track(&clip->morph[k], false, &fc);
        keys += clip->morph[k].count;
    }
    const char *name = clip->name ? clip->name : "?";
    int fixes = 0;
    if (fc.nan) core_log_warn("%s: clip '%s': dropped %d key(s) with a NaN/inf time or value", context, name, fc.nan);
    if (fc.zero_quat) core_log_warn("%s: clip '%s': dropped %d zero-length rotation key(s)", context, name, fc.zero_quat);
    if (fc.unnormalised) core_log_warn("%s: clip '%s': normalised %d rotation key(s)", context, name, fc.unnormalised);
    if (fc.negative) core_log_warn("%s: clip '%s': clamped %d negative key time(s) to 0", context, name, fc.negative);
    if (fc.unsorted) core_log_warn("%s: clip '%s': sorted %d track(s) with unordered key times", context, name, fc.unsorted);
    fixes += fc.nan + fc.zero_quat + fc.unnormalised + fc.negative + fc.unsorted;
    if (keys == 0) {
        core_log_warn("%s: clip '%s' has no keys; it holds the bind pose", context, name);
        fixes++;
    }
    clip->still = keys == 0 || (!(clip->duration > 0.0f) && !(fc.max_time > 0.0f));
    if (!(clip->duration > 0.0f) || !isfinite(clip->duration)) {
        float d = fc.max_time > 0.0f ? fc.max_time : 1.0f;
        core_log_warn("%s: clip '%s': duration %g is not positive; using %g s", context, name,
                      (double)clip->duration, (double)d);
        clip->duration = d;
        fixes++;
    } else if (fc.max_time > clip->duration * (1.0f + 1e-5f)) {
        core_log_warn("%s: clip '%s': keys run to %g s past the duration %g s; duration extended", context, name,
                      (double)fc.max_time, (double)clip->duration);
        clip->duration = fc.max_time;
        fixes++;
    }
    return fixes;
}

/* ---- clip selection ------------------------------------------------------------- */
static bool slice_track(const character_track_t *src, bool rot, float t0, float t1, character_track_t *dst)
{
    dst->count = 0;
    dst->keys = NULL;
    if (src->count == 0) return true;
    dst->keys = malloc(sizeof *dst->keys * (size_t)(src->count + 2));
    if (!dst->keys) return false;
    character_key_t k = {0};
    k.time = 0.0f;
    character_track_sample(src, t0, rot, k.v);
    dst->keys[dst->count++] = k;
    for (int i = 0; i < src->count; i++)
        if (src->keys[i].time > t0 && src->keys[i].time < t1) {
            k = src->keys[i];
            k.time -= t0;
            dst->keys[dst->count++] = k;
        }
    k.time = t1 - t0;
    character_track_sample(src, t1, rot, k.v);
    dst->keys[dst->count++] = k;
    return true;
}

bool character_clip_parse_range(const char *spec, double *a, double *b)
{
    const char *colon = spec ? strchr(spec, ':') : NULL;
    if (!colon) return false;
    char *e1, *e2;
    *a = strtod(spec, &e1);
    *b = strtod(colon + 1, &e2);
    return e1 == colon && e1 != spec && e2 != colon + 1 && *e2 == 0;
}

bool character_clip_range_check(const character_model_t *model, double a, double b, char *why, size_t why_size)
{
    if (model->clip_count == 0) {
        snprintf(why, why_size, "the model has no clips");
        return false;
    }
    const character_clip_t *src = &model->clips[0];
    double tps = src->ticks_per_second > 0.0f ? src->ticks_per_second : 1.0, ticks = src->duration * tps;
    if (!isfinite(a) || !isfinite(b)) snprintf(why, why_size, "%g:%g is not a pair of finite numbers", a, b);
    else if (a < 0.0) snprintf(why, why_size, "start %g is negative", a);
    else if (!(b > a)) snprintf(why, why_size, "end %g is not after start %g", b, a);
    else if (b > ticks * (1.0 + 1e-5) + 1e-6)
        snprintf(why, why_size, "end %g is past the timeline's %.6g ticks (clip 0 '%s')", b, ticks, src->name);
    else return true;
    return false;
}

static bool slice_tracks(const character_track_t *src, int n, bool rot, float t0, float t1, character_track_t *dst)
{
    bool ok = true;
    for (int i = 0; i < n; i++) ok &= slice_track(&src[i], rot, t0, t1, &dst[i]);
    return ok;
}

/* A clip character_clip_range cut: reached through its range only, so that
 * a character sharing the model never gets another one's named range. */
static bool clip_is_cut(const character_clip_t *c) { return c->cut[0] != 0.0f || c->cut[1] != 0.0f; }

int character_clip_range(character_model_t *model, const char *name, double a, double b)
{
    char why[160];
    if (!character_clip_range_check(model, a, b, why, sizeof why)) return -1;
    for (int i = 0; i < model->clip_count; i++) {
        const character_clip_t *c = &model->clips[i];
        if (clip_is_cut(c) && c->cut[0] == (float)a && c->cut[1] == (float)b && !strcmp(c->name, name)) return i;
    }
    const character_clip_t *src = &model->clips[0];
    float tps = src->ticks_per_second > 0.0f ? src->ticks_per_second : 1.0f;
    float t0 = (float)(a / tps), t1 = fminf((float)(b / tps), src->duration);
    character_clip_t *grown = realloc(model->clips, sizeof *grown * (size_t)(model->clip_count + 1));
    if (!grown) return -1;
    model->clips = grown;
    src = &model->clips[0];
    character_clip_t *c = &model->clips[model->clip_count];
    memset(c, 0, sizeof *c);
    c->name = dup_str(name);
    c->duration = t1 - t0;
    c->ticks_per_second = src->ticks_per_second;
    c->cut[0] = (float)a, c->cut[1] = (float)b;
    c->channels = calloc((size_t)model->bone_count, sizeof *c->channels);
    c->morph_count = src->morph_count;
    c->morph = calloc((size_t)c->morph_count + 1, sizeof *c->morph);
    bool ok = c->name && c->channels && c->morph;
    for (int i = 0; ok && i < model->bone_count; i++) {
        ok &= slice_track(&src->channels[i].pos, false, t0, t1, &c->channels[i].pos);
        ok &= slice_track(&src->channels[i].rot, true, t0, t1, &c->channels[i].rot);
        ok &= slice_track(&src->channels[i].scale, false, t0, t1, &c->channels[i].scale);
    }
    ok = ok && slice_tracks(src->morph, c->morph_count, false, t0, t1, c->morph);
    model->clip_count++;
    if (!ok) core_log_error("%s:%d: out of memory slicing clip '%s'", __FILE__, __LINE__, name);
    return ok ? model->clip_count - 1 : -1;
}

int character_clip_playable(const character_model_t *model, int clip)
{
    for (int k = 0; k < model->clip_count; k++) {
        int j = (clip + k) % model->clip_count;
        if (!model->clips[j].still) return j;
    }
    return clip;
}

int character_clip_find(character_model_t *model, const char *spec)
{
    if (!spec || !*spec) return model->clip_count > 0 ? 0 : -1;
    for (int i = 0; i < model->clip_count; i++)
        if (!clip_is_cut(&model->clips[i]) && !strcmp(model->clips[i].name, spec)) return i;
    for (int i = 0; i < model->clip_count; i++)
        if (!clip_is_cut(&model->clips[i]) && !strcasecmp(model->clips[i].name, spec)) return i;
    for (int i = 0; i < model->clip_count; i++) {
        const char *bar = strrchr(model->clips[i].name, '|');
        if (!clip_is_cut(&model->clips[i]) && bar && !strcasecmp(bar + 1, spec)) return i;
    }
    char *end;
    long idx = strtol(spec, &end, 10);
    if (end != spec && *end == 0) {
        return idx >= 0 && idx < model->clip_count ? (int)idx : -1;
    }
    double a, b;
    if (character_clip_parse_range(spec, &a, &b)) return character_clip_range(model, spec, a, b);
    return -1;
}

int character_clip_keys(const character_clip_t *clip, int bone_count)
{
    int keys = 0;
    for (int b = 0; b < bone_count; b++)
        keys += clip->channels[b].pos.count + clip->channels[b].rot.count + clip->channels[b].scale.count;
    for (int k = 0; clip->morph && k < clip->morph_count; k++) keys += clip->morph[k].count;
    return keys;
}

size_t character_clip_list(const character_model_t *model, char *buf, size_t size)
{
    size_t n = 0;
    if (size) buf[0] = 0;
    for (int i = 0; i < model->clip_count && n < size; i++) {
        const character_clip_t *c = &model->clips[i];
        int w = snprintf(buf + n, size - n, "%s%d '%s' (%.3g s)", i ? ", " : "", i, c->name, (double)c->duration);
        n += w > 0 ? (size_t)w : 0;
    }
    if (model->clip_count && n < size) {
        const character_clip_t *c = &model->clips[0];
        int w = snprintf(buf + n, size - n, ", or a range A:B of clip 0's %.6g ticks",
                         (double)(c->duration * c->ticks_per_second));
        n += w > 0 ? (size_t)w : 0;
    }
    return n;
}

/* ---- import ------------------------------------------------------------------- */
typedef struct load_ctx_t {
    const char *path;
    const struct aiScene *scene;
    const struct aiNode **nodes;
    int node_count;
    float (*global)[16];
    bool *has_offset;
    bool hl1; /* a Half-Life 1 model (hl1_restore_parents) */
} load_ctx_t;

static int count_nodes(const struct aiNode *n)
{
    int c = 1;
    for (unsigned i = 0; i < n->mNumChildren; i++) c += count_nodes(n->mChildren[i]);
    return c;
}

static void flatten(load_ctx_t *ctx, character_model_t *m, const struct aiNode *n, int parent)
{
    int idx = ctx->node_count++;
    ctx->nodes[idx] = n;
    character_bone_t *b = &m->bones[idx];
    b->parent = parent;
    b->name = dup_str(n->mName.length ? n->mName.data : "node");
    mat_from_ai(&n->mTransformation, b->bind_local);
    struct aiVector3D s, p;
    struct aiQuaternion q;
    aiDecomposeMatrix(&n->mTransformation, &s, &q, &p);
    b->bind_t[0] = p.x, b->bind_t[1] = p.y, b->bind_t[2] = p.z;
    b->bind_r[0] = q.x, b->bind_r[1] = q.y, b->bind_r[2] = q.z, b->bind_r[3] = q.w;
    b->bind_s[0] = s.x, b->bind_s[1] = s.y, b->bind_s[2] = s.z;
    if (parent >= 0) character_mat4_mul(ctx->global[parent], b->bind_local, ctx->global[idx]);
    else memcpy(ctx->global[idx], b->bind_local, sizeof ctx->global[idx]);
    for (unsigned i = 0; i < n->mNumChildren; i++) flatten(ctx, m, n->mChildren[i], idx);
}

/* A mesh with triangles. Faces decide, not mPrimitiveTypes: assimp 5.2's
 * triangulation leaves the flags of a polygon mesh saying LINE | TRIANGLE |
 * POLYGON (Blender's all-quad OBJ export was taken for lines). */
static bool is_triangle_mesh(const struct aiMesh *mesh)
{
    if (mesh->mNumVertices == 0 || !mesh->mFaces) return false;
    for (unsigned f = 0; f < mesh->mNumFaces; f++)
        if (mesh->mFaces[f].mNumIndices == 3) return true;
    return false;
}

/* Inserts (bone, w) into the 4 slots, keeping the largest weights.
 * Returns true when a weight was dropped. */
static bool add_influence(character_vertex_t *v, int bone, float w)
{
    int smallest = 0;
    for (int k = 1; k < CHARACTER_MAX_INFLUENCES; k++)
        if (v->weights[k] < v->weights[smallest]) smallest = k;
    bool dropped = v->weights[smallest] > 0.0f;
    if (w > v->weights[smallest]) {
        v->weights[smallest] = w;
        v->joints[smallest] = (uint16_t)bone;
    }
    return dropped;
}

/* ---- textures ----------------------------------------------------------------- */
/* The embedded texture that `ref` names ("*N", or an mTextures entry's
 * file name), or NULL. */
static const struct aiTexture *embedded_texture(const struct aiScene *scene, const char *ref)
{
    if (!scene->mTextures || !scene->mNumTextures) return NULL;
    if (ref[0] == '*') {
        char *end;
        long i = strtol(ref + 1, &end, 10);
        return end != ref + 1 && !*end && i >= 0 && i < (long)scene->mNumTextures ? scene->mTextures[i] : NULL;
    }
    const char *base = character_path_basename(ref);
    for (unsigned i = 0; i < scene->mNumTextures; i++) {
        const struct aiTexture *t = scene->mTextures[i];
        if (t->mFilename.length && !strcmp(character_path_basename(t->mFilename.data), base)) return t;
    }
    return NULL;
}

/* Copies an embedded texture into m->texture_embedded: a compressed file as
 * is, raw BGRA texels as they are. */
static bool copy_embedded(character_model_t *m, const struct aiTexture *t)
{
    size_t size = t->mHeight ? (size_t)t->mWidth * t->mHeight * 4 : t->mWidth;
    if (!t->pcData || size == 0) return false;
    m->texture_embedded.data = malloc(size);
    if (!m->texture_embedded.data) return false;
    memcpy(m->texture_embedded.data, t->pcData, size);
    m->texture_embedded.size = size;
    m->texture_embedded.width = (int)t->mWidth;
    m->texture_embedded.height = (int)t->mHeight;
    return true;
}

const char *character_path_basename(const char *p)
{
    const char *slash = strrchr(p, '/'), *back = strrchr(p, '\\');
    const char *last = slash > back ? slash : back;
    return last ? last + 1 : p;
}

bool character_texture_find(const char *model_path, const char *ref, char *out, size_t out_size, char *tried,
                            size_t tried_size)
{
    const char *slash = strrchr(model_path, '/');
    int dir = slash ? (int)(slash - model_path) + 1 : 0;
    const char *base = character_path_basename(ref);
    char cand[4][1024];
    int n = 0;
    if (ref[0] == '/') snprintf(cand[n++], sizeof cand[0], "%s", ref);
    else if (base != ref) snprintf(cand[n++], sizeof cand[0], "%.*s%s", dir, model_path, ref);
    snprintf(cand[n++], sizeof cand[0], "%.*s%s", dir, model_path, base);
    snprintf(cand[n++], sizeof cand[0], "%.*stextures/%s", dir, model_path, base);
    snprintf(cand[n++], sizeof cand[0], "%.*s../textures/%s", dir, model_path, base);
    size_t used = 0;
    if (tried_size) tried[0] = 0;
    for (int i = 0; i < n; i++) {
        if (access(cand[i], R_OK) == 0 && strlen(cand[i]) < out_size) {
            snprintf(out, out_size, "%s", cand[i]);
            return true;
        }
        if (used < tried_size) {
            int w = snprintf(tried + used, tried_size - used, "%s%s", i ? ", " : "", cand[i]);
            used += w > 0 ? (size_t)w : 0;
        }
    }
    return false;
}

/* The diffuse texture named `ref`: embedded, else a file found by
 * character_texture_find. Every problem is a warning (the model draws in its
 * base colour). */
static void load_texture(character_model_t *m, const struct aiScene *scene, const char *ref, const char *path)
{
    const struct aiTexture *emb = embedded_texture(scene, ref);
    if (emb) {
        if (!copy_embedded(m, emb))
            core_log_warn("%s: embedded texture '%s' is empty; using the plain base colour", path, ref);
        return;
    }
    const char *base = character_path_basename(ref);
    if (!base[0] || base[0] == '$' || ref[0] == '*') {
        /* "", a folder, "*N" past mTextures, assimp's "$texture_dummy.bmp" */
        core_log_warn("%s: the material names no usable texture file; using the plain base colour", path);
        return;
    }
    char tried[2048];
    if (!character_texture_find(path, ref, m->texture_path, sizeof m->texture_path, tried, sizeof tried)) {
        m->texture_path[0] = 0;
        core_log_warn("%s: texture '%s' not found (tried %s); using the plain base colour", path, ref, tried);
    }
}

static void load_material(character_model_t *m, const struct aiScene *scene, const struct aiMesh *mesh,
                          const char *path)
{
    m->base_color[0] = m->base_color[1] = m->base_color[2] = 0.8f;
    m->base_color[3] = 1.0f;
    m->texture_path[0] = 0;
    if (!scene->mMaterials || mesh->mMaterialIndex >= scene->mNumMaterials) return;
    const struct aiMaterial *mat = scene->mMaterials[mesh->mMaterialIndex];
    struct aiColor4D c;
    if (aiGetMaterialColor(mat, AI_MATKEY_BASE_COLOR, &c) == aiReturn_SUCCESS ||
        aiGetMaterialColor(mat, AI_MATKEY_COLOR_DIFFUSE, &c) == aiReturn_SUCCESS) {
        m->base_color[0] = c.r, m->base_color[1] = c.g, m->base_color[2] = c.b, m->base_color[3] = c.a;
    }
    struct aiString tex;
    if (aiGetMaterialTexture(mat, aiTextureType_BASE_COLOR, 0, &tex, NULL, NULL, NULL, NULL, NULL, NULL) !=
            aiReturn_SUCCESS &&
        aiGetMaterialTexture(mat, aiTextureType_DIFFUSE, 0, &tex, NULL, NULL, NULL, NULL, NULL, NULL) !=
            aiReturn_SUCCESS)
        return;
    load_texture(m, scene, tex.data, path);
}

/* ---- Half-Life 1 models ---------------------------------------------------------
 * assimp 5.2's HL1 reader puts every bone directly under "<MDL_bones>" (the
 * file's parent links are lost) while each local transform and offset
 * matrix is relative to the real parent: posed as a flat list the model is
 * a heap. The parents are read back from the file (studiohdr_t: numbones at
 * byte 140, boneindex at 144; mstudiobone_t: 112 bytes, name[32] then the
 * parent index), the bones being "<MDL_bones>"'s children in file order. */
#define HL1_BONE_SIZE 112

static int32_t read_i32(const unsigned char *p) { return (int32_t)((uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24); }

/* Re-parents the HL1 bones and recomputes their bind globals; true when
 * the file was an HL1 model whose links were restored. */
static bool hl1_restore_parents(load_ctx_t *ctx, character_model_t *m)
{
    if (strcmp(m->bones[0].name, "<MDL_root>") != 0) return false;
    int first = -1;
    for (int i = 0; i < m->bone_count && first < 0; i++)
        if (!strcmp(m->bones[i].name, "<MDL_bones>")) first = i + 1;
    if (first < 0) return false;
    int n = (int)ctx->nodes[first - 1]->mNumChildren;
    size_t size = 0;
    char why[256];
    unsigned char *file = (unsigned char *)core_fs_read(ctx->path, &size, why, sizeof why);
    bool ok = file && size >= 148 && !memcmp(file, "IDST", 4) && read_i32(file + 140) == n;
    int32_t index = ok ? read_i32(file + 144) : 0;
    ok = ok && index > 0 && (size_t)index + (size_t)n * HL1_BONE_SIZE <= size && first + n <= m->bone_count;
    for (int i = 0; ok && i < n; i++) {
        int32_t parent = read_i32(file + index + (size_t)i * HL1_BONE_SIZE + 32);
        if (parent < -1 || parent >= i) ok = false;
        else if (parent >= 0) m->bones[first + i].parent = first + parent;
    }
    free(file);
    if (!ok) {
        core_log_warn("%s: the HL1 bone links could not be read; the bones stay unlinked", ctx->path);
        return false;
    }
    for (int i = first; i < first + n; i++)
        character_mat4_mul(ctx->global[m->bones[i].parent], m->bones[i].bind_local, ctx->global[i]);
    return true;
}

/* A morph weight channel (named after the node whose meshes it drives) into
 * the weight track of each of that node's morph targets; a target the key
 * does not list has weight 0 there. False when out of memory. */
static bool load_morph_channel(load_ctx_t *ctx, character_model_t *m, character_clip_t *c,
                               const struct aiMeshMorphAnim *ch, double tps)
{
    int node = character_bone_find(m, ch->mName.data), used = 0;
    for (int k = 0; node >= 0 && k < m->morph_count; k++) {
        character_morph_t *mo = &m->morphs[k];
        character_track_t *t = &c->morph[k];
        if (mo->node != node || t->count) continue;
        used++;
        t->keys = calloc(ch->mNumKeys + 1, sizeof *t->keys);
        if (!t->keys) return false;
        for (unsigned j = 0; ch->mKeys && j < ch->mNumKeys; j++) {
            const struct aiMeshMorphKey *key = &ch->mKeys[j];
            character_key_t *out = &t->keys[t->count++];
            *out = (character_key_t){.time = (float)(key->mTime / tps)};
            for (unsigned v = 0; key->mValues && key->mWeights && v < key->mNumValuesAndWeights; v++)
                if ((int)key->mValues[v] == mo->target) out->v[0] = (float)key->mWeights[v];
            if (isfinite(out->v[0])) mo->max_weight = fmaxf(mo->max_weight, fabsf(out->v[0]));
        }
    }
    if (!used)
        core_log_warn("%s: clip '%s': morph channel for '%s' drives no morph target; ignored", ctx->path, c->name,
                      ch->mName.data);
    return true;
}

static bool load_clips(load_ctx_t *ctx, character_model_t *m)
{
    const struct aiScene *sc = ctx->scene;
    if (sc->mNumAnimations == 0) return true;
    m->clips = calloc(sc->mNumAnimations, sizeof *m->clips);
    if (!m->clips) return false;
    for (unsigned a = 0; a < sc->mNumAnimations; a++) {
        const struct aiAnimation *an = sc->mAnimations[a];
        character_clip_t *c = &m->clips[m->clip_count++];
        char name[64];
        snprintf(name, sizeof name, "clip%u", a);
        c->name = dup_str(an->mName.length ? an->mName.data : name);
        double tps = an->mTicksPerSecond > 0.0 ? an->mTicksPerSecond : 25.0;
        c->ticks_per_second = (float)tps;
        /* assimp 5.2's HL1 reader states the duration as frames times the
         * frame rate, in ticks of one frame: fps times too long */
        c->duration = (float)(an->mDuration / tps / (ctx->hl1 ? tps : 1.0));
        c->channels = calloc((size_t)m->bone_count, sizeof *c->channels);
        c->morph_count = m->morph_count;
        c->morph = calloc((size_t)m->morph_count + 1, sizeof *c->morph);
        if (!c->name || !c->channels || !c->morph) return false;
        if (an->mNumMeshChannels)
            core_log_warn("%s: clip '%s': %u mesh (vertex) animation channel(s) ignored: assimp delivers no frames",
                          ctx->path, c->name, an->mNumMeshChannels);
        for (unsigned i = 0; an->mMorphMeshChannels && i < an->mNumMorphMeshChannels; i++)
            if (!load_morph_channel(ctx, m, c, an->mMorphMeshChannels[i], tps)) return false;
        for (unsigned i = 0; i < an->mNumChannels; i++) {
            const struct aiNodeAnim *na = an->mChannels[i];
            int b = character_bone_find(m, na->mNodeName.data);
            if (b < 0) {
                core_log_warn("%s: clip '%s': channel for unknown node '%s' ignored", ctx->path, c->name,
                              na->mNodeName.data);
                continue;
            }
            character_channel_t *ch = &c->channels[b];
            if (ch->pos.count || ch->rot.count || ch->scale.count) {
                core_log_warn("%s: clip '%s': second channel for node '%s' ignored", ctx->path, c->name,
                              na->mNodeName.data);
                continue;
            }
            if (!na->mNumPositionKeys && !na->mNumRotationKeys && !na->mNumScalingKeys)
                core_log_warn("%s: clip '%s': channel for '%s' has zero keys; bone keeps its bind pose", ctx->path,
                              c->name, na->mNodeName.data);
            ch->pos.keys = calloc(na->mNumPositionKeys + 1, sizeof *ch->pos.keys);
            ch->rot.keys = calloc(na->mNumRotationKeys + 1, sizeof *ch->rot.keys);
            ch->scale.keys = calloc(na->mNumScalingKeys + 1, sizeof *ch->scale.keys);
            if (!ch->pos.keys || !ch->rot.keys || !ch->scale.keys) return false;
            for (unsigned k = 0; na->mPositionKeys && k < na->mNumPositionKeys; k++) {
                const struct aiVectorKey *key = &na->mPositionKeys[k];
                ch->pos.keys[ch->pos.count++] =
                    (character_key_t){(float)(key->mTime / tps), {key->mValue.x, key->mValue.y, key->mValue.z, 0}};
            }
            for (unsigned k = 0; na->mRotationKeys && k < na->mNumRotationKeys; k++) {
                const struct aiQuatKey *key = &na->mRotationKeys[k];
                ch->rot.keys[ch->rot.count++] = (character_key_t){
                    (float)(key->mTime / tps), {key->mValue.x, key->mValue.y, key->mValue.z, key->mValue.w}};
            }
            for (unsigned k = 0; na->mScalingKeys && k < na->mNumScalingKeys; k++) {
                const struct aiVectorKey *key = &na->mScalingKeys[k];
                ch->scale.keys[ch->scale.count++] =
                    (character_key_t){(float)(key->mTime / tps), {key->mValue.x, key->mValue.y, key->mValue.z, 0}};
            }
        }
        character_clip_fixup(c, m->bone_count, ctx->path);
    }
    return true;
}

/* Inverse bind matrices from every mesh's aiBones (first one wins). */
static void load_offsets(load_ctx_t *ctx, character_model_t *m)
{
    for (int n = 0; n < ctx->node_count; n++) {
        const struct aiNode *node = ctx->nodes[n];
        for (unsigned mi = 0; mi < node->mNumMeshes; mi++) {
            const struct aiMesh *mesh = ctx->scene->mMeshes[node->mMeshes[mi]];
            if (!is_triangle_mesh(mesh)) continue;
            for (unsigned bi = 0; bi < mesh->mNumBones; bi++) {
                const struct aiBone *bone = mesh->mBones[bi];
                int b = character_bone_find(m, bone->mName.data);
                if (b < 0) {
                    core_log_warn("%s: mesh '%s': bone '%s' has no node; its weights are dropped", ctx->path,
                                  mesh->mName.data, bone->mName.data);
                    continue;
                }
                float off[16];
                mat_from_ai(&bone->mOffsetMatrix, off);
                if (ctx->has_offset[b]) {
                    float diff = 0.0f;
                    for (int e = 0; e < 16; e++) diff = fmaxf(diff, fabsf(off[e] - m->bones[b].inverse_bind[e]));
                    if (diff > 1e-4f)
                        core_log_warn("%s: bone '%s' has different bind matrices in two meshes; keeping the first",
                                      ctx->path, bone->mName.data);
                    continue;
                }
                memcpy(m->bones[b].inverse_bind, off, sizeof off);
                ctx->has_offset[b] = true;
            }
        }
    }
}

/* The morph targets (aiAnimMesh) of the mesh instance whose vertices start
 * at base, as deltas from its vertices before any rebinding (raw: the
 * file's positions and normals); `to_bind` is the rebinding of the
 * vertices flagged in rebound, applied to both ends of each delta.
 * False when out of memory. */
static bool load_morphs(character_model_t *m, int n, const struct aiMesh *mesh, int base, const float *to_bind,
                        const bool *rebound, const char *path)
{
    int nv = (int)mesh->mNumVertices, skipped = 0;
    for (unsigned a = 0; a < mesh->mNumAnimMeshes; a++) {
        const struct aiAnimMesh *am = mesh->mAnimMeshes[a];
        if (!am || !am->mVertices || (int)am->mNumVertices != nv) {
            skipped++;
            continue;
        }
        character_morph_t *grown = realloc(m->morphs, sizeof *grown * (size_t)(m->morph_count + 1));
        if (!grown) return false;
        m->morphs = grown;
        character_morph_t *mo = &m->morphs[m->morph_count];
        *mo = (character_morph_t){.node = n, .target = (int)a, .first = base, .count = nv,
                                  .weight = isfinite(am->mWeight) ? am->mWeight : 0.0f};
        mo->max_weight = fabsf(mo->weight);
        mo->delta = calloc((size_t)nv, sizeof *mo->delta);
        if (!mo->delta) return false;
        m->morph_count++;
        for (int v = 0; v < nv; v++) {
            const struct aiVector3D *p0 = &mesh->mVertices[v], *p1 = &am->mVertices[v];
            float a0[3] = {p0->x, p0->y, p0->z}, a1[3] = {p1->x, p1->y, p1->z}, n0[3] = {0, 0, 0}, n1[3];
            if (mesh->mNormals) n0[0] = mesh->mNormals[v].x, n0[1] = mesh->mNormals[v].y, n0[2] = mesh->mNormals[v].z;
            memcpy(n1, n0, sizeof n1);
            if (am->mNormals) n1[0] = am->mNormals[v].x, n1[1] = am->mNormals[v].y, n1[2] = am->mNormals[v].z;
            if (rebound[v]) {
                character_mat4_point(to_bind, a0, a0), character_mat4_point(to_bind, a1, a1);
                transform_normal(to_bind, n0, n0), transform_normal(to_bind, n1, n1);
            }
            for (int k = 0; k < 3; k++) {
                mo->delta[v][k] = isfinite(a1[k] - a0[k]) ? a1[k] - a0[k] : 0.0f;
                mo->delta[v][3 + k] = isfinite(n1[k] - n0[k]) ? n1[k] - n0[k] : 0.0f;
            }
        }
    }
    if (skipped)
        core_log_warn("%s: mesh '%s': %d morph target(s) without positions for every vertex ignored", path,
                      mesh->mName.data, skipped);
    return true;
}

/* Appends one mesh instance (mesh on node n) with its morph targets and
 * adds to the warning counters. False when out of memory. */
static bool load_mesh(character_model_t *m, int n, const struct aiMesh *mesh, int *dropped,
                      int *unbound, int *bad_weights, const char *path)
{
    int base = m->vertex_count;
    for (unsigned v = 0; v < mesh->mNumVertices; v++) {
        character_vertex_t *vx = &m->vertices[base + (int)v];
        memset(vx, 0, sizeof *vx);
        vx->pos[0] = mesh->mVertices[v].x, vx->pos[1] = mesh->mVertices[v].y, vx->pos[2] = mesh->mVertices[v].z;
        if (mesh->mNormals)
            vx->normal[0] = mesh->mNormals[v].x, vx->normal[1] = mesh->mNormals[v].y,
            vx->normal[2] = mesh->mNormals[v].z;
        else
            vx->normal[1] = 1.0f;
        if (mesh->mTextureCoords[0])
            vx->uv[0] = mesh->mTextureCoords[0][v].x, vx->uv[1] = mesh->mTextureCoords[0][v].y;
    }
    bool *dropped_v = calloc(mesh->mNumVertices, sizeof(bool)), *rebound = calloc(mesh->mNumVertices, sizeof(bool));
    for (unsigned bi = 0; bi < mesh->mNumBones; bi++) {
        const struct aiBone *bone = mesh->mBones[bi];
        int b = character_bone_find(m, bone->mName.data);
        if (b < 0) continue;
        for (unsigned w = 0; w < bone->mNumWeights; w++) {
            const struct aiVertexWeight *vw = &bone->mWeights[w];
            if (vw->mVertexId >= mesh->mNumVertices) {
                (*bad_weights)++;
                continue;
            }
            float wt = vw->mWeight;
            if (!isfinite(wt) || wt < 0.0f) {
                (*bad_weights)++;
                continue;
            }
            if (wt == 0.0f) continue;
            if (add_influence(&m->vertices[base + (int)vw->mVertexId], b, wt) && dropped_v)
                dropped_v[vw->mVertexId] = true;
        }
    }
    /* the node's bind matrix for rigidly bound vertices: p' = inverse_bind^-1 p
     * makes skinning at bind reproduce the node's transform of p */
    float to_bind[16];
    if (!character_mat4_invert(m->bones[n].inverse_bind, to_bind)) mat_identity(to_bind);
    for (unsigned v = 0; v < mesh->mNumVertices; v++) {
        character_vertex_t *vx = &m->vertices[base + (int)v];
        if (dropped_v && dropped_v[v]) (*dropped)++;
        float sum = 0.0f;
        for (int k = 0; k < CHARACTER_MAX_INFLUENCES; k++) sum += vx->weights[k];
        if (sum > 0.0f) {
            for (int k = 0; k < CHARACTER_MAX_INFLUENCES; k++) vx->weights[k] /= sum;
            continue;
        }
        if (mesh->mNumBones) (*unbound)++;
        if (rebound) rebound[v] = true;
        float p[3], nn[3];
        character_mat4_point(to_bind, vx->pos, p);
        transform_normal(to_bind, vx->normal, nn);
        memcpy(vx->pos, p, sizeof p), memcpy(vx->normal, nn, sizeof nn);
        memset(vx->joints, 0, sizeof vx->joints);
        memset(vx->weights, 0, sizeof vx->weights);
        vx->joints[0] = (uint16_t)n;
        vx->weights[0] = 1.0f;
    }
    free(dropped_v);
    bool morphs_ok = rebound && load_morphs(m, n, mesh, base, to_bind, rebound, path);
    free(rebound);
    for (unsigned f = 0; f < mesh->mNumFaces; f++) {
        const struct aiFace *face = &mesh->mFaces[f];
        if (face->mNumIndices != 3) continue;
        bool ok = true;
        for (int k = 0; k < 3; k++) ok &= face->mIndices[k] < mesh->mNumVertices;
        if (!ok) continue;
        for (int k = 0; k < 3; k++) m->indices[m->index_count++] = (uint32_t)base + face->mIndices[k];
    }
    m->vertex_count += (int)mesh->mNumVertices;
    return morphs_ok;
}

/* No clips: bake the bind pose (skinned, morph targets at their default
 * weights) into the vertices, keep one bone. */
static bool collapse_to_rigid(character_model_t *m)
{
    character_pose_t pose;
    float *p = malloc(sizeof(float) * 3 * (size_t)m->vertex_count);
    float *n = malloc(sizeof(float) * 3 * (size_t)m->vertex_count);
    if (!p || !n || !character_pose_init(&pose, m)) {
        free(p), free(n);
        return false;
    }
    character_skin_cpu(m, &pose, p, n);
    character_pose_free(&pose);
    for (int k = 0; k < m->morph_count; k++) free(m->morphs[k].delta);
    free(m->morphs);
    m->morphs = NULL;
    m->morph_count = 0;
    for (int v = 0; v < m->vertex_count; v++) {
        character_vertex_t *vx = &m->vertices[v];
        memcpy(vx->pos, p + 3 * v, sizeof vx->pos);
        memcpy(vx->normal, n + 3 * v, sizeof vx->normal);
        memset(vx->joints, 0, sizeof vx->joints);
        memset(vx->weights, 0, sizeof vx->weights);
        vx->weights[0] = 1.0f;
    }
    free(p), free(n);
    for (int i = 1; i < m->bone_count; i++) free(m->bones[i].name);
    free(m->bones[0].name);
    character_bone_t *b = &m->bones[0];
    memset(b, 0, sizeof *b);
    b->name = dup_str("root");
    b->parent = -1;
    mat_identity(b->inverse_bind);
    mat_identity(b->bind_local);
    b->bind_r[3] = 1.0f;
    b->bind_s[0] = b->bind_s[1] = b->bind_s[2] = 1.0f;
    m->bone_count = 1;
    m->rigid = true;
    return b->name != NULL;
}

/* ---- file metadata ---------------------------------------------------------------- */
static bool meta_number(const struct aiMetadata *md, const char *key, double *out)
{
    for (unsigned i = 0; md && i < md->mNumProperties; i++) {
        if (strcmp(md->mKeys[i].data, key) != 0 || !md->mValues[i].mData) continue;
        const void *d = md->mValues[i].mData;
        switch (md->mValues[i].mType) {
        case AI_BOOL: *out = *(const bool *)d; return true;
        case AI_INT32: *out = *(const int32_t *)d; return true;
        case AI_UINT64: *out = (double)*(const uint64_t *)d; return true;
        case AI_FLOAT: *out = *(const float *)d; return true;
        case AI_DOUBLE: *out = *(const double *)d; return true;
        default: return false;
        }
    }
    return false;
}

/* Signed axis code from "<name>Axis" (0, 1, 2) and "<name>AxisSign". */
static int meta_axis(const struct aiMetadata *md, const char *axis_key, const char *sign_key)
{
    double a, s = 1.0;
    if (!meta_number(md, axis_key, &a) || !(a == 0.0 || a == 1.0 || a == 2.0)) return 0;
    meta_number(md, sign_key, &s);
    return (s < 0.0 ? -1 : 1) * (int)(a + 1.0);
}

/* Units (FBX's UnitScaleFactor: centimetres per unit), axes and the
 * extension; also warns when an OBJ names a material library that is not
 * there (assimp only falls back to a default material). */
static void load_file_info(character_model_t *m, const struct aiScene *sc, const char *path)
{
    const struct aiMetadata *md = sc->mMetaData;
    double unit;
    if ((meta_number(md, "UnitScaleFactor", &unit) || meta_number(md, "OriginalUnitScaleFactor", &unit)) &&
        unit > 0.0 && isfinite(unit))
        m->file.unit_metres = (float)(unit / 100.0);
    m->file.up = meta_axis(md, "UpAxis", "UpAxisSign");
    m->file.front = meta_axis(md, "FrontAxis", "FrontAxisSign");
    if (abs(m->file.up) == abs(m->file.front)) m->file.front = 0;
    const char *base = character_path_basename(path), *dot = strrchr(base, '.');
    size_t k = 0;
    for (const char *c = dot ? dot + 1 : ""; *c && k + 1 < sizeof m->file.format; c++)
        m->file.format[k++] = (char)tolower((unsigned char)*c);
    m->file.format[k] = 0;
    if (strcmp(m->file.format, "obj") != 0) return;
    FILE *f = fopen(path, "r");
    char line[1024], lib[1024], found[1024], tried[2048];
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, " mtllib %1023[^\r\n]", lib) == 1 &&
            !character_texture_find(path, lib, found, sizeof found, tried, sizeof tried))
            core_log_warn("%s: material library '%s' not found (tried %s); default material", path, lib, tried);
    if (f) fclose(f);
}

static bool fail(char *err, size_t err_size, const char *path, const char *fmt, const char *arg)
{
    char msg[512];
    snprintf(msg, sizeof msg, fmt, arg);
    if (err && err_size) snprintf(err, err_size, "%s", msg);
    core_log_error("%s: %s", path, msg);
    return false;
}

bool character_load(character_model_t *model, const char *path, char *err, size_t err_size)
{
    memset(model, 0, sizeof *model);
    /* no aiProcess_ValidateDataStructure: inconsistent files are repaired
     * here with warnings instead of rejected */
    const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals |
                           aiProcess_SortByPType;
    char why[512];
    const struct aiScene *sc = mesh_import(path, flags, why, sizeof why);
    if (!sc) return fail(err, err_size, path, "%s", why);
    if (!sc->mRootNode) {
        aiReleaseImport(sc);
        return fail(err, err_size, path, "%s", "no scene nodes");
    }
    load_ctx_t ctx = {.path = path, .scene = sc};
    int nn = count_nodes(sc->mRootNode);
    if (nn > 65535) {
        aiReleaseImport(sc);
        return fail(err, err_size, path, "%s", "more than 65535 nodes");
    }
    ctx.nodes = calloc((size_t)nn, sizeof *ctx.nodes);
    ctx.global = calloc((size_t)nn, sizeof *ctx.global);
    ctx.has_offset = calloc((size_t)nn, sizeof *ctx.has_offset);
    model->bones = calloc((size_t)nn, sizeof *model->bones);
    bool ok = ctx.nodes && ctx.global && ctx.has_offset && model->bones;
    if (ok) {
        model->bone_count = nn;
        flatten(&ctx, model, sc->mRootNode, -1);
        ctx.hl1 = hl1_restore_parents(&ctx, model);
        for (int i = 0; i < nn; i++)
            if (!character_mat4_invert(ctx.global[i], model->bones[i].inverse_bind)) {
                core_log_warn("%s: node '%s' has a singular transform", path, model->bones[i].name);
                mat_identity(model->bones[i].inverse_bind);
            }
        load_offsets(&ctx, model);
        /* count mesh instances */
        size_t nv = 0, ni = 0;
        for (int n = 0; n < nn; n++)
            for (unsigned mi = 0; mi < ctx.nodes[n]->mNumMeshes; mi++) {
                const struct aiMesh *mesh = sc->mMeshes[ctx.nodes[n]->mMeshes[mi]];
                if (!is_triangle_mesh(mesh)) continue;
                nv += mesh->mNumVertices;
                ni += 3 * (size_t)mesh->mNumFaces;
            }
        if (nv == 0) {
            free(ctx.nodes), free(ctx.global), free(ctx.has_offset);
            character_model_free(model);
            aiReleaseImport(sc);
            return fail(err, err_size, path, "%s", "no triangle vertices in the file");
        }
        if (nv > INT32_MAX || ni > INT32_MAX) {
            free(ctx.nodes), free(ctx.global), free(ctx.has_offset);
            character_model_free(model);
            aiReleaseImport(sc);
            return fail(err, err_size, path, "%s", "too many vertices");
        }
        model->vertices = calloc(nv, sizeof *model->vertices);
        model->indices = calloc(ni, sizeof *model->indices);
        ok = model->vertices && model->indices;
        int dropped = 0, unbound = 0, bad = 0;
        bool material = false;
        for (int n = 0; ok && n < nn; n++)
            for (unsigned mi = 0; ok && mi < ctx.nodes[n]->mNumMeshes; mi++) {
                const struct aiMesh *mesh = sc->mMeshes[ctx.nodes[n]->mMeshes[mi]];
                if (!is_triangle_mesh(mesh)) continue;
                if (!material) load_material(model, sc, mesh, path);
                material = true;
                ok = load_mesh(model, n, mesh, &dropped, &unbound, &bad, path);
            }
        if (dropped)
            core_log_warn("%s: %d vertices had more than %d influences; kept the largest", path, dropped,
                          CHARACTER_MAX_INFLUENCES);
        if (unbound) core_log_warn("%s: %d skinned vertices had zero total weight; bound to their mesh node", path, unbound);
        if (bad) core_log_warn("%s: dropped %d invalid vertex weights (NaN, negative or bad vertex id)", path, bad);
        load_file_info(model, sc, path);
        ok = ok && load_clips(&ctx, model);
        if (ok && model->clip_count == 0) {
            /* formats whose vertex animation assimp 5.2 reads as one frame */
            static const char *const vertex_anim[] = {"md2", "md3", "mdc", "iqm"};
            for (size_t i = 0; i < sizeof vertex_anim / sizeof vertex_anim[0]; i++)
                if (!strcmp(model->file.format, vertex_anim[i]))
                    core_log_warn("%s: %s animation is not loaded by assimp 5.2 (one frame); the model walks rigidly",
                                  path, vertex_anim[i]);
            ok = collapse_to_rigid(model);
        }
    }
    free(ctx.nodes), free(ctx.global), free(ctx.has_offset);
    aiReleaseImport(sc);
    if (!ok) {
        character_model_free(model);
        return fail(err, err_size, path, "%s", "out of memory");
    }
    core_log_info("%s: %d vertices, %d triangles, %d bones, %d morph targets, %d clips%s", path, model->vertex_count,
                  model->index_count / 3, model->bone_count, model->morph_count, model->clip_count,
                  model->rigid ? " (rigid)" : "");
    return true;
}

bool character_print_clips(const char *path, FILE *out)
{
    char resolved[1024], err[512];
    if (!core_fs_resolve(path, resolved, sizeof resolved)) {
        core_log_error("--list-clips: model file %s not found", path);
        return false;
    }
    character_model_t m;
    if (!character_load(&m, resolved, err, sizeof err)) return false; /* logged by the loader */
    fprintf(out, "%s: %d clip%s%s\n", path, m.clip_count, m.clip_count == 1 ? "" : "s",
            m.clip_count ? "" : " (the model stands in its bind pose)");
    for (int i = 0; i < m.clip_count; i++) {
        const character_clip_t *c = &m.clips[i];
        fprintf(out, "  %d \"%s\": %.3f s, %d keys, %.6g ticks at %.6g per s\n", i, c->name, (double)c->duration,
                character_clip_keys(c, m.bone_count), (double)(c->duration * c->ticks_per_second),
                (double)c->ticks_per_second);
    }
    character_model_free(&m);
    return true;
}

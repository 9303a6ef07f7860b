/* meadow_gen_models: writes the generated models under models/ and the
 * loader fixtures under tests/data/models/.
 *
 *   models/humanoid.gltf   skinned humanoid, 15 joints, clips "walk", "idle"
 *   models/quadruped.gltf  dog-like animal, 17 joints, clip "walk"
 *   models/torus.obj       torus, major radius 2 m, minor radius 0.8 m
 *   models/sphere.obj      sphere, radius 2 m
 *   tests/data/models/clips.gltf   a quad with two morph targets, a clip of
 *                                  duration 0 first, then a morph clip
 *   tests/data/models/broken.gltf  unsorted/NaN/negative key times, a
 *                                  zero quaternion, a zero-weight vertex
 *
 * Meshes are built from capsules (one or more per joint), y up, feet at y=0,
 * facing +Z. Every joint's rest rotation is identity, so its inverse bind
 * matrix is a pure translation by minus its bind-pose position. Vertices near
 * a joint blend linearly with the neighbouring joint (0.5/0.5 at the joint).
 * glTF buffers are embedded as base64 data URIs. Output is deterministic:
 * fixed tessellation, fixed key sampling, fixed float formatting.
 * No paper equations here; this is content generation. */
#include "core/core.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_F 3.14159265358979f
#define DEG (PI_F / 180.0f)
#define MAX_JOINTS 32
#define MAX_SEGMENTS 32
#define MAX_CLIPS 4

/* ---- byte buffers (core_buf_t) ------------------------------------------- */
static void buf_align4(core_buf_t *b)
{
    static const char zeros[4] = {0};
    if (b->len % 4) core_buf_put(b, zeros, 4 - b->len % 4);
}

static void base64_append(core_buf_t *out, const unsigned char *src, size_t n)
{
    static const char tab[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    for (size_t i = 0; i < n; i += 3) {
        uint32_t v = (uint32_t)src[i] << 16;
        if (i + 1 < n) v |= (uint32_t)src[i + 1] << 8;
        if (i + 2 < n) v |= src[i + 2];
        char q[4] = {tab[(v >> 18) & 63], tab[(v >> 12) & 63], i + 1 < n ? tab[(v >> 6) & 63] : '=',
                     i + 2 < n ? tab[v & 63] : '='};
        core_buf_put(out, q, 4);
    }
}

/* ---- rig description ----------------------------------------------------- */
typedef struct gen_joint_t {
    const char *name;
    int parent;
    float t[3]; /* translation relative to the parent joint */
} gen_joint_t;

/* A capsule from a to b (bind-pose model space) skinned to `joint`; vertices
 * within `blend` (fraction of the length) of an end blend with the joint named
 * for that end (-1: none). */
typedef struct gen_segment_t {
    int joint, joint_a, joint_b;
    float a[3], b[3];
    float radius;
    float squash; /* scale of the second perpendicular axis (0 = 1) */
} gen_segment_t;

typedef struct gen_anim_t {
    float r[MAX_JOINTS][4]; /* local rotation quaternion x,y,z,w */
    float t[3];             /* root translation */
} gen_anim_t;

typedef void (*gen_clip_fn)(float phase, gen_anim_t *out);

typedef struct gen_clip_t {
    const char *name;
    float duration;
    int keys;
    gen_clip_fn fn;
} gen_clip_t;

typedef struct gen_rig_t {
    const char *name;
    float color[4];
    int joint_count;
    gen_joint_t joints[MAX_JOINTS];
    int segment_count;
    gen_segment_t segments[MAX_SEGMENTS];
    int clip_count;
    gen_clip_t clips[MAX_CLIPS];
} gen_rig_t;

typedef struct gen_vertex_t {
    float p[3], n[3], uv[2];
    uint16_t j[4];
    float w[4];
} gen_vertex_t;

typedef struct gen_mesh_t {
    gen_vertex_t *v;
    int vcount, vcap;
    uint32_t *idx;
    int icount, icap;
} gen_mesh_t;

static void joint_world(const gen_rig_t *rig, int j, float out[3])
{
    out[0] = out[1] = out[2] = 0.0f;
    for (; j >= 0; j = rig->joints[j].parent)
        for (int k = 0; k < 3; k++) out[k] += rig->joints[j].t[k];
}

/* Quaternion from intrinsic rotations about X, then Y, then Z (q = qx*qy*qz). */
static void quat_xyz(float ax, float ay, float az, float q[4])
{
    float cx = cosf(ax * 0.5f), sx = sinf(ax * 0.5f);
    float cy = cosf(ay * 0.5f), sy = sinf(ay * 0.5f);
    float cz = cosf(az * 0.5f), sz = sinf(az * 0.5f);
    /* qx*qy */
    float a[4] = {sx * cy, cx * sy, sx * sy, cx * cy};
    /* (qx*qy)*qz with qz = (0,0,sz,cz) */
    q[0] = a[0] * cz + a[1] * sz;
    q[1] = a[1] * cz - a[0] * sz;
    q[2] = a[2] * cz + a[3] * sz;
    q[3] = a[3] * cz - a[2] * sz;
}

static void mesh_push_vertex(gen_mesh_t *m, const gen_vertex_t *v)
{
    if (m->vcount == m->vcap) {
        m->vcap = m->vcap ? m->vcap * 2 : 1024;
        m->v = realloc(m->v, (size_t)m->vcap * sizeof *m->v);
        if (!m->v) exit(1);
    }
    m->v[m->vcount++] = *v;
}

static void mesh_push_index(gen_mesh_t *m, uint32_t i)
{
    if (m->icount == m->icap) {
        m->icap = m->icap ? m->icap * 2 : 4096;
        m->idx = realloc(m->idx, (size_t)m->icap * sizeof *m->idx);
        if (!m->idx) exit(1);
    }
    m->idx[m->icount++] = i;
}

static void normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    if (l > 0.0f)
        for (int k = 0; k < 3; k++) v[k] /= l;
}

static void cross3(const float a[3], const float b[3], float o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Capsule: SIDES around, CAP rings per hemisphere and BODY rings along the
 * cylinder (at BODY_T of the length) so the weight ramps have vertices to
 * act on. Weights: linear ramp from 0.5/0.5 at an end joint to 1.0 on the
 * own joint at BLEND of the length. */
enum { SIDES = 10, CAP = 3, BODY = 4 };
static const float BODY_T[BODY] = {0.15f, 0.3f, 0.7f, 0.85f};
static const float BLEND = 0.3f;

static void mesh_add_capsule(gen_mesh_t *m, const gen_segment_t *s)
{
    float d[3] = {s->b[0] - s->a[0], s->b[1] - s->a[1], s->b[2] - s->a[2]};
    float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    normalize3(d);
    float ref[3] = {0, 0, 1};
    if (fabsf(d[2]) > 0.9f) ref[0] = 1, ref[2] = 0;
    float u[3], w[3];
    cross3(d, ref, u);
    normalize3(u);
    cross3(d, u, w);
    float squash = s->squash > 0.0f ? s->squash : 1.0f;
    uint32_t base = (uint32_t)m->vcount;
    /* ring r: bottom cap (phi -90..0), body rings, top cap (phi 0..90) */
    int rings = 2 * (CAP + 1) + BODY;
    for (int r = 0; r < rings; r++) {
        float phi = 0.0f, h;
        if (r <= CAP) {
            phi = -0.5f * PI_F + (float)r / CAP * 0.5f * PI_F;
            h = s->radius * sinf(phi);
        } else if (r <= CAP + BODY) {
            h = BODY_T[r - CAP - 1] * len;
        } else {
            phi = (float)(r - CAP - BODY - 1) / CAP * 0.5f * PI_F;
            h = len + s->radius * sinf(phi);
        }
        float rho = s->radius * cosf(phi);
        float t = len > 0.0f ? h / len : 0.0f;
        float tc = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
        float wa = 0.0f, wb = 0.0f;
        if (s->joint_a >= 0 && tc < BLEND) wa = 0.5f * (1.0f - tc / BLEND);
        if (s->joint_b >= 0 && tc > 1.0f - BLEND) wb = 0.5f * (1.0f - (1.0f - tc) / BLEND);
        for (int k = 0; k <= SIDES; k++) {
            float th = (float)k / SIDES * 2.0f * PI_F;
            float cu = cosf(th), sw = sinf(th) * squash;
            gen_vertex_t v = {0};
            float nn[3];
            for (int c = 0; c < 3; c++) {
                v.p[c] = s->a[c] + d[c] * h + (u[c] * cu + w[c] * sw) * rho;
                nn[c] = d[c] * sinf(phi) + (u[c] * cu + w[c] * sinf(th) / squash) * cosf(phi);
            }
            normalize3(nn);
            memcpy(v.n, nn, sizeof nn);
            v.uv[0] = (float)k / SIDES;
            v.uv[1] = tc;
            int slot = 0;
            v.j[slot] = (uint16_t)s->joint;
            v.w[slot++] = 1.0f - wa - wb;
            if (wa > 0.0f) v.j[slot] = (uint16_t)s->joint_a, v.w[slot++] = wa;
            if (wb > 0.0f) v.j[slot] = (uint16_t)s->joint_b, v.w[slot++] = wb;
            mesh_push_vertex(m, &v);
        }
    }
    for (int r = 0; r + 1 < rings; r++)
        for (int k = 0; k < SIDES; k++) {
            uint32_t i0 = base + (uint32_t)(r * (SIDES + 1) + k), i1 = i0 + 1;
            uint32_t i2 = i0 + SIDES + 1, i3 = i2 + 1;
            /* counter-clockwise seen from outside: (u, w, d) is right-handed */
            mesh_push_index(m, i0), mesh_push_index(m, i1), mesh_push_index(m, i2);
            mesh_push_index(m, i1), mesh_push_index(m, i3), mesh_push_index(m, i2);
        }
}

/* ---- glTF writer ----------------------------------------------------------- */
typedef struct gltf_t {
    core_buf_t bin, views, accessors;
    int view_count, accessor_count;
} gltf_t;

enum { GL_USHORT = 5123, GL_UINT = 5125, GL_FLOAT = 5126 };

/* Appends data as its own bufferView and accessor; min/max (if non-NULL)
 * hold `ncomp` floats. Returns the accessor index. */
static int gltf_accessor(gltf_t *g, const void *data, int count, int ctype, const char *type, int ncomp,
                         const float *min, const float *max)
{
    int csize = ctype == GL_USHORT ? 2 : 4;
    size_t bytes = (size_t)count * (size_t)ncomp * (size_t)csize;
    buf_align4(&g->bin);
    size_t off = g->bin.len;
    core_buf_put(&g->bin, data, bytes);
    core_buf_printf(&g->views, "%s{\"buffer\":0,\"byteOffset\":%zu,\"byteLength\":%zu}", g->view_count ? "," : "", off,
                    bytes);
    core_buf_printf(&g->accessors, "%s{\"bufferView\":%d,\"componentType\":%d,\"count\":%d,\"type\":\"%s\"",
                    g->accessor_count ? "," : "", g->view_count, ctype, count, type);
    if (min && max) {
        core_buf_printf(&g->accessors, ",\"min\":[");
        for (int k = 0; k < ncomp; k++) core_buf_printf(&g->accessors, "%s%.6g", k ? "," : "", (double)min[k]);
        core_buf_printf(&g->accessors, "],\"max\":[");
        for (int k = 0; k < ncomp; k++) core_buf_printf(&g->accessors, "%s%.6g", k ? "," : "", (double)max[k]);
        core_buf_printf(&g->accessors, "]");
    }
    core_buf_printf(&g->accessors, "}");
    g->view_count++;
    return g->accessor_count++;
}

static void minmax(const float *data, int count, int ncomp, int stride, float *mn, float *mx)
{
    for (int k = 0; k < ncomp; k++) mn[k] = INFINITY, mx[k] = -INFINITY;
    for (int i = 0; i < count; i++)
        for (int k = 0; k < ncomp; k++) {
            float v = data[(size_t)i * (size_t)stride + (size_t)k];
            if (!isnan(v)) mn[k] = fminf(mn[k], v), mx[k] = fmaxf(mx[k], v);
        }
}

/* Assembles the final document: `body` holds everything except the buffer,
 * bufferViews and accessors (and has no trailing brace). */
static bool gltf_finish(gltf_t *g, core_buf_t *body, const char *path)
{
    buf_align4(&g->bin);
    core_buf_printf(body, ",\"bufferViews\":[%s],\"accessors\":[%s]", core_buf_str(&g->views),
                    core_buf_str(&g->accessors));
    core_buf_printf(body, ",\"buffers\":[{\"byteLength\":%zu,\"uri\":\"data:application/octet-stream;base64,",
                    g->bin.len);
    base64_append(body, (const unsigned char *)g->bin.data, g->bin.len);
    core_buf_printf(body, "\"}]}\n");
    bool ok = core_fs_write_atomic(path, body->data, body->len);
    core_buf_free(&g->bin), core_buf_free(&g->views), core_buf_free(&g->accessors);
    return ok;
}

/* The animations: one shared time accessor per clip; rotation channels for
 * every joint the clip moves, translation for the root joint (node J0). */
static void write_clips(gltf_t *g, core_buf_t *body, const gen_rig_t *rig, int J0)
{
    core_buf_printf(body, ",\"animations\":[");
    for (int c = 0; c < rig->clip_count; c++) {
        const gen_clip_t *clip = &rig->clips[c];
        int k = clip->keys;
        float *times = malloc(sizeof(float) * (size_t)k);
        gen_anim_t *frames = calloc((size_t)k, sizeof *frames);
        if (!times || !frames) exit(1);
        for (int i = 0; i < k; i++) {
            times[i] = clip->duration * (float)i / (float)(k - 1);
            for (int j = 0; j < MAX_JOINTS; j++) frames[i].r[j][3] = 1.0f;
            clip->fn((float)i / (float)(k - 1), &frames[i]);
        }
        float tmin = 0.0f, tmax = clip->duration;
        int a_time = gltf_accessor(g, times, k, GL_FLOAT, "SCALAR", 1, &tmin, &tmax);
        core_buf_printf(body, "%s{\"name\":\"%s\",\"samplers\":[", c ? "," : "", clip->name);
        int sampler = 0;
        core_buf_t channels = {0};
        float *out = malloc(sizeof(float) * 4 * (size_t)k);
        if (!out) exit(1);
        for (int j = 0; j < rig->joint_count; j++) {
            bool moves = false;
            for (int i = 0; i < k; i++) moves |= fabsf(frames[i].r[j][3]) < 0.999999f;
            if (!moves) continue;
            for (int i = 0; i < k; i++) memcpy(out + 4 * i, frames[i].r[j], 16);
            int a_out = gltf_accessor(g, out, k, GL_FLOAT, "VEC4", 4, NULL, NULL);
            core_buf_printf(body, "%s{\"input\":%d,\"output\":%d,\"interpolation\":\"LINEAR\"}", sampler ? "," : "",
                            a_time, a_out);
            core_buf_printf(&channels, "%s{\"sampler\":%d,\"target\":{\"node\":%d,\"path\":\"rotation\"}}",
                            sampler ? "," : "", sampler, J0 + j);
            sampler++;
        }
        for (int i = 0; i < k; i++)
            for (int a = 0; a < 3; a++) out[3 * i + a] = rig->joints[0].t[a] + frames[i].t[a];
        int a_out = gltf_accessor(g, out, k, GL_FLOAT, "VEC3", 3, NULL, NULL);
        core_buf_printf(body, ",{\"input\":%d,\"output\":%d,\"interpolation\":\"LINEAR\"}", a_time, a_out);
        core_buf_printf(&channels, ",{\"sampler\":%d,\"target\":{\"node\":%d,\"path\":\"translation\"}}", sampler, J0);
        core_buf_printf(body, "],\"channels\":[%s]}", channels.data);
        core_buf_free(&channels);
        free(out), free(times), free(frames);
    }
    core_buf_printf(body, "]");
}

static bool write_rig(const gen_rig_t *rig, const char *path)
{
    gen_mesh_t mesh = {0};
    for (int s = 0; s < rig->segment_count; s++) mesh_add_capsule(&mesh, &rig->segments[s]);

    int n = mesh.vcount;
    float *pos = malloc(sizeof(float) * 3 * (size_t)n), *nor = malloc(sizeof(float) * 3 * (size_t)n);
    float *uv = malloc(sizeof(float) * 2 * (size_t)n), *wt = malloc(sizeof(float) * 4 * (size_t)n);
    uint16_t *jt = malloc(sizeof(uint16_t) * 4 * (size_t)n);
    if (!pos || !nor || !uv || !wt || !jt) exit(1);
    for (int i = 0; i < n; i++) {
        memcpy(pos + 3 * i, mesh.v[i].p, 12), memcpy(nor + 3 * i, mesh.v[i].n, 12);
        memcpy(uv + 2 * i, mesh.v[i].uv, 8), memcpy(wt + 4 * i, mesh.v[i].w, 16);
        memcpy(jt + 4 * i, mesh.v[i].j, 8);
    }

    gltf_t g = {0};
    float mn[16], mx[16];
    minmax(pos, n, 3, 3, mn, mx);
    int a_pos = gltf_accessor(&g, pos, n, GL_FLOAT, "VEC3", 3, mn, mx);
    int a_nor = gltf_accessor(&g, nor, n, GL_FLOAT, "VEC3", 3, NULL, NULL);
    int a_uv = gltf_accessor(&g, uv, n, GL_FLOAT, "VEC2", 2, NULL, NULL);
    int a_jt = gltf_accessor(&g, jt, n, GL_USHORT, "VEC4", 4, NULL, NULL);
    int a_wt = gltf_accessor(&g, wt, n, GL_FLOAT, "VEC4", 4, NULL, NULL);
    int a_idx = gltf_accessor(&g, mesh.idx, mesh.icount, GL_UINT, "SCALAR", 1, NULL, NULL);

    /* inverse bind matrices: translation by minus the joint's bind position */
    float ibm[MAX_JOINTS][16];
    for (int j = 0; j < rig->joint_count; j++) {
        float p[3];
        joint_world(rig, j, p);
        memset(ibm[j], 0, sizeof ibm[j]);
        ibm[j][0] = ibm[j][5] = ibm[j][10] = ibm[j][15] = 1.0f;
        ibm[j][12] = -p[0], ibm[j][13] = -p[1], ibm[j][14] = -p[2];
    }
    int a_ibm = gltf_accessor(&g, ibm, rig->joint_count, GL_FLOAT, "MAT4", 16, NULL, NULL);

    /* nodes: 0 = rig root, 1 = mesh node, 2.. = joints */
    const int J0 = 2;
    core_buf_t body = {0};
    core_buf_printf(&body, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"meadow_gen_models\"},\"scene\":0,");
    core_buf_printf(&body, "\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"name\":\"%s\",\"children\":[1", rig->name);
    for (int j = 0; j < rig->joint_count; j++)
        if (rig->joints[j].parent < 0) core_buf_printf(&body, ",%d", J0 + j);
    core_buf_printf(&body, "]},{\"name\":\"%s_mesh\",\"mesh\":0,\"skin\":0}", rig->name);
    for (int j = 0; j < rig->joint_count; j++) {
        const gen_joint_t *jt_ = &rig->joints[j];
        core_buf_printf(&body, ",{\"name\":\"%s\",\"translation\":[%.6g,%.6g,%.6g]", jt_->name, (double)jt_->t[0],
                        (double)jt_->t[1], (double)jt_->t[2]);
        int first = 1;
        for (int c = 0; c < rig->joint_count; c++)
            if (rig->joints[c].parent == j) {
                core_buf_printf(&body, "%s%d", first ? ",\"children\":[" : ",", J0 + c);
                first = 0;
            }
        core_buf_printf(&body, "%s}", first ? "" : "]");
    }
    core_buf_printf(&body, "],\"skins\":[{\"name\":\"%s_skin\",\"inverseBindMatrices\":%d,\"skeleton\":%d,\"joints\":[",
                    rig->name, a_ibm, J0);
    for (int j = 0; j < rig->joint_count; j++) core_buf_printf(&body, "%s%d", j ? "," : "", J0 + j);
    core_buf_printf(&body, "]}],\"meshes\":[{\"name\":\"%s_mesh\",\"primitives\":[{\"attributes\":{\"POSITION\":%d,"
                           "\"NORMAL\":%d,\"TEXCOORD_0\":%d,\"JOINTS_0\":%d,\"WEIGHTS_0\":%d},\"indices\":%d,"
                           "\"material\":0}]}]",
                    rig->name, a_pos, a_nor, a_uv, a_jt, a_wt, a_idx);
    core_buf_printf(&body, ",\"materials\":[{\"name\":\"%s_skin\",\"pbrMetallicRoughness\":{\"baseColorFactor\":"
                           "[%.4g,%.4g,%.4g,%.4g],\"metallicFactor\":0,\"roughnessFactor\":0.9}}]",
                    rig->name, (double)rig->color[0], (double)rig->color[1], (double)rig->color[2],
                    (double)rig->color[3]);

    write_clips(&g, &body, rig, J0);

    bool ok = gltf_finish(&g, &body, path);
    printf("%s: %d vertices, %d triangles, %d joints, %d clips\n", path, n, mesh.icount / 3, rig->joint_count,
           rig->clip_count);
    core_buf_free(&body);
    free(pos), free(nor), free(uv), free(wt), free(jt), free(mesh.v), free(mesh.idx);
    return ok;
}

/* ---- humanoid ----------------------------------------------------------- */
enum {
    H_HIPS, H_SPINE, H_CHEST, H_NECK, H_HEAD,
    H_UARM_L, H_LARM_L, H_UARM_R, H_LARM_R,
    H_ULEG_L, H_LLEG_L, H_FOOT_L, H_ULEG_R, H_LLEG_R, H_FOOT_R,
    H_COUNT
};

/* ---- walk cycles ------------------------------------------------------------ */
/* A leg is a two-bone chain in the sagittal (y, z) plane: upper bone of
 * length a, lower bone of length b, both hanging straight down at bind, each
 * bent by a rotation about X (negative X swings the end towards +Z). The
 * foot target follows a fixed path relative to the hip: during stance
 * (phase [0, duty)) it slides straight back from +stride/2 to -stride/2 at
 * the ground height, at constant speed stride / (duty * duration); during
 * swing (u in [0, 1]) it is lifted by lift * sqrt(sin(pi u)) and carried
 * forward on a cubic Hermite curve whose end velocities equal the stance
 * velocity. The steep lift clears the lowest quarter of the lift height
 * within u < 0.02, while the foot still moves back at nearly the stance
 * speed, so a stride estimate from the lowest part of the foot path (see
 * character_clip_stride) sees the stance speed. Keys every 1/40 cycle
 * land on the stance boundaries (multiples of 0.1). */
typedef struct gen_gait_t {
    float duty;   /* fraction of the cycle a foot is on the ground */
    float stride; /* foot travel relative to the hip during stance, metres */
    float lift;   /* peak foot lift during swing, metres */
} gen_gait_t;

/* Foot target relative to its stance path: z along the body (+Z forward),
 * y above the ground, for a leg at local phase ph in [0, 1). */
static void gait_foot(const gen_gait_t *g, float ph, float *y, float *z)
{
    float half = 0.5f * g->stride;
    if (ph < g->duty) {
        *y = 0.0f;
        *z = half - g->stride * ph / g->duty;
        return;
    }
    float u = (ph - g->duty) / (1.0f - g->duty);
    float m = -g->stride * (1.0f - g->duty) / g->duty; /* stance dz/du in swing units */
    float u2 = u * u, u3 = u2 * u;
    float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u, h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    *z = -half * h00 + m * h10 + half * h01 + m * h11;
    *y = g->lift * sqrtf(sinf(PI_F * u));
}

/* Two-bone IK: rotations about X of the upper bone (*upper) and the lower
 * bone relative to it (*lower, >= 0: the knee points forward) that put the
 * chain's end at (dy, dz) from its root. Targets beyond reach are pulled in
 * to 99.8% of a + b. */
static void leg_ik(float a, float b, float dy, float dz, float *upper, float *lower)
{
    float r = sqrtf(dy * dy + dz * dz);
    float rmax = 0.998f * (a + b);
    if (r > rmax) dy *= rmax / r, dz *= rmax / r, r = rmax;
    float ck = (r * r - a * a - b * b) / (2.0f * a * b);
    ck = ck > 1.0f ? 1.0f : ck < -1.0f ? -1.0f : ck;
    *lower = acosf(ck);
    /* a bone hanging down, rotated by x about X, points along (-cos x, -sin x) in (y, z) */
    float phi = atan2f(-dz, -dy);
    *upper = phi - atan2f(b * sinf(*lower), a + b * cosf(*lower));
}

/* Poses the leg whose upper joint is `u` (lower u + 1, foot u + 2) so the
 * foot joint follows the gait at local phase ph, with the foot kept level.
 * hip_y: the upper joint's height; ground_y: the foot joint's height at
 * bind (the foot rests on the ground there). The stance path is centred
 * under the hip. */
static void gait_leg(const gen_gait_t *g, float ph, int u, float a, float b, float hip_y, float ground_y,
                     gen_anim_t *o)
{
    float fy, fz, up, lo;
    gait_foot(g, ph - floorf(ph), &fy, &fz);
    leg_ik(a, b, ground_y + fy - hip_y, fz, &up, &lo);
    quat_xyz(up, 0, 0, o->r[u]);
    quat_xyz(lo, 0, 0, o->r[u + 1]);
    quat_xyz(-(up + lo), 0, 0, o->r[u + 2]);
}

/* Humanoid: stance 60% of a 1 s cycle, 0.6 m of foot travel (1.0 m/s),
 * left foot touching down at phase 0 at +0.3 m, the right half a cycle
 * later. Leg bones 0.42 + 0.40 m, hip joints 0.82 m above the ankles at
 * bind: the hips ride 1.5 to 6.5 cm lower, highest at mid-stance (phases 0.3
 * and 0.8), so both feet reach the ground in double support; the stance
 * knee flexes 10 to 34 degrees. */
static const gen_gait_t g_humanoid_gait = {0.6f, 0.6f, 0.1f};

static void humanoid_walk(float ph, gen_anim_t *o)
{
    float c = cosf(2.0f * PI_F * ph);
    float hip_drop = -0.04f + 0.025f * cosf(4.0f * PI_F * (ph - 0.3f));
    o->t[1] = hip_drop;
    float hip_y = 0.88f + hip_drop;
    gait_leg(&g_humanoid_gait, ph, H_ULEG_L, 0.42f, 0.40f, hip_y, 0.06f, o);
    gait_leg(&g_humanoid_gait, ph + 0.5f, H_ULEG_R, 0.42f, 0.40f, hip_y, 0.06f, o);
    /* arms swing against the legs (left arm back while the left foot is
     * forward); elbows stay a little bent */
    quat_xyz(22.0f * DEG * c, 0, 4.0f * DEG, o->r[H_UARM_L]);
    quat_xyz(-22.0f * DEG * c, 0, -4.0f * DEG, o->r[H_UARM_R]);
    quat_xyz(-(15.0f + 10.0f * c) * DEG, 0, 0, o->r[H_LARM_L]);
    quat_xyz(-(15.0f - 10.0f * c) * DEG, 0, 0, o->r[H_LARM_R]);
    quat_xyz(0, 6.0f * DEG * c, 0, o->r[H_SPINE]);
    quat_xyz(0, -4.0f * DEG * c, 0, o->r[H_CHEST]);
}

static void humanoid_idle(float ph, gen_anim_t *o)
{
    float s = sinf(2.0f * PI_F * ph);
    quat_xyz(-2.0f * DEG * s, 0, 0, o->r[H_CHEST]);
    quat_xyz(3.0f * DEG * s, 8.0f * DEG * sinf(4.0f * PI_F * ph) * 0.5f, 0, o->r[H_HEAD]);
    quat_xyz(2.0f * DEG * s, 0, 5.0f * DEG, o->r[H_UARM_L]);
    quat_xyz(2.0f * DEG * s, 0, -5.0f * DEG, o->r[H_UARM_R]);
    quat_xyz(-8.0f * DEG, 0, 0, o->r[H_LARM_L]);
    quat_xyz(-8.0f * DEG, 0, 0, o->r[H_LARM_R]);
    o->t[1] = -0.005f * (0.5f - 0.5f * cosf(2.0f * PI_F * ph));
}

static void seg(gen_rig_t *r, int joint, int ja, int jb, const float a[3], const float b[3], float radius,
                float squash)
{
    gen_segment_t *s = &r->segments[r->segment_count++];
    s->joint = joint, s->joint_a = ja, s->joint_b = jb;
    memcpy(s->a, a, sizeof s->a), memcpy(s->b, b, sizeof s->b);
    s->radius = radius, s->squash = squash;
}

/* Segment from joint j's bind position to joint k's (or to an offset). */
static void seg_joints(gen_rig_t *r, int j, int ja, int jb, int k, const float off[3], float radius, float squash)
{
    float a[3], b[3];
    joint_world(r, j, a);
    if (k >= 0) joint_world(r, k, b);
    else memcpy(b, a, sizeof b);
    if (off)
        for (int c = 0; c < 3; c++) b[c] += off[c];
    seg(r, j, ja, jb, a, b, radius, squash);
}

static void build_humanoid(gen_rig_t *r)
{
    memset(r, 0, sizeof *r);
    r->name = "humanoid";
    r->color[0] = 0.72f, r->color[1] = 0.42f, r->color[2] = 0.30f, r->color[3] = 1.0f;
    static const gen_joint_t joints[H_COUNT] = {
        {"hips", -1, {0, 0.92f, 0}},        {"spine", H_HIPS, {0, 0.12f, 0}},
        {"chest", H_SPINE, {0, 0.18f, 0}},  {"neck", H_CHEST, {0, 0.22f, 0}},
        {"head", H_NECK, {0, 0.08f, 0}},    {"upperarm_l", H_CHEST, {0.19f, 0.18f, 0}},
        {"lowerarm_l", H_UARM_L, {0, -0.28f, 0}}, {"upperarm_r", H_CHEST, {-0.19f, 0.18f, 0}},
        {"lowerarm_r", H_UARM_R, {0, -0.28f, 0}}, {"upperleg_l", H_HIPS, {0.1f, -0.04f, 0}},
        {"lowerleg_l", H_ULEG_L, {0, -0.42f, 0}}, {"foot_l", H_LLEG_L, {0, -0.4f, 0}},
        {"upperleg_r", H_HIPS, {-0.1f, -0.04f, 0}}, {"lowerleg_r", H_ULEG_R, {0, -0.42f, 0}},
        {"foot_r", H_LLEG_R, {0, -0.4f, 0}},
    };
    r->joint_count = H_COUNT;
    memcpy(r->joints, joints, sizeof joints);

    float hp[3];
    joint_world(r, H_HIPS, hp);
    float pa[3] = {hp[0] - 0.1f, hp[1] - 0.02f, hp[2]}, pb[3] = {hp[0] + 0.1f, hp[1] - 0.02f, hp[2]};
    seg(r, H_HIPS, -1, -1, pa, pb, 0.11f, 0.8f);                         /* pelvis */
    seg_joints(r, H_SPINE, H_HIPS, H_CHEST, H_CHEST, NULL, 0.12f, 0.7f);  /* belly */
    float sh_l[3], sh_r[3];
    joint_world(r, H_UARM_L, sh_l), joint_world(r, H_UARM_R, sh_r);
    float ca[3], cb[3];
    joint_world(r, H_CHEST, ca);
    memcpy(cb, ca, sizeof cb);
    cb[1] = sh_l[1] - 0.04f;
    seg(r, H_CHEST, H_SPINE, -1, ca, cb, 0.15f, 0.65f);                    /* rib cage */
    float s1[3] = {sh_r[0] + 0.03f, sh_r[1] - 0.02f, 0}, s2[3] = {sh_l[0] - 0.03f, sh_l[1] - 0.02f, 0};
    seg(r, H_CHEST, -1, -1, s1, s2, 0.07f, 0.8f);                          /* shoulders */
    seg_joints(r, H_NECK, H_CHEST, H_HEAD, H_HEAD, NULL, 0.05f, 0);
    const float head_off[3] = {0, 0.12f, 0.01f};
    seg_joints(r, H_HEAD, H_NECK, -1, -1, head_off, 0.1f, 0);
    const float hand[3] = {0, -0.26f, 0};
    seg_joints(r, H_UARM_L, H_CHEST, H_LARM_L, H_LARM_L, NULL, 0.05f, 0);
    seg_joints(r, H_LARM_L, H_UARM_L, -1, -1, hand, 0.04f, 0);
    seg_joints(r, H_UARM_R, H_CHEST, H_LARM_R, H_LARM_R, NULL, 0.05f, 0);
    seg_joints(r, H_LARM_R, H_UARM_R, -1, -1, hand, 0.04f, 0);
    const float toe[3] = {0, -0.01f, 0.16f};
    seg_joints(r, H_ULEG_L, H_HIPS, H_LLEG_L, H_LLEG_L, NULL, 0.075f, 0);
    seg_joints(r, H_LLEG_L, H_ULEG_L, H_FOOT_L, H_FOOT_L, NULL, 0.055f, 0);
    seg_joints(r, H_FOOT_L, H_LLEG_L, -1, -1, toe, 0.05f, 0.7f);
    seg_joints(r, H_ULEG_R, H_HIPS, H_LLEG_R, H_LLEG_R, NULL, 0.075f, 0);
    seg_joints(r, H_LLEG_R, H_ULEG_R, H_FOOT_R, H_FOOT_R, NULL, 0.055f, 0);
    seg_joints(r, H_FOOT_R, H_LLEG_R, -1, -1, toe, 0.05f, 0.7f);

    r->clip_count = 2;
    r->clips[0] = (gen_clip_t){"walk", 1.0f, 41, humanoid_walk};
    r->clips[1] = (gen_clip_t){"idle", 2.0f, 9, humanoid_idle};
}

/* ---- quadruped -------------------------------------------------------------- */
enum {
    Q_BODY, Q_CHEST, Q_NECK, Q_HEAD, Q_TAIL,
    Q_FL_U, Q_FL_L, Q_FL_P, Q_FR_U, Q_FR_L, Q_FR_P,
    Q_BL_U, Q_BL_L, Q_BL_P, Q_BR_U, Q_BR_L, Q_BR_P,
    Q_COUNT
};

/* Quadruped: diagonal gait, front-left with back-right, front-right with
 * back-left half a cycle later; stance 60% of a 0.8 s cycle, 0.3 m of paw
 * travel (0.625 m/s), 6 cm paw lift. Hip joints sit 0.35 m above the paws
 * at bind (legs 0.18 + 0.17 front, 0.19 + 0.16 back); the body rides 1.1 to
 * 4.1 cm lower, highest at mid-stance. The chest does not roll so the front
 * hips stay where the IK expects them. */
static const gen_gait_t g_quadruped_gait = {0.6f, 0.3f, 0.06f};

static void quadruped_walk(float ph, gen_anim_t *o)
{
    float drop = -0.026f + 0.015f * cosf(4.0f * PI_F * (ph - 0.3f));
    o->t[1] = drop;
    float hip_y = 0.39f + drop;
    const gen_gait_t *g = &g_quadruped_gait;
    gait_leg(g, ph, Q_FL_U, 0.18f, 0.17f, hip_y, 0.04f, o);
    gait_leg(g, ph, Q_BR_U, 0.19f, 0.16f, hip_y, 0.04f, o);
    gait_leg(g, ph + 0.5f, Q_FR_U, 0.18f, 0.17f, hip_y, 0.04f, o);
    gait_leg(g, ph + 0.5f, Q_BL_U, 0.19f, 0.16f, hip_y, 0.04f, o);
    quat_xyz(0, 20.0f * DEG * sinf(4.0f * PI_F * ph), 0, o->r[Q_TAIL]);
    quat_xyz(4.0f * DEG * sinf(4.0f * PI_F * ph), 0, 0, o->r[Q_HEAD]);
}

static void build_quadruped(gen_rig_t *r)
{
    memset(r, 0, sizeof *r);
    r->name = "quadruped";
    r->color[0] = 0.55f, r->color[1] = 0.38f, r->color[2] = 0.22f, r->color[3] = 1.0f;
    static const gen_joint_t joints[Q_COUNT] = {
        {"body", -1, {0, 0.42f, -0.18f}},  {"chest", Q_BODY, {0, 0.01f, 0.36f}},
        {"neck", Q_CHEST, {0, 0.04f, 0.08f}}, {"head", Q_NECK, {0, 0.12f, 0.06f}},
        {"tail", Q_BODY, {0, 0.03f, -0.06f}},
        {"frontleg_upper_l", Q_CHEST, {0.08f, -0.04f, 0}}, {"frontleg_lower_l", Q_FL_U, {0, -0.18f, 0}},
        {"frontpaw_l", Q_FL_L, {0, -0.17f, 0}},
        {"frontleg_upper_r", Q_CHEST, {-0.08f, -0.04f, 0}}, {"frontleg_lower_r", Q_FR_U, {0, -0.18f, 0}},
        {"frontpaw_r", Q_FR_L, {0, -0.17f, 0}},
        {"backleg_upper_l", Q_BODY, {0.08f, -0.03f, 0}}, {"backleg_lower_l", Q_BL_U, {0, -0.19f, 0}},
        {"backpaw_l", Q_BL_L, {0, -0.16f, 0}},
        {"backleg_upper_r", Q_BODY, {-0.08f, -0.03f, 0}}, {"backleg_lower_r", Q_BR_U, {0, -0.19f, 0}},
        {"backpaw_r", Q_BR_L, {0, -0.16f, 0}},
    };
    r->joint_count = Q_COUNT;
    memcpy(r->joints, joints, sizeof joints);

    seg_joints(r, Q_BODY, -1, Q_CHEST, Q_CHEST, NULL, 0.1f, 0.9f);
    const float chest_off[3] = {0, 0.02f, 0.08f};
    seg_joints(r, Q_CHEST, Q_BODY, -1, -1, chest_off, 0.105f, 0.9f);
    seg_joints(r, Q_NECK, Q_CHEST, Q_HEAD, Q_HEAD, NULL, 0.05f, 0);
    const float snout[3] = {0, -0.03f, 0.14f};
    seg_joints(r, Q_HEAD, Q_NECK, -1, -1, snout, 0.06f, 0);
    const float tail_off[3] = {0, 0.07f, -0.2f};
    seg_joints(r, Q_TAIL, Q_BODY, -1, -1, tail_off, 0.022f, 0);
    const float paw_off[3] = {0, -0.005f, 0.05f};
    static const int uppers[4] = {Q_FL_U, Q_FR_U, Q_BL_U, Q_BR_U};
    for (int leg = 0; leg < 4; leg++) {
        int u = uppers[leg];
        int attach = leg < 2 ? Q_CHEST : Q_BODY;
        seg_joints(r, u, attach, u + 1, u + 1, NULL, 0.04f, 0);
        seg_joints(r, u + 1, u, u + 2, u + 2, NULL, 0.03f, 0);
        seg_joints(r, u + 2, u + 1, -1, -1, paw_off, 0.035f, 0);
    }
    r->clip_count = 1;
    r->clips[0] = (gen_clip_t){"walk", 0.8f, 41, quadruped_walk};
}

/* ---- OBJ meshes --------------------------------------------------------------- */
/* Parametric surface (u,v) in [0,1]^2 wrapped in both directions. */
typedef void (*gen_surface_fn)(float u, float v, float p[3], float n[3]);

static const float g_torus_major = 2.0f, g_torus_minor = 0.8f, g_sphere_radius = 2.0f;

static void torus_fn(float u, float v, float p[3], float n[3])
{
    float a = 2.0f * PI_F * u, b = 2.0f * PI_F * v;
    n[0] = cosf(b) * cosf(a), n[1] = sinf(b), n[2] = cosf(b) * sinf(a);
    p[0] = (g_torus_major + g_torus_minor * cosf(b)) * cosf(a);
    p[1] = g_torus_minor * sinf(b);
    p[2] = (g_torus_major + g_torus_minor * cosf(b)) * sinf(a);
}

static void sphere_fn(float u, float v, float p[3], float n[3])
{
    float a = 2.0f * PI_F * u, b = PI_F * (v - 0.5f);
    n[0] = cosf(b) * cosf(a), n[1] = sinf(b), n[2] = cosf(b) * sinf(a);
    for (int k = 0; k < 3; k++) p[k] = g_sphere_radius * n[k];
}

/* Grid of (nu+1) x (nv+1) vertices; faces wind counter-clockwise seen from
 * outside. For the sphere the pole rows are degenerate triangles; they are
 * skipped. */
static bool write_obj(const char *path, const char *name, gen_surface_fn fn, int nu, int nv, bool poles)
{
    core_buf_t b = {0};
    core_buf_printf(&b, "# %s, written by meadow_gen_models\no %s\n", name, name);
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            float p[3], n[3];
            fn((float)i / nu, (float)j / nv, p, n);
            core_buf_printf(&b, "v %.6f %.6f %.6f\n", (double)p[0], (double)p[1], (double)p[2]);
        }
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            float p[3], n[3];
            fn((float)i / nu, (float)j / nv, p, n);
            core_buf_printf(&b, "vn %.6f %.6f %.6f\n", (double)n[0], (double)n[1], (double)n[2]);
        }
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) core_buf_printf(&b, "vt %.6f %.6f\n", (double)i / nu, (double)j / nv);
    int tris = 0;
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            int i0 = j * (nu + 1) + i + 1, i1 = i0 + 1, i2 = i0 + nu + 1, i3 = i2 + 1;
            if (!(poles && j == 0)) {
                core_buf_printf(&b, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", i0, i0, i0, i2, i2, i2, i1, i1, i1);
                tris++;
            }
            if (!(poles && j == nv - 1)) {
                core_buf_printf(&b, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", i1, i1, i1, i2, i2, i2, i3, i3, i3);
                tris++;
            }
        }
    bool ok = core_fs_write_atomic(path, b.data, b.len);
    printf("%s: %d vertices, %d triangles\n", path, (nu + 1) * (nv + 1), tris);
    core_buf_free(&b);
    return ok;
}

/* ---- loader fixtures ------------------------------------------------------------ */
/* The fixtures' unit quad in the XY plane, facing +Z: positions (with their
 * bounds) and normals as two accessors; its triangles are g_quad_indices. */
static const uint16_t g_quad_indices[6] = {0, 1, 2, 0, 2, 3};

static void fixture_quad(gltf_t *g, int *a_pos, int *a_nor)
{
    const float pos[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    const float nor[4][3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    float mn[3], mx[3];
    minmax(&pos[0][0], 4, 3, 3, mn, mx);
    *a_pos = gltf_accessor(g, pos, 4, GL_FLOAT, "VEC3", 3, mn, mx);
    *a_nor = gltf_accessor(g, nor, 4, GL_FLOAT, "VEC3", 3, NULL, NULL);
}

/* gltf_finish for a fixture, announced on stdout. */
static bool fixture_finish(gltf_t *g, core_buf_t *body, const char *path, const char *what)
{
    bool ok = gltf_finish(g, body, path);
    printf("%s: %s\n", path, what);
    core_buf_free(body);
    return ok;
}

/* Two joints ("root", "arm"), one skinned triangle pair and one animation whose
 * key data is inconsistent on purpose: the rotation times are unsorted and one
 * is NaN, one rotation is the zero quaternion, the translation times start
 * below zero, and one vertex has all weights zero. */
static bool write_broken_fixture(const char *path)
{
    gltf_t g = {0};
    const uint16_t jt[4][4] = {{0, 0, 0, 0}, {0, 1, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}};
    const float wt[4][4] = {{1, 0, 0, 0}, {0.5f, 0.5f, 0, 0}, {1, 0, 0, 0}, {0, 0, 0, 0}};
    int a_pos, a_nor;
    fixture_quad(&g, &a_pos, &a_nor);
    int a_jt = gltf_accessor(&g, jt, 4, GL_USHORT, "VEC4", 4, NULL, NULL);
    int a_wt = gltf_accessor(&g, wt, 4, GL_FLOAT, "VEC4", 4, NULL, NULL);
    int a_idx = gltf_accessor(&g, g_quad_indices, 6, GL_USHORT, "SCALAR", 1, NULL, NULL);
    const float ibm[2][16] = {{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                              {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1}};
    int a_ibm = gltf_accessor(&g, ibm, 2, GL_FLOAT, "MAT4", 16, NULL, NULL);
    const float rt[5] = {0.0f, 1.0f, 0.5f, NAN, 0.25f};
    const float rq[5][4] = {{0, 0, 0, 1}, {0, 0, 1, 0}, {0, 0, 0.70710678f, 0.70710678f}, {0, 0, 0, 1}, {0, 0, 0, 0}};
    float rmin = 0.0f, rmax = 1.0f;
    int a_rt = gltf_accessor(&g, rt, 5, GL_FLOAT, "SCALAR", 1, &rmin, &rmax);
    int a_rq = gltf_accessor(&g, rq, 5, GL_FLOAT, "VEC4", 4, NULL, NULL);
    const float tt[2] = {-0.5f, 2.0f};
    const float tv[2][3] = {{0, 0, 0}, {0, 2, 0}};
    float tmin = -0.5f, tmax = 2.0f;
    int a_tt = gltf_accessor(&g, tt, 2, GL_FLOAT, "SCALAR", 1, &tmin, &tmax);
    int a_tv = gltf_accessor(&g, tv, 2, GL_FLOAT, "VEC3", 3, NULL, NULL);

    core_buf_t body = {0};
    core_buf_printf(&body, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"meadow_gen_models (broken fixture)\"},"
                           "\"scene\":0,\"scenes\":[{\"nodes\":[0,1]}],\"nodes\":["
                           "{\"name\":\"quad\",\"mesh\":0,\"skin\":0},"
                           "{\"name\":\"root\",\"children\":[2]},"
                           "{\"name\":\"arm\",\"translation\":[0,1,0]}],"
                           "\"skins\":[{\"inverseBindMatrices\":%d,\"joints\":[1,2]}],"
                           "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":%d,\"NORMAL\":%d,"
                           "\"JOINTS_0\":%d,\"WEIGHTS_0\":%d},\"indices\":%d}]}],",
                    a_ibm, a_pos, a_nor, a_jt, a_wt, a_idx);
    core_buf_printf(&body, "\"animations\":[{\"name\":\"bend\",\"samplers\":["
                           "{\"input\":%d,\"output\":%d,\"interpolation\":\"LINEAR\"},"
                           "{\"input\":%d,\"output\":%d,\"interpolation\":\"LINEAR\"}],"
                           "\"channels\":[{\"sampler\":0,\"target\":{\"node\":2,\"path\":\"rotation\"}},"
                           "{\"sampler\":1,\"target\":{\"node\":1,\"path\":\"translation\"}}]}]",
                    a_rt, a_rq, a_tt, a_tv);
    return fixture_finish(&g, &body, path, "loader fixture");
}

/* One unskinned quad ("body", 1 x 1 in the XY plane) with two morph targets
 * (0 lifts the top edge by 0.5 in y, 1 moves the right edge by 0.5 in x)
 * and two animations: "pose", a single translation key at t = 0 (a clip of
 * duration 0), then "grow", the morph weights (0, 0) -> (1, 0) -> (0, 1)
 * over 2 s. */
static bool write_clips_fixture(const char *path)
{
    gltf_t g = {0};
    const float lift[4][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0.5f, 0}, {0, 0.5f, 0}};
    const float widen[4][3] = {{0, 0, 0}, {0.5f, 0, 0}, {0.5f, 0, 0}, {0, 0, 0}};
    float mn[3], mx[3];
    int a_pos, a_nor;
    fixture_quad(&g, &a_pos, &a_nor);
    int a_idx = gltf_accessor(&g, g_quad_indices, 6, GL_USHORT, "SCALAR", 1, NULL, NULL);
    minmax(&lift[0][0], 4, 3, 3, mn, mx);
    int a_lift = gltf_accessor(&g, lift, 4, GL_FLOAT, "VEC3", 3, mn, mx);
    minmax(&widen[0][0], 4, 3, 3, mn, mx);
    int a_widen = gltf_accessor(&g, widen, 4, GL_FLOAT, "VEC3", 3, mn, mx);
    const float t0[1] = {0}, v0[1][3] = {{0, 0, 0}};
    int a_t0 = gltf_accessor(&g, t0, 1, GL_FLOAT, "SCALAR", 1, t0, t0);
    int a_v0 = gltf_accessor(&g, v0, 1, GL_FLOAT, "VEC3", 3, NULL, NULL);
    const float tw[3] = {0, 1, 2}, ww[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    int a_tw = gltf_accessor(&g, tw, 3, GL_FLOAT, "SCALAR", 1, &tw[0], &tw[2]);
    int a_ww = gltf_accessor(&g, ww, 6, GL_FLOAT, "SCALAR", 1, NULL, NULL);

    core_buf_t body = {0};
    core_buf_printf(&body, "{\"asset\":{\"version\":\"2.0\",\"generator\":\"meadow_gen_models (clips fixture)\"},"
                           "\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"name\":\"body\",\"mesh\":0}],"
                           "\"meshes\":[{\"weights\":[0,0],\"primitives\":[{\"attributes\":{\"POSITION\":%d,"
                           "\"NORMAL\":%d},\"indices\":%d,\"targets\":[{\"POSITION\":%d},{\"POSITION\":%d}]}]}],",
                    a_pos, a_nor, a_idx, a_lift, a_widen);
    core_buf_printf(&body, "\"animations\":[{\"name\":\"pose\",\"samplers\":[{\"input\":%d,\"output\":%d,"
                           "\"interpolation\":\"LINEAR\"}],\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,"
                           "\"path\":\"translation\"}}]},"
                           "{\"name\":\"grow\",\"samplers\":[{\"input\":%d,\"output\":%d,\"interpolation\":\"LINEAR\"}],"
                           "\"channels\":[{\"sampler\":0,\"target\":{\"node\":0,\"path\":\"weights\"}}]}]",
                    a_t0, a_v0, a_tw, a_ww);
    return fixture_finish(&g, &body, path, "clips fixture");
}

int main(int argc, char **argv)
{
    const char *models = MEADOW_SOURCE_DIR "/models";
    const char *fixtures = MEADOW_SOURCE_DIR "/tests/data/models";
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--models") && i + 1 < argc) models = argv[++i];
        else if (!strcmp(argv[i], "--fixtures") && i + 1 < argc) fixtures = argv[++i];
        else {
            fprintf(stderr, "usage: %s [--models DIR] [--fixtures DIR]\n", argv[0]);
            return 2;
        }
    }
    if (!core_fs_mkdirs(models) || !core_fs_mkdirs(fixtures)) return 1;
    char path[4096];
    bool ok = true;
    gen_rig_t *rig = malloc(sizeof *rig);
    if (!rig) return 1;
    build_humanoid(rig);
    snprintf(path, sizeof path, "%s/humanoid.gltf", models);
    ok &= write_rig(rig, path);
    build_quadruped(rig);
    snprintf(path, sizeof path, "%s/quadruped.gltf", models);
    ok &= write_rig(rig, path);
    free(rig);
    snprintf(path, sizeof path, "%s/torus.obj", models);
    ok &= write_obj(path, "torus", torus_fn, 48, 24, false);
    snprintf(path, sizeof path, "%s/sphere.obj", models);
    ok &= write_obj(path, "sphere", sphere_fn, 32, 16, true);
    snprintf(path, sizeof path, "%s/broken.gltf", fixtures);
    ok &= write_broken_fixture(path);
    snprintf(path, sizeof path, "%s/clips.gltf", fixtures);
    ok &= write_clips_fixture(path);
    return ok ? 0 : 1;
}

/* character_walk: GL-free walking helpers of the character module: the
 * natural stride speed of a clip measured from its foot motion (so the clip
 * can be played at walk speed / natural speed), the per-frame placement on
 * the path (scene_walk_eval) and terrain, and the collision spheres laid
 * along the fitted capsules. No paper equations: the grass papers take the
 * character only as collision proxies. */
#include "character/character.h"
#include "character/character_walk.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define CONTACT_FRACTION 0.25f
#define FOOT_HEIGHT_FRACTION 0.25f

void character_clip_stride(const character_model_t *model, int clip, character_stride_t *out)
{
    memset(out, 0, sizeof *out);
    if (clip < 0 || clip >= model->clip_count || model->vertex_count == 0) return;
    int nb = model->bone_count;
    bool *leaf = malloc((size_t)nb * sizeof *leaf), *dominates = calloc((size_t)nb, sizeof *dominates);
    character_pose_t pose;
    if (!leaf || !dominates || !character_pose_init(&pose, model)) {
        free(leaf), free(dominates);
        return;
    }
    for (int b = 0; b < nb; b++) leaf[b] = true;
    for (int b = 0; b < nb; b++)
        if (model->bones[b].parent >= 0) leaf[model->bones[b].parent] = false;
    float ymin = FLT_MAX, ymax = -FLT_MAX;
    for (int v = 0; v < model->vertex_count; v++) {
        const character_vertex_t *vx = &model->vertices[v];
        int best = 0;
        for (int k = 1; k < CHARACTER_MAX_INFLUENCES; k++)
            if (vx->weights[k] > vx->weights[best]) best = k;
        dominates[vx->joints[best]] = true;
        ymin = fminf(ymin, vx->pos[1]), ymax = fmaxf(ymax, vx->pos[1]);
    }
    float foot_limit = ymin + FOOT_HEIGHT_FRACTION * (ymax - ymin);
    for (int b = 0; b < nb && out->foot_count < CHARACTER_MAX_FEET; b++)
        if (leaf[b] && dominates[b] && pose.global[b][13] < foot_limit) out->feet[out->foot_count++] = b;

    enum { N = CHARACTER_STRIDE_SAMPLES };
    float x[CHARACTER_MAX_FEET][N], y[CHARACTER_MAX_FEET][N], z[CHARACTER_MAX_FEET][N];
    float dur = model->clips[clip].duration, dt = dur / N;
    for (int i = 0; i < N; i++) {
        character_sample_clip(model, clip, (float)i * dt, true, &pose);
        character_pose_globals(model, &pose);
        for (int f = 0; f < out->foot_count; f++) {
            x[f][i] = pose.global[out->feet[f]][12];
            y[f][i] = pose.global[out->feet[f]][13];
            z[f][i] = pose.global[out->feet[f]][14];
        }
    }
    double back = 0.0, time = 0.0;
    for (int f = 0; f < out->foot_count; f++) {
        int low = 0;
        float hi = -FLT_MAX;
        for (int i = 0; i < N; i++) {
            if (y[f][i] < y[f][low]) low = i;
            hi = fmaxf(hi, y[f][i]);
        }
        float limit = y[f][low] + CONTACT_FRACTION * (hi - y[f][low]);
        /* contiguous run of samples around the lowest one, in [begin, end] */
        int begin = 0, end = 0;
        while (begin > -(N - 1) && y[f][(low + begin - 1 + N) % N] <= limit) begin--;
        while (end - begin < N - 1 && y[f][(low + end + 1) % N] <= limit) end++;
        int i0 = (low + begin + N) % N, i1 = (low + end) % N;
        float z0 = z[f][i0], z1 = z[f][i1];
        back -= z1 - z0;
        out->contact_motion[0] += x[f][i1] - x[f][i0];
        out->contact_motion[1] += z1 - z0;
        time += (end - begin) * dt;
        float b = (float)((low + begin + N) % N) / N;
        out->contact_begin[f] = b;
        out->contact_end[f] = b + (float)(end - begin) / N;
    }
    out->natural_speed = time > 0.0 ? (float)(back / time) : 0.0f;
    out->contact_time = (float)time;
    character_pose_free(&pose);
    free(leaf), free(dominates);
}

int character_walk_facing(const character_model_t *model, float height)
{
    float best[2] = {0.0f, 0.0f}, best_speed = 0.0f;
    for (int c = 0; c < model->clip_count; c++) {
        character_stride_t st;
        character_clip_stride(model, c, &st);
        if (!(st.contact_time > 0.0f)) continue;
        float mx = st.contact_motion[0], mz = st.contact_motion[1];
        float speed = sqrtf(mx * mx + mz * mz) / st.contact_time;
        if (speed > best_speed) best_speed = speed, best[0] = mx, best[1] = mz;
    }
    if (best_speed < CHARACTER_FACING_MIN_SPEED * height) return 0;
    /* the stance feet move backwards: the model faces -motion */
    float fx = -best[0], fz = -best[1];
    if (fabsf(fx) > 2.0f * fabsf(fz)) return fx > 0.0f ? 1 : -1;
    if (fabsf(fz) > 2.0f * fabsf(fx)) return fz > 0.0f ? 3 : -3;
    return 0;
}

bool character_walk_face(character_model_t *m, const char *path, float yaw, character_import_t *im, char *err,
                         size_t err_size)
{
    if (!strcmp(im->forward_from, "scene") || yaw != 0.0f) return true;
    int facing = character_walk_facing(m, im->height);
    if (facing == 0) return true;
    if (facing != 3) {
        character_import_t turn;
        if (!character_import(m, path, &(character_import_desc_t){.height = im->height, .up = 2, .forward = facing},
                              &turn, err, err_size))
            return false;
        /* the file's axis that now faces +Z: row |facing| of the first import's rotation */
        float r[16];
        character_import_matrix(1.0f, im->up, im->forward, 0.0f, 0.0f, r);
        int row = abs(facing) - 1;
        for (int k = 0; k < 3; k++)
            if (fabsf(r[4 * k + row]) > 0.5f) im->forward = (k + 1) * (r[4 * k + row] * (float)facing > 0.0f ? 1 : -1);
        memcpy(im->box_min, turn.box_min, sizeof im->box_min);
        memcpy(im->box_max, turn.box_max, sizeof im->box_max);
    }
    im->forward_from = "walk";
    im->forward_confidence = character_import_evidence("walk");
    return true;
}

float character_walk_rate(const character_stride_t *stride, float speed, float scale)
{
    float natural = stride->natural_speed * scale;
    return fabsf(natural) < CHARACTER_MIN_STRIDE_SPEED ? 1.0f : speed / natural;
}

void character_walk_place(const scene_character_t *c, const terrain_mesh_t *terrain, float rate, float time,
                          float *clip_time, float position[3], float dir[2], float model[16])
{
    vec2 p, d;
    scene_walk_eval(c->waypoints, c->waypoint_count, c->speed, time, c->loop, p, d);
    /* The clip phase follows the distance walked, so it freezes when a
     * non-looping walk ends and never drifts from the feet. Characters that
     * cannot move (no path) play the clip at its own pace. */
    float length = scene_walk_length(c->waypoints, c->waypoint_count, c->loop);
    if (length > 0.0f && c->speed > 0.0f) {
        float walked = c->speed * time;
        if (!c->loop && walked > length) walked = length;
        *clip_time = walked / c->speed * rate;
    } else {
        *clip_time = time;
    }
    float h = terrain ? terrain_height_at(terrain, p[0], p[1], NULL) : 0.0f;
    if (h < -FLT_MAX * 0.5f) h = 0.0f; /* off a mesh terrain: keep the ground plane */
    position[0] = p[0], position[1] = h, position[2] = p[1];
    dir[0] = d[0], dir[1] = d[1];
    /* Ry(yaw) maps the model's +Z onto (dir.x, 0, dir.z); columns: */
    float s = c->scale;
    memset(model, 0, 16 * sizeof(float));
    model[0] = d[1] * s, model[2] = -d[0] * s;
    model[5] = s;
    model[8] = d[0] * s, model[10] = d[1] * s;
    model[12] = position[0], model[13] = position[1], model[14] = position[2];
    model[15] = 1.0f;
}

int character_capsule_sphere_count(const character_capsule_t *c)
{
    float L = sqrtf((c->b[0] - c->a[0]) * (c->b[0] - c->a[0]) + (c->b[1] - c->a[1]) * (c->b[1] - c->a[1]) +
                    (c->b[2] - c->a[2]) * (c->b[2] - c->a[2]));
    return c->radius > 0.0f ? (int)ceilf(L / c->radius) + 1 : 1;
}

void character_capsule_spheres(const float a[3], const float b[3], float radius, int n, float (*out)[4])
{
    /* n spheres evenly from a to b, spacing s <= radius. Inflating each to
     * sqrt(r^2 + (s/2)^2) makes their union contain the whole capsule: a
     * point within r of the axis lies within s/2 of a centre along it. */
    float L = sqrtf((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) + (b[2] - a[2]) * (b[2] - a[2]));
    float s = n > 1 ? L / (float)(n - 1) : 0.0f;
    float r = sqrtf(radius * radius + 0.25f * s * s);
    for (int i = 0; i < n; i++) {
        float t = n > 1 ? (float)i / (float)(n - 1) : 0.5f;
        for (int k = 0; k < 3; k++) out[i][k] = a[k] + t * (b[k] - a[k]);
        out[i][3] = r;
    }
}

int character_pose_step(float distance, float lod_distance)
{
    if (!(lod_distance > 0.0f) || !(distance > lod_distance)) return 1;
    float step = floorf(distance / lod_distance) + 1.0f;
    return step < (float)CHARACTER_POSE_STEP_MAX ? (int)step : CHARACTER_POSE_STEP_MAX;
}

bool character_pose_due(uint64_t update, int index, int step)
{
    return step <= 1 || (update + (uint64_t)index) % (uint64_t)step == 0;
}

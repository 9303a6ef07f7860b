/* test_character_models: the generated models in models/ load through
 * assimp with the expected skeletons, clips and weights; the walk clip moves
 * the feet and loops, each foot on the ground while it moves back and lifted
 * while it swings forward (quadruped: diagonal pairs); bind-pose skinning reproduces the vertices; fitted
 * capsules hold >= 95% of their bones' skinned vertices; and
 * meadow_gen_models regenerates the committed files byte for byte. */
#include "character/character_ref.h"
#include "core/core.h"
#include "test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static bool load(character_model_t *m, const char *rel)
{
    char path[1024], err[256];
    CHECK(core_fs_resolve(rel, path, sizeof path));
    bool ok = character_load(m, path, err, sizeof err);
    CHECK_MSG(ok, "%s: %s", rel, err);
    return ok;
}

static void check_weights(const character_model_t *m)
{
    int bad = 0;
    for (int v = 0; v < m->vertex_count; v++) {
        const character_vertex_t *vx = &m->vertices[v];
        float s = 0.0f;
        for (int k = 0; k < CHARACTER_MAX_INFLUENCES; k++) {
            s += vx->weights[k];
            if (vx->weights[k] < 0.0f || vx->joints[k] >= m->bone_count) bad++;
        }
        if (fabsf(s - 1.0f) > 1e-5f) bad++;
    }
    CHECK_MSG(bad == 0, "%d bad weights", bad);
}

/* Triangles wind counter-clockwise seen from outside: the face normal
 * agrees with the vertex normals (degenerate pole triangles skipped). */
static void check_winding(const character_model_t *m)
{
    int bad = 0, tested = 0;
    for (int i = 0; i < m->index_count; i += 3) {
        const float *a = m->vertices[m->indices[i]].pos, *b = m->vertices[m->indices[i + 1]].pos;
        const float *c = m->vertices[m->indices[i + 2]].pos;
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
        float fn[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        if (fn[0] * fn[0] + fn[1] * fn[1] + fn[2] * fn[2] < 1e-14f) continue;
        float d = 0.0f;
        for (int k = 0; k < 3; k++)
            for (int e = 0; e < 3; e++) d += fn[e] * m->vertices[m->indices[i + k]].normal[e];
        tested++;
        bad += d <= 0.0f;
    }
    CHECK_MSG(bad == 0 && tested > 0, "%d of %d triangles wind inwards", bad, tested);
}

static void bone_position(const character_model_t *m, int clip, float t, int bone, float out[3])
{
    character_pose_t pose;
    CHECK(character_pose_init(&pose, m));
    character_sample_clip(m, clip, t, true, &pose);
    character_pose_globals(m, &pose);
    memcpy(out, &pose.global[bone][12], sizeof(float) * 3);
    character_pose_free(&pose);
}

static float dist3(const float a[3], const float b[3])
{
    return sqrtf((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

/* Gait direction, brute force from the bone positions: over 200 samples of
 * the loop, a foot near the bottom of its height range (lowest 10%: on the
 * ground) moves backwards (-Z) relative to the root at a speed within
 * [lo, hi] m/s, and near the top (highest half: lifted) moves forwards. */
static void check_gait(const character_model_t *m, int clip, const char *foot, double lo, double hi)
{
    enum { N = 200 };
    int b = character_bone_find(m, foot);
    CHECK_MSG(b >= 0, "%s", foot);
    if (b < 0) return;
    float dur = m->clips[clip].duration, y[N], z[N];
    for (int i = 0; i < N; i++) {
        float p[3];
        bone_position(m, clip, dur * (float)i / N, b, p);
        y[i] = p[1], z[i] = p[2];
    }
    float ymin = y[0], ymax = y[0];
    for (int i = 1; i < N; i++) ymin = fminf(ymin, y[i]), ymax = fmaxf(ymax, y[i]);
    double ground_v = 0.0, lifted_v = 0.0;
    int ground_n = 0, lifted_n = 0;
    for (int i = 0; i < N; i++) {
        double v = (z[(i + 1) % N] - z[(i + N - 1) % N]) / (2.0 * dur / N);
        double h = (y[i] - ymin) / (ymax - ymin);
        if (h < 0.1) ground_v += v, ground_n++;
        if (h > 0.5) lifted_v += v, lifted_n++;
    }
    ground_v /= ground_n > 0 ? ground_n : 1, lifted_v /= lifted_n > 0 ? lifted_n : 1;
    printf("%s: lift %.3f m, mean z speed on the ground %.3f m/s (%d samples), lifted %.3f m/s (%d samples)\n", foot,
           (double)(ymax - ymin), ground_v, ground_n, lifted_v, lifted_n);
    CHECK(ymax - ymin > 0.03f);
    CHECK_MSG(-ground_v >= lo && -ground_v <= hi, "%s: ground speed %.3f m/s", foot, -ground_v);
    CHECK_MSG(lifted_v > 0.0, "%s: lifted speed %.3f m/s", foot, lifted_v);
}

/* Per-bone containment (no merging) and union containment after merging. */
static void check_capsules(const character_model_t *m, int clip, float t)
{
    character_pose_t pose;
    CHECK(character_pose_init(&pose, m));
    character_sample_clip(m, clip, t, true, &pose);
    character_pose_globals(m, &pose);
    float *p = malloc(sizeof(float) * 3 * (size_t)m->vertex_count);
    character_skin_cpu(m, &pose, p, NULL);
    character_capsule_t *caps = malloc(sizeof *caps * (size_t)m->bone_count);
    int n = character_fit_capsules(m, &pose, p, caps, m->bone_count);
    CHECK(n >= 10);
    for (int c = 0; c < n; c++) {
        int owned = 0, inside = 0;
        for (int v = 0; v < m->vertex_count; v++) {
            const character_vertex_t *vx = &m->vertices[v];
            int best = 0;
            for (int k = 1; k < CHARACTER_MAX_INFLUENCES; k++)
                if (vx->weights[k] > vx->weights[best]) best = k;
            if (vx->joints[best] != caps[c].bone) continue;
            owned++;
            inside += character_capsule_distance(&caps[c], p + 3 * v) <= 1e-4f;
        }
        CHECK(owned == caps[c].vertex_count);
        CHECK_MSG(inside >= 0.95 * owned, "bone %s: %d of %d inside", m->bones[caps[c].bone].name, inside, owned);
        CHECK_MSG(caps[c].radius < 0.2f, "bone %s radius %g", m->bones[caps[c].bone].name, (double)caps[c].radius);
        /* the local end points map back to the model-space ones */
        float back[3];
        character_mat4_point(pose.global[caps[c].bone], caps[c].local_a, back);
        CHECK(dist3(back, caps[c].a) < 1e-4f);
    }
    n = character_fit_capsules(m, &pose, p, caps, 6);
    CHECK(n == 6);
    int total = 0, inside = 0;
    for (int c = 0; c < n; c++) total += caps[c].vertex_count;
    CHECK(total == m->vertex_count);
    for (int v = 0; v < m->vertex_count; v++) {
        bool in = false;
        for (int c = 0; c < n && !in; c++) in = character_capsule_distance(&caps[c], p + 3 * v) <= 1e-4f;
        inside += in;
    }
    CHECK_MSG(inside >= 0.95 * m->vertex_count, "merged: %d of %d inside", inside, m->vertex_count);
    free(caps);
    free(p);
    character_pose_free(&pose);
}

static void test_obj_winding(void)
{
    character_model_t m;
    if (load(&m, "models/torus.obj")) {
        check_winding(&m);
        character_model_free(&m);
    }
    if (load(&m, "models/sphere.obj")) {
        check_winding(&m);
        character_model_free(&m);
    }
}

static void test_humanoid(void)
{
    character_model_t m;
    if (!load(&m, "models/humanoid.gltf")) return;
    CHECK(m.bone_count >= 10 && !m.rigid);
    CHECK(m.vertex_count > 500 && m.index_count / 3 >= 300 && m.index_count / 3 <= 5000);
    int walk = character_clip_find(&m, "walk"), idle = character_clip_find(&m, "idle");
    CHECK(walk >= 0 && idle >= 0 && walk != idle);
    check_weights(&m);
    check_winding(&m);
    for (int i = 0; i < m.bone_count; i++) CHECK(m.bones[i].parent < i);
    const char *names[] = {"hips", "spine", "chest", "neck", "head", "upperarm_l", "lowerarm_l", "upperarm_r",
                           "lowerarm_r", "upperleg_l", "lowerleg_l", "foot_l", "upperleg_r", "lowerleg_r",
                           "foot_r"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        CHECK_MSG(character_bone_find(&m, names[i]) >= 0, "%s", names[i]);
    CHECK(m.bones[character_bone_find(&m, "foot_l")].parent == character_bone_find(&m, "lowerleg_l"));
    CHECK(m.base_color[0] > 0.6f && m.base_color[2] < 0.4f);

    /* bind pose: ~1.7 m tall, feet on y=0, toes towards +Z; skinning at bind
     * reproduces the vertices */
    character_pose_t pose;
    CHECK(character_pose_init(&pose, &m));
    float *p = malloc(sizeof(float) * 3 * (size_t)m.vertex_count);
    float *n = malloc(sizeof(float) * 3 * (size_t)m.vertex_count);
    character_skin_cpu(&m, &pose, p, n);
    double worst = 0.0, worst_n = 0.0;
    for (int v = 0; v < m.vertex_count; v++)
        for (int k = 0; k < 3; k++) {
            worst = fmax(worst, fabs(p[3 * v + k] - m.vertices[v].pos[k]));
            worst_n = fmax(worst_n, fabs(n[3 * v + k] - m.vertices[v].normal[k]));
        }
    CHECK_MSG(worst < 1e-5 && worst_n < 1e-4, "bind skinning error %g / normals %g", worst, worst_n);
    character_bounds_t bd;
    character_bounds(&m, p, &bd);
    CHECK_NEAR(bd.min[1], 0.0, 0.005);
    CHECK(bd.max[1] > 1.6f && bd.max[1] < 1.85f);
    CHECK(bd.max[2] > -bd.min[2]);
    CHECK(bd.radius >= 0.5f * (bd.max[1] - bd.min[1]));

    /* walk: feet move between t = 0 and t = 0.5, and the clip loops */
    if (walk >= 0) {
        CHECK_NEAR(m.clips[walk].duration, 1.0, 1e-4);
        int fl = character_bone_find(&m, "foot_l"), fr = character_bone_find(&m, "foot_r");
        float a[3], b[3], c[3];
        bone_position(&m, walk, 0.0f, fl, a);
        bone_position(&m, walk, 0.5f, fl, b);
        bone_position(&m, walk, 1.0f - 1e-4f, fl, c);
        CHECK_MSG(dist3(a, b) > 0.2f, "left foot moved %g m", (double)dist3(a, b));
        CHECK(a[2] > b[2]); /* left foot forward at t=0, back at t=0.5 */
        CHECK(dist3(a, c) < 1e-3f);
        bone_position(&m, walk, 0.0f, fr, a);
        bone_position(&m, walk, 0.5f, fr, b);
        CHECK(dist3(a, b) > 0.2f && a[2] < b[2]);
        /* LBS versus per-influence blending of transformed points */
        character_sample_clip(&m, walk, 0.3f, true, &pose);
        character_pose_globals(&m, &pose);
        character_skin_cpu(&m, &pose, p, NULL);
        worst = 0.0;
        for (int v = 0; v < m.vertex_count; v += 7) {
            float acc[3] = {0, 0, 0}, q[3];
            const character_vertex_t *vx = &m.vertices[v];
            for (int k = 0; k < CHARACTER_MAX_INFLUENCES; k++) {
                float gi[16];
                character_mat4_mul(pose.global[vx->joints[k]], m.bones[vx->joints[k]].inverse_bind, gi);
                character_mat4_point(gi, vx->pos, q);
                for (int e = 0; e < 3; e++) acc[e] += vx->weights[k] * q[e];
            }
            for (int e = 0; e < 3; e++) worst = fmax(worst, fabs(acc[e] - p[3 * v + e]));
        }
        CHECK_MSG(worst < 1e-5, "LBS mismatch %g", worst);
        check_gait(&m, walk, "foot_l", 0.6, 2.0);
        check_gait(&m, walk, "foot_r", 0.6, 2.0);
        check_capsules(&m, walk, 0.3f);
        /* frame range in ticks (1000/s): the first half of the walk */
        int half = character_clip_find(&m, "0:500");
        CHECK(half >= 0);
        if (half >= 0) {
            CHECK_NEAR(m.clips[half].duration, 0.5, 1e-5);
            bone_position(&m, half, 0.25f, fl, a);
            bone_position(&m, walk, 0.25f, fl, b);
            CHECK(dist3(a, b) < 1e-5f);
        }
    }
    free(p), free(n);
    character_pose_free(&pose);
    character_model_free(&m);
}

static void test_quadruped(void)
{
    character_model_t m;
    if (!load(&m, "models/quadruped.gltf")) return;
    CHECK(m.bone_count >= 14 && !m.rigid);
    check_weights(&m);
    check_winding(&m);
    int walk = character_clip_find(&m, "walk");
    CHECK(walk >= 0);
    character_pose_t pose;
    CHECK(character_pose_init(&pose, &m));
    float *p = malloc(sizeof(float) * 3 * (size_t)m.vertex_count);
    character_skin_cpu(&m, &pose, p, NULL);
    character_bounds_t bd;
    character_bounds(&m, p, &bd);
    CHECK_NEAR(bd.min[1], 0.0, 0.005);
    CHECK(bd.max[1] > 0.5f && bd.max[1] < 0.75f);
    CHECK(bd.max[2] - bd.min[2] > bd.max[0] - bd.min[0]); /* long along Z */
    if (walk >= 0) {
        int fl = character_bone_find(&m, "frontpaw_l"), fr = character_bone_find(&m, "frontpaw_r");
        CHECK(fl >= 0 && fr >= 0);
        float a[3], b[3];
        bone_position(&m, walk, 0.0f, fl, a);
        bone_position(&m, walk, 0.4f, fl, b);
        CHECK(dist3(a, b) > 0.1f);
        const char *paws[] = {"frontpaw_l", "frontpaw_r", "backpaw_l", "backpaw_r"};
        for (int i = 0; i < 4; i++) check_gait(&m, walk, paws[i], 0.3, 1.2);
        /* diagonal gait: front-left and back-right touch down together */
        int bl = character_bone_find(&m, "backpaw_l"), br = character_bone_find(&m, "backpaw_r");
        float c[3], d[3];
        for (int i = 0; i < 8; i++) {
            float t = m.clips[walk].duration * (float)i / 8;
            bone_position(&m, walk, t, fl, a), bone_position(&m, walk, t, br, b);
            bone_position(&m, walk, t, fr, c), bone_position(&m, walk, t, bl, d);
            CHECK_NEAR(a[1], b[1], 1e-3);
            CHECK_NEAR(c[1], d[1], 1e-3);
        }
        check_capsules(&m, walk, 0.2f);
    }
    free(p);
    character_pose_free(&pose);
    character_model_free(&m);
}

static bool same_file(const char *a, const char *b)
{
    size_t na, nb;
    char *da = core_fs_read(a, &na, NULL, 0), *db = core_fs_read(b, &nb, NULL, 0);
    bool same = da && db && na == nb && !memcmp(da, db, na);
    free(da), free(db);
    return same;
}

static void test_generator_matches_committed(void)
{
    const char *out = getenv("MEADOW_TEST_OUT");
    char dir[1024], cmd[4096], a[1200], b[1200];
    snprintf(dir, sizeof dir, "%s", out ? out : "/tmp/meadow-test_character_models");
    snprintf(cmd, sizeof cmd, "'%s' --models '%s/models' --fixtures '%s/fixtures' > /dev/null", MEADOW_GEN_MODELS,
             dir, dir);
    CHECK(system(cmd) == 0);
    const char *files[] = {"models/humanoid.gltf", "models/quadruped.gltf", "models/torus.obj", "models/sphere.obj"};
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        snprintf(a, sizeof a, "%s/%s", dir, files[i]);
        CHECK(core_fs_resolve(files[i], b, sizeof b));
        CHECK_MSG(same_file(a, b), "%s differs from the generator's output; rerun meadow_gen_models", files[i]);
    }
    static const char *const fixtures[] = {"broken.gltf", "clips.gltf"};
    for (size_t i = 0; i < sizeof fixtures / sizeof fixtures[0]; i++) {
        char rel[256];
        snprintf(a, sizeof a, "%s/fixtures/%s", dir, fixtures[i]);
        snprintf(rel, sizeof rel, "tests/data/models/%s", fixtures[i]);
        CHECK(core_fs_resolve(rel, b, sizeof b));
        CHECK_MSG(same_file(a, b), "%s differs from the generator's output", fixtures[i]);
    }
}

int main(void)
{
    core_log_set_quiet(true);
    test_humanoid();
    test_quadruped();
    test_obj_winding();
    test_generator_matches_committed();
    TEST_END();
}

/* test_character_ref: clip sampling, hierarchy, skinning, capsules, bounds,
 * clip repair, clip selection (names, indices, ranges and their errors,
 * the fallback from a clip without duration) and morph targets before
 * skinning on tiny in-memory models with hand-computed expected values. */
#include "character/character_ref.h"
#include "core/core.h"
#include "test.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979

static void set_track(character_track_t *t, int n, const float *times, const float (*v)[4])
{
    t->count = n;
    t->keys = calloc((size_t)n, sizeof *t->keys);
    for (int i = 0; i < n; i++) {
        t->keys[i].time = times[i];
        memcpy(t->keys[i].v, v[i], sizeof v[i]);
    }
}

static void add_bone(character_model_t *m, const char *name, int parent, float tx, float ty, float tz)
{
    character_bone_t *b = &m->bones[m->bone_count++];
    memset(b, 0, sizeof *b);
    b->name = strdup(name);
    b->parent = parent;
    b->bind_t[0] = tx, b->bind_t[1] = ty, b->bind_t[2] = tz;
    b->bind_r[3] = 1.0f;
    b->bind_s[0] = b->bind_s[1] = b->bind_s[2] = 1.0f;
    character_trs_matrix(b->bind_t, b->bind_r, b->bind_s, b->bind_local);
}

/* inverse binds from the bind pose (pure translations here) */
static void set_inverse_binds(character_model_t *m)
{
    character_pose_t pose;
    m->clip_count = 0;
    for (int i = 0; i < m->bone_count; i++) {
        memset(m->bones[i].inverse_bind, 0, sizeof m->bones[i].inverse_bind);
        m->bones[i].inverse_bind[0] = m->bones[i].inverse_bind[5] = m->bones[i].inverse_bind[10] =
            m->bones[i].inverse_bind[15] = 1.0f;
    }
    CHECK(character_pose_init(&pose, m));
    for (int i = 0; i < m->bone_count; i++) CHECK(character_mat4_invert(pose.global[i], m->bones[i].inverse_bind));
    character_pose_free(&pose);
}

static void add_vertex(character_model_t *m, float x, float y, float z, int j0, float w0, int j1, float w1)
{
    character_vertex_t *v = &m->vertices[m->vertex_count++];
    memset(v, 0, sizeof *v);
    v->pos[0] = x, v->pos[1] = y, v->pos[2] = z;
    v->normal[0] = 1.0f;
    v->joints[0] = (uint16_t)j0, v->weights[0] = w0;
    v->joints[1] = (uint16_t)j1, v->weights[1] = w1;
}

/* root --(0,1,0)--> upper --(1,0,0)--> tip. Clip "bend" (1 s): root moves
 * from x=0 to x=2, upper turns 0 -> 180 deg about Z. */
static void build_arm(character_model_t *m)
{
    memset(m, 0, sizeof *m);
    m->bones = calloc(3, sizeof *m->bones);
    add_bone(m, "root", -1, 0, 0, 0);
    add_bone(m, "upper", 0, 0, 1, 0);
    add_bone(m, "tip", 1, 1, 0, 0);
    set_inverse_binds(m);
    m->vertices = calloc(2, sizeof *m->vertices);
    add_vertex(m, 1.0f, 1.0f, 0.0f, 1, 1.0f, 0, 0.0f);  /* A: on upper */
    add_vertex(m, 0.5f, 1.0f, 0.0f, 0, 0.5f, 1, 0.5f);  /* B: half/half */
    m->clips = calloc(1, sizeof *m->clips);
    m->clip_count = 1;
    character_clip_t *c = &m->clips[0];
    c->name = strdup("bend");
    c->duration = 1.0f;
    c->ticks_per_second = 10.0f;
    c->channels = calloc(3, sizeof *c->channels);
    const float times[2] = {0.0f, 1.0f};
    const float tr[2][4] = {{0, 0, 0, 0}, {2, 0, 0, 0}};
    const float rot[2][4] = {{0, 0, 0, 1}, {0, 0, 1, 0}};
    set_track(&c->channels[0].pos, 2, times, tr);
    set_track(&c->channels[1].rot, 2, times, rot);
}

static float quat_angle_z(const float q[4]) { return (float)(2.0 * atan2(q[2], q[3]) * 180.0 / PI); }

static void test_hand_pose(void)
{
    character_model_t m;
    build_arm(&m);
    character_pose_t pose;
    CHECK(character_pose_init(&pose, &m));

    /* bind pose: skinning reproduces the vertices */
    float p[6], n[6];
    character_skin_cpu(&m, &pose, p, n);
    CHECK_NEAR(p[0], 1.0, 1e-6); CHECK_NEAR(p[1], 1.0, 1e-6); CHECK_NEAR(p[3], 0.5, 1e-6);

    /* t = 0.5: root at (1,0,0); upper = T(0,1,0) Rz(90) */
    character_sample_clip(&m, 0, 0.5f, false, &pose);
    character_pose_globals(&m, &pose);
    const float expect_g1[16] = {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 1, 1, 0, 1};
    for (int e = 0; e < 16; e++) CHECK_NEAR(pose.global[1][e], expect_g1[e], 1e-6);
    /* tip = (1,1,0) + Rz(90) (1,0,0) = (1,2,0) */
    CHECK_NEAR(pose.global[2][12], 1.0, 1e-6);
    CHECK_NEAR(pose.global[2][13], 2.0, 1e-6);
    CHECK_NEAR(pose.global[2][14], 0.0, 1e-6);
    character_skin_cpu(&m, &pose, p, n);
    /* A (1,1,0) -> bone space (1,0,0) -> rotated (0,1,0) -> + (1,1,0) */
    CHECK_NEAR(p[0], 1.0, 1e-6); CHECK_NEAR(p[1], 2.0, 1e-6); CHECK_NEAR(p[2], 0.0, 1e-6);
    CHECK_NEAR(n[0], 0.0, 1e-6); CHECK_NEAR(n[1], 1.0, 1e-6);
    /* B: root gives (1.5,1,0), upper gives (1,1.5,0); blended (1.25,1.25,0) */
    CHECK_NEAR(p[3], 1.25, 1e-6); CHECK_NEAR(p[4], 1.25, 1e-6); CHECK_NEAR(p[5], 0.0, 1e-6);

    /* translation lerp and slerp at t = 0.25: x = 0.5, angle 45 deg (a plain
     * normalised lerp would give 2 atan(1/3) = 36.87 deg) */
    character_sample_clip(&m, 0, 0.25f, false, &pose);
    CHECK_NEAR(pose.t[0][0], 0.5, 1e-6);
    CHECK_NEAR(quat_angle_z(pose.r[1]), 45.0, 1e-3);
    float nl = (float)(2.0 * atan2(0.25, 0.75) * 180.0 / PI);
    CHECK(fabsf(quat_angle_z(pose.r[1]) - nl) > 5.0f);
    /* constant angular velocity */
    for (int i = 1; i < 10; i++) {
        character_sample_clip(&m, 0, (float)i / 10.0f, false, &pose);
        CHECK_NEAR(quat_angle_z(pose.r[1]), 18.0 * i, 1e-3);
        float len = 0.0f;
        for (int k = 0; k < 4; k++) len += pose.r[1][k] * pose.r[1][k];
        CHECK_NEAR(len, 1.0, 1e-6);
    }

    /* looping: 1.25 and -0.75 wrap to 0.25; without loop 1.25 clamps to 1 */
    float ref[4];
    character_sample_clip(&m, 0, 0.25f, true, &pose);
    memcpy(ref, pose.r[1], sizeof ref);
    character_sample_clip(&m, 0, 1.25f, true, &pose);
    for (int k = 0; k < 4; k++) CHECK_NEAR(pose.r[1][k], ref[k], 1e-5);
    CHECK_NEAR(pose.t[0][0], 0.5, 1e-5);
    character_sample_clip(&m, 0, -0.75f, true, &pose);
    for (int k = 0; k < 4; k++) CHECK_NEAR(pose.r[1][k], ref[k], 1e-5);
    character_sample_clip(&m, 0, 1.25f, false, &pose);
    character_pose_globals(&m, &pose);
    CHECK_NEAR(pose.t[0][0], 2.0, 1e-6);
    /* root (2,0,0); upper at (2,1,0) turned 180; tip = (2,1,0) - (1,0,0) */
    CHECK_NEAR(pose.global[2][12], 1.0, 1e-5); CHECK_NEAR(pose.global[2][13], 1.0, 1e-5);

    character_pose_free(&pose);
    character_model_free(&m);
}

static void test_slerp(void)
{
    /* shortest path: +10 deg and 350 deg (= -10 deg) about Y meet at 0 */
    float a[4] = {0, (float)sin(5.0 * PI / 180), 0, (float)cos(5.0 * PI / 180)};
    float b[4] = {0, (float)sin(175.0 * PI / 180), 0, (float)cos(175.0 * PI / 180)};
    float q[4];
    character_quat_slerp(a, b, 0.5f, q);
    CHECK_NEAR(fabs(q[3]), 1.0, 1e-6);
    CHECK_NEAR(q[1], 0.0, 1e-6);
    /* end points are exact, and 90 deg apart gives 30 deg at t = 1/3 */
    float x0[4] = {0, 0, 0, 1}, x90[4] = {(float)sin(PI / 4), 0, 0, (float)cos(PI / 4)};
    character_quat_slerp(x0, x90, 0.0f, q);
    CHECK_NEAR(q[3], 1.0, 1e-6);
    character_quat_slerp(x0, x90, 1.0f, q);
    CHECK_NEAR(q[0], x90[0], 1e-6); CHECK_NEAR(q[3], x90[3], 1e-6);
    character_quat_slerp(x0, x90, 1.0f / 3.0f, q);
    CHECK_NEAR(2.0 * atan2(q[0], q[3]) * 180.0 / PI, 30.0, 1e-3);
    /* nearly parallel quaternions use nlerp and stay unit length */
    float y1[4] = {0, (float)sin(0.0005), 0, (float)cos(0.0005)};
    character_quat_slerp(x0, y1, 0.5f, q);
    CHECK_NEAR(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3], 1.0, 1e-6);
    CHECK_NEAR(q[1], sin(0.00025), 1e-6);
}

static void test_fixup(void)
{
    character_clip_t c = {0};
    c.name = "broken";
    c.duration = 2.0f;
    c.channels = calloc(1, sizeof *c.channels);
    const float times[5] = {0.5f, NAN, 0.0f, 3.0f, 1.0f};
    const float rot[5][4] = {{0, 0, 0, 2}, {0, 0, 0, 1}, {0, 0, 0, 1}, {0, 0, 1, 0}, {0, 0, 0, 0}};
    set_track(&c.channels[0].rot, 5, times, rot);
    int warns = core_log_warn_count();
    int fixes = character_clip_fixup(&c, 1, "test");
    /* NaN time, zero quaternion, unnormalised, unsorted, past duration */
    CHECK_MSG(fixes == 5, "fixes=%d", fixes);
    CHECK(core_log_warn_count() - warns == 5);
    CHECK(c.channels[0].rot.count == 3);
    CHECK_NEAR(c.channels[0].rot.keys[0].time, 0.0, 0);
    CHECK_NEAR(c.channels[0].rot.keys[1].time, 0.5, 0);
    CHECK_NEAR(c.channels[0].rot.keys[2].time, 3.0, 0);
    CHECK_NEAR(c.channels[0].rot.keys[1].v[3], 1.0, 1e-6);
    CHECK_NEAR(c.duration, 3.0, 0);
    /* a consistent clip is left alone */
    CHECK(character_clip_fixup(&c, 1, "test") == 0);
    /* zero duration becomes the last key time; negative times clamp to 0 */
    c.duration = 0.0f;
    c.channels[0].rot.keys[0].time = -1.0f;
    CHECK(character_clip_fixup(&c, 1, "test") == 2);
    CHECK_NEAR(c.duration, 3.0, 0);
    CHECK_NEAR(c.channels[0].rot.keys[0].time, 0.0, 0);
    free(c.channels[0].rot.keys);
    /* no keys at all: warned, bind pose, duration 1 s */
    c.channels[0].rot.count = 0;
    c.channels[0].rot.keys = NULL;
    c.duration = -1.0f;
    warns = core_log_warn_count();
    CHECK(character_clip_fixup(&c, 1, "test") == 2);
    CHECK(core_log_warn_count() - warns == 2);
    CHECK_NEAR(c.duration, 1.0, 0);
    free(c.channels);
}

static void test_clip_find(void)
{
    character_model_t m;
    build_arm(&m);
    m.clips = realloc(m.clips, 2 * sizeof *m.clips);
    memset(&m.clips[1], 0, sizeof m.clips[1]);
    m.clips[1].name = strdup("Armature|run");
    m.clips[1].duration = 1.0f;
    m.clips[1].channels = calloc(3, sizeof *m.clips[1].channels);
    m.clip_count = 2;
    CHECK(character_clip_find(&m, NULL) == 0);
    CHECK(character_clip_find(&m, "bend") == 0);
    CHECK(character_clip_find(&m, "BEND") == 0);
    CHECK(character_clip_find(&m, "run") == 1);
    CHECK(character_clip_find(&m, "1") == 1);
    CHECK(character_clip_find(&m, "7") == -1);
    CHECK(character_clip_find(&m, "nope") == -1);
    CHECK(character_clip_find(&m, "5:5") == -1);
    /* ticks 2..6 at 10 ticks/s: a 0.4 s clip starting at 0.2 s */
    int r = character_clip_find(&m, "2:6");
    CHECK(r == 2);
    CHECK(character_clip_find(&m, "2:6") == 2);
    CHECK(m.clip_count == 3);
    if (r == 2) {
        CHECK_NEAR(m.clips[2].duration, 0.4, 1e-6);
        character_pose_t a, b;
        CHECK(character_pose_init(&a, &m) && character_pose_init(&b, &m));
        for (int i = 0; i <= 4; i++) {
            float t = 0.1f * (float)i;
            character_sample_clip(&m, 2, t, false, &a);
            character_sample_clip(&m, 0, 0.2f + t, false, &b);
            CHECK_NEAR(a.t[0][0], b.t[0][0], 1e-5);
            for (int k = 0; k < 4; k++) CHECK_NEAR(a.r[1][k], b.r[1][k], 1e-5);
        }
        character_pose_free(&a), character_pose_free(&b);
    }
    character_model_free(&m);
}

/* Ranges of clip 0's timeline (10 ticks at 10 per second): the reasons
 * of bad ones, named ranges made once per name and range; a clip without
 * duration gives way to the next one that moves. */
static void test_clip_ranges(void)
{
    character_model_t m;
    build_arm(&m);
    char why[160];
    double a = 0, b = 0;
    CHECK(character_clip_parse_range("1:2.5", &a, &b) && a == 1 && b == 2.5);
    CHECK(!character_clip_parse_range("a:2", &a, &b) && !character_clip_parse_range(":2", &a, &b));
    CHECK(!character_clip_parse_range("1:", &a, &b) && !character_clip_parse_range("1:2x", &a, &b));
    CHECK(!character_clip_parse_range("walk", &a, &b));
    CHECK(!character_clip_range_check(&m, -1, 3, why, sizeof why));
    CHECK_MSG(strstr(why, "start -1 is negative") != NULL, "%s", why);
    CHECK(!character_clip_range_check(&m, 5, 2, why, sizeof why));
    CHECK_MSG(strstr(why, "end 2 is not after start 5") != NULL, "%s", why);
    CHECK(!character_clip_range_check(&m, 0, 11, why, sizeof why));
    CHECK_MSG(strstr(why, "end 11 is past the timeline's 10 ticks (clip 0 'bend')") != NULL, "%s", why);
    CHECK(character_clip_range_check(&m, 0, 10, why, sizeof why));
    CHECK(character_clip_find(&m, "5:2") == -1 && character_clip_find(&m, "-1:3") == -1);
    CHECK(character_clip_find(&m, "0:11") == -1 && m.clip_count == 1);
    CHECK(character_clip_range(&m, "walk", 0, 11) == -1 && m.clip_count == 1);
    int walk = character_clip_range(&m, "walk", 2, 6);
    CHECK(walk == 1 && character_clip_range(&m, "walk", 2, 6) == 1 && m.clip_count == 2);
    int other = character_clip_range(&m, "walk", 0, 10); /* another character's "walk" */
    CHECK(other == 2 && m.clip_count == 3);
    CHECK(character_clip_find(&m, "walk") == -1); /* a named range is no file clip */
    if (walk == 1 && other == 2) {
        CHECK(!strcmp(m.clips[1].name, "walk") && m.clips[1].cut[0] == 2 && m.clips[1].cut[1] == 6);
        CHECK_NEAR(m.clips[1].duration, 0.4, 1e-6);
        CHECK_NEAR(m.clips[2].duration, 1.0, 1e-6);
    }
    /* playback falls back from a still clip to the next that moves, wrapping */
    CHECK(character_clip_playable(&m, 0) == 0);
    m.clips[1].still = true;
    CHECK(character_clip_playable(&m, 1) == 2);
    m.clips[2].still = true;
    CHECK(character_clip_playable(&m, 1) == 0);
    m.clips[0].still = true;
    CHECK(character_clip_playable(&m, 1) == 1); /* none moves: itself */
    character_model_free(&m);
}

/* Morph targets before skinning: vertex A (1,1,0) on "upper" with a delta
 * of (0, 0.5, 0) and a normal delta of (-1, 1, 0). Weight keys 0 -> 1 over
 * the clip, default 0.25. At t = 0.5 (w 0.5, upper turned 90 degrees,
 * global T(1,1,0) Rz(90)): A = (1, 1.25, 0) -> bone space (1, 0.25, 0) ->
 * (0.75, 2, 0); the normal (0.5, 0.5, 0) -> (-0.5, 0.5, 0), normalised. */
static void test_morph(void)
{
    character_model_t m;
    build_arm(&m);
    m.morphs = calloc(1, sizeof *m.morphs);
    m.morph_count = 1;
    m.morphs[0] = (character_morph_t){.node = 1, .first = 0, .count = 1, .weight = 0.25f, .max_weight = 1.0f};
    m.morphs[0].delta = calloc(1, sizeof *m.morphs[0].delta);
    const float d[6] = {0, 0.5f, 0, -1, 1, 0};
    memcpy(m.morphs[0].delta[0], d, sizeof d);
    character_clip_t *c = &m.clips[0];
    c->morph_count = 1;
    c->morph = calloc(1, sizeof *c->morph);
    const float times[2] = {0.0f, 1.0f}, w[2][4] = {{0, 0, 0, 0}, {1, 0, 0, 0}};
    set_track(&c->morph[0], 2, times, w);
    character_pose_t pose;
    CHECK(character_pose_init(&pose, &m));
    CHECK(pose.morph_count == 1 && pose.morph[0] == 0.25f);
    float p[6], n[6];
    character_skin_cpu(&m, &pose, p, n); /* bind: the default weight */
    CHECK_NEAR(p[0], 1.0, 1e-6); CHECK_NEAR(p[1], 1.125, 1e-6); CHECK_NEAR(p[3], 0.5, 1e-6);
    character_sample_clip(&m, 0, 0.5f, false, &pose);
    CHECK_NEAR(pose.morph[0], 0.5, 1e-6);
    character_pose_globals(&m, &pose);
    character_skin_cpu(&m, &pose, p, n);
    CHECK_NEAR(p[0], 0.75, 1e-5); CHECK_NEAR(p[1], 2.0, 1e-5); CHECK_NEAR(p[2], 0.0, 1e-6);
    CHECK_NEAR(n[0], -sqrt(0.5), 1e-5); CHECK_NEAR(n[1], sqrt(0.5), 1e-5);
    /* B, outside the morph's range, is skinned as before */
    CHECK_NEAR(p[3], 1.25, 1e-5); CHECK_NEAR(p[4], 1.25, 1e-5);
    character_vertex_t out[2];
    character_morph_apply(&m, &pose, out);
    CHECK(out[0].pos[0] == 1.0f && out[0].pos[1] == 1.25f && out[0].normal[0] == 0.5f && out[0].normal[1] == 0.5f);
    CHECK(memcmp(&out[1], &m.vertices[1], sizeof out[1]) == 0);
    CHECK_NEAR(character_morph_reach(&m, 0), 0.5, 1e-6);
    CHECK(character_morph_reach(&m, 1) == 0.0f);
    /* a range of the clip carries the weights: ticks 0..5 (0..0.5 s) */
    int half = character_clip_range(&m, "half", 0, 5);
    CHECK(half == 1);
    if (half == 1) {
        character_sample_clip(&m, half, 0.25f, false, &pose);
        CHECK_NEAR(pose.morph[0], 0.25, 1e-6);
    }
    /* a clip whose only keys are morph weights moves (not still) */
    character_clip_t only = {.name = "weights", .duration = 0.0f, .morph_count = 1};
    only.channels = calloc(3, sizeof *only.channels);
    only.morph = calloc(1, sizeof *only.morph);
    set_track(&only.morph[0], 2, times, w);
    CHECK(character_clip_fixup(&only, 3, "test") == 1 && !only.still); /* the duration is repaired */
    CHECK_NEAR(only.duration, 1.0, 0);
    free(only.morph[0].keys), free(only.morph), free(only.channels);
    character_pose_free(&pose);
    character_model_free(&m);
}

/* Capsule on a cylinder of points along X (radius 0.3, x in [0,2]) owned by
 * one bone, and a second cluster on another bone; then merge to one. */
static void test_capsules_and_bounds(void)
{
    character_model_t m;
    memset(&m, 0, sizeof m);
    m.bones = calloc(2, sizeof *m.bones);
    add_bone(&m, "a", -1, 0, 0, 0);
    add_bone(&m, "b", 0, 0, 3, 0);
    set_inverse_binds(&m);
    m.vertices = calloc(200, sizeof *m.vertices);
    for (int i = 0; i <= 10; i++)
        for (int k = 0; k < 12; k++) {
            float th = (float)(2.0 * PI * k / 12);
            add_vertex(&m, 0.2f * (float)i, 0.3f * cosf(th), 0.3f * sinf(th), 0, 1.0f, 1, 0.0f);
        }
    int na = m.vertex_count;
    for (int k = 0; k < 6; k++) add_vertex(&m, 0.1f * (float)k, 3.0f, 0.0f, 1, 0.7f, 0, 0.3f);
    character_pose_t pose;
    CHECK(character_pose_init(&pose, &m));
    float *p = malloc(sizeof(float) * 3 * (size_t)m.vertex_count);
    character_skin_cpu(&m, &pose, p, NULL);
    character_capsule_t caps[4];
    int n = character_fit_capsules(&m, &pose, p, caps, 4);
    CHECK(n == 2);
    CHECK(caps[0].bone == 0 && caps[0].vertex_count == na);
    CHECK_NEAR(caps[0].radius, 0.3, 1e-3);
    float lo = fminf(caps[0].a[0], caps[0].b[0]), hi = fmaxf(caps[0].a[0], caps[0].b[0]);
    CHECK_NEAR(lo, 0.0, 3e-3); CHECK_NEAR(hi, 2.0, 3e-3); /* radius margin pulls the ends in */
    CHECK_NEAR(caps[0].a[1], 0.0, 1e-4); CHECK_NEAR(caps[0].a[2], 0.0, 1e-4);
    /* bone b's points lie on a line: zero-ish radius, ends at x=0 and 0.5;
     * local ends are relative to b's bind position (0,3,0) */
    CHECK(caps[1].bone == 1 && caps[1].vertex_count == 6);
    CHECK(caps[1].radius < 1e-4f);
    CHECK_NEAR(fmaxf(caps[1].a[0], caps[1].b[0]), 0.5, 1e-4);
    CHECK_NEAR(caps[1].local_a[1], 0.0, 1e-5);
    for (int v = 0; v < m.vertex_count; v++) {
        const character_capsule_t *c = v < na ? &caps[0] : &caps[1];
        CHECK(character_capsule_distance(c, p + 3 * v) <= 1e-5f);
    }
    /* merged into one capsule that holds everything */
    n = character_fit_capsules(&m, &pose, p, caps, 1);
    CHECK(n == 1 && caps[0].vertex_count == m.vertex_count);
    for (int v = 0; v < m.vertex_count; v++) CHECK(character_capsule_distance(&caps[0], p + 3 * v) <= 1e-5f);
    CHECK(character_fit_capsules(&m, &pose, p, caps, 0) == 0);

    character_bounds_t bd;
    character_bounds(&m, p, &bd);
    CHECK_NEAR(bd.min[0], 0.0, 1e-6); CHECK_NEAR(bd.max[0], 2.0, 1e-6);
    CHECK_NEAR(bd.min[1], -0.3, 1e-6); CHECK_NEAR(bd.max[1], 3.0, 1e-6);
    CHECK_NEAR(bd.center[1], 1.35, 1e-6);
    /* farthest point from (1, 1.35, ~0): (0,3,0) or (2,-0.3,..) */
    float far = sqrtf(1.0f + 1.65f * 1.65f);
    CHECK(bd.radius >= far - 1e-5f && bd.radius <= far + 0.05f);
    free(p);
    character_pose_free(&pose);
    character_model_free(&m);
}

int main(void)
{
    core_log_set_quiet(true);
    test_hand_pose();
    test_slerp();
    test_fixup();
    test_clip_find();
    test_clip_ranges();
    test_morph();
    test_capsules_and_bounds();
    TEST_END();
}

/* test_character_walk: characters walking over the terrain.
 * - root on the terrain (|y - terrain_height_at| < 1 cm) and the model's +Z
 *   along the path direction, computed independently by finite differences
 *   of scene_walk_eval; lowest skinned vertex on a flat ground within 1 cm;
 * - the walk clips' natural stride speed is positive and plausible (they
 *   walk forwards and play forwards); stance-foot slip: with the playback
 *   rate from character_clip_stride the contact foot's world speed stays
 *   small, and is far smaller than with the clip played the other way;
 * - proxy spheres contain >= 95% of the skinned vertices of their bones, and
 *   the swept spheres contain the vertices at the middle of a long step;
 * - the stride estimate of a synthetic foot moving at a known speed;
 * - facing from the walk: the generated models face +Z; turned by 90, -90
 *   and 180 degrees they face +X, -X, -Z; a humanoid.gltf whose root node
 *   turns it to face +X is turned back by character_set_make (summary:
 *   forward from "walk") and walks with its +Z along the path;
 * - the animation level of detail's rule: the step between poses by
 *   distance (1 within, +1 per lod_distance beyond, at most 8, off at 0),
 *   and each character due exactly once in any `step` consecutive updates,
 *   the characters of one step spread over them. */
#include "test.h"
#include "test_gl.h"

#include "character/character.h"
#include "character/character_walk.h"

#include <string.h>

static scene_character_t walker(const char *model, int n, const float (*wp)[2], bool loop)
{
    scene_character_t c = {.speed = 1.2f, .scale = 1.0f, .waypoint_count = n, .loop = loop};
    snprintf(c.model, sizeof c.model, "%s", model);
    for (int i = 0; i < n; i++) c.waypoints[i][0] = wp[i][0], c.waypoints[i][1] = wp[i][1];
    return c;
}

static void check_on_terrain(void)
{
    terrain_mesh_t hill;
    CHECK(terrain_make_heightfield(&hill, &(terrain_desc_t){.size = 40, .resolution = 64, .height = 1.5f}, 7));
    const float wp[4][2] = {{-8, -6}, {7, -5}, {6, 8}, {-5, 6}};
    scene_character_t c[2] = {walker("models/humanoid.gltf", 4, wp, true),
                              walker("models/quadruped.gltf", 4, wp, true)};
    c[1].scale = 1.5f, c[1].speed = 0.8f;
    character_set_t set;
    CHECK(character_set_make(&set, &(character_set_desc_t){.characters = c, .count = 2, .terrain = &hill}));
    double worst_y = 0, worst_dir = 0;
    for (int i = 0; i < 40; i++) {
        float t = 0.37f + 1.9f * (float)i;
        character_set_update(&set, t, 1.0f / 60.0f);
        for (int k = 0; k < 2; k++) {
            const character_instance_t *in = &set.items[k];
            float o[3], zero[3] = {0, 0, 0};
            character_mat4_point(in->model, zero, o);
            worst_y = fmax(worst_y, fabs(o[1] - terrain_height_at(&hill, o[0], o[2], NULL)));
            vec2 p0, p1, d;
            scene_walk_eval(c[k].waypoints, 4, c[k].speed, t - 1e-3f, true, p0, d);
            scene_walk_eval(c[k].waypoints, 4, c[k].speed, t + 1e-3f, true, p1, d);
            float fx = p1[0] - p0[0], fz = p1[1] - p0[1], fl = sqrtf(fx * fx + fz * fz);
            if (fl < 1.5e-3f) continue; /* a corner inside the window */
            /* model +Z in world = third column, divided by the scale */
            float mx = in->model[8] / c[k].scale, mz = in->model[10] / c[k].scale;
            worst_dir = fmax(worst_dir, fabs(mx - fx / fl) + fabs(mz - fz / fl));
            CHECK_NEAR(in->model[9], 0.0, 1e-6);
        }
    }
    printf("hilly terrain: max |root y - ground| %.3g m, max facing error %.3g\n", worst_y, worst_dir);
    CHECK(worst_y < 0.01);
    CHECK(worst_dir < 1e-3);
    character_set_destroy(&set);
    terrain_free(&hill);
}

typedef struct slip_t {
    double mean, max, net; /* m/s during contact; net = |displacement| / time over stances */
} slip_t;

/* World-space speed of each foot while in contact (clip phase inside the
 * foot's contact window), sampled at 240 Hz over two cycles. */
static slip_t measure_slip(character_set_t *set, float t0)
{
    character_instance_t *in = &set->items[0];
    const character_stride_t *st = &in->stride;
    const float h = 1.0f / 240.0f;
    double sum = 0, mx = 0, time = 0, net = 0, net_time = 0;
    float prev[CHARACTER_MAX_FEET][3], start[CHARACTER_MAX_FEET][3];
    bool was[CHARACTER_MAX_FEET] = {0};
    float run_time[CHARACTER_MAX_FEET] = {0};
    float cycle = set->assets[in->asset].model.clips[in->clip].duration / fabsf(in->rate);
    int steps = (int)(2.0f * cycle / h);
    for (int s = 0; s <= steps; s++) {
        character_set_update(set, t0 + (float)s * h, h);
        for (int f = 0; f < st->foot_count; f++) {
            const float *g = in->pose.global[st->feet[f]];
            float w[3];
            character_mat4_point(in->model, &g[12], w);
            float dur = set->assets[in->asset].model.clips[in->clip].duration;
            float ph = fmodf(in->clip_time / dur, 1.0f);
            ph += ph < 0.0f ? 1.0f : 0.0f;
            bool contact = (ph >= st->contact_begin[f] && ph <= st->contact_end[f]) || ph + 1.0f <= st->contact_end[f];
            if (contact && was[f]) {
                double v = sqrt((w[0] - prev[f][0]) * (w[0] - prev[f][0]) + (w[2] - prev[f][2]) * (w[2] - prev[f][2])) / h;
                sum += v * h, time += h, mx = fmax(mx, v);
                run_time[f] += h;
            }
            if (contact && !was[f]) memcpy(start[f], w, sizeof w), run_time[f] = 0;
            if (!contact && was[f] && run_time[f] > 0) {
                net += sqrt((prev[f][0] - start[f][0]) * (prev[f][0] - start[f][0]) +
                            (prev[f][2] - start[f][2]) * (prev[f][2] - start[f][2]));
                net_time += run_time[f];
            }
            memcpy(prev[f], w, sizeof w);
            was[f] = contact;
        }
    }
    return (slip_t){time > 0 ? sum / time : 1e9, mx, net_time > 0 ? net / net_time : 1e9};
}

/* lo..hi: plausible natural stride speed of the model's walk clip, m/s. */
static void check_slip(const char *model, double lo, double hi)
{
    terrain_mesh_t flat;
    CHECK(terrain_make_heightfield(&flat, &(terrain_desc_t){.size = 80, .resolution = 4, .height = 1e-6f}, 1));
    const float wp[2][2] = {{-30, 2}, {30, -1}};
    scene_character_t c = walker(model, 2, wp, false);
    character_set_t set;
    CHECK(character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1, .terrain = &flat}));
    character_instance_t *in = &set.items[0];
    CHECK(in->stride.foot_count >= 2);
    slip_t good = measure_slip(&set, 3.0f);
    /* Lowest skinned vertex: the feet touch the ground. */
    const character_model_t *m = &set.assets[0].model;
    float *pos = malloc((size_t)m->vertex_count * 3 * sizeof(float));
    double lowest_max = -1e9, lowest_min = 1e9;
    for (int i = 0; i < 16; i++) {
        character_set_update(&set, 3.0f + 0.071f * (float)i, 0.0f);
        character_skin_cpu(m, &in->pose, pos, NULL);
        float lowest = 1e9f;
        for (int v = 0; v < m->vertex_count; v++) {
            float w[3];
            character_mat4_point(in->model, &pos[3 * v], w);
            lowest = fminf(lowest, w[1]);
        }
        lowest_max = fmax(lowest_max, lowest), lowest_min = fmin(lowest_min, lowest);
    }
    free(pos);
    float matched = in->rate;
    in->rate = -matched; /* the clip played the other way round */
    slip_t wrong = measure_slip(&set, 3.0f);
    in->rate = matched;
    printf("%s: %d feet, natural stride speed %.3f m/s, rate %.3f; contact-foot world speed mean %.3f m/s, "
           "max %.3f m/s, net drift %.4f m/s (reversed rate: mean %.3f m/s); lowest vertex y in [%.4f, %.4f] m\n",
           model, in->stride.foot_count, in->stride.natural_speed, matched, good.mean, good.max, good.net,
           wrong.mean, lowest_min, lowest_max);
    /* The clip walks forwards: stance feet move back relative to the body,
     * so the clip plays forwards at a walk-speed rate. */
    CHECK_MSG(in->stride.natural_speed >= lo && in->stride.natural_speed <= hi, "natural speed %.3f not in [%g, %g]",
              (double)in->stride.natural_speed, lo, hi);
    CHECK(matched > 0.0f);
    CHECK(good.net < 0.03);   /* over a whole stance the foot stays put */
    CHECK(good.mean < 0.10);  /* measured: see docs/CHARACTERS.md */
    CHECK(wrong.mean > 5.0 * good.mean);
    /* The clips hold the stance foot at its bind height (IK), so the lowest
     * vertex stays on flat ground; placement adds nothing (root y is exact). */
    CHECK(lowest_min > -0.01 && lowest_max < 0.01);
    character_set_destroy(&set);
    terrain_free(&flat);
}

/* Inside the union of spheres [first, first + n) with 1 mm tolerance. */
static bool inside(const float (*s)[4], int first, int n, const float p[3])
{
    for (int i = first; i < first + n; i++) {
        float dx = p[0] - s[i][0], dy = p[1] - s[i][1], dz = p[2] - s[i][2];
        if (dx * dx + dy * dy + dz * dz <= (s[i][3] + 1e-3f) * (s[i][3] + 1e-3f)) return true;
    }
    return false;
}

static int dominant(const character_vertex_t *v)
{
    int best = 0;
    for (int k = 1; k < CHARACTER_MAX_INFLUENCES; k++)
        if (v->weights[k] > v->weights[best]) best = k;
    return v->joints[best];
}

static void check_proxies(const char *model)
{
    const float wp[2][2] = {{-3, 0}, {3, 1}};
    scene_character_t c = walker(model, 2, wp, true);
    character_set_t set;
    CHECK(character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1}));
    character_instance_t *in = &set.items[0];
    const character_model_t *m = &set.assets[0].model;
    float *pos = malloc((size_t)m->vertex_count * 3 * sizeof(float));
    float(*sp)[4] = malloc((size_t)in->sphere_count * sizeof *sp);
    int tested = 0, hit = 0, worst_bone = -1;
    double worst_frac = 1.0;
    for (int i = 0; i < 6; i++) {
        character_set_update(&set, 0.2f + 0.37f * (float)i, 0.0f);
        CHECK(character_proxy_spheres(in, sp, in->sphere_count) == in->sphere_count);
        character_skin_cpu(m, &in->pose, pos, NULL);
        for (int cI = 0; cI < in->capsule_count; cI++) {
            int first = in->capsule_first_sphere[cI], n = in->capsule_first_sphere[cI + 1] - first;
            int bt = 0, bh = 0;
            for (int v = 0; v < m->vertex_count; v++) {
                if (dominant(&m->vertices[v]) != in->capsules[cI].bone) continue;
                float w[3];
                character_mat4_point(in->model, &pos[3 * v], w);
                bt++, bh += inside((const float(*)[4])sp, first, n, w);
            }
            tested += bt, hit += bh;
            if (bt && (double)bh / bt < worst_frac) worst_frac = (double)bh / bt, worst_bone = in->capsules[cI].bone;
        }
    }
    double frac = (double)hit / tested;
    printf("%s: %d capsules, %d spheres; %.2f%% of %d bone vertices inside their capsule's spheres "
           "(worst bone %s %.1f%%)\n",
           model, in->capsule_count, in->sphere_count, 100 * frac, tested,
           worst_bone >= 0 ? m->bones[worst_bone].name : "-", 100 * worst_frac);
    CHECK(frac >= 0.95);

    /* Sweep: a long step (1/15 s); the pose half-way through must be inside
     * the swept spheres. */
    const float step = 1.0f / 15.0f, t1 = 1.23f;
    character_set_update(&set, t1 - step * 0.5f, 0.0f);
    character_skin_cpu(m, &in->pose, pos, NULL);
    float *mid = malloc((size_t)m->vertex_count * 3 * sizeof(float));
    for (int v = 0; v < m->vertex_count; v++) character_mat4_point(in->model, &pos[3 * v], &mid[3 * v]);
    character_set_update(&set, t1 - step, 0.0f);
    character_set_update(&set, t1, step);
    int in_swept = 0, in_now = 0;
    for (int v = 0; v < m->vertex_count; v++) {
        in_swept += inside((const float(*)[4])in->spheres, 0, in->sphere_count, &mid[3 * v]);
        in_now += inside((const float(*)[4])in->sphere_now, 0, in->sphere_count, &mid[3 * v]);
    }
    printf("%s: mid-step vertices inside swept spheres %.2f%%, inside end-of-step spheres %.2f%%\n", model,
           100.0 * in_swept / m->vertex_count, 100.0 * in_now / m->vertex_count);
    CHECK(in_swept >= 0.95 * m->vertex_count);
    CHECK(in_swept > in_now);
    free(mid), free(pos), free(sp);
    character_set_destroy(&set);
}

/* A two-bone rig whose foot slides back at 0.5 m/s on the ground for half
 * a 1 s cycle and returns 5 cm higher: the stride estimate must be 0.5. */
static void check_stride_synthetic(void)
{
    character_bone_t bones[2] = {{.name = "root", .parent = -1}, {.name = "foot", .parent = 0}};
    for (int b = 0; b < 2; b++) {
        bones[b].bind_r[3] = 1, bones[b].bind_s[0] = bones[b].bind_s[1] = bones[b].bind_s[2] = 1;
        for (int k = 0; k < 4; k++) bones[b].inverse_bind[5 * k] = bones[b].bind_local[5 * k] = 1;
    }
    /* root at y = 1, foot bone at y = 0 (local -1) */
    bones[0].bind_t[1] = 1.0f, bones[0].bind_local[13] = 1.0f, bones[0].inverse_bind[13] = -1.0f;
    bones[1].bind_t[1] = -1.0f, bones[1].bind_local[13] = -1.0f;
    character_vertex_t verts[2] = {{.pos = {0, 1.5f, 0}, .weights = {1}}, {.pos = {0, 0, 0}, .joints = {1}, .weights = {1}}};
    character_key_t keys[5] = {{0.0f, {0, -1, 0.125f}}, {0.5f, {0, -1, -0.125f}}, {0.501f, {0, -0.95f, -0.125f}},
                               {0.999f, {0, -0.95f, 0.125f}}, {1.0f, {0, -1, 0.125f}}};
    character_channel_t ch[2];
    memset(ch, 0, sizeof ch);
    ch[1].pos = (character_track_t){5, keys};
    character_clip_t clip = {.name = "slide", .duration = 1.0f, .ticks_per_second = 1, .channels = ch};
    character_model_t m = {.vertices = verts, .vertex_count = 2, .bones = bones, .bone_count = 2, .clips = &clip,
                           .clip_count = 1};
    character_stride_t st;
    character_clip_stride(&m, 0, &st);
    printf("synthetic stride: %d foot, natural speed %.4f m/s (expected 0.5)\n", st.foot_count, st.natural_speed);
    CHECK(st.foot_count == 1 && st.feet[0] == 1);
    CHECK_NEAR(st.natural_speed, 0.5, 1e-3);
    CHECK_NEAR(character_walk_rate(&st, 1.0f, 2.0f), 1.0, 1e-3); /* 1 m/s at scale 2: one clip second per second */
}

static void check_facing(void)
{
    static const struct { float yaw; int facing; } turns[] = {{0, 3}, {90, 1}, {-90, -1}, {180, -3}};
    const char *names[2] = {"models/humanoid.gltf", "models/quadruped.gltf"};
    for (int k = 0; k < 2; k++)
        for (int t = 0; t < 4; t++) {
            char path[1024], err[256];
            character_model_t m;
            character_import_t o;
            CHECK(core_fs_resolve(names[k], path, sizeof path) && character_load(&m, path, err, sizeof err));
            CHECK(character_import(&m, path, &(character_import_desc_t){.yaw = turns[t].yaw}, &o, err, sizeof err));
            int f = character_walk_facing(&m, o.height);
            CHECK_MSG(f == turns[t].facing, "%s turned %g: facing %d, want %d", names[k], (double)turns[t].yaw, f,
                      turns[t].facing);
            character_model_free(&m);
        }
    /* a file whose root node turns the humanoid to face +X */
    char src[1024], dst[1100], err[256];
    CHECK(core_fs_resolve("models/humanoid.gltf", src, sizeof src));
    size_t size = 0;
    char *text = core_fs_read(src, &size, err, sizeof err), *at = text ? strstr(text, "\"name\":\"humanoid\"") : NULL;
    CHECK(at != NULL);
    if (!at) {
        free(text);
        return;
    }
    const char *env = getenv("MEADOW_TEST_OUT"), *dir = env ? env : "/tmp/meadow-test_character_walk";
    CHECK(core_fs_mkdirs(dir));
    snprintf(dst, sizeof dst, "%s/turned.gltf", dir);
    core_buf_t b = {0};
    core_buf_put(&b, text, (size_t)(at - text));
    core_buf_printf(&b, "\"rotation\":[0,0.70710678,0,0.70710678],%s", at);
    CHECK(core_buf_write(&b, dst));
    core_buf_free(&b);
    free(text);
    const float wp[2][2] = {{0, 0}, {0, 10}};
    scene_character_t c = walker(dst, 2, wp, false);
    character_set_t set;
    CHECK(character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1}));
    if (!set.count) return;
    const character_import_t *im = &set.assets[0].import;
    CHECK_MSG(!strcmp(im->forward_from, "walk") && im->forward == 1, "forward %d from %s", im->forward,
              im->forward_from);
    /* walking +Z: the walk's facing after the turn is +Z again */
    CHECK(character_walk_facing(&set.assets[0].model, im->height) == 3);
    character_set_destroy(&set);
}

static void check_pose_lod(void)
{
    CHECK(character_pose_step(500.0f, 0.0f) == 1);
    CHECK(character_pose_step(80.0f, 80.0f) == 1);
    CHECK(character_pose_step(80.5f, 80.0f) == 2);
    CHECK(character_pose_step(159.0f, 80.0f) == 2);
    CHECK(character_pose_step(160.0f, 80.0f) == 3);
    CHECK(character_pose_step(1e6f, 80.0f) == CHARACTER_POSE_STEP_MAX);
    for (int step = 1; step <= CHARACTER_POSE_STEP_MAX; step++) {
        for (int i = 0; i < 20; i++) {
            int due = 0;
            for (uint64_t u = 1000; u < 1000 + (uint64_t)step; u++) due += character_pose_due(u, i, step);
            CHECK(due == 1);
        }
        for (uint64_t u = 0; u < 40; u++) {
            int due = 0;
            for (int i = 0; i < step; i++) due += character_pose_due(u, i, step);
            CHECK(due == 1);
        }
    }
    printf("pose level of detail: steps and stagger hold\n");
}

int main(void)
{
    core_log_set_quiet(true);
    check_stride_synthetic();
    check_pose_lod();
    test_gl_init();
    check_on_terrain();
    check_slip("models/humanoid.gltf", 0.6, 2.0);   /* 1.74 m figure, 1 s cycle */
    check_slip("models/quadruped.gltf", 0.3, 1.2);  /* 0.6 m animal, 0.8 s cycle */
    check_proxies("models/humanoid.gltf");
    check_proxies("models/quadruped.gltf");
    check_facing();
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

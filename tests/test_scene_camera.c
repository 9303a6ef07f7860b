/* test_scene_camera: view/projection against hand-computed values, a
 * camera looking straight down, frustum planes (signed distances of known
 * points, and agreement with a brute-force clip-space test), AABB culling,
 * camera/collider/walk path evaluation at keys and midpoints, free-fly
 * moves, and fixed-step clock counts. */
#include <stdio.h>

#include "core/core.h"
#include "scene/camera.h"
#include "scene/path.h"
#include "test.h"

static void test_matrices(void)
{
    cam_t cam = {.position = {0, 0, 5}, .target = {0, 0, 0}, .fov = 90, .near = 1, .far = 100,
                 .aspect = 1};
    mat4 view, proj;
    cam_view(&cam, view);
    vec4 o = {0, 0, 0, 1}, e;
    glm_mat4_mulv(view, o, e);
    CHECK_NEAR(e[0], 0, 1e-6);
    CHECK_NEAR(e[2], -5, 1e-6);
    cam_proj(&cam, proj);
    /* GL depth: near plane -> -1, far plane -> +1; fov 90 aspect 1: x = -z on the edge. */
    vec4 pn = {0, 0, -1, 1}, pf = {0, 0, -100, 1}, pe = {10, 0, -10, 1}, c;
    glm_mat4_mulv(proj, pn, c);
    CHECK_NEAR(c[2] / c[3], -1, 1e-5);
    glm_mat4_mulv(proj, pf, c);
    CHECK_NEAR(c[2] / c[3], 1, 1e-5);
    glm_mat4_mulv(proj, pe, c);
    CHECK_NEAR(c[0] / c[3], 1, 1e-5);

    /* Straight down: the screen's up is -z, as for a camera pitched down
     * from looking along -z (up = +y made every entry NaN or 0). */
    cam_t down = {.position = {2, 10, 3}, .target = {2, 0, 3}, .fov = 90, .near = 1, .far = 100, .aspect = 1};
    cam_view(&down, view);
    vec4 below = {2, 0, 3, 1}, ahead = {2, 0, 2, 1};
    glm_mat4_mulv(view, below, e);
    CHECK_NEAR(e[0], 0, 1e-5);
    CHECK_NEAR(e[1], 0, 1e-5);
    CHECK_NEAR(e[2], -10, 1e-5);
    glm_mat4_mulv(view, ahead, e);
    CHECK_NEAR(e[1], 1, 1e-5);

    cam_t d = {0};
    cam_defaults(&d);
    CHECK(d.fov == 60 && d.near == 0.1f && d.far == 200 && d.position[1] == 8 && d.position[2] == 24);
}

static void test_frustum(void)
{
    cam_t cam = {.position = {0, 0, 0}, .target = {0, 0, -1}, .fov = 90, .near = 1, .far = 100,
                 .aspect = 1};
    mat4 vp;
    vec4 planes[6];
    cam_viewproj(&cam, vp);
    cam_frustum_planes(vp, planes);
    const float s = 1.0f / sqrtf(2.0f);
    /* Hand-computed: inside means |x| <= -z, |y| <= -z, 1 <= -z <= 100, so
     * left (x - z)/sqrt2, right (-x - z)/sqrt2, bottom (y - z)/sqrt2,
     * top (-y - z)/sqrt2, near -z - 1, far z + 100. */
    const float want[6][4] = {{s, 0, -s, 0}, {-s, 0, -s, 0}, {0, s, -s, 0},
                              {0, -s, -s, 0}, {0, 0, -1, -1}, {0, 0, 1, 100}};
    for (int i = 0; i < 6; i++)
        for (int k = 0; k < 4; k++) CHECK_NEAR(planes[i][k], want[i][k], 1e-4 * fmax(1, fabs(want[i][k])));
    /* Signed distances of a known point. */
    vec3 p = {0, 0, -10};
    CHECK_NEAR(glm_vec3_dot(planes[0], p) + planes[0][3], 10 * s, 1e-4);
    CHECK_NEAR(glm_vec3_dot(planes[4], p) + planes[4][3], 9, 1e-3);
    CHECK_NEAR(glm_vec3_dot(planes[5], p) + planes[5][3], 90, 1e-2);

    /* Brute force: a random point is inside all planes iff its clip
     * coordinates satisfy -w <= x, y, z <= w. Use a tilted camera. */
    cam_t tilt = {.position = {3, 4, 5}, .target = {-1, 0, -2}, .fov = 50, .near = 0.5f, .far = 40,
                  .aspect = 1.6f};
    cam_viewproj(&tilt, vp);
    cam_frustum_planes(vp, planes);
    core_rng_t rng;
    core_rng_seed(&rng, 3, 0);
    int mismatches = 0, inside = 0;
    for (int i = 0; i < 20000; i++) {
        vec4 q = {core_rng_range(&rng, -40, 40), core_rng_range(&rng, -40, 40),
                  core_rng_range(&rng, -40, 40), 1};
        vec4 cc;
        glm_mat4_mulv(vp, q, cc);
        float margin = 1e-3f * fabsf(cc[3]);
        bool clip_in = fabsf(cc[0]) <= cc[3] && fabsf(cc[1]) <= cc[3] && fabsf(cc[2]) <= cc[3];
        bool clip_sure = fabsf(cc[0]) <= cc[3] - margin && fabsf(cc[1]) <= cc[3] - margin &&
                         fabsf(cc[2]) <= cc[3] - margin;
        bool clip_out = fabsf(cc[0]) > cc[3] + margin || fabsf(cc[1]) > cc[3] + margin ||
                        fabsf(cc[2]) > cc[3] + margin;
        bool plane_in = true;
        for (int k = 0; k < 6; k++) plane_in &= glm_vec3_dot(planes[k], q) + planes[k][3] >= 0;
        if ((clip_sure && !plane_in) || (clip_out && plane_in)) mismatches++;
        inside += clip_in;
    }
    printf("frustum: %d of 20000 random points inside, %d mismatches\n", inside, mismatches);
    CHECK(inside > 100);
    CHECK(mismatches == 0);

    /* AABB culling with the simple camera. */
    cam_viewproj(&cam, vp);
    cam_frustum_planes(vp, planes);
    CHECK(cam_aabb_in_frustum(planes, (vec3){-1, -1, -11}, (vec3){1, 1, -9}));
    CHECK(!cam_aabb_in_frustum(planes, (vec3){49, -1, -11}, (vec3){51, 1, -9}));
    CHECK(!cam_aabb_in_frustum(planes, (vec3){-1, -1, 2}, (vec3){1, 1, 4}));
    CHECK(!cam_aabb_in_frustum(planes, (vec3){-1, -1, -300}, (vec3){1, 1, -200}));
    /* Straddling the right plane (x = 10 at z = -10): partly visible. */
    CHECK(cam_aabb_in_frustum(planes, (vec3){9, -1, -11}, (vec3){30, 1, -9}));
    /* Encloses the whole frustum. */
    CHECK(cam_aabb_in_frustum(planes, (vec3){-500, -500, -500}, (vec3){500, 500, 500}));
}

static void test_cam_path(void)
{
    /* x = t^2 at integer keys: Catmull-Rom tangents at inner keys are exact
     * (central differences of a parabola), so the mid-segment value between
     * keys 1 and 2 is 0.5 p1 + 0.125 m1 + 0.5 p2 - 0.125 m2 = 2.25. */
    cam_path_t path = {.count = 4};
    for (int i = 0; i < 4; i++) {
        path.keys[i].t = (float)i;
        glm_vec3_copy((vec3){(float)(i * i), 1, 0}, path.keys[i].position);
        glm_vec3_copy((vec3){0, 0, (float)(-2 * i)}, path.keys[i].target);
    }
    cam_t cam = {0};
    for (int i = 0; i < 4; i++) {
        cam_path_eval(&path, (float)i, &cam);
        CHECK_NEAR(cam.position[0], i * i, 1e-5);
        CHECK_NEAR(cam.target[2], -2 * i, 1e-5);
    }
    cam_path_eval(&path, 1.5f, &cam);
    CHECK_NEAR(cam.position[0], 2.25, 1e-5);
    CHECK_NEAR(cam.position[1], 1, 1e-6);
    CHECK_NEAR(cam.target[2], -3, 1e-5); /* linear in t */
    cam_path_eval(&path, 0.5f, &cam);
    /* First segment: m0 = (1-0)/1 = 1 (one-sided), m1 = 2: 0 + 0.125 + 0.5 - 0.25. */
    CHECK_NEAR(cam.position[0], 0.375, 1e-5);
    cam_path_eval(&path, -3, &cam);
    CHECK_NEAR(cam.position[0], 0, 1e-6);
    cam_path_eval(&path, 99, &cam);
    CHECK_NEAR(cam.position[0], 9, 1e-6);
    CHECK_NEAR(cam.target[2], -6, 1e-6);

    /* Uneven key times, motion linear in time: reproduced exactly. */
    cam_path_t lin = {.count = 3};
    const float ts[3] = {0, 1, 3};
    for (int i = 0; i < 3; i++) {
        lin.keys[i].t = ts[i];
        glm_vec3_copy((vec3){2 * ts[i], 0, -ts[i]}, lin.keys[i].position);
    }
    for (float t = 0; t <= 3; t += 0.25f) {
        cam_path_eval(&lin, t, &cam);
        CHECK_NEAR(cam.position[0], 2 * t, 1e-5);
        CHECK_NEAR(cam.position[2], -t, 1e-5);
    }
    /* Empty path leaves the camera alone. */
    cam_t keep = {.position = {7, 7, 7}};
    cam_path_t none = {0};
    cam_path_eval(&none, 1, &keep);
    CHECK(keep.position[0] == 7);
}

static void test_scene_path(void)
{
    scene_path_t p = {.count = 3};
    p.keys[0] = (scene_path_key_t){0, {0, 0, 0}};
    p.keys[1] = (scene_path_key_t){2, {4, 0, 0}};
    p.keys[2] = (scene_path_key_t){3, {4, 0, 2}};
    vec3 pos, vel;
    scene_path_eval(&p, 1, false, pos, vel);
    CHECK_NEAR(pos[0], 2, 1e-6);
    CHECK_NEAR(vel[0], 2, 1e-6);
    scene_path_eval(&p, 2, false, pos, vel);
    CHECK_NEAR(pos[0], 4, 1e-6);
    CHECK_NEAR(pos[2], 0, 1e-6);
    scene_path_eval(&p, 2.5f, false, pos, vel);
    CHECK_NEAR(pos[0], 4, 1e-6);
    CHECK_NEAR(pos[2], 1, 1e-6);
    CHECK_NEAR(vel[0], 0, 1e-6);
    CHECK_NEAR(vel[2], 2, 1e-6);
    scene_path_eval(&p, -1, false, pos, vel);
    CHECK(pos[0] == 0 && vel[0] == 0);
    scene_path_eval(&p, 5, false, pos, vel);
    CHECK(pos[0] == 4 && pos[2] == 2 && vel[2] == 0);
    /* Loop: period 3. */
    scene_path_eval(&p, 4, true, pos, vel);
    CHECK_NEAR(pos[0], 2, 1e-5);
    CHECK_NEAR(vel[0], 2, 1e-5);
    scene_path_eval(&p, -0.5f, true, pos, NULL);
    CHECK_NEAR(pos[0], 4, 1e-5);
    CHECK_NEAR(pos[2], 1, 1e-5);
    scene_path_eval(&p, 3000 + 1, true, pos, NULL);
    CHECK_NEAR(pos[0], 2, 1e-3);
    /* Velocity equals the finite difference of position. */
    vec3 a, b;
    scene_path_eval(&p, 0.7f, false, a, vel);
    scene_path_eval(&p, 0.71f, false, b, NULL);
    CHECK_NEAR((b[0] - a[0]) / 0.01f, vel[0], 1e-2);
    /* Static and empty paths. */
    scene_path_t one = {.count = 1, .keys = {{5, {1, 2, 3}}}};
    scene_path_eval(&one, 100, true, pos, vel);
    CHECK(pos[1] == 2 && vel[1] == 0);
    scene_path_t none = {0};
    scene_path_eval(&none, 1, false, pos, vel);
    CHECK(pos[0] == 0 && pos[1] == 0 && vel[0] == 0);
}

static void test_walk(void)
{
    const vec2 sq[4] = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
    vec2 pos, dir;
    CHECK_NEAR(scene_walk_length(sq, 4, true), 8, 1e-6);
    CHECK_NEAR(scene_walk_length(sq, 4, false), 6, 1e-6);
    scene_walk_eval(sq, 4, 1, 1, true, pos, dir);
    CHECK_NEAR(pos[0], 1, 1e-6);
    CHECK_NEAR(pos[1], 0, 1e-6);
    CHECK_NEAR(dir[0], 1, 1e-6);
    scene_walk_eval(sq, 4, 1, 3, true, pos, dir);
    CHECK_NEAR(pos[0], 2, 1e-6);
    CHECK_NEAR(pos[1], 1, 1e-6);
    CHECK_NEAR(dir[1], 1, 1e-6);
    scene_walk_eval(sq, 4, 1, 7, true, pos, dir); /* closing segment (0,2)->(0,0) */
    CHECK_NEAR(pos[0], 0, 1e-6);
    CHECK_NEAR(pos[1], 1, 1e-6);
    CHECK_NEAR(dir[1], -1, 1e-6);
    scene_walk_eval(sq, 4, 2, 4.5f, true, pos, dir); /* 9 m = 1 m into lap 2 */
    CHECK_NEAR(pos[0], 1, 1e-5);
    CHECK_NEAR(pos[1], 0, 1e-5);
    scene_walk_eval(sq, 4, 1, 7, false, pos, dir); /* stops at the end */
    CHECK_NEAR(pos[0], 0, 1e-6);
    CHECK_NEAR(pos[1], 2, 1e-6);
    CHECK_NEAR(dir[0], -1, 1e-6);
    const vec2 dup[3] = {{0, 0}, {0, 0}, {3, 0}};
    scene_walk_eval(dup, 3, 1, 1, false, pos, dir);
    CHECK_NEAR(pos[0], 1, 1e-6);
    CHECK_NEAR(dir[0], 1, 1e-6);
    const vec2 single[1] = {{5, 6}};
    scene_walk_eval(single, 1, 1, 10, true, pos, dir);
    CHECK(pos[0] == 5 && pos[1] == 6 && dir[0] == 0 && dir[1] == 1);
}

static void test_free_fly(void)
{
    cam_t cam = {.position = {0, 0, 0}, .target = {0, 0, -1}};
    cam_move(&cam, 2, 1, 0.5f);
    CHECK_NEAR(cam.position[0], 1, 1e-6);
    CHECK_NEAR(cam.position[1], 0.5, 1e-6);
    CHECK_NEAR(cam.position[2], -2, 1e-6);
    CHECK_NEAR(cam.target[2], -3, 1e-6);
    cam = (cam_t){.position = {0, 0, 0}, .target = {0, 0, -2}};
    cam_rotate(&cam, GLM_PI_2f, 0); /* turn left: -z -> -x, distance kept */
    CHECK_NEAR(cam.target[0], -2, 1e-5);
    CHECK_NEAR(cam.target[2], 0, 1e-5);
    cam_rotate(&cam, 0, glm_rad(30));
    CHECK_NEAR(cam.target[1], 1, 1e-5);
    cam_rotate(&cam, 0, 3.0f); /* clamped to 89 degrees */
    CHECK_NEAR(cam.target[1], 2 * sin(glm_rad(89)), 1e-4);
}

static void test_clock(void)
{
    scene_clock_t c;
    scene_clock_init(&c, 0, true);
    CHECK_NEAR(c.dt, 1.0 / 60.0, 1e-12);
    int total = 0;
    for (int i = 0; i < 10; i++) total += scene_clock_advance(&c, i * 0.37);
    CHECK(total == 10 && c.steps == 10);
    CHECK_NEAR(scene_clock_time(&c), 10.0 / 60.0, 1e-12);

    scene_clock_init(&c, 1.0 / 60.0, false);
    CHECK(scene_clock_advance(&c, 1.0 / 120.0) == 0);
    CHECK(scene_clock_advance(&c, 1.0 / 120.0) == 1);
    CHECK(scene_clock_advance(&c, 0.05) == 3);
    total = 0;
    for (int i = 0; i < 600; i++) total += scene_clock_advance(&c, 1.0 / 60.0);
    CHECK_MSG(total == 600, "600 frames of 1/60 s gave %d steps", total);
    /* Jittered frames: steps track floor(total time / dt) within one step. */
    scene_clock_init(&c, 0.01, false);
    core_rng_t rng;
    core_rng_seed(&rng, 1, 0);
    double sum = 0;
    total = 0;
    for (int i = 0; i < 1000; i++) {
        double r = core_rng_range(&rng, 0.001f, 0.03f);
        sum += r;
        total += scene_clock_advance(&c, r);
    }
    CHECK_MSG(abs(total - (int)floor(sum / 0.01)) <= 1, "%d steps for %g s", total, sum);
    /* A long stall is capped and reported, never silently. */
    int warns = core_log_warn_count();
    CHECK(scene_clock_advance(&c, 1.0) == SCENE_CLOCK_MAX_STEPS);
    CHECK(core_log_warn_count() == warns + 1);
    CHECK(c.accum == 0 && c.dropped == 1);
}

int main(void)
{
    core_log_set_quiet(true);
    test_matrices();
    test_frustum();
    test_cam_path();
    test_scene_path();
    test_walk();
    test_free_fly();
    test_clock();
    TEST_END();
}

/* camera and clock: view/projection matrices, Gribb-Hartmann frustum planes,
 * AABB culling, Catmull-Rom camera paths, free-fly moves and the fixed-step
 * clock (see camera.h). */
#include "scene/camera.h"

#include <math.h>

#include "core/core.h"
#include "scene/scene_fields.h"

void cam_defaults(cam_t *cam)
{
    if (cam->fov <= 0) cam->fov = SCENE_DEFAULT_FOV;
    if (cam->near <= 0) cam->near = SCENE_DEFAULT_NEAR;
    if (cam->far <= 0) cam->far = SCENE_DEFAULT_FAR;
    if (cam->aspect <= 0) cam->aspect = 16.0f / 9.0f;
    if (glm_vec3_eq(cam->position, 0.0f) && glm_vec3_eq(cam->target, 0.0f)) {
        cam->position[0] = 0.0f;
        cam->position[1] = SCENE_DEFAULT_CAMERA_Y;
        cam->position[2] = SCENE_DEFAULT_CAMERA_Z;
    }
}

/* Unit view direction and distance to the target (-z, 1 when degenerate). */
static float view_dir(const cam_t *cam, vec3 f)
{
    glm_vec3_sub((float *)cam->target, (float *)cam->position, f);
    float d = glm_vec3_norm(f);
    if (d <= 1e-6f) {
        f[0] = 0;
        f[1] = 0;
        f[2] = -1;
        return 1.0f;
    }
    glm_vec3_scale(f, 1.0f / d, f);
    return d;
}

/* Looking straight up or down, +y is the view direction itself and the
 * basis degenerates (a blank frame): the screen's up is then the direction
 * a camera pitched there from looking along -z has, -z looking down and +z
 * looking up. */
void cam_view(const cam_t *cam, mat4 out)
{
    vec3 f, up = {0, 1, 0};
    view_dir(cam, f);
    if (hypotf(f[0], f[2]) <= 1e-4f) {
        up[1] = 0;
        up[2] = f[1] < 0 ? -1.0f : 1.0f;
    }
    glm_look((float *)cam->position, f, up, out);
}

void cam_proj(const cam_t *cam, mat4 out)
{
    glm_perspective(glm_rad(cam->fov), cam->aspect, cam->near, cam->far, out);
}

void cam_viewproj(const cam_t *cam, mat4 out)
{
    mat4 v, p;
    cam_view(cam, v);
    cam_proj(cam, p);
    glm_mat4_mul(p, v, out);
}

void cam_frustum_planes(const mat4 m, vec4 planes[6])
{
    /* Row r of the column-major matrix is (m[0][r], m[1][r], m[2][r], m[3][r]);
     * clip-space tests -w <= x,y,z <= w become row3 +- row0/1/2 >= 0. */
    for (int i = 0; i < 6; i++) {
        int r = i / 2;
        float s = (i % 2) ? -1.0f : 1.0f;
        for (int c = 0; c < 4; c++) planes[i][c] = m[c][3] + s * m[c][r];
        float len = sqrtf(planes[i][0] * planes[i][0] + planes[i][1] * planes[i][1] +
                          planes[i][2] * planes[i][2]);
        if (len > 0) glm_vec4_scale(planes[i], 1.0f / len, planes[i]);
    }
}

bool cam_aabb_in_frustum(const vec4 planes[6], const vec3 box_min, const vec3 box_max)
{
    for (int i = 0; i < 6; i++) {
        const float *p = planes[i];
        float x = p[0] >= 0 ? box_max[0] : box_min[0];
        float y = p[1] >= 0 ? box_max[1] : box_min[1];
        float z = p[2] >= 0 ? box_max[2] : box_min[2];
        if (p[0] * x + p[1] * y + p[2] * z + p[3] < 0) return false;
    }
    return true;
}

/* Catmull-Rom tangent of component `pos` (0) or `target` (1) at key i. */
static void key_tangent(const cam_path_t *path, int i, int which, vec3 out)
{
    int a = i > 0 ? i - 1 : i, b = i + 1 < path->count ? i + 1 : i;
    const cam_path_key_t *ka = &path->keys[a], *kb = &path->keys[b];
    const float *pa = which ? ka->target : ka->position;
    const float *pb = which ? kb->target : kb->position;
    float dt = kb->t - ka->t;
    for (int c = 0; c < 3; c++) out[c] = dt > 0 ? (pb[c] - pa[c]) / dt : 0.0f;
}

void cam_path_eval(const cam_path_t *path, float t, cam_t *cam)
{
    int n = path->count;
    if (n <= 0) return;
    const cam_path_key_t *k = path->keys;
    if (n == 1 || t <= k[0].t) {
        glm_vec3_copy((float *)k[0].position, cam->position);
        glm_vec3_copy((float *)k[0].target, cam->target);
        return;
    }
    if (t >= k[n - 1].t) {
        glm_vec3_copy((float *)k[n - 1].position, cam->position);
        glm_vec3_copy((float *)k[n - 1].target, cam->target);
        return;
    }
    int i = 0;
    while (i + 2 < n && t >= k[i + 1].t) i++;
    float h = k[i + 1].t - k[i].t;
    float u = (t - k[i].t) / h, u2 = u * u, u3 = u2 * u;
    float h00 = 2 * u3 - 3 * u2 + 1, h10 = u3 - 2 * u2 + u;
    float h01 = -2 * u3 + 3 * u2, h11 = u3 - u2;
    for (int which = 0; which < 2; which++) {
        vec3 m0, m1;
        key_tangent(path, i, which, m0);
        key_tangent(path, i + 1, which, m1);
        const float *p0 = which ? k[i].target : k[i].position;
        const float *p1 = which ? k[i + 1].target : k[i + 1].position;
        float *out = which ? cam->target : cam->position;
        for (int c = 0; c < 3; c++)
            out[c] = h00 * p0[c] + h10 * h * m0[c] + h01 * p1[c] + h11 * h * m1[c];
    }
}

void cam_move(cam_t *cam, float forward, float right, float up)
{
    vec3 f, r, delta;
    view_dir(cam, f);
    r[0] = -f[2];
    r[1] = 0;
    r[2] = f[0];
    float rl = sqrtf(r[0] * r[0] + r[2] * r[2]);
    if (rl < 1e-6f) {
        r[0] = 1;
        r[2] = 0;
    } else {
        r[0] /= rl;
        r[2] /= rl;
    }
    for (int c = 0; c < 3; c++) delta[c] = f[c] * forward + r[c] * right;
    delta[1] += up;
    glm_vec3_add(cam->position, delta, cam->position);
    glm_vec3_add(cam->target, delta, cam->target);
}

void cam_rotate(cam_t *cam, float yaw, float pitch)
{
    vec3 f;
    float dist = view_dir(cam, f);
    /* f = (cos p sin a, sin p, cos p cos a); rotating by +yaw about +y adds to a. */
    float a = atan2f(f[0], f[2]) + yaw;
    float p = asinf(glm_clamp(f[1], -1.0f, 1.0f)) + pitch;
    float lim = glm_rad(89.0f);
    p = glm_clamp(p, -lim, lim);
    cam->target[0] = cam->position[0] + dist * cosf(p) * sinf(a);
    cam->target[1] = cam->position[1] + dist * sinf(p);
    cam->target[2] = cam->position[2] + dist * cosf(p) * cosf(a);
}

void scene_clock_init(scene_clock_t *clock, double dt, bool headless)
{
    *clock = (scene_clock_t){.dt = dt > 0 ? dt : 1.0 / 60.0, .headless = headless};
}

int scene_clock_advance(scene_clock_t *clock, double real_dt)
{
    if (clock->headless) {
        clock->steps++;
        return 1;
    }
    if (real_dt > 0) clock->accum += real_dt;
    /* The small epsilon makes k * dt of real time give exactly k steps despite
     * round-off in the accumulator. */
    double steps = floor(clock->accum / clock->dt + 1e-6);
    int n;
    if (steps > SCENE_CLOCK_MAX_STEPS) {
        n = SCENE_CLOCK_MAX_STEPS;
        if (clock->dropped++ % 256 == 0)
            core_log_warn("scene clock: %.3f s behind, simulating %d steps of %.4f s and dropping "
                          "the rest (SCENE_CLOCK_MAX_STEPS); %d drops so far",
                          clock->accum, n, clock->dt, clock->dropped);
        clock->accum = 0;
    } else {
        n = (int)steps;
        clock->accum -= n * clock->dt;
        if (clock->accum < 0) clock->accum = 0;
    }
    clock->steps += (uint64_t)n;
    return n;
}

double scene_clock_time(const scene_clock_t *clock)
{
    return (double)clock->steps * clock->dt;
}

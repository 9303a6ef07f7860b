/* camera and clock: perspective camera (cglm, GL conventions: right-handed,
 * y up, clip depth -1..1), frustum planes (Gribb & Hartmann), AABB culling,
 * scripted camera paths (Catmull-Rom through keys), free-fly helpers, and the
 * fixed-timestep simulation clock. GL-free. */
#ifndef MEADOW_SCENE_CAMERA_H
#define MEADOW_SCENE_CAMERA_H

#include <stdbool.h>
#include <stdint.h>

#include <cglm/cglm.h>

#include "scene/path.h"

/* Zero means default for fov/near/far/aspect (see cam_defaults). */
typedef struct cam_t {
    vec3 position; /* metres */
    vec3 target;   /* point looked at; up is always +y */
    float fov;     /* vertical field of view, degrees; default 60 */
    float near;    /* default 0.1 m */
    float far;     /* default 200 m */
    float aspect;  /* width / height; default 16/9 */
} cam_t;

/* Fills zero fov/near/far/aspect with the defaults above. If position and
 * target are both zero the camera is placed at (0, 8, 24) looking at the
 * origin. */
void cam_defaults(cam_t *cam);

/* View matrix (world -> eye), glm_lookat with up = +y; looking straight
 * down (up), up = -z (+z); position = target looks along -z. */
void cam_view(const cam_t *cam, mat4 out);
/* Perspective projection, GL clip space (z in -1..1). */
void cam_proj(const cam_t *cam, mat4 out);
/* proj * view. */
void cam_viewproj(const cam_t *cam, mat4 out);

/* Frustum planes from a view-projection matrix (Gribb & Hartmann), in the
 * order left, right, bottom, top, near, far. Each plane (a,b,c,d) is
 * normalised so that a*x + b*y + c*z + d is the signed distance in world
 * units, positive inside. */
void cam_frustum_planes(const mat4 viewproj, vec4 planes[6]);
/* Conservative AABB test (positive-vertex test): false only when the box lies
 * entirely outside one plane. */
bool cam_aabb_in_frustum(const vec4 planes[6], const vec3 box_min, const vec3 box_max);

/* ---- scripted camera path ---- */
typedef struct cam_path_key_t {
    float t; /* seconds; keys strictly increasing in t */
    vec3 position;
    vec3 target;
} cam_path_key_t;

typedef struct cam_path_t {
    int count; /* 0 = no path: cam_path_eval leaves the camera unchanged */
    cam_path_key_t keys[SCENE_MAX_PATH_KEYS];
} cam_path_t;

/* Sets cam->position and cam->target at time t: a cubic Hermite spline with
 * Catmull-Rom tangents m_i = (p_{i+1} - p_{i-1}) / (t_{i+1} - t_{i-1})
 * (one-sided differences at the end keys), so it passes exactly through
 * every key and reproduces motion that is linear in time exactly. Clamped before the
 * first and after the last key. Other fields of cam are left alone. */
void cam_path_eval(const cam_path_t *path, float t, cam_t *cam);

/* ---- free-fly helpers (interactive keys / mouse) ---- */
/* Moves position and target together, in metres, along the view direction
 * (forward), the horizontal right axis and world up (+y). */
void cam_move(cam_t *cam, float forward, float right, float up);
/* Turns the view around the camera position by yaw (about +y, positive turns
 * left) and pitch (positive looks up), in radians. Pitch is clamped to
 * +-89 degrees; the distance to the target is kept. */
void cam_rotate(cam_t *cam, float yaw, float pitch);

/* ---- fixed-timestep clock ---- */
#define SCENE_CLOCK_MAX_STEPS 8 /* per advance; excess real time is dropped with a warning */

typedef struct scene_clock_t {
    double dt;      /* fixed step, seconds */
    double accum;   /* real time not yet simulated */
    uint64_t steps; /* fixed steps taken so far */
    bool headless;  /* every advance is exactly one step */
    int dropped;    /* advances that hit SCENE_CLOCK_MAX_STEPS */
} scene_clock_t;

/* dt 0 = 1/60 s. */
void scene_clock_init(scene_clock_t *clock, double dt, bool headless);
/* Adds real_dt seconds and returns the number of fixed steps to simulate now.
 * Headless: always 1, real_dt ignored (deterministic). Interactive: floor of
 * the accumulated time over dt, at most SCENE_CLOCK_MAX_STEPS; when the cap
 * is hit the remaining backlog is dropped and a warning is logged. */
int scene_clock_advance(scene_clock_t *clock, double real_dt);
/* Simulated time = steps * dt. */
double scene_clock_time(const scene_clock_t *clock);

#endif

/* scene paths: keyed motion for analytic colliders (piecewise linear in time)
 * and constant-speed walks along waypoint polylines for characters.
 * GL-free. */
#ifndef MEADOW_SCENE_PATH_H
#define MEADOW_SCENE_PATH_H

#include <stdbool.h>

#include <cglm/cglm.h>

/* Maximum keys of any scene path (collider, camera) and waypoints of a walk. */
#define SCENE_MAX_PATH_KEYS 64

typedef struct scene_path_key_t {
    float t;        /* seconds; keys strictly increasing in t */
    vec3 position;  /* metres, world space, y up */
} scene_path_key_t;

typedef struct scene_path_t {
    int count; /* 0 = at the origin, 1 = static */
    scene_path_key_t keys[SCENE_MAX_PATH_KEYS];
} scene_path_t;

/* Piecewise-linear position and velocity at time t.
 * - loop false: clamped before the first and after the last key (velocity 0
 *   there).
 * - loop true: t wraps with period (t_last - t_first); the path jumps from the
 *   last key back to the first, so repeat the first position as the last key
 *   for a closed loop.
 * vel_out is the slope of the current segment (m/s); either out may be NULL. */
void scene_path_eval(const scene_path_t *path, float t, bool loop, vec3 pos_out, vec3 vel_out);

/* Walk along n waypoints (x,z) at constant speed (m/s) for t seconds.
 * - loop true: the polyline is closed (last waypoint back to the first) and
 *   the walk repeats forever.
 * - loop false: stops at the last waypoint, facing along the last segment.
 * pos gets (x,z); dir gets the unit walking direction (x,z) of the current
 * segment ((0,1) when undefined: n < 2 or all waypoints equal).
 * Zero-length segments are skipped. */
void scene_walk_eval(const vec2 *waypoints, int n, float speed, float t, bool loop, vec2 pos,
                     vec2 dir);
/* Length in metres of the walk (including the closing segment when loop). */
float scene_walk_length(const vec2 *waypoints, int n, bool loop);

#endif

/* scene paths: piecewise-linear keyed motion and constant-speed waypoint
 * walks (see path.h). Double precision for time wrapping so long runs do not
 * drift. */
#include "scene/path.h"

#include <math.h>

void scene_path_eval(const scene_path_t *path, float t, bool loop, vec3 pos_out, vec3 vel_out)
{
    vec3 pos = {0, 0, 0}, vel = {0, 0, 0};
    int n = path->count;
    if (n == 1) {
        glm_vec3_copy((float *)path->keys[0].position, pos);
    } else if (n > 1) {
        const scene_path_key_t *k = path->keys;
        double t0 = k[0].t, t1 = k[n - 1].t, tt = t;
        if (loop && t1 > t0) {
            double period = t1 - t0;
            tt = t0 + fmod(tt - t0, period);
            if (tt < t0) tt += period;
        }
        if (tt < t0) {
            glm_vec3_copy((float *)k[0].position, pos);
        } else if (tt >= t1) {
            glm_vec3_copy((float *)k[n - 1].position, pos);
        } else {
            int i = 0;
            while (i + 2 < n && tt >= k[i + 1].t) i++;
            double span = (double)k[i + 1].t - k[i].t;
            float u = (float)((tt - k[i].t) / span);
            glm_vec3_lerp((float *)k[i].position, (float *)k[i + 1].position, u, pos);
            glm_vec3_sub((float *)k[i + 1].position, (float *)k[i].position, vel);
            glm_vec3_scale(vel, (float)(1.0 / span), vel);
        }
    }
    if (pos_out) glm_vec3_copy(pos, pos_out);
    if (vel_out) glm_vec3_copy(vel, vel_out);
}

static float seg_len(const vec2 *w, int a, int b)
{
    return hypotf(w[b][0] - w[a][0], w[b][1] - w[a][1]);
}

float scene_walk_length(const vec2 *waypoints, int n, bool loop)
{
    float len = 0;
    for (int i = 0; i + 1 < n; i++) len += seg_len(waypoints, i, i + 1);
    if (loop && n > 1) len += seg_len(waypoints, n - 1, 0);
    return len;
}

void scene_walk_eval(const vec2 *waypoints, int n, float speed, float t, bool loop, vec2 pos,
                     vec2 dir)
{
    pos[0] = pos[1] = 0;
    dir[0] = 0;
    dir[1] = 1;
    if (n <= 0) return;
    pos[0] = waypoints[0][0];
    pos[1] = waypoints[0][1];
    float total = scene_walk_length(waypoints, n, loop);
    if (n < 2 || total <= 0) return;
    int segs = loop ? n : n - 1;
    double s = (double)speed * t;
    if (loop) {
        s = fmod(s, total);
        if (s < 0) s += total;
    } else if (s < 0) {
        s = 0;
    }
    int last = -1;
    for (int i = 0; i < segs; i++) {
        int a = i, b = (i + 1) % n;
        float len = seg_len(waypoints, a, b);
        if (len <= 0) continue;
        last = i;
        dir[0] = (waypoints[b][0] - waypoints[a][0]) / len;
        dir[1] = (waypoints[b][1] - waypoints[a][1]) / len;
        if (s <= len) {
            float u = (float)(s / len);
            pos[0] = waypoints[a][0] + u * (waypoints[b][0] - waypoints[a][0]);
            pos[1] = waypoints[a][1] + u * (waypoints[b][1] - waypoints[a][1]);
            return;
        }
        s -= len;
    }
    /* Past the end (non-looping walk, or float round-off on a loop). */
    int b = (last + 1) % n;
    pos[0] = waypoints[b][0];
    pos[1] = waypoints[b][1];
}

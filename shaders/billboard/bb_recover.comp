#version 450
/* bb_recover.comp: the recovery pass of Orthmann et al. 2009 over the
 * billboards of COLLIDING and RECOVERING leaves, in place on the points
 * buffer. One thread per billboard of the listed leaf ranges (Ranges:
 * first billboard and count per range, with the running start of each
 * range's threads); a billboard without a deformed mesh has nothing to
 * recover and returns at once. A billboard hit this frame (state
 * COLLIDING) only turns RECOVERING. Otherwise its timer runs down and its
 * stored mesh blends towards the wind pose w by eq. 8,
 * v = (1 - t^3) w + t^3 v_c, t = time left / recover time; when t reaches 0
 * the mesh equals w, the slot goes back to the pool and the billboard is a
 * plain wind-animated quad again. (This was a geometry shader with
 * transform feedback over every listed billboard and a copy back: on the
 * H100 that cost 4.2 ms for 28k billboards on meadow_large, for about 400
 * deformed ones.) */
#define BB_NO_GENERATE
#include "common/bindings_billboard.glsl"
#include "common/bb.glsl"
#include "billboard/bb_points.glsl"
#include "billboard/bb_pool.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BB_BIND_POINTS) buffer Points { bb_point points[]; };
/* Range r: x first billboard, y count, z first thread (running sum of y). */
layout(std430, binding = BB_BIND_RANGES) readonly buffer Ranges { uvec4 ranges[]; };

uniform int u_range_count;
uniform uint u_threads;
uniform float u_time;
uniform float u_dt;
uniform bb_wind u_wind;

void main()
{
    uint t = gl_GlobalInvocationID.x;
    if (t >= u_threads) return;
    int lo = 0, hi = u_range_count - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (ranges[mid].z <= t) lo = mid;
        else hi = mid - 1;
    }
    uint i = ranges[lo].x + (t - ranges[lo].z);
    bb_point p = points[i];
    uint slot = p.pad0;
    if (slot == BB_NO_SLOT) return;
    if (p.state == BB_STATE_COLLIDING) {
        p.state = BB_STATE_RECOVERING;
    } else {
        /* Eq. 8 blends the pose of the last collision v_c with the wind
         * pose: v(t) = (1 - (t/T)^3) w + (t/T)^3 v_c. The stored mesh is
         * updated in place every frame, so each step blends by the ratio
         * of successive t^3 (t_new / t_old, cubed in bb_recover); applying
         * t/T itself every frame would compound and recover far faster
         * than T. */
        float t_old = p.recover_time;
        p.recover_time = max(p.recover_time - u_dt, 0.0);
        vec3 right, up;
        bb_frame(p, right, up);
        bb_build_rest(p, right, up);
        bb_load_mesh(slot);
        vec3 w[BB_N * BB_M];
        bb_wind_pose(u_wind, u_time, w);
        bb_recover(w, t_old > 0.0 ? p.recover_time / t_old : 0.0);
        bb_store_mesh(slot);
        if (p.recover_time <= 0.0) {
            int top = atomicAdd(free_top, 1);
            free_stack[top] = slot;
            p.pad0 = BB_NO_SLOT;
            p.state = BB_STATE_IDLE;
        }
    }
    points[i] = p;
}

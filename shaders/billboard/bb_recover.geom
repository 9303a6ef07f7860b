#version 450
/* bb_recover.geom: the recovery pass of Orthmann et al. 2009 over the
 * billboards of COLLIDING and RECOVERING leaves (transform feedback in and
 * out). A billboard hit this frame (state COLLIDING) only turns RECOVERING.
 * Otherwise its timer runs down and its stored mesh blends towards the wind
 * pose w by eq. 8, v = (1 - t^3) w + t^3 v_c, t = time left / recover time;
 * when t reaches 0 the mesh equals w, the slot goes back to the pool and the
 * billboard is a plain wind-animated quad again. */
#define BB_NO_GENERATE
#include "common/bb.glsl"
#define BB_POINTS_IN
#define BB_POINTS_OUT
#include "billboard/bb_points.glsl"
#include "billboard/bb_pool.glsl"

layout(points) in;
layout(points, max_vertices = 1) out;

uniform float u_time;
uniform float u_dt;
uniform float u_recover;
uniform bb_wind u_wind;

void main()
{
    bb_point p = bb_load_point();
    uint slot = p.pad0;
    if (slot != BB_NO_SLOT) {
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
    }
    bb_emit_point(p);
}

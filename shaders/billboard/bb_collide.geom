#version 450
/* bb_collide.geom: the collision pass of Orthmann et al. 2009 over the
 * billboards of COLLIDING octree leaves (transform feedback in and out). A
 * billboard whose bounding sphere meets an object's bounding sphere (swept:
 * the capsule between its previous and current position) gets a
 * pool slot (its refined mesh starts from the current wind pose), then every
 * non-root vertex is pushed out of the objects' depth cube maps (eq. 1-5) and
 * the springs relaxed K times (eq. 6-7) by bb_collide from common/bb.glsl,
 * every vertex kept on or above the terrain (bb_ground.glsl);
 * state becomes COLLIDING and the recovery timer restarts. Each draw sees
 * one batch of at most BB_MAX_CUBES objects (bb.c: BB_PASS_OBJECTS, bound
 * as a range of the objects buffer); entries carry their cube-array layer. */
#define BB_NO_GENERATE
#include "common/bindings_billboard.glsl"
#include "billboard/bb_ground.glsl"
#include "common/bb.glsl"
#define BB_POINTS_IN
#define BB_POINTS_OUT
#include "billboard/bb_points.glsl"
#include "billboard/bb_pool.glsl"

layout(points) in;
layout(points, max_vertices = 1) out;

struct bb_object {
    mat4 w2c;
    mat4 c2w;
    vec4 cube;   /* cube-space centre, half edge */
    vec4 sphere; /* world-space bounding sphere; radius < 0: skip */
    ivec4 layer; /* x: first of the object's 6 cube-array layers */
    vec4 sweep;  /* xyz previous - current world position (swept collision; 0: none) */
};
layout(std140, binding = BB_UBO_OBJECTS) uniform Objects { bb_object u_obj[BB_MAX_CUBES]; };

layout(binding = BB_TEX_CUBES) uniform sampler2DArray u_cubes;
uniform int u_count;
uniform int u_res;
uniform float u_time;
uniform float u_recover;
uniform float u_r1;
uniform float u_r2;
uniform int u_iterations;
uniform int u_paper; /* bb_field_desc_t.paper */
uniform bb_wind u_wind;

void main()
{
    bb_point p = bb_load_point();
    vec3 right, up;
    bb_frame(p, right, up);
    vec3 bc = p.position + up * (0.5 * p.size.y);
    float br = 0.5 * length(p.size) + u_wind.strength;
    bb_cube cubes[BB_MAX_CUBES];
    mat4 w2c[BB_MAX_CUBES], c2w[BB_MAX_CUBES];
    vec3 sweep[BB_MAX_CUBES];
    int n = 0;
    for (int k = 0; k < u_count; k++) {
        vec4 s = u_obj[k].sphere;
        vec3 sw = u_obj[k].sweep.xyz;
        float ss = dot(sw, sw);
        vec3 nearest = s.xyz + (ss > 0.0 ? sw * clamp(dot(bc - s.xyz, sw) / ss, 0.0, 1.0) : vec3(0.0));
        if (s.w < 0.0 || distance(bc, nearest) >= br + s.w) continue;
        cubes[n] = bb_cube(u_obj[k].cube.xyz, u_obj[k].cube.w, u_res, u_obj[k].layer.x);
        w2c[n] = u_obj[k].w2c;
        c2w[n] = u_obj[k].c2w;
        sweep[n] = sw;
        n++;
    }
    if (n > 0) {
        uint slot = p.pad0;
        bb_build_rest(p, right, up);
        bool ok = true;
        if (slot == BB_NO_SLOT) {
            int old = atomicAdd(free_top, -1);
            if (old <= 0) {
                atomicAdd(free_top, 1);
                atomicAdd(exhausted, 1u);
                ok = false;
            } else {
                slot = free_stack[old - 1];
                vec3 w[BB_N * BB_M];
                bb_wind_pose(u_wind, u_time, w);
                for (int v = 0; v < BB_N * BB_M; v++) bb_pos[v] = w[v];
            }
        } else {
            bb_load_mesh(slot);
        }
        if (ok) {
            bb_collide(u_cubes, cubes, w2c, c2w, sweep, n, u_r1, u_r2, u_iterations, u_paper != 0);
            bb_store_mesh(slot);
            p.pad0 = slot;
            p.state = BB_STATE_COLLIDING;
            p.recover_time = u_recover;
        }
    }
    bb_emit_point(p);
}

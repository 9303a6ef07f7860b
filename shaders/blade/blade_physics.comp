#version 450
/* blade_physics.comp: one simulation step per blade (Jahrmann & Wimmer
 * 2017 eq. 3-16), the twin of blade_ref_step_one in src/blade/blade_ref.c:
 * forces r + g + w on the start-of-step state, v2 += (r + g + w) k with
 * k = blade_step_gain (exact for frozen g, w),
 * validation, sphere collision, and only after a contact the validation of
 * the tip mapped back through the first one's rescale, Coulomb friction and
 * the collision exit (departures, see blade_ref.h), and, beyond both
 * papers, the same for the cube proxies of the collide set
 * (collision after the spheres, exit after the sphere exit; twins of
 * blade_ref.c's collide_cubes / exit_cubes),
 * eta += k d.d (BLADE_ETA_DT / dt) then eta = clamp(eta - a dt, 0, 1). Blades of height <= 0 (patch
 * padding) are left untouched. One invocation per blade; each blade tests
 * only the spheres its work group listed (list_near_spheres). The cube-proxy
 * code is compiled only with BLADE_CUBES (blade.c makes both programs and
 * uses this one only while cube proxies are set): present but unused, it
 * made the step twice as slow on the H100 (fan128 0.39 -> 0.83 ms, nature
 * 0.066 -> 0.101 ms, commit a4a6f17). */
#define BB_NO_GENERATE
#include "common/bb.glsl"
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"

layout(local_size_x = 256) in; /* GROUP_SIZE */

layout(std430, binding = BLADE_BIND_BLADES) buffer Blades { Blade blades[]; };
layout(std430, binding = BLADE_BIND_ETA) buffer Eta { float eta[]; };
layout(std430, binding = BLADE_BIND_WINDS) readonly buffer Winds { BladeWind winds[]; };
layout(std430, binding = BLADE_BIND_SPHERES) readonly buffer Spheres { BladeSphere spheres[]; };
layout(std430, binding = BLADE_BIND_CUBES) readonly buffer Cubes { BladeCube cubes[]; };

uniform uint u_blade_count;
uniform float u_dt;
uniform float u_time;
uniform vec4 u_gravity;        /* xyz unit direction, w magnitude (0: off) */
uniform vec4 u_gravity_centre; /* xyz centre, w mix t */
uniform float u_collision_decay;
uniform float u_collision_gain;
uniform int u_wind_count;
uniform int u_sphere_count;
uniform int u_length_mode;     /* BLADE_LENGTH_QUADRATURE or BLADE_LENGTH_PAPER */
uniform int u_paper;           /* 1: the paper's step as printed (blade_env_t.paper) */
#ifdef BLADE_CUBES
uniform int u_cube_count;      /* cube-map colliders (0: none) */
uniform int u_cube_res;
layout(binding = BLADE_TEX_CUBES) uniform sampler2DArray u_cube_tex; /* layers 6k .. 6k+5: object k */

bb_cube cube_of(int k)
{
    return bb_cube(cubes[k].cube.xyz, cubes[k].cube.w, u_cube_res, 6 * k);
}

/* Does any object whose cube map does not hold the root hold v2 or m? */
bool cube_holds(Blade b, vec3 v2, vec3 m)
{
    for (int k = 0; k < u_cube_count; k++) {
        bb_cube c = cube_of(k);
        if (blade_inside_cube(u_cube_tex, cubes[k], c, b.v0.xyz)) continue;
        if (blade_inside_cube(u_cube_tex, cubes[k], c, v2) || blade_inside_cube(u_cube_tex, cubes[k], c, m))
            return true;
    }
    return false;
}

void cube_exit_straight(inout Blade b)
{
    if (!cube_holds(b, b.v2.xyz, blade_midpoint(b))) return;
    float h = b.v1.w;
    vec3 v0 = b.v0.xyz;
    vec3 td = blade_safe_normalize(b.v2.xyz - v0);
    float best = -2.0;
    vec3 bu = vec3(0.0);
    for (int i = 0; i < BLADE_CUBE_DIRECTIONS; i++) {
        vec3 u = blade_cube_direction(b, i);
        float c = dot(u, td);
        if (c <= best) continue;
        if (cube_holds(b, v0 + u * h, v0 + u * (0.5 * h))) continue;
        best = c;
        bu = u;
    }
    if (best < -1.5) return;
    b.v1.xyz = v0 + bu * (0.5 * h);
    b.v2.xyz = v0 + bu * h;
}
#endif

/* Spheres near this work group (beyond both papers): the 256 blades of a
 * group are one Morton-ordered patch, so the group lists the spheres whose
 * swept capsule comes within reach of its roots' box and every blade loops
 * over that list only, in the order of the full list (same sums, same
 * results). Reach: twice the farthest tip or midpoint from its root after
 * the forces, plus five radii (one sphere moves v2 by at most its radius
 * plus four times the midpoint's penetration). fan128 (128 balls): each
 * blade tested every ball before. The set has no fixed size (the buffer
 * grows with the scene, blade_gpu_update): it is masked LIST_MAX spheres
 * at a time, and a group with more than LIST_MAX near spheres tests every
 * sphere of the set instead (a far sphere adds nothing: the same results
 * as the list, slower). */
#define GROUP_SIZE 256
#define LIST_WORDS 16 /* one chunk of the mask: LIST_MAX spheres */
#define LIST_MAX (LIST_WORDS * 32)
shared uint s_lo[3], s_hi[3]; /* root box, floats as order-preserving uints */
shared uint s_reach;          /* float bits, >= 0 */
shared uint s_mask[LIST_WORDS];
shared uint s_count;          /* near spheres; > LIST_MAX: the list is full, every sphere is tested */
shared uint s_list[LIST_MAX];

uint float_key(float f)
{
    uint u = floatBitsToUint(f);
    return (u & 0x80000000u) != 0u ? ~u : u | 0x80000000u;
}

float key_float(uint k)
{
    return uintBitsToFloat((k & 0x80000000u) != 0u ? k & 0x7fffffffu : ~k);
}

/* Fills s_list / s_count; every invocation of the group calls it. */
void list_near_spheres(bool live, Blade b)
{
    uint l = gl_LocalInvocationIndex;
    if (l < 3u) {
        s_lo[l] = 0xffffffffu;
        s_hi[l] = 0u;
    }
    if (l == 0u) {
        s_reach = 0u;
        s_count = 0u;
    }
    if (l < uint(LIST_WORDS)) s_mask[l] = 0u;
    barrier();
    if (live) {
        vec3 v0 = b.v0.xyz;
        for (int a = 0; a < 3; a++) {
            atomicMin(s_lo[a], float_key(v0[a]));
            atomicMax(s_hi[a], float_key(v0[a]));
        }
        float reach = max(length(b.v2.xyz - v0), length(blade_midpoint(b) - v0));
        atomicMax(s_reach, floatBitsToUint(max(reach, b.v1.w)));
    }
    barrier();
    vec3 lo = vec3(key_float(s_lo[0]), key_float(s_lo[1]), key_float(s_lo[2]));
    vec3 hi = vec3(key_float(s_hi[0]), key_float(s_hi[1]), key_float(s_hi[2]));
    float reach = 2.0 * uintBitsToFloat(s_reach);
    bool any = s_lo[0] <= s_hi[0];
    uint count = uint(u_sphere_count);
    for (uint base = 0u; base < count; base += uint(LIST_MAX)) {
        uint end = min(base + uint(LIST_MAX), count);
        for (uint k = base + l; any && k < end; k += uint(GROUP_SIZE)) {
            BladeSphere s = spheres[k];
            vec3 c0 = s.centre_radius.xyz, c1 = c0 + s.sweep.xyz;
            float m = reach + 5.0 * s.centre_radius.w;
            if (all(lessThanEqual(min(c0, c1) - m, hi)) && all(greaterThanEqual(max(c0, c1) + m, lo)))
                atomicOr(s_mask[(k - base) >> 5u], 1u << (k & 31u));
        }
        barrier();
        if (l == 0u) {
            uint n = s_count;
            for (int w = 0; w < LIST_WORDS; w++) {
                uint bits = s_mask[w];
                s_mask[w] = 0u;
                while (bits != 0u) {
                    if (n < uint(LIST_MAX)) s_list[n] = base + uint(w) * 32u + uint(findLSB(bits));
                    n++;
                    bits &= bits - 1u;
                }
            }
            s_count = n;
        }
        barrier();
    }
}

/* The number of spheres a blade of the group loops over, and the j-th. */
uint near_count()
{
    return s_count <= uint(LIST_MAX) ? s_count : uint(u_sphere_count);
}

BladeSphere near_sphere(uint j)
{
    return spheres[s_count <= uint(LIST_MAX) ? s_list[j] : j];
}

void main()
{
    uint i = gl_GlobalInvocationID.x;
    bool live = i < u_blade_count;
    Blade b;
    float e = 0.0, rescale = 1.0;
    if (live) {
        b = blades[i];
        live = b.v1.w > 0.0;
    }
    Blade start = b;
    if (live) {
        e = eta[i];
        vec3 r = blade_recovery(b, e);
        vec3 g = blade_gravity(b, u_gravity, u_gravity_centre);
        vec3 wi = vec3(0.0);
        for (int k = 0; k < u_wind_count; k++) wi = wi + blade_wind_field(winds[k], b.v0.xyz, u_time);
        vec3 w = blade_wind(b, wi);
        float k = u_paper != 0 ? u_dt : blade_step_gain(b.up.w * max(1.0 - e, 0.1), u_dt);
        b.v2.xyz = b.v2.xyz + ((r + g) + w) * k;
        rescale = blade_validate(b, u_length_mode);
    }
    list_near_spheres(live, b);
    if (!live) return;
    uint ns = near_count();
    vec3 d = vec3(0.0);
    for (uint j = 0u; j < ns; j++) d = d + blade_collide_sphere(b, near_sphere(j), u_length_mode, rescale);
#ifdef BLADE_CUBES
    for (int k = 0; k < u_cube_count; k++) d = d + blade_collide_cube(b, u_cube_tex, cubes[k], cube_of(k));
#endif
    if (dot(d, d) > 0.0 && u_paper != 0) {
        blade_revalidate(b, u_length_mode, rescale);
    } else if (dot(d, d) > 0.0) {
        blade_revalidate(b, u_length_mode, rescale);
        bool held = false;
        for (uint j = 0u; j < ns && !held; j++) held = blade_sphere_holds(start, near_sphere(j));
#ifdef BLADE_CUBES
        for (int k = 0; k < u_cube_count && !held; k++) {
            bb_cube c = cube_of(k);
            held = blade_inside_cube(u_cube_tex, cubes[k], c, start.v2.xyz) ||
                   blade_inside_cube(u_cube_tex, cubes[k], c, blade_midpoint(start));
        }
#endif
        if (!held) blade_friction(b, start, d, u_length_mode);
        for (int round = 0; round < BLADE_EXIT_ROUNDS; round++) {
            for (uint j = 0u; j < ns; j++) {
                BladeSphere s = near_sphere(j);
                blade_exit_rotate(b, s, b.v2.xyz);
                blade_exit_rotate(b, s, blade_midpoint(b));
            }
        }
        for (uint j = 0u; j < ns; j++) blade_exit_straight(b, near_sphere(j));
#ifdef BLADE_CUBES
        for (int round = 0; round < BLADE_EXIT_ROUNDS; round++) {
            for (int k = 0; k < u_cube_count; k++) {
                blade_cube_exit_rotate(b, u_cube_tex, cubes[k], cube_of(k), b.v2.xyz);
                blade_cube_exit_rotate(b, u_cube_tex, cubes[k], cube_of(k), blade_midpoint(b));
            }
        }
        cube_exit_straight(b);
#endif
    }
    e = e + u_collision_gain * dot(d, d) * (u_dt > 0.0 && u_paper == 0 ? BLADE_ETA_DT / u_dt : 1.0);
    eta[i] = clamp(e - u_collision_decay * u_dt, 0.0, 1.0);
    blades[i] = b;
}

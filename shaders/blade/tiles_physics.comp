#version 450
/* tiles_physics.comp: one Jahrmann & Wimmer 2017 step (eq. 3-16, the twin
 * of blade_physics.comp / blade_ref_step_one, second validation, friction
 * and collision exit included) for
 * the blades of the listed pool slots only (Fan et al. 2015: simulate what
 * the scene needs). Invocation i: slot list[i / B] & 0x7fffffff, blade
 * i % B. Each slot tests only the spheres of its tile's object list,
 * every one (slot_spheres[2 slot] = the list's first word,
 * slot_spheres[2 slot + 1] = its length; the words are sphere indices).
 * Slots flagged recovering (bit 31) also write their motion:
 * atomicMax(motion[slot], bits of |v2 - P(t)|), P the procedural pose
 * (tiles_common.glsl); non-negative floats order like their bits. */
#include "blade/tiles_common.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = BLADE_TILES_BIND_POOL) buffer Pool { Blade pool[]; };
layout(std430, binding = BLADE_TILES_BIND_ETA) buffer Eta { float eta[]; };
layout(std430, binding = BLADE_TILES_BIND_SPHERES) readonly buffer Spheres { BladeSphere spheres[]; };
layout(std430, binding = BLADE_TILES_BIND_SLOT_SPHERES) readonly buffer SlotSpheres { uint slot_spheres[]; };
layout(std430, binding = BLADE_TILES_BIND_LIST) readonly buffer List { uint list[]; };
layout(std430, binding = BLADE_TILES_BIND_MOTION) buffer Motion { uint motion[]; };

uniform uint u_count; /* slots * B */
uniform float u_dt;
uniform float u_collision_decay;
uniform float u_collision_gain;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    uint entry = list[i / u_template_blades];
    uint slot = entry & 0x7fffffffu;
    uint idx = slot * u_template_blades + i % u_template_blades;
    Blade b = pool[idx];
    float h = b.v1.w;
    if (h <= 0.0) return;
    uint sbase = slot_spheres[2u * slot];
    int ns = int(slot_spheres[2u * slot + 1u]);
    float e = eta[idx];
    Blade start = b;
    vec3 r = blade_recovery(b, e);
    vec3 g = blade_gravity(b, u_gravity, u_gravity_centre);
    vec3 w = blade_wind(b, tiles_wind_sum(b.v0.xyz));
    b.v2.xyz = b.v2.xyz + ((r + g) + w) * blade_step_gain(b.up.w * max(1.0 - e, 0.1), u_dt);
    float rescale = blade_validate(b, u_length_mode);
    vec3 d = vec3(0.0);
    for (int k = 0; k < ns; k++)
        d = d + blade_collide_sphere(b, spheres[slot_spheres[sbase + uint(k)]], u_length_mode, rescale);
    if (dot(d, d) > 0.0) {
        blade_revalidate(b, u_length_mode, rescale);
        bool held = false;
        for (int k = 0; k < ns && !held; k++)
            held = blade_sphere_holds(start, spheres[slot_spheres[sbase + uint(k)]]);
        if (!held) blade_friction(b, start, d, u_length_mode);
        for (int round = 0; round < BLADE_EXIT_ROUNDS; round++) {
            for (int k = 0; k < ns; k++) {
                BladeSphere s = spheres[slot_spheres[sbase + uint(k)]];
                blade_exit_rotate(b, s, b.v2.xyz);
                blade_exit_rotate(b, s, blade_midpoint(b));
            }
        }
        for (int k = 0; k < ns; k++) blade_exit_straight(b, spheres[slot_spheres[sbase + uint(k)]]);
    }
    e = e + u_collision_gain * dot(d, d) * (u_dt > 0.0 ? BLADE_ETA_DT / u_dt : 1.0);
    eta[idx] = min(max(e - u_collision_decay * u_dt, 0.0), 1.0); /* clamp as blade_ref_step_one */
    pool[idx] = b;
    if ((entry & 0x80000000u) != 0u) {
        Blade rest = b;
        rest.v1.xyz = b.v0.xyz + b.up.xyz * h;
        rest.v2.xyz = rest.v1.xyz;
        Blade p = tiles_pose(rest);
        atomicMax(motion[slot], floatBitsToUint(length(b.v2.xyz - p.v2.xyz)));
    }
}

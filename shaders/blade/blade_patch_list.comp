#version 450
/* blade_patch_list.comp: blade mode's patch test, second pass: the list
 * of the patches blade_patch_cull.comp kept, bucket after bucket (nearest
 * first; within a bucket in any order), and the indirect dispatch of
 * blade_cull.comp over their blades. Every work group scans the bucket
 * counts in shared memory (one invocation per bucket: BLADE_PATCH_BUCKETS
 * = the group size) and places its own patches at their bucket's offset
 * plus their place; group 0 writes the list's length, the dispatch
 * (ceil(listed P / 256) groups, 1, 1) and its invocations listed P, P =
 * u_patch_size. No atomics: the places were taken by the first pass. */
#include "common/bindings_blade.glsl"
#include "blade/blade_patch.glsl"

layout(local_size_x = BLADE_PATCH_BUCKETS) in;

layout(std430, binding = BLADE_BIND_PATCH_KEYS) readonly buffer Keys { uvec2 keys[]; };
layout(std430, binding = BLADE_BIND_PATCHES) writeonly buffer Patches { uint patches[]; };

uniform uint u_patch_count;
uniform uint u_patch_size;

shared uint s_sum[BLADE_PATCH_BUCKETS];

void main()
{
    uint t = gl_LocalInvocationID.x;
    uint own = counts.buckets[t];
    s_sum[t] = own;
    barrier();
    /* inclusive scan (Hillis and Steele) */
    for (uint step = 1u; step < uint(BLADE_PATCH_BUCKETS); step *= 2u) {
        uint add = t >= step ? s_sum[t - step] : 0u;
        barrier();
        s_sum[t] += add;
        barrier();
    }
    uint total = s_sum[BLADE_PATCH_BUCKETS - 1];
    barrier();
    s_sum[t] -= own; /* exclusive: the bucket's first place */
    barrier();
    if (gl_WorkGroupID.x == 0u && t == 0u) {
        uint invocations = total * u_patch_size;
        counts.patches_listed = total;
        counts.dispatch[0] = (invocations + 255u) / 256u;
        counts.dispatch[1] = 1u;
        counts.dispatch[2] = 1u;
        counts.dispatch[3] = invocations;
    }
    uint p = gl_GlobalInvocationID.x;
    if (p >= u_patch_count) return;
    uvec2 key = keys[p];
    if (key.x == 0xffffffffu) return;
    patches[s_sum[key.x] + key.y] = p;
}

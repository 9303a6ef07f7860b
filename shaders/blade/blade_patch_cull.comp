#version 450
/* blade_patch_cull.comp: blade mode's patch test, first pass (beyond
 * Jahrmann & Wimmer 2017, whose culling is per blade, eq. 17-20). One
 * invocation per patch: a patch whose box lies outside one clip plane
 * grown by the blades' frustum tolerance (blade_patch_outside, the twin of
 * blade_ref_box_outside) adds its real blades to patch_culled; any other
 * takes the next place of its distance bucket (blade_patch_bucket) with
 * atomicAdd and keeps (bucket, place) in keys. With u_frustum 0 (the
 * frustum test disabled) every patch is listed. blade_patch_list.comp
 * then writes the list, nearest bucket first. */
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "blade/blade_patch.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = BLADE_BIND_PATCH_BOXES) readonly buffer Boxes { PatchBox boxes[]; };
layout(std430, binding = BLADE_BIND_PATCH_KEYS) writeonly buffer Keys { uvec2 keys[]; };

uniform uint u_patch_count;
uniform mat4 u_view_proj;
uniform vec3 u_cam_pos;
uniform float u_frustum_tolerance;
uniform int u_frustum;
uniform float u_bucket_range; /* the cull distance */

void main()
{
    uint p = gl_GlobalInvocationID.x;
    if (p >= u_patch_count) return;
    vec3 lo = boxes[p].lo.xyz, hi = boxes[p].hi.xyz;
    if (u_frustum != 0 && blade_patch_outside(lo, hi, u_view_proj, u_frustum_tolerance)) {
        atomicAdd(counts.patch_culled, floatBitsToUint(boxes[p].lo.w));
        keys[p] = uvec2(0xffffffffu, 0u);
        return;
    }
    uint bucket = blade_patch_bucket(u_cam_pos, lo, hi, u_bucket_range, uint(BLADE_PATCH_BUCKETS));
    keys[p] = uvec2(bucket, atomicAdd(counts.buckets[bucket], 1u));
}

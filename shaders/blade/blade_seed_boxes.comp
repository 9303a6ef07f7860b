#version 450
/* blade_seed_boxes.comp: the patch boxes of a field seeded on the GPU, the
 * twin of blade_seed_plan_field's: one invocation per patch takes the
 * bounds of its roots grown by its largest height + width / 2 and counts
 * its real blades (height > 0) into lo.w (uint bits), as blade_gpu_make
 * writes the boxes of a field seeded on the CPU. Grid-stride over
 * u_patch_count. */
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "blade/blade_patch.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BLADE_BIND_BLADES) readonly buffer Blades { Blade blades[]; };
layout(std430, binding = BLADE_BIND_PATCH_BOXES) writeonly buffer Boxes { PatchBox boxes[]; };

uniform uint u_patch_count, u_patch_size;

void main()
{
    uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint p = gl_GlobalInvocationID.x; p < u_patch_count; p += stride) {
        vec3 lo = vec3(1.0 / 0.0), hi = vec3(-1.0 / 0.0);
        float grow = 0.0;
        uint real = 0u;
        for (uint i = p * u_patch_size; i < (p + 1u) * u_patch_size; i++) {
            Blade b = blades[i];
            lo = min(lo, b.v0.xyz);
            hi = max(hi, b.v0.xyz);
            grow = max(grow, b.v1.w + 0.5 * b.v2.w);
            if (b.v1.w > 0.0) real++;
        }
        boxes[p].lo = vec4(lo - grow, uintBitsToFloat(real));
        boxes[p].hi = vec4(hi + grow, 0.0);
    }
}

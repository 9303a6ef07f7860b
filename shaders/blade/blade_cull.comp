#version 450
/* blade_cull.comp: per-blade culling (Jahrmann & Wimmer 2017 sec. 6,
 * eq. 17-20), the twin of blade_ref_cull_one in src/blade/blade_ref.c.
 * The thinning with distance (common/lod.glsl, lod_blade on the global
 * blade index, d_proj and the blade's width; u_lod_cull = u_max_distance)
 * comes first: a survivor is drawn weight * scale times as wide (its width
 * factor), and the orientation test widens its threshold by that factor
 * (blade_lod_orientation). Weight 0 is a distance cull.
 * Tests in order: orientation, frustum, distance, occlusion; the first that
 * fails culls the blade and increments its counter (counts.culled[0..3]
 * in that order, blade_patch.glsl; summed per workgroup first). A survivor appends its index to
 * `survivors` and increments the draw command: instanceCount when
 * u_count_instances != 0 (one instance per blade, count = vertices per
 * blade set by the host), else count (one vertex / patch per blade,
 * instanceCount = 1). Padding blades (height <= 0) are dropped without
 * counting. A survivor is written as (index, the float bits of its width
 * factor). The host resets instanceCount (or count) and the counters
 * with glClearBufferSubData before the patch test;
 * nothing here synchronizes across work groups. Survivor order is
 * arbitrary: compare with the CPU list as a set. With u_use_patches the
 * dispatch is indirect and its invocations cover only the patches listed
 * in `patches` by the GPU patch test (blade_patch_cull.comp,
 * blade_patch_list.comp; their count is counts.dispatch[3]): invocation i
 * handles blade patches[i / P] * P + i % P, P = u_patch_size; the distance
 * test still uses the global blade index. */
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "blade/blade_patch.glsl"
#include "common/lod.glsl"
#include "blade/cull_counts.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = BLADE_BIND_BLADES) readonly buffer Blades { Blade blades[]; };
layout(std430, binding = BLADE_BIND_SURVIVORS) writeonly buffer Survivors { uvec2 survivors[]; };
layout(std430, binding = BLADE_BIND_COMMAND) buffer Command {
    uint count;
    uint instanceCount;
    uint first;
    uint baseInstance;
} cmd;
layout(std430, binding = BLADE_BIND_PATCHES) readonly buffer Patches { uint patches[]; };

/* Window depth of the previous frame (or a depth pre-pass); NDC = 2 d - 1. */
layout(binding = BLADE_TEX_DEPTH) uniform sampler2D u_depth;

uniform uint u_blade_count;    /* invocations without u_use_patches: the blades */
uniform vec3 u_cam_pos;
uniform mat4 u_view_proj;
uniform float u_max_distance;
uniform float u_orientation_threshold;
uniform float u_frustum_tolerance;
uniform float u_depth_bias;
uniform int u_use_depth;
uniform uint u_disable;          /* BLADE_CULL_* bits */
uniform int u_count_instances;
uniform int u_use_patches;
uniform uint u_patch_size;

uint cull(Blade b, uint index, out float factor)
{
    factor = 1.0;
    float h = b.v1.w;
    if (h <= 0.0) return BLADE_CULL_PADDING;
    vec3 v0 = b.v0.xyz;
    vec3 up = b.up.xyz;
    vec3 view = v0 - u_cam_pos;
    vec3 view_ground = view - up * dot(view, up);
    /* the thinning first: the orientation test widens its threshold by it */
    float dproj = length(view_ground);
    vec2 lod = vec2(1.0);
    if ((u_disable & BLADE_CULL_DISTANCE) == 0u && dproj <= u_max_distance) lod = lod_blade(index, dproj, b.v2.w);
    factor = lod.x * lod.y;

    if ((u_disable & BLADE_CULL_ORIENTATION) == 0u) {
        vec3 width_dir, front;
        blade_frame(b, width_dir, front);
        vec3 dir_c = blade_safe_normalize(view_ground);
        if (abs(dot(dir_c, width_dir)) > blade_lod_orientation(u_orientation_threshold, factor))
            return BLADE_CULL_ORIENTATION;
    }

    vec4 c0 = u_view_proj * vec4(v0, 1.0);
    vec4 cm = u_view_proj * vec4(blade_midpoint(b), 1.0);
    vec4 c2 = u_view_proj * vec4(b.v2.xyz, 1.0);
    if ((u_disable & BLADE_CULL_FRUSTUM) == 0u) {
        float t = u_frustum_tolerance;
        if (!blade_in_frustum(c0, t) && !blade_in_frustum(cm, t) && !blade_in_frustum(c2, t))
            return BLADE_CULL_FRUSTUM;
    }

    if ((u_disable & BLADE_CULL_DISTANCE) == 0u && (dproj > u_max_distance || lod.x <= 0.0))
        return BLADE_CULL_DISTANCE;

    if (u_use_depth != 0 && (u_disable & BLADE_CULL_OCCLUSION) == 0u) {
        float bias = u_depth_bias;
        if (blade_occluded(u_depth, c0, bias) && blade_occluded(u_depth, cm, bias) &&
            blade_occluded(u_depth, c2, bias))
            return BLADE_CULL_OCCLUSION;
    }
    return BLADE_CULL_VISIBLE;
}

void main()
{
    cull_counts_clear();
    barrier();
    uint i = gl_GlobalInvocationID.x;
    if (i < (u_use_patches != 0 ? counts.dispatch[3] : u_blade_count)) {
        if (u_use_patches != 0) i = patches[i / u_patch_size] * u_patch_size + i % u_patch_size;
        float factor;
        uint why = cull(blades[i], i, factor);
        if (why == BLADE_CULL_VISIBLE) {
            uint slot = u_count_instances != 0 ? atomicAdd(cmd.instanceCount, 1u) : atomicAdd(cmd.count, 1u);
            survivors[slot] = uvec2(i, floatBitsToUint(factor));
        } else if (why != BLADE_CULL_PADDING) {
            cull_counts_add(why);
        }
    }
    barrier();
    uint mine = cull_counts_mine();
    if (mine > 0u) atomicAdd(counts.culled[gl_LocalInvocationIndex], mine);
}

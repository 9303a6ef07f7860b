#version 450
/* blade_seed.comp: blade mode's field seeded on the GPU, the GLSL twin of
 * blade_seed_plan_blade (src/blade/blade_seed_plan.h, with blade_seed.h's
 * blade_seed_point and blade_seed_normal for the root and its up): invocation i finds its ordered triangle by binary search of
 * the plan's offsets, draws its six uniforms from the stream of (triangle,
 * index in it) and writes the rest pose; padding copies the last real
 * blade at height 0. With u_extent on, the extent map thins it as
 * blade_seed_extent_keeps does (extent.glsl's wrap) and the thinned real blades are counted.
 * Every blade and its collision strength (0) is written: the buffers
 * start uninitialized (gfx_buffer_desc_t.uninitialized).
 * Grid-stride over u_padded_count, so any field fits the dispatch limit. */
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "common/hash.glsl"
#include "common/extent.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = BLADE_BIND_BLADES) writeonly buffer Blades { Blade blades[]; };
layout(std430, binding = BLADE_BIND_ETA) writeonly buffer Eta { float eta[]; };
layout(std430, binding = BLADE_SEED_BIND_POSITIONS) readonly buffer Positions { float positions[]; };
layout(std430, binding = BLADE_SEED_BIND_NORMALS) readonly buffer Normals { float normals[]; };
layout(std430, binding = BLADE_SEED_BIND_INDICES) readonly buffer Indices { uint indices[]; };
layout(std430, binding = BLADE_SEED_BIND_ORDER) readonly buffer Order { uint order[]; };
layout(std430, binding = BLADE_SEED_BIND_OFFSETS) readonly buffer Offsets { uint offsets[]; };
layout(std430, binding = BLADE_SEED_BIND_THINNED) buffer Thinned { uint thinned; };
layout(binding = BLADE_SEED_TEX_EXTENT) uniform sampler2D u_extent_map; /* R8: 0..255 as 0..1 */

uniform uint u_blade_count, u_padded_count, u_tri_count, u_key;
uniform int u_normals; /* 1: interpolated vertex normals */
uniform vec2 u_height, u_width, u_stiffness, u_angle; /* ranges */
uniform int u_extent;  /* 1: thin by u_extent_map */
uniform vec2 u_extent_origin;
uniform float u_extent_spacing;
uniform uint u_extent_key;

const uint PLAN_GOLDEN = 0x9e3779b9u;
const uint PLAN_EXTENT_SALT = 0x5bd1e995u;

float plan_draw(uint s, uint n) { return hash_float(s + n * PLAN_GOLDEN); }

vec3 corner(uint t, uint k)
{
    uint v = indices[3u * t + k];
    return vec3(positions[3u * v], positions[3u * v + 1u], positions[3u * v + 2u]);
}

vec3 corner_normal(uint t, uint k)
{
    uint v = indices[3u * t + k];
    return vec3(normals[3u * v], normals[3u * v + 1u], normals[3u * v + 2u]);
}

uint plan_triangle(uint i)
{
    uint lo = 0u, hi = u_tri_count - 1u;
    while (lo < hi) {
        uint mid = lo + (hi - lo + 1u) / 2u;
        if (offsets[mid] <= i) lo = mid;
        else hi = mid - 1u;
    }
    return lo;
}

bool extent_keeps(uint i, vec3 v0)
{
    ivec2 tx = extent_texel(u_extent_map, v0.xz, u_extent_origin, u_extent_spacing);
    uint texel = uint(round(texelFetch(u_extent_map, tx, 0).r * 255.0));
    return hash_u32(i ^ hash_u32(u_extent_key ^ PLAN_EXTENT_SALT)) % 255u < texel;
}

Blade plan_blade(uint index)
{
    uint i = min(index, u_blade_count - 1u);
    uint k = plan_triangle(i);
    uint t = order[k], j = i - offsets[k];
    uint s = hash_u32(hash_u32(u_key ^ hash_u32(t)) + j);
    float r = sqrt(plan_draw(s, 0u)), u1 = plan_draw(s, 1u);
    vec3 bary = vec3(1.0 - r, r * (1.0 - u1), r * u1);
    vec3 a = corner(t, 0u), b = corner(t, 1u), c = corner(t, 2u);
    vec3 v0 = bary.x * a + bary.y * b + bary.z * c;
    vec3 up = vec3(0.0);
    float len = 0.0;
    if (u_normals != 0) {
        up = bary.x * corner_normal(t, 0u) + bary.y * corner_normal(t, 1u) + bary.z * corner_normal(t, 2u);
        len = length(up);
    }
    if (len < 1e-12) {
        up = cross(b - a, c - a);
        len = length(up);
        if (len < 1e-12) {
            up = vec3(0.0, 1.0, 0.0);
            len = 1.0;
        }
    }
    up /= len;
    float h = u_height.x + (u_height.y - u_height.x) * plan_draw(s, 2u);
    float w = u_width.x + (u_width.y - u_width.x) * plan_draw(s, 3u);
    float st = u_stiffness.x + (u_stiffness.y - u_stiffness.x) * plan_draw(s, 4u);
    float an = u_angle.x + (u_angle.y - u_angle.x) * plan_draw(s, 5u);
    if (index >= u_blade_count) {
        h = 0.0;
        w = 0.0;
    }
    Blade bl;
    bl.v0 = vec4(v0, an);
    bl.v1 = vec4(v0 + up * h, h);
    bl.v2 = vec4(v0 + up * h, w);
    bl.up = vec4(up, st);
    return bl;
}

void main()
{
    uint stride = gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    for (uint i = gl_GlobalInvocationID.x; i < u_padded_count; i += stride) {
        Blade bl = plan_blade(i);
        if (u_extent != 0 && i < u_blade_count && !extent_keeps(i, bl.v0.xyz)) {
            bl.v1 = vec4(bl.v0.xyz, 0.0);
            bl.v2 = vec4(bl.v0.xyz, 0.0);
            atomicAdd(thinned, 1u);
        }
        blades[i] = bl;
        eta[i] = 0.0;
    }
}

#version 450
/* tiles_cull.comp: per-blade culling of the tiled field (Jahrmann & Wimmer
 * 2017 eq. 17-20: orientation, frustum, distance, occlusion; the tests,
 * their order, the thinning and the occlusion rule and bias of
 * blade_cull.comp). Invocation i: entry list[i / B] = (tile, slot), blade
 * k = i % B: the blade is the pool state of the slot, or, for an idle tile
 * (slot TILES_NO_SLOT), the procedural pose of the template blade. The
 * thinning (common/lod.glsl, lod_blade) ranks by k (templates are Morton
 * ordered, so the thinning is spatially even), reads the eye distance and
 * the pose's width, and a survivor is drawn weight * scale times as wide,
 * so the thinned field covers the ground as the full one; the orientation
 * test culls a widened blade only when it is as thin on screen as the
 * test means (blade_lod_orientation). With u_use_depth the blade is culled when v0,
 * its midpoint and v2 all lie behind the opaque depth in u_depth
 * (blade_occluded). The first test that fails counts the blade in its
 * counter (cmd.culled[0..3]: orientation, frustum, distance, occlusion).
 * A survivor is counted in cmd.total and, within u_capacity, appended as a
 * whole blade (and its id tile * B + k): with u_split, a blade whose root
 * lies beyond u_fade_start at the end of `drawn`, counted back from
 * u_capacity - 1 (the fade command), any other at the front (the solid
 * command); without, every blade at the front. A command counts in word
 * u_count_word of its four: 1 (instanceCount: the pulled strips, one
 * instance per blade) or 0 (count: the tessellation path, one patch vertex
 * per blade). Front and end cannot meet, as each append first took one of
 * the u_capacity places in cmd.total. Past the capacity it is dropped and
 * counted in cmd.overflow (u_group_append: counted and placed per
 * workgroup, below). The host zeroes the counted words before the
 * dispatch. */
#include "blade/tiles_common.glsl"
#include "common/extent.glsl"
#include "common/lod.glsl"
#include "blade/cull_counts.glsl"

layout(local_size_x = 256) in; /* CULL_GROUP */

layout(std430, binding = BLADE_TILES_BIND_POOL) readonly buffer Pool { Blade pool[]; };
layout(std430, binding = BLADE_TILES_BIND_LIST) readonly buffer List { uvec2 list[]; };
layout(std430, binding = BLADE_TILES_BIND_DRAWN) writeonly buffer Drawn { Blade drawn[]; };
layout(std430, binding = BLADE_TILES_BIND_COMMAND) buffer Command {
    uint solid[4]; /* count, instanceCount, first, baseInstance */
    uint overflow;
    uint total;
    uint pad0, pad1;
    uint fade[4];
    uint culled[4];
} cmd;
layout(std430, binding = BLADE_TILES_BIND_DRAWN_IDS) writeonly buffer DrawnIds { uint drawn_ids[]; };

uniform uint u_count; /* entries * B */
uniform uint u_capacity;
uniform vec3 u_cam_pos;
uniform mat4 u_view_proj;
uniform float u_max_distance; /* u_lod_cull too */
uniform float u_orientation_threshold;
uniform float u_frustum_tolerance;
uniform uint u_disable;
uniform bool u_split;
uniform float u_fade_start;
uniform uint u_count_word; /* 1: instanceCount (pulled strips), 0: count (patches) */
/* Opaque window depth (blade_cull.comp's u_depth): the hardware path's
 * resolved depth, the compute path's farthest opaque sample. */
layout(binding = BLADE_TILES_TEX_DEPTH) uniform sampler2D u_depth;
uniform bool u_use_depth;
uniform float u_depth_bias;
/* Shared coverage map (blade_tiles_desc_t.extent): the billboards' rule. */
uniform bool u_extent_on;
layout(binding = BLADE_TILES_TEX_EXTENT) uniform sampler2D u_extent;
uniform vec2 u_extent_origin;
uniform float u_extent_spacing;
uniform uint u_extent_seed;

bool extent_keep(vec3 v0, uint id)
{
    ivec2 texel = extent_texel(u_extent, v0.xz, u_extent_origin, u_extent_spacing);
    uint e = uint(texelFetch(u_extent, texel, 0).r * 255.0 + 0.5);
    return hash_u32(id ^ hash_u32(u_extent_seed ^ 0x5bd1e995u)) % 255u < e;
}

/* The blade's ground vector from the camera (v0 - camera without its part
 * along up): the orientation test. The distance test and the thinning read
 * the hybrid's switch distance (grass_distance) instead of eq. 19's
 * d_proj, so the thinning ends where the fade and the tiles'
 * representation switch. */
vec3 ground_view(Blade b)
{
    vec3 view = b.v0.xyz - u_cam_pos;
    return view - b.up.xyz * dot(view, b.up.xyz);
}

/* Which test culls the blade (BLADE_CULL_*, VISIBLE when none); d: its
 * eye distance, lod: the thinning's weight and scale ((1, 1) without the
 * distance test). */
uint cull(Blade b, vec3 view_ground, float d, vec2 lod)
{
    vec3 v0 = b.v0.xyz;
    if ((u_disable & BLADE_CULL_ORIENTATION) == 0u) {
        vec3 width_dir, front;
        blade_frame(b, width_dir, front);
        float t = blade_lod_orientation(u_orientation_threshold, lod.x * lod.y);
        if (abs(dot(blade_safe_normalize(view_ground), width_dir)) > t) return BLADE_CULL_ORIENTATION;
    }
    vec4 c0 = u_view_proj * vec4(v0, 1.0);
    vec4 cm = u_view_proj * vec4(blade_midpoint(b), 1.0);
    vec4 c2 = u_view_proj * vec4(b.v2.xyz, 1.0);
    if ((u_disable & BLADE_CULL_FRUSTUM) == 0u) {
        float t = u_frustum_tolerance;
        if (!blade_in_frustum(c0, t) && !blade_in_frustum(cm, t) && !blade_in_frustum(c2, t))
            return BLADE_CULL_FRUSTUM;
    }
    if ((u_disable & BLADE_CULL_DISTANCE) == 0u && (d > u_max_distance || lod.x <= 0.0)) return BLADE_CULL_DISTANCE;
    if (u_use_depth && (u_disable & BLADE_CULL_OCCLUSION) == 0u) {
        float bias = u_depth_bias;
        if (blade_occluded(u_depth, c0, bias) && blade_occluded(u_depth, cm, bias) &&
            blade_occluded(u_depth, c2, bias))
            return BLADE_CULL_OCCLUSION;
    }
    return BLADE_CULL_VISIBLE;
}

/* The culled counts are summed per workgroup (blade/cull_counts.glsl).
 * With u_group_append (the compute rasterizer's cull) the survivors'
 * places are taken per workgroup too: in invocation order (a prefix sum
 * over the workgroup), one atomic per list and workgroup. The hardware
 * draw keeps one atomic per blade, taken before the workgroup's barrier:
 * its blades then lie in the order their warps reached the counter, and
 * drawn in that order they cost the H200 0.5 ms less on meadow_large than
 * grouped by workgroup. */
#define CULL_GROUP 256u
uniform bool u_group_append;
shared uint s_scan[CULL_GROUP]; /* solid | fade << 16, inclusive prefix sums */
shared uint s_solid, s_fade, s_solid_base, s_fade_base, s_kept;

/* Blade i's state and id; false when it is culled (counted in s_culled)
 * or thinned away by the extent map. */
bool survives(uint i, out Blade b, out uint id, out float d)
{
    uvec2 e = list[i / u_template_blades];
    uint k = i % u_template_blades;
    id = e.x * u_template_blades + k;
    d = 0.0;
    if (e.y != TILES_NO_SLOT) {
        b = pool[e.y * u_template_blades + k];
    } else {
        b = tiles_rest(e.x, k);
        if (b.v1.w <= 0.0) return false;
        b = tiles_pose(b);
    }
    if (b.v1.w <= 0.0) return false;
    vec3 view_ground = ground_view(b);
    d = grass_distance(b.v0.xyz, u_cam_pos);
    vec2 lod = vec2(1.0);
    if ((u_disable & BLADE_CULL_DISTANCE) == 0u && d <= u_max_distance) lod = lod_blade(k, d, b.v2.w);
    uint why = cull(b, view_ground, d, lod);
    if (why != BLADE_CULL_VISIBLE) {
        cull_counts_add(why);
        return false;
    }
    if (u_extent_on && !extent_keep(b.v0.xyz, id)) return false;
    b.v2.w *= lod.x * lod.y;
    return true;
}

/* Blade b's place in `drawn` taken alone, one atomic per blade; false
 * past the capacity. */
bool place_alone(bool fade, out uint slot)
{
    slot = 0u;
    if (atomicAdd(cmd.total, 1u) >= u_capacity) {
        atomicAdd(cmd.overflow, 1u);
        return false;
    }
    slot = fade ? u_capacity - 1u - atomicAdd(cmd.fade[u_count_word], 1u) : atomicAdd(cmd.solid[u_count_word], 1u);
    return true;
}

/* The workgroup's survivors placed together (u_group_append); false for
 * this invocation's blade when it is not live or past the capacity. */
bool place_grouped(bool live, bool fade, out uint slot)
{
    uint li = gl_LocalInvocationIndex;
    uint mine = live ? (fade ? 1u << 16 : 1u) : 0u;
    s_scan[li] = mine;
    barrier();
    for (uint o = 1u; o < CULL_GROUP; o <<= 1) {
        uint add = li >= o ? s_scan[li - o] : 0u;
        barrier();
        s_scan[li] += add;
        barrier();
    }
    uint before = s_scan[li] - mine, all = s_scan[CULL_GROUP - 1u];
    uint survivors = (all & 0xffffu) + (all >> 16), j = (before & 0xffffu) + (before >> 16);
    if (li == 0u) {
        uint base = survivors > 0u ? atomicAdd(cmd.total, survivors) : 0u;
        s_kept = min(base < u_capacity ? u_capacity - base : 0u, survivors);
        if (survivors > s_kept) atomicAdd(cmd.overflow, survivors - s_kept);
    }
    barrier();
    /* the kept survivors are the first s_kept in order, so a kept blade's
     * place among its list's kept blades is its prefix, and the last kept
     * one's inclusive prefix counts the kept blades of each list */
    bool kept = live && j < s_kept;
    if (kept && j + 1u == s_kept) {
        s_solid = s_scan[li] & 0xffffu;
        s_fade = s_scan[li] >> 16;
    }
    barrier();
    if (li == 0u) {
        s_solid_base = s_solid > 0u ? atomicAdd(cmd.solid[u_count_word], s_solid) : 0u;
        s_fade_base = s_fade > 0u ? atomicAdd(cmd.fade[u_count_word], s_fade) : 0u;
    }
    barrier();
    slot = fade ? u_capacity - 1u - (s_fade_base + (before >> 16)) : s_solid_base + (before & 0xffffu);
    return kept;
}

void main()
{
    uint li = gl_LocalInvocationIndex;
    cull_counts_clear();
    if (li == 0u) s_solid = s_fade = 0u;
    barrier();
    Blade b;
    uint id = 0u, slot = 0u;
    float d = 0.0;
    bool live = gl_GlobalInvocationID.x < u_count && survives(gl_GlobalInvocationID.x, b, id, d);
    bool fade = live && u_split && d > u_fade_start;
    if (!u_group_append) live = live && place_alone(fade, slot);
    barrier();
    uint mine = cull_counts_mine();
    if (mine > 0u) atomicAdd(cmd.culled[li], mine);
    if (u_group_append) live = place_grouped(live, fade, slot);
    if (!live) return;
    drawn[slot] = b;
    drawn_ids[slot] = id;
}

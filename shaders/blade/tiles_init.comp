#version 450
/* tiles_init.comp: initialises the pool slots of newly activated tiles
 * (Fan et al. 2015 activation) with the procedural pose of
 * tiles_common.glsl at the current time, eta = 0, so a tile switching from
 * template drawing to simulation does not pop. Invocation i: entry
 * list[i / B] = (slot, tile), blade i % B (B = u_template_blades).
 *
 * A tile flagged for seeding (bit 31 of the tile) takes the billboards'
 * deformation instead (billboards -> blades hand-over, hybrid_slope.h): of
 * its slope cell as the billboards draw it (weight w of eq. 8 since the
 * cell was written, R = u_slope_recover) and the mean of the deformed
 * billboards rooted in the cell right now (Bb sums, weight 1, eta 0), the
 * one with the larger weighted magnitude sets the blade's direction
 * (slope_apply with the blade's front as fallback), v2 = v0 + L d' with L
 * the pose's |v2 - v0|, validated by eq. 9-13, and eta = w * cell eta. */
#include "blade/tiles_common.glsl"
#include "common/slope.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = BLADE_TILES_BIND_POOL) writeonly buffer Pool { Blade pool[]; };
layout(std430, binding = BLADE_TILES_BIND_ETA) writeonly buffer Eta { float eta[]; };
layout(std430, binding = BLADE_TILES_BIND_LIST) readonly buffer List { uvec2 list[]; };
layout(std430, binding = HYBRID_BIND_SLOPE_MAP) readonly buffer Map { SlopeCell cells[]; };
layout(std430, binding = HYBRID_BIND_SLOPE_BB_SUMS) readonly buffer BbSums { SlopeSum bb_sums[]; };

uniform uint u_count; /* entries * B */
uniform float u_slope_recover;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    uvec2 e = list[i / u_template_blades];
    uint k = i % u_template_blades;
    uint idx = e.x * u_template_blades + k;
    uint tile = e.y & 0x7fffffffu;
    Blade b = tiles_pose(tiles_rest(tile, k));
    float eta0 = 0.0;
    int c = slope_cell_at(b.v0.xz);
    if ((e.y & 0x80000000u) != 0u && b.v1.w > 0.0 && c >= 0) {
        SlopeCell m = cells[c];
        float w = m.b.y > 0.0 ? slope_weight(u_time - m.b.x, u_slope_recover) : 0.0;
        vec4 cell = vec4(m.a.xyz, 0.0);
        SlopeSum s = bb_sums[c];
        if (s.b.x > 0u) {
            vec4 bb = vec4(s.a) * (1.0 / (float(s.b.x) * SLOPE_FIXED));
            if (bb.z > w * m.a.z) {
                cell = vec4(bb.xyz, 0.0);
                w = 1.0;
                m.a.w = 0.0;
            }
        }
        vec3 width_dir, front;
        blade_frame(b, width_dir, front);
        vec2 f = length(front.xz) > 1e-6 ? normalize(front.xz) : vec2(1.0, 0.0);
        vec3 d = b.v2.xyz - b.v0.xyz;
        float len = length(d);
        vec3 dn = slope_apply(blade_safe_normalize(d), f, cell, w);
        b.v2.xyz = b.v0.xyz + len * dn;
        blade_validate(b, u_length_mode);
        eta0 = w * m.a.w;
    }
    pool[idx] = b;
    eta[idx] = eta0;
}

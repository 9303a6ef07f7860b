#version 450
/* tiles_draw.vert: vertex pulling of the blades appended by
 * tiles_cull.comp: one instance per blade, a triangle strip of
 * 2 (u_max_level + 1) vertices per column (2 columns with the eq. 23
 * displacement, blade_strip_uv) built by blade_geom.glsl (Jahrmann & Wimmer
 * 2017 eq. 21, 23, 24), as blade_pull.vert. With u_from_end instance i
 * is blade u_capacity - 1 - i (the fade list, tiles_cull.comp). The
 * debug overlays (blade_tiles_set_overlay) tint blades by tile state, level
 * of detail or collision strength. */
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "common/switch.glsl"
#include "blade/blade_geom.glsl"

layout(std430, binding = BLADE_TILES_BIND_DRAWN) readonly buffer Drawn { Blade drawn[]; };
layout(std430, binding = BLADE_TILES_BIND_DRAWN_IDS) readonly buffer DrawnIds { uint drawn_ids[]; };
layout(std430, binding = BLADE_TILES_BIND_TILE_INFO) readonly buffer TileInfo { uint tile_info[]; }; /* state | slot << 2 */
layout(std430, binding = BLADE_TILES_BIND_DRAW_ETA) readonly buffer Eta { float eta[]; };

uniform mat4 u_view_proj;
uniform uint u_capacity;
uniform bool u_from_end;
uniform uint u_template_blades;
uniform int u_overlay; /* BLADE_TILES_OVERLAY_*: 0 off, 1 tile state, 2 LOD, 3 eta */

out vec3 f_pos;
out vec3 f_normal;
out float f_v;
out flat float f_root_dist;
out flat vec4 f_overlay; /* rgb over the shaded colour with weight a */

vec4 overlay(uint index, int lod)
{
    if (u_overlay == 0) return vec4(0.0);
    uint id = drawn_ids[index];
    uint info = tile_info[id / u_template_blades];
    uint state = info & 3u, slot = info >> 2;
    if (u_overlay == 1)
        return state == 1u ? vec4(1.0, 0.1, 0.1, 0.75) : (state == 2u ? vec4(1.0, 0.85, 0.1, 0.75) : vec4(0.0));
    if (u_overlay == 2) {
        float l = float(lod) / float(max(u_max_level, 1));
        return vec4(l, 1.0 - abs(2.0 * l - 1.0), 1.0 - l, 0.75);
    }
    float e = slot == 0xffffu ? 0.0 : eta[slot * u_template_blades + id % u_template_blades];
    return vec4(1.0, 1.0 - e, 1.0 - e, 0.8);
}

void main()
{
    uint index = u_from_end ? u_capacity - 1u - uint(gl_InstanceID) : uint(gl_InstanceID);
    Blade b = drawn[index];
    int n = blade_lod(b);
    vec2 uv = blade_strip_uv(gl_VertexID, n);
    float v = uv.y;
    vec3 p, nrm;
    blade_build(b, uv.x, v, p, nrm);
    f_pos = p;
    f_normal = nrm;
    f_v = v;
    f_root_dist = grass_distance(b.v0.xyz, u_camera);
    f_overlay = overlay(index, n);
    gl_Position = u_view_proj * vec4(p, 1.0);
}

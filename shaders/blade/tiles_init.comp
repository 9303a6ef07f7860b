#version 450
/* tiles_init.comp: initialises the pool slots of newly activated tiles
 * (Fan et al. 2015 activation) with the procedural pose of
 * tiles_common.glsl at the current time, eta = 0, so a tile switching from
 * template drawing to simulation does not pop. Invocation i: entry
 * list[i / B] = (slot, tile), blade i % B (B = u_template_blades). */
#include "blade/tiles_common.glsl"

layout(local_size_x = 256) in;

layout(std430, binding = 1) writeonly buffer Pool { Blade pool[]; };
layout(std430, binding = 2) writeonly buffer Eta { float eta[]; };
layout(std430, binding = 6) readonly buffer List { uvec2 list[]; };

uniform uint u_count; /* entries * B */

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    uvec2 e = list[i / u_template_blades];
    uint k = i % u_template_blades;
    uint idx = e.x * u_template_blades + k;
    pool[idx] = tiles_pose(tiles_rest(e.y, k));
    eta[idx] = 0.0;
}

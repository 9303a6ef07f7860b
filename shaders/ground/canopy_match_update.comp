#version 450
/* canopy_match_update.comp: one step of the canopy match (ground.c; its C
 * twin ground_match_step): where both sides of canopy_match.comp counted
 * at least u_min_pixels, the gain moves by the ratio of the frame's mean to
 * the canopy's (of the fixed-point sums, + 1) to the power u_rate per
 * channel, within [u_range.x, u_range.y]; then the sums start again. */
#include "common/bindings_ground.glsl"
#include "ground/canopy_match.glsl"

layout(local_size_x = 1) in;

uniform uint u_min_pixels;
uniform float u_rate;
uniform vec2 u_range;

void main()
{
    if (frame_sum.a >= u_min_pixels && ref_sum.a >= u_min_pixels) {
        vec3 f = vec3(frame_sum.rgb) / float(frame_sum.a), r = vec3(ref_sum.rgb) / float(ref_sum.a);
        gain.rgb = clamp(gain.rgb * pow((f + 1.0) / (r + 1.0), vec3(u_rate)), u_range.x, u_range.y);
    }
    frame_sum = uvec4(0u);
    ref_sum = uvec4(0u);
}

/* canopy_match.glsl: the canopy match's state as its two passes
 * (canopy_match.comp, canopy_match_update.comp) share it, the layout of
 * ground_match_state_t (src/ground/ground_match.h): the gain (rgb, a factor
 * on the canopy's stored colour), then one frame's sums per side, rgb in
 * fixed point (GROUND_MATCH_FIXED per unit of linear light) and the
 * pixels counted. */
#ifndef CANOPY_MATCH_GLSL
#define CANOPY_MATCH_GLSL

#include "common/bindings_ground.glsl"

layout(std430, binding = GROUND_BIND_MATCH) buffer Match
{
    vec4 gain;
    uvec4 frame_sum; /* the frame's grass pixels */
    uvec4 ref_sum;   /* the canopy's */
};

#endif

#version 450
/* bb_point.vert: passes one stored billboard (bb_point_t, see the attribute
 * table in common/bb.glsl) to the collision, recovery and render geometry
 * shaders of Orthmann et al. 2009. */
layout(location = 0) in vec4 a_pos_angle;
layout(location = 1) in vec4 a_growth_mess;
layout(location = 2) in vec2 a_size;
layout(location = 3) in uvec2 a_layer_state;
layout(location = 4) in float a_recover;
layout(location = 5) in uint a_seed;
layout(location = 6) in uvec2 a_pad;

out vec4 v_pos_angle;
out vec4 v_growth_mess;
out vec2 v_size;
flat out uvec2 v_layer_state;
out float v_recover;
flat out uint v_seed;
flat out uvec2 v_pad;

void main()
{
    v_pos_angle = a_pos_angle;
    v_growth_mess = a_growth_mess;
    v_size = a_size;
    v_layer_state = a_layer_state;
    v_recover = a_recover;
    v_seed = a_seed;
    v_pad = a_pad;
}

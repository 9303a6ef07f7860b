// terrain.frag: the terrain's colour (ground/terrain_ground.glsl's
// terrain_shade): soil and short-grass ground colour, lit like the grass;
// in the hybrid, beyond the billboards, the ground canopy (common/canopy.glsl,
// its colour per vertex: ground/terrain_canopy.glsl):
// the ground's colour mixed with the canopy's by its cover, thinned by the
// extent map as the blades and billboards are, faded in over
// u_canopy_fade (start, end of the switch distance; end <= 0: no band); and
// nearer, under blades thinned with distance (common/lod.glsl), the ground
// mixed towards the canopy by the share of it the removed blades covered
// (canopy_under), so blades and ground keep the full field's mean colour.
// Where the canopy continues the tiles' blades (u_canopy_switch, no
// billboards between), one rule does both and the fade: the canopy stands
// for the blades not drawn, under the overhang of those drawn before the
// switch (canopy_overhang of the whole column and the cut one).
// Ground and canopy take the global illumination's ambient light per
// fragment when it is on (common/gi.glsl; the canopy per vertex, its table
// taking any ambient linear in the blade normals: ground/terrain_canopy.glsl).
#version 450 core
#include "ground/terrain_ground.glsl"
in vec3 v_pos;
in vec3 v_normal;
in vec4 v_canopy; /* the canopy's colour and cover, per vertex (ground/terrain_canopy.glsl) */
in vec4 v_canopy_cut; /* the same below the overhang's cut (terrain_canopy's cut) */
out vec4 o_color;

void main()
{
    o_color = vec4(terrain_shade(v_pos, normalize(v_normal), v_canopy, v_canopy_cut, false), 1.0);
}

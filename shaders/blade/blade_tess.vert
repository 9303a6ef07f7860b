#version 450
/* blade_tess.vert: tessellation path, one patch vertex per surviving blade
 * (Jahrmann & Wimmer 2017 sec. 6.3): passes the blade index and its width
 * factor (the thinning's weight * scale) from the survivor list written by
 * blade_cull.comp to the control shader. */
#include "common/bindings_blade.glsl"

layout(std430, binding = BLADE_BIND_SURVIVORS) readonly buffer Survivors { uvec2 survivors[]; };

out flat uint vs_blade;
out flat float vs_width;

void main()
{
    uvec2 s = survivors[gl_VertexID];
    vs_blade = s.x;
    vs_width = uintBitsToFloat(s.y);
}

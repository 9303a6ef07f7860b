#version 450
/* blade_tess.vert: tessellation path, one patch vertex per surviving blade
 * (Jahrmann & Wimmer 2017 sec. 6.3): passes the blade index from the
 * survivor list written by blade_cull.comp to the control shader. */
#include "common/bindings_blade.glsl"

layout(std430, binding = BLADE_BIND_SURVIVORS) readonly buffer Survivors { uint survivors[]; };

out flat uint vs_blade;

void main()
{
    vs_blade = survivors[gl_VertexID];
}

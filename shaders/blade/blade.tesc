#version 450
/* blade.tesc: tessellation level by distance (Jahrmann & Wimmer 2017
 * sec. 6.3): quads domain, u across the width (1 segment, 2 with the eq. 23
 * displacement so the raised midrib u = 0.5 has vertices), v along the
 * blade (blade_lod segments, the same count the vertex-pulling path uses).
 * The blade's width factor (the thinning's, blade_tess.vert) goes on to
 * the evaluation shader. */
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "blade/blade_geom.glsl"

layout(vertices = 1) out;
layout(std430, binding = BLADE_BIND_BLADES) readonly buffer Blades { Blade blades[]; };

in flat uint vs_blade[];
in flat float vs_width[];
patch out uint tc_blade;
patch out float tc_width;

void main()
{
    uint i = vs_blade[gl_InvocationID];
    tc_blade = i;
    tc_width = vs_width[gl_InvocationID];
    float n = float(blade_lod(blades[i]));
    float across = float(blade_columns());
    gl_TessLevelOuter[0] = n;
    gl_TessLevelOuter[1] = across;
    gl_TessLevelOuter[2] = n;
    gl_TessLevelOuter[3] = across;
    gl_TessLevelInner[0] = across;
    gl_TessLevelInner[1] = n;
}

#version 450
/* tiles_tess.vert: tessellation path of the tiled field (Jahrmann & Wimmer
 * 2017 sec. 6.3): one patch vertex per blade appended by tiles_cull.comp,
 * passing its index in `drawn` (bound as blade.tesc's and blade.tese's
 * Blades) to the control shader. With u_from_end vertex i is blade
 * u_capacity - 1 - i (the fade list), as tiles_draw.vert. Its width
 * factor is 1: tiles_cull.comp wrote the drawn width into the blade. */
uniform uint u_capacity;
uniform bool u_from_end;

out flat uint vs_blade;
out flat float vs_width;

void main()
{
    vs_blade = u_from_end ? u_capacity - 1u - uint(gl_VertexID) : uint(gl_VertexID);
    vs_width = 1.0;
}

#version 450
/* bb_tile.vert: one point per tile of candidate cells (attribute-less draw)
 * for the billboard generation geometry shader (Orthmann et al. 2009, sec. 3). */
flat out int v_tile;

void main()
{
    v_tile = gl_VertexID;
}

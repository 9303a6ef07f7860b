#version 450
/* bb_ring.vert: one point per generation tile of a billboard ring cell
 * (attribute-less draw, src/billboard/bb_ring.c) for bb_ring.geom: the
 * vertex index is the tile. */
flat out int v_tile;

void main() { v_tile = gl_VertexID; }

/* bb_gen_leaves.glsl: the entries of one billboard generation draw, in
 * Morton order of their leaves (twin: bb_gen_entry_t in src/billboard/bb.c):
 * one per leaf on a heightfield, one per (leaf, triangle) pair on a mesh
 * terrain. */
#include "common/bindings_billboard.glsl"
struct bb_gen_entry {
    ivec4 cells;  /* candidate cells [x0, z0] .. (x1, z1) of the leaf (mesh
                     terrains: [i0, j0] .. (i1, j1) of triangle tri) */
    int tiles_x;  /* tiles per row of the footprint */
    uint leaf;    /* Morton index */
    uint first;   /* first vertex (tile) of the entry in the draw */
    uint tri;     /* mesh terrains: the triangle (index into tris[]); else 0 */
};

layout(std430, binding = BB_BIND_GEN_ENTRIES) readonly buffer GenEntries { bb_gen_entry entries[]; };
uniform int u_entry_count;

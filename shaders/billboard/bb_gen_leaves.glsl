/* bb_gen_leaves.glsl: the leaves of one billboard generation draw, in
 * Morton order (twin: bb_gen_entry_t in src/billboard/bb.c). */
struct bb_gen_entry {
    ivec4 cells;  /* candidate cells [x0, z0] .. (x1, z1) of the leaf */
    int tiles_x;  /* tiles per row of the footprint */
    uint leaf;    /* Morton index */
    uint first;   /* first vertex (tile) of the leaf in the draw */
    uint pad;
};

layout(std430, binding = 1) readonly buffer GenEntries { bb_gen_entry entries[]; };
uniform int u_entry_count;

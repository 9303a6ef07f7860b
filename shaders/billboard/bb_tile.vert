#version 450
/* bb_tile.vert: one point per tile of candidate cells (attribute-less draw)
 * for the billboard generation geometry shader (Orthmann et al. 2009, sec. 3).
 * One draw covers every octree leaf: the leaves' tiles follow each other in
 * Morton order, and a binary search over their first vertices finds the
 * leaf of this vertex. */
#include "billboard/bb_gen_leaves.glsl"

flat out int v_tile;  /* tile within the leaf's footprint */
flat out int v_entry; /* index into entries[] */

void main()
{
    int lo = 0, hi = u_entry_count - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (entries[mid].first <= uint(gl_VertexID)) lo = mid;
        else hi = mid - 1;
    }
    v_entry = lo;
    v_tile = gl_VertexID - int(entries[lo].first);
}

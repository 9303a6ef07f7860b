#version 450
/* bb_generate.geom: billboard generation of Orthmann et al. 2009 (sec. 3,
 * layout textures). One invocation per tile of BB_TILE x BB_TILE candidate
 * cells of an octree leaf's footprint (entries[v_entry[0]]); emits one point
 * per accepted candidate (bb_generate, twin of bb_layout_sample) whose root,
 * placed on the terrain height texture, lies in that leaf. With
 * BB_GEN_TRIANGLES (mesh terrains) an entry is a (leaf, triangle) pair and
 * its cells are the triangle's own candidates (bb_generate_tri, twin of
 * bb_layout_sample_tri), whose roots lie on the triangle. The entries'
 * tiles follow each other in Morton order of their leaves in one draw, and
 * transform feedback keeps primitive order, so the buffer is ordered by
 * leaf; the per-leaf count goes to an SSBO with atomics. */
#include "common/hash.glsl"
#include "common/bindings_billboard.glsl"
#include "billboard/bb_ground.glsl"
#include "common/bb.glsl"
#define BB_POINTS_OUT
#include "billboard/bb_points.glsl"
#include "billboard/bb_gen_leaves.glsl"

layout(points) in;
layout(points, max_vertices = BB_TILE_POINTS) out;

flat in int v_tile[];
flat in int v_entry[];

layout(binding = BB_TEX_EXTENT) uniform sampler2D u_extent;
layout(binding = BB_TEX_DIRECTION) uniform sampler2D u_direction;
layout(binding = BB_TEX_MESSINESS) uniform sampler2D u_messiness;
uniform bb_gen u_gen;
uniform vec3 u_tree_min;
uniform vec3 u_tree_max;
uniform int u_side;

layout(std430, binding = BB_BIND_LEAF_COUNTS) buffer LeafCounts { uint leaf_count[]; };
#ifdef BB_GEN_TRIANGLES
layout(std430, binding = BB_BIND_GEN_TRIS) readonly buffer GenTris { bb_gen_tri tris[]; };
#endif

/* Twin of bb_leaf_coord / bb_leaf_of in src/billboard/bb_octree.c. */
uint leaf_of(vec3 p)
{
    uint m = 0u;
    for (int a = 0; a < 3; a++) {
        float f = (p[a] - u_tree_min[a]) / (u_tree_max[a] - u_tree_min[a]) * float(u_side);
        int c = int(floor(f));
        if (!(f >= 0.0)) c = 0;
        else if (c >= u_side) c = u_side - 1;
        uint r = 0u;
        for (int b = 0; b < 6; b++) r |= ((uint(c) >> b) & 1u) << (3 * b);
        m |= r << a;
    }
    return m;
}

void main()
{
    bb_gen_entry e = entries[v_entry[0]];
    int tx = v_tile[0] % e.tiles_x, tz = v_tile[0] / e.tiles_x;
#ifdef BB_GEN_TRIANGLES
    bb_gen_tri tri = tris[e.tri];
#endif
    for (int dz = 0; dz < BB_TILE; dz++) {
        for (int dx = 0; dx < BB_TILE; dx++) {
            int ix = e.cells.x + tx * BB_TILE + dx, iz = e.cells.y + tz * BB_TILE + dz;
            if (ix >= e.cells.z || iz >= e.cells.w) continue;
            bb_point p;
#ifdef BB_GEN_TRIANGLES
            if (!bb_generate_tri(u_extent, u_direction, u_messiness, u_gen, tri, e.tri, ix, iz, p)) continue;
#else
            if (!bb_generate(u_extent, u_direction, u_messiness, u_gen, ix, iz, p)) continue;
            if (p.position.x > u_tree_max.x || p.position.z > u_tree_max.z) continue;
            float y = terrain_height(p.position.x, p.position.z);
            if (y < -1e37) continue;
            p.position.y = y;
#endif
            if (leaf_of(p.position) != e.leaf) continue;
            p.pad0 = BB_NO_SLOT;
            atomicAdd(leaf_count[e.leaf], 1u);
            bb_emit_point(p);
        }
    }
}

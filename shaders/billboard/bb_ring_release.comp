#version 450
/* bb_ring_release.comp: a billboard ring cell that leaves the window while
 * its billboards are deformed (src/billboard/bb_ring.c) gives their
 * deformed-mesh slots back to the pool before the entering cell is
 * generated over it: one thread per point of the slot's range
 * [u_first, u_first + u_count); a point holding a mesh slot (pad0) pushes
 * it on the free stack (bb_pool.glsl, as bb_recover.comp does) and turns
 * plain. The cell's deformation is dropped, not kept. */
#define BB_NO_GENERATE
#include "common/bindings_billboard.glsl"
#include "common/bb.glsl"
#include "billboard/bb_points.glsl"
#include "billboard/bb_pool.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BB_BIND_POINTS) buffer Points { bb_point points[]; };
uniform uint u_first;
uniform uint u_count;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    uint slot = points[u_first + i].pad0;
    if (slot == BB_NO_SLOT) return;
    int top = atomicAdd(free_top, 1);
    free_stack[top] = slot;
    points[u_first + i].pad0 = BB_NO_SLOT;
    points[u_first + i].state = BB_STATE_IDLE;
}

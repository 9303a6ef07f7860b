/* bb_pool.glsl: the fixed pool of deformed billboard meshes (Orthmann et al.
 * 2009 keep the refined N x M mesh of every colliding billboard). Slot s holds
 * BB_N*BB_M vertices (world space, w unused) at meshes[s*BB_N*BB_M + v]. Free
 * slots form a stack: the collision pass only pops, the recovery pass only
 * pushes, so one atomic per operation is enough. A pop on an empty stack is
 * undone and counted in `exhausted` (the CPU logs it). */
#ifndef BB_POOL_GLSL
#define BB_POOL_GLSL

#include "common/bindings_billboard.glsl"

layout(std430, binding = BB_BIND_POOL) buffer Pool {
    int free_top;
    uint exhausted;
    uint pad_a;
    uint pad_b;
    uint free_stack[];
};

layout(std430, binding = BB_BIND_MESHES) buffer Meshes { vec4 meshes[]; };

void bb_load_mesh(uint slot)
{
    for (int v = 0; v < BB_N * BB_M; v++) bb_pos[v] = meshes[int(slot) * BB_N * BB_M + v].xyz;
}

void bb_store_mesh(uint slot)
{
    for (int v = 0; v < BB_N * BB_M; v++) meshes[int(slot) * BB_N * BB_M + v] = vec4(bb_pos[v], 1.0);
}

#endif

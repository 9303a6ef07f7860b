#version 450
/* raster_args.comp: turns counts written on the GPU into
 * glDispatchComputeIndirect arguments. u_queue 0: ceil(min(src[u_src_index],
 * u_max) / u_group) work groups (surviving blades). u_queue 1: the queued
 * triangles of raster.glsl (src = its header): ceil(medium / u_group)
 * groups for the medium list and one per large triangle, each list at most
 * u_max. */
layout(local_size_x = 1) in;

#include "common/bindings_raster.glsl"

layout(std430, binding = RASTER_BIND_ARGS_SRC) readonly buffer Src { uint src[]; };
layout(std430, binding = RASTER_BIND_ARGS) writeonly buffer Args { uint args[]; };

uniform uint u_src_index;
uniform uint u_max;
uniform uint u_group;
uniform int u_queue;

void main()
{
    if (u_queue != 0) {
        args[0] = (min(src[2], u_max) + u_group - 1u) / u_group + min(src[0], u_max);
    } else {
        uint n = min(src[u_src_index], u_max);
        args[0] = (n + u_group - 1u) / u_group;
    }
    args[1] = 1u;
    args[2] = 1u;
}

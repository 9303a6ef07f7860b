#version 450
/* raster_args.comp: turns a count written on the GPU (surviving blades,
 * queued large triangles) into glDispatchComputeIndirect arguments:
 * ceil(min(count, u_max) / u_group) work groups. */
layout(local_size_x = 1) in;

layout(std430, binding = 0) readonly buffer Src { uint src[]; };
layout(std430, binding = 1) writeonly buffer Args { uint args[]; };

uniform uint u_src_index;
uniform uint u_max;
uniform uint u_group;

void main()
{
    uint n = min(src[u_src_index], u_max);
    args[0] = (n + u_group - 1u) / u_group;
    args[1] = 1u;
    args[2] = 1u;
}

#version 450
/* upload_copy.comp (test_gfx_upload): with u_iters > 0, one invocation
 * spins u_iters dependent steps so that the GPU falls behind the commands
 * queued after it; with u_iters = 0, copies the uploaded list into row
 * u_row of the output, as a queued dispatch reads a list the CPU uploaded
 * just before it. */
layout(local_size_x = 64) in;
#include "common/bindings_tests.glsl"

layout(std430, binding = TEST_BIND_IN) readonly buffer Src { uint src[]; };
layout(std430, binding = TEST_BIND_OUT) buffer Out { uint result[]; };

uniform uint u_iters;
uniform uint u_row;
uniform uint u_len;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (u_iters > 0u) {
        if (i != 0u) return;
        uint h = result[0];
        for (uint k = 0u; k < u_iters; k++) h = (h ^ (h >> 13u)) * 1664525u + k;
        result[0] = h;
        return;
    }
    if (i < u_len) result[1u + u_row * u_len + i] = src[i];
}

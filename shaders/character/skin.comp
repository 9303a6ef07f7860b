// skin.comp: linear blend skinning of a character, p' = (sum_i w_i S_i) p,
// n' = normalize(mat3(sum_i w_i S_i) n), with S_i = global_i * inverse_bind_i
// (the GPU twin of character_skin_cpu in src/character/character_ref.c).
// One invocation per vertex; output in model space, laid out for a VAO:
// vec4 position (w = 1), vec4 normal (w = 0), 32 bytes per vertex.
#version 450 core
layout(local_size_x = 64) in;
#include "common/bindings_character.glsl"

// character_vertex_t (56 bytes = 14 words): pos[3], normal[3], uv[2],
// uint16 joints[4] (2 words), weights[4]. Read as words so the packed
// joints are never reinterpreted as floats.
layout(std430, binding = CHARACTER_BIND_VERTICES) readonly buffer BindVertices { uint bind_words[]; };
layout(std430, binding = CHARACTER_BIND_BONES) readonly buffer Bones { mat4 skin[]; };
struct SkinnedVertex {
    vec4 pos;
    vec4 normal;
};
layout(std430, binding = CHARACTER_BIND_SKINNED) writeonly buffer Skinned { SkinnedVertex skinned[]; };

uniform uint u_vertex_count;

float word(uint i) { return uintBitsToFloat(bind_words[i]); }

void main()
{
    uint v = gl_GlobalInvocationID.x;
    if (v >= u_vertex_count) return;
    uint b = v * 14u;
    vec3 p = vec3(word(b), word(b + 1u), word(b + 2u));
    vec3 n = vec3(word(b + 3u), word(b + 4u), word(b + 5u));
    uint j01 = bind_words[b + 8u], j23 = bind_words[b + 9u];
    uint joints[4] = uint[4](j01 & 0xffffu, j01 >> 16, j23 & 0xffffu, j23 >> 16);
    mat4 m = mat4(0.0);
    for (uint k = 0u; k < 4u; k++) {
        float w = word(b + 10u + k);
        if (w != 0.0) m += w * skin[joints[k]];
    }
    vec3 nn = mat3(m) * n;
    float len = length(nn);
    skinned[v].pos = vec4((m * vec4(p, 1.0)).xyz, 1.0);
    skinned[v].normal = vec4(len > 0.0 ? nn / len : nn, 0.0);
}

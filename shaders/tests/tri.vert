// tri.vert: one attribute-less triangle covering the lower-left half.
#version 450 core
#include "tests/ok_include.glsl"
void main()
{
    vec2 p[3] = vec2[](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(-1.0, 1.0));
    gl_Position = vec4(p[gl_VertexID] * TEST_INCLUDED, 0.0, 1.0);
}

// broken.frag: deliberately fails to compile on line 7 (test_gfx_smoke
// checks that the error names this file and line).
#version 450 core
#include "tests/ok_include.glsl"
out vec4 o_color;
void main() {
    o_color = vec4(undeclared_symbol, 1.0);
}

// text.vert: HUD glyph quads in pixels (top-left origin) to clip space.
#version 450 core
layout(location = 0) in vec2 a_pos;
uniform vec2 u_viewport;
void main()
{
    vec2 ndc = a_pos / u_viewport * 2.0 - 1.0;
    gl_Position = vec4(ndc.x, -ndc.y, 0.0, 1.0);
}

// floor.vert: trivial pass-through for the hardware-floor measurement.
#version 450 core
layout(location = 0) in vec4 a_pos;
void main() { gl_Position = a_pos; }

// floor.frag: constant colour for the hardware-floor measurement.
#version 450 core
out vec4 o_color;
void main() { o_color = vec4(0.2, 0.6, 0.1, 1.0); }

// sky.frag: horizon-to-zenith gradient from the view ray.
#version 450 core
#include "common/lighting.glsl"
in vec2 v_ndc;
uniform mat4 u_inv_viewproj;
out vec4 o_color;
void main()
{
    vec4 a = u_inv_viewproj * vec4(v_ndc, -1.0, 1.0);
    vec4 b = u_inv_viewproj * vec4(v_ndc, 1.0, 1.0);
    vec3 dir = normalize(b.xyz / b.w - a.xyz / a.w);
    o_color = vec4(sky_color(dir), 1.0);
}

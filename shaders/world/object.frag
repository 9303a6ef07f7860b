// object.frag: lit solid-colour objects.
#version 450 core
#include "common/lighting.glsl"
in vec3 v_pos;
in vec3 v_normal;
uniform vec3 u_sun;
uniform vec3 u_camera;
uniform vec3 u_albedo;
out vec4 o_color;
void main()
{
    vec3 c = shade(u_albedo, normalize(v_normal), u_sun, 1.0);
    vec3 to_frag = v_pos - u_camera;
    o_color = vec4(apply_fog(c, length(to_frag), normalize(to_frag)), 1.0);
}

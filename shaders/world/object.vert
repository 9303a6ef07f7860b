// object.vert: rigid objects (analytic colliders) with a model matrix.
#version 450 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
uniform mat4 u_viewproj;
uniform mat4 u_model;
out vec3 v_pos;
out vec3 v_normal;
void main()
{
    vec4 w = u_model * vec4(a_pos, 1.0);
    v_pos = w.xyz;
    v_normal = mat3(u_model) * a_normal;
    gl_Position = u_viewproj * w;
}

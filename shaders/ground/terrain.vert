// terrain.vert: terrain mesh positions to clip space.
#version 450 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;
uniform mat4 u_viewproj;
out vec3 v_pos;
out vec3 v_normal;
void main()
{
    v_pos = a_pos;
    v_normal = a_normal;
    gl_Position = u_viewproj * vec4(a_pos, 1.0);
}

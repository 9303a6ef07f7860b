// character.frag: characters lit like the rest of the meadow (lighting.glsl
// sun, sky ambient and fog); base colour times the diffuse texture when the
// model has one.
#version 450 core
#include "common/bindings_character.glsl"
#include "common/lighting.glsl"
in vec3 v_pos;
in vec3 v_normal;
in vec2 v_uv;
uniform vec3 u_sun;
uniform vec3 u_camera;
uniform vec4 u_base_color;
uniform bool u_use_texture;
layout(binding = CHARACTER_TEX_DIFFUSE) uniform sampler2D u_texture;
out vec4 o_color;
void main()
{
    vec3 albedo = u_base_color.rgb;
    if (u_use_texture) albedo *= texture(u_texture, v_uv).rgb;
    vec3 c = shade(albedo, normalize(v_normal), u_sun, 1.0);
    vec3 to_frag = v_pos - u_camera;
    o_color = vec4(apply_fog(c, length(to_frag), normalize(to_frag)), 1.0);
}

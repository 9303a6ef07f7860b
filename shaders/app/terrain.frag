// terrain.frag: soil and short-grass ground colour, lit like the grass.
#version 450 core
#include "common/lighting.glsl"
#include "common/hash.glsl"
in vec3 v_pos;
in vec3 v_normal;
uniform vec3 u_camera;
uniform vec3 u_sun;
out vec4 o_color;

float value_noise(vec2 p)
{
    vec2 i = floor(p), f = fract(p);
    vec2 u = f * f * (3.0 - 2.0 * f);
    float a = hash_float(uint(int(i.x) * 73856093) ^ uint(int(i.y) * 19349663));
    float b = hash_float(uint(int(i.x + 1.0) * 73856093) ^ uint(int(i.y) * 19349663));
    float c = hash_float(uint(int(i.x) * 73856093) ^ uint(int(i.y + 1.0) * 19349663));
    float d = hash_float(uint(int(i.x + 1.0) * 73856093) ^ uint(int(i.y + 1.0) * 19349663));
    return mix(mix(a, b, u.x), mix(c, d, u.x), u.y);
}

void main()
{
    vec3 n = normalize(v_normal);
    float noise = value_noise(v_pos.xz * 1.7) * 0.6 + value_noise(v_pos.xz * 7.3) * 0.4;
    vec3 soil = vec3(0.30, 0.24, 0.16);
    vec3 turf = vec3(0.20, 0.32, 0.10);
    vec3 albedo = mix(soil, turf, smoothstep(0.3, 0.7, noise));
    vec3 c = shade(albedo, n, u_sun, 1.0);
    vec3 to_frag = v_pos - u_camera;
    o_color = vec4(apply_fog(c, length(to_frag), normalize(to_frag)), 1.0);
}

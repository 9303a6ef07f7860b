#version 450
/* canopy_match.comp: what the canopy match compares (ground.c,
 * ground_match): over the pixels whose ground (the opaque depth the grass
 * was drawn over) lies in the seam measure's near window before the tiles'
 * switch band, the mean
 * linear-light colour of the frame's grass pixels, and that of the same
 * pixels with the ground shaded as the canopy from the camera on, as the
 * seam measure draws its reference (terrain_shade as canopy). A pixel counts as grass on a side
 * where it differs from the bare ground (the measure's background: the
 * ground drawn without grass or canopy) by more than 8/255 in a channel
 * (measure_seam_frame_classify's rule). Where the opaque surface stands
 * 0.15 m or more over the terrain, a collider or a character: left out, as
 * the measure leaves out what is not ground. The ground point is where the
 * pixel centre's ray meets the terrain as drawn (ground_hit), its normal
 * the terrain's there: a heightfield's vertex normals and heights
 * interpolated over the mesh's triangles (the tiles' ground texture,
 * common/heightfield.glsl), or the world's function (MATCH_WORLD). Each workgroup sums its pixels and adds them to
 * the match buffer in fixed point. On large targets a pixel in u_stride^2
 * stands for its block (1080 rows: 1 in 16; the window still holds about
 * 2,000 grass pixels on meadow_large). */
#include "common/bindings_ground.glsl"
#include "ground/canopy_match.glsl"
#include "common/switch.glsl"
#include "ground/terrain_ground.glsl"
#ifdef MATCH_WORLD
#include "common/world_height.glsl"
#else
#include "common/heightfield.glsl"
layout(binding = GROUND_TEX_MATCH_GRID) uniform sampler2D u_grid; /* the tiles' ground texture */
uniform int u_grid_res;
uniform float u_grid_half; /* the field's half side (m) */
#endif

layout(local_size_x = 8, local_size_y = 8) in;

#ifdef MATCH_MS
layout(binding = GROUND_TEX_MATCH_COLOR) uniform sampler2DMS u_color;
#else
layout(binding = GROUND_TEX_MATCH_COLOR) uniform sampler2D u_color;
#endif
layout(binding = GROUND_TEX_MATCH_DEPTH) uniform sampler2D u_depth; /* the opaque depth under the grass */
uniform int u_samples;
uniform int u_stride; /* every u_stride-th pixel of every u_stride-th row */
uniform mat4 u_inv_viewproj;
uniform vec2 u_window; /* the near window [x, y) of the ground's eye distance (m) */

shared vec4 s_sum[2][64]; /* the frame's, the canopy's */

/* The opaque surface at pixel p (w 0: the far plane or off the target). */
vec4 surface_at(ivec2 p, ivec2 size)
{
    if (any(lessThan(p, ivec2(0))) || any(greaterThanEqual(p, size))) return vec4(0.0);
    float z = texelFetch(u_depth, p, 0).r;
    if (z >= 1.0) return vec4(0.0);
    vec4 ndc = vec4((vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0, z * 2.0 - 1.0, 1.0);
    vec4 w = u_inv_viewproj * ndc;
    return vec4(w.xyz / w.w, 1.0);
}

/* The terrain at xz as drawn: (unit normal, height). */
vec4 ground_at(vec2 xz)
{
#ifdef MATCH_WORLD
    return vec4(world_normal(xz), world_height(xz));
#else
    vec4 r = heightfield_at(u_grid, u_grid_res, u_grid_half, xz);
    return vec4(normalize(r.xyz), r.w);
#endif
}

/* Where the ray through pixel p's centre meets the terrain, from g (the
 * terrain at one of p's depth samples, off the centre: at grazing views
 * metres away along the ground, where the soil's noise is another colour):
 * secant steps on the ray's height over the ground. */
vec3 ground_hit(vec3 g, ivec2 p, ivec2 size)
{
    vec4 far = u_inv_viewproj * vec4((vec2(p) + 0.5) / vec2(size) * 2.0 - 1.0, 1.0, 1.0);
    vec3 dir = normalize(far.xyz / far.w - u_camera);
    float t1 = dot(g - u_camera, dir), t0 = 0.98 * t1;
    float f0 = (u_camera + dir * t0).y - ground_at((u_camera + dir * t0).xz).w;
    float f1 = (u_camera + dir * t1).y - ground_at((u_camera + dir * t1).xz).w;
    for (int k = 0; k < 4 && abs(f1 - f0) > 1e-7; k++) {
        float t = t1 - f1 * (t1 - t0) / (f1 - f0);
        t0 = t1;
        f0 = f1;
        t1 = t;
        f1 = (u_camera + dir * t1).y - ground_at((u_camera + dir * t1).xz).w;
    }
    vec3 h = u_camera + dir * t1;
    return abs(f1) < 0.05 ? h : g;
}

vec3 frame_color(ivec2 p)
{
#ifdef MATCH_MS
    vec3 c = vec3(0.0);
    for (int s = 0; s < u_samples; s++) c += texelFetch(u_color, p, s).rgb;
    return c / float(u_samples);
#else
    return texelFetch(u_color, p, 0).rgb;
#endif
}

/* The sRGB transfer of the frames' 8-bit values (eval_srgb_to_linear): the
 * seam measure averages in linear light. */
vec3 srgb_to_linear(vec3 c)
{
    c = clamp(c, 0.0, 1.0);
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), greaterThan(c, vec3(0.04045)));
}

bool differs(vec3 a, vec3 b)
{
    return any(greaterThan(abs(a - b), vec3(8.0 / 255.0)));
}

void main()
{
    ivec2 size = textureSize(u_depth, 0);
    ivec2 p = ivec2(gl_GlobalInvocationID.xy) * u_stride;
    uint i = gl_LocalInvocationIndex;
    vec4 frame = vec4(0.0), ref = vec4(0.0);
    vec4 g = surface_at(p, size);
    float d = g.w > 0.0 ? grass_distance(g.xyz, u_camera) : 0.0;
    /* in the window, unless a collider or a character stands over the
     * ground there: not the measure's either (MEASURE_SEAM_GROUND_EPS, its
     * rule) */
    if (g.w > 0.0 && d >= u_window.x && d < u_window.y && g.y - ground_at(g.xz).w < 0.15) {
        vec3 q = ground_hit(g.xyz, p, size), n = ground_at(q.xz).xyz;
        vec4 cut;
        vec4 canopy = terrain_canopy(q, n, cut);
        vec3 to = q - u_camera, f = frame_color(p);
        vec3 bare = apply_fog(terrain_ground_color(q, n), length(to), normalize(to));
        vec3 r = terrain_shade(q, n, canopy, cut, true);
        if (differs(f, bare)) frame = vec4(srgb_to_linear(f), 1.0);
        if (differs(r, bare)) ref = vec4(srgb_to_linear(r), 1.0);
    }
    s_sum[0][i] = frame;
    s_sum[1][i] = ref;
    barrier();
    for (uint k = 32u; k > 0u; k >>= 1) {
        if (i < k) {
            s_sum[0][i] += s_sum[0][i + k];
            s_sum[1][i] += s_sum[1][i + k];
        }
        barrier();
    }
    if (i < 2u && s_sum[i][0].w > 0.0) {
        uvec3 v = uvec3(round(s_sum[i][0].rgb * float(GROUND_MATCH_FIXED)));
        uint a = uint(s_sum[i][0].w);
        if (i == 0u) {
            atomicAdd(frame_sum.r, v.r);
            atomicAdd(frame_sum.g, v.g);
            atomicAdd(frame_sum.b, v.b);
            atomicAdd(frame_sum.a, a);
        } else {
            atomicAdd(ref_sum.r, v.r);
            atomicAdd(ref_sum.g, v.g);
            atomicAdd(ref_sum.b, v.b);
            atomicAdd(ref_sum.a, a);
        }
    }
}

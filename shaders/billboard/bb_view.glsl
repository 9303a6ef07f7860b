/* bb_view.glsl: the view-dependent clump cards (beyond Orthmann et al.
 * 2009): a card blends the clump bakes of the four views around its view
 * direction, bilinear in view elevation and in the wind's azimuth relative
 * to the view, dithered per pixel (bb_view_weights, bb_view_pick; twins in
 * src/billboard/bb_view.c; bb_view_weights  there says how the views are laid
 * out). The
 * clump array holds the V L albedo layers (view v of layer k at v L + k),
 * then their V L light layers (bb.c upload_layout, bb_layout.c). */
#ifndef BB_VIEW_GLSL
#define BB_VIEW_GLSL

#include "common/hash.glsl"

uniform ivec2 u_views;              /* elevations, azimuths */
uniform float u_view_elevation_max; /* radians */
uniform int u_view_layers;          /* L */
uniform vec2 u_view_wind;           /* the wind's xz direction, unit */
uniform int u_view_lit;             /* 1: cards show the light layers (bb_view_desc_t.on);
                                       0: lit as Orthmann's cards */

void bb_view_weights(vec3 to_eye, vec2 wind, ivec2 views, float elevation_max, out ivec4 view, out vec4 w)
{
    float len = length(to_eye), hl = length(to_eye.xz);
    vec3 z = hl > 1e-6 ? vec3(to_eye.x / hl, 0.0, to_eye.z / hl) : vec3(0.0, 0.0, 1.0);
    vec3 x = vec3(z.z, 0.0, -z.x);
    float elev = asin(clamp(to_eye.y / max(len, 1e-12), 0.0, 1.0));
    int ne = views.x, na = views.y;
    float t = ne > 1 ? min(elev / elevation_max, 1.0) * float(ne - 1) : 0.0;
    int e0 = ne > 1 ? int(min(floor(t), float(ne - 2))) : 0, e1 = ne > 1 ? e0 + 1 : 0;
    float fe = ne > 1 ? t - float(e0) : 0.0;
    float wx = dot(wind, x.xz), wz = dot(wind, z.xz);
    float phi = wx == 0.0 && wz == 0.0 ? 0.0 : atan(wx, -wz);
    phi = phi < 0.0 ? phi + 6.2831853 : phi;
    float s = phi / 6.2831853 * float(na);
    float fs = floor(s);
    int a0 = int(fs) % na, a1 = (a0 + 1) % na;
    float fa = s - fs;
    view = ivec4(e0 * na + a0, e0 * na + a1, e1 * na + a0, e1 * na + a1);
    w = vec4((1.0 - fe) * (1.0 - fa), (1.0 - fe) * fa, fe * (1.0 - fa), fe * fa);
}

/* The view of the four (weights w, summing to 1) that a pixel with draw xi
 * in [0, 1) shows: the first whose running sum of weights exceeds xi. */
int bb_view_pick(ivec4 view, vec4 w, float xi)
{
    float sum = 0.0;
    for (int i = 0; i < 3; i++) {
        sum += w[i];
        if (xi < sum) return view[i];
    }
    return view[3];
}

/* A pixel's draw for bb_view_pick, unlike the coverage mask's and the
 * fade's hashes of the pixel. */
float bb_view_xi(uvec2 px)
{
    return hash_float((px.x * 7919u + px.y * 104729u) ^ 0x9e3779b9u);
}

/* Clump layer `layer` at uv (gradients dx, dy) seen along to_eye, from the
 * view the pixel's draw xi picks (bb_view_pick): its albedo and alpha, and
 * in light its light layer (the blades' lit colour, blade_clump.c; views
 * off: none in the array, 0). A pixel shows one bake, not a mix: the
 * views' alpha images are calibrated one by one, and a mix of two would
 * put half-alpha ghosts of both where alpha-to-coverage rounds up; the
 * pixels of a card mix the views in proportion to their weights. */
vec4 bb_view_texel(sampler2DArray clumps, vec2 uv, float layer, vec2 dx, vec2 dy, vec3 to_eye, float xi, out vec3 light)
{
    ivec4 view;
    vec4 w;
    bb_view_weights(to_eye, u_view_wind, u_views, u_view_elevation_max, view, w);
    float l = float(bb_view_pick(view, w, xi) * u_view_layers) + layer;
    float lights = float(u_views.x * u_views.y * u_view_layers);
    light = u_view_lit != 0 ? textureGrad(clumps, vec3(uv, l + lights), dx, dy).xyz : vec3(0.0);
    return textureGrad(clumps, vec3(uv, l), dx, dy);
}

#endif

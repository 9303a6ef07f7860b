/* blade_geom.glsl: the blade geometry of Jahrmann & Wimmer 2017 sec. 6.3,
 * shared by the tessellation evaluation shader (blade.tese) and the
 * vertex-pulling path (blade_pull.vert) so both build the same surface.
 *   eq. 21 De Casteljau on the curve v0 v1 v2 at height parameter v:
 *     a = v0 + v (v1 - v0), b = v1 + v (v2 - v1), c = a + v (b - a),
 *     c0 = c - w/2 t1, c1 = c + w/2 t1 (t1 the width direction),
 *     p = (1 - t) c0 + t c1, n = normalize(cross(b - a, t1)).
 *   shape: t = 0.5 + (u - 0.5) f(v), f the width profile:
 *     quad 1; triangle 1 - v (the paper's u + 0.5v - uv); quadratic 1 - v^2
 *     (centred: the tip ends on the midrib); triangle_tip
 *     1 - max(v - tau, 0) / (1 - tau), tau = 0.5; dandelion (1 - v) times
 *     a tooth pattern 0.35 + 0.65 |2 fract(4v) - 1| (own profile after the
 *     paper's figure: teeth show from 8 segments on).
 *   eq. 23 (optional, as printed, scaled by u_displacement = k, 1 the
 *     paper): d = k (w / 2) n (0.5 - |u - 0.5| (1 - v)), p += d. The
 *     paper's w is the half width (eq. 21 spans c -+ w t1), so w / 2 here.
 *     The midrib (u = 0.5) stands w / 4 off the curve along n over the
 *     whole blade, the edges 0 at the root up to w / 4 at the tip: a fold
 *     of depth (w / 4)(1 - v). It needs vertices at u = 0.5, so with
 *     displacement > 0 the tessellation and both pulled strips build 2
 *     columns across the width (blade_columns, blade_strip_uv).
 *   eq. 24 (optional, this project's reading, docs/BLADES.md): width
 *     w / max(|n . view|, width_correction), at most 4 w, so blades seen
 *     edge-on do not fall below a pixel and alias.
 *   eq. 24 as printed (optional, u_width_printed = (w_min, w_span, focal
 *     length), all px, w_span 0: off; after the reading above): w_p = w
 *     focal / |camera - c|, Phi = 1 - clamp((w_p - w_min) / w_span, 0, 1),
 *     t = t (1 - Phi) + u Phi^2: a blade thinner than w_min pixels is a
 *     quad.
 * Level of detail: segments along the blade, from u_max_level at the
 * camera down to max(u_max_level / 4, 1) at u_lod_distance (root distance). */
#ifndef BLADE_GEOM_GLSL
#define BLADE_GEOM_GLSL

#define SHAPE_QUADRATIC 0
#define SHAPE_QUAD 1
#define SHAPE_TRIANGLE 2
#define SHAPE_TRIANGLE_TIP 3
#define SHAPE_DANDELION 4

uniform int u_shape;
uniform float u_displacement;
uniform float u_width_correction;
uniform vec3 u_width_printed; /* eq. 24 as printed: w_min, w_span (0: off), focal length; px */
uniform vec3 u_camera;
uniform int u_max_level;
uniform float u_lod_distance;

/* Segments across the width: 2 when eq. 23 folds the midrib, else 1. */
int blade_columns() { return u_displacement > 0.0 ? 2 : 1; }

/* (u, v) of vertex k of a pulled strip (blade_pull.vert, tiles_draw.vert)
 * of a blade with n segments: S = 2 (u_max_level + 1) vertices per column,
 * vertex j of a column at (j & 1, min(j / 2, n) / n), so past level n the
 * strip collapses into degenerate triangles. With 2 columns (eq. 23; u in
 * [0, 0.5], then [0.5, 1]) they are joined by 2 degenerate vertices (the
 * last of the first, the first of the second): 2 S + 2 vertices. */
vec2 blade_strip_uv(int k, int n)
{
    int s = 2 * (u_max_level + 1), column = 0;
    if (k == s) {
        k = s - 1;
    } else if (k > s) {
        column = 1;
        k = max(k - s - 2, 0);
    }
    return vec2((float(column) + float(k & 1)) / float(blade_columns()), float(min(k / 2, n)) / float(n));
}

int blade_lod(Blade b)
{
    float d = clamp(length(b.v0.xyz - u_camera) / u_lod_distance, 0.0, 1.0);
    float lo = float(max(u_max_level / 4, 1));
    return int(floor(mix(float(u_max_level), lo, d) + 0.5));
}

float blade_profile(float v)
{
    if (u_shape == SHAPE_QUAD) return 1.0;
    if (u_shape == SHAPE_TRIANGLE) return 1.0 - v;
    if (u_shape == SHAPE_TRIANGLE_TIP) return 1.0 - max(v - 0.5, 0.0) / 0.5;
    if (u_shape == SHAPE_DANDELION) return (1.0 - v) * (0.35 + 0.65 * abs(2.0 * fract(4.0 * v) - 1.0));
    return 1.0 - v * v;
}

void blade_build(Blade b, float u, float v, out vec3 pos, out vec3 normal)
{
    vec3 v0 = b.v0.xyz, v1 = b.v1.xyz, v2 = b.v2.xyz;
    float w = b.v2.w;
    vec3 t1, front;
    blade_frame(b, t1, front);
    vec3 a = v0 + v * (v1 - v0);
    vec3 bb = v1 + v * (v2 - v1);
    vec3 c = a + v * (bb - a);
    vec3 n = blade_safe_normalize(cross(bb - a, t1));
    if (dot(n, n) == 0.0) n = front;
    if (u_width_correction > 0.0) {
        float nv = abs(dot(n, blade_safe_normalize(u_camera - c)));
        w = w * min(1.0 / max(nv, u_width_correction), 4.0);
    }
    vec3 c0 = c - t1 * (0.5 * w);
    vec3 c1 = c + t1 * (0.5 * w);
    float t = 0.5 + (u - 0.5) * blade_profile(v);
    if (u_width_printed.y > 0.0) {
        float wp = w * u_width_printed.z / max(length(u_camera - c), 1e-6);
        float phi = 1.0 - min(max((wp - u_width_printed.x) / u_width_printed.y, 0.0), 1.0);
        t = t * (1.0 - phi) + u * phi * phi;
    }
    pos = mix(c0, c1, t);
    if (u_displacement > 0.0) pos += n * (u_displacement * (0.5 * w) * (0.5 - abs(u - 0.5) * (1.0 - v)));
    normal = n;
}

#endif

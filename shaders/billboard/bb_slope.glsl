/* bb_slope.glsl: the billboards' side of the blades -> billboards
 * hand-over (after Qiu et al.; src/hybrid/hybrid_slope.h). A plain
 * billboard rooted in a slope cell tilts its top edge: the top centre moves
 * on the sphere around the root to the direction slope_apply gives (fallback
 * the billboard's normal, weight w of eq. 8 since the cell was written), so
 * the handed-over trail recovers like a deformed billboard. A deformed
 * billboard (mesh in bb_pos) keeps its own shape where it is bent more than
 * the cell says; otherwise its rows move towards the cell's top centre,
 * row j by j / (M - 1) of the gap (root row fixed). Include after
 * common/bb.glsl and billboard/bb_points.glsl. */
#ifndef BB_SLOPE_GLSL
#define BB_SLOPE_GLSL

#include "common/slope.glsl"

layout(std430, binding = HYBRID_BIND_SLOPE_MAP) readonly buffer SlopeMap { SlopeCell slope_cells[]; };

uniform int u_slope_on;
uniform float u_slope_time;
uniform float u_slope_recover;

/* How far the top corners ta, tb (wind pose) of plain billboard p move. */
vec3 bb_slope_shift(bb_point p, vec3 ta, vec3 tb)
{
    if (u_slope_on == 0) return vec3(0.0);
    int k = slope_cell_at(p.position.xz);
    if (k < 0) return vec3(0.0);
    SlopeCell m = slope_cells[k];
    if (m.b.y <= 0.0) return vec3(0.0);
    float w = slope_weight(u_slope_time - m.b.x, u_slope_recover);
    if (w <= 0.0) return vec3(0.0);
    vec3 tc = 0.5 * (ta + tb);
    vec3 dir = tc - p.position;
    float len = length(dir);
    vec3 right, up;
    bb_frame(p, right, up);
    vec3 n = cross(right, up);
    vec2 f = length(n.xz) > 1e-6 ? normalize(n.xz) : vec2(1.0, 0.0);
    return p.position + len * slope_apply(dir / len, f, vec4(m.a.xyz, 0.0), w) - tc;
}

/* bb_pos holds the deformed mesh of p; ta, tb its top corners in the wind
 * pose. */
void bb_slope_mesh(bb_point p, vec3 ta, vec3 tb)
{
    vec3 shift = bb_slope_shift(p, ta, tb);
    if (dot(shift, shift) == 0.0) return;
    vec3 pose = 0.5 * (ta + tb);
    vec3 top = vec3(0.0);
    for (int i = 0; i < BB_N; i++) top = top + bb_pos[(BB_M - 1) * BB_N + i];
    top = top * (1.0 / float(BB_N));
    if (length(shift) <= length(top - pose)) return;
    vec3 gap = pose + shift - top;
    for (int j = 1; j < BB_M; j++)
        for (int i = 0; i < BB_N; i++) bb_pos[j * BB_N + i] += gap * (float(j) / float(BB_M - 1));
}

#endif

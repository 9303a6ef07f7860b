/* bb_lod.glsl: coverage-preserving thinning of the billboard cards, the
 * twin of src/billboard/bb_lod.c (bb_lod.h documents it): common/lod.glsl's
 * lod_blade with the card's seed for the blade's index and its width for
 * the blade's. The host sets the u_lod_* uniforms with blade_lod_uniforms
 * from bb_lod_rule (bb_render_uniforms; rule off: every card as it is).
 * Include after common/bb.glsl and billboard/bb_points.glsl. */
#ifndef BB_LOD_GLSL
#define BB_LOD_GLSL

#include "common/lod.glsl"

/* x: weight (0: culled), y: widening of card p seen from eye; rule off:
 * (1, 1) at once (the cards drawn exactly as without thinning). */
vec2 bb_lod_card(bb_point p, vec3 eye)
{
    if (u_lod_rule == LOD_OFF) return vec2(1.0);
    return lod_blade(p.seed, grass_distance(p.position, eye), p.size.x);
}

/* Card p as drawn: its width times weight * widening (k); false when
 * culled. */
bool bb_lod_thin(inout bb_point p, vec3 eye, out float k)
{
    vec2 w = bb_lod_card(p, eye);
    k = w.x * w.y;
    p.size.x *= k;
    return w.x > 0.0;
}

/* A deformed card's mesh (bb_pos) k times as wide about its root along
 * its right axis. */
void bb_lod_mesh(vec3 root, vec3 right, float k)
{
    for (int v = 0; v < BB_N * BB_M; v++) bb_pos[v] += right * (dot(bb_pos[v] - root, right) * (k - 1.0));
}

#endif

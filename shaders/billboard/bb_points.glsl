/* bb_points.glsl: the billboard point stream of Orthmann et al. 2009 as seen
 * by the geometry shaders of src/billboard/bb.c: per-vertex inputs from
 * bb_point.vert, transform-feedback outputs with the exact 64-byte layout of
 * bb_point_t, the quad frame (twin of bb_point_frame in bb.c) and the rest
 * quad (twin of bb_mesh_init_quad). Include after common/bb.glsl.
 * pad0 holds the billboard's slot in the deformed-mesh pool (BB_NO_SLOT when
 * it is a plain quad). Define BB_POINTS_IN for the vertex-stream inputs and
 * BB_POINTS_OUT for the transform-feedback outputs. */
#ifndef BB_POINTS_GLSL
#define BB_POINTS_GLSL

#include "common/switch.glsl"

#define BB_NO_SLOT 0xffffffffu

/* Per-billboard brightness (the clump texel's factor in bb_shade): 1 +- 0.15
 * messiness, uniform from the seed. Its mean is 1, so the variation does not
 * move the field's colour off the blades' (the clumps hold the blades'
 * albedo). */
float bb_tint(bb_point p)
{
    return 1.0 + 0.3 * p.messiness * (fract(float(p.seed >> 8) * (1.0 / 16777216.0)) - 0.5);
}

#ifdef BB_POINTS_IN
in vec4 v_pos_angle[];
in vec4 v_growth_mess[];
in vec2 v_size[];
flat in uvec2 v_layer_state[];
in float v_recover[];
flat in uint v_seed[];
flat in uvec2 v_pad[];

bb_point bb_load_point()
{
    return bb_point(v_pos_angle[0].xyz, v_pos_angle[0].w, v_growth_mess[0].xyz, v_growth_mess[0].w,
                    v_size[0], v_layer_state[0].x, v_layer_state[0].y, v_recover[0], v_seed[0],
                    v_pad[0].x, v_pad[0].y);
}
#endif

#ifdef BB_POINTS_OUT
out vec4 o_pos_angle;
out vec4 o_growth_mess;
out vec2 o_size;
flat out uvec2 o_layer_state;
out float o_recover;
flat out uint o_seed;
flat out uvec2 o_pad;

void bb_emit_point(bb_point p)
{
    o_pos_angle = vec4(p.position, p.angle);
    o_growth_mess = vec4(p.growth, p.messiness);
    o_size = p.size;
    o_layer_state = uvec2(p.layer, p.state);
    o_recover = p.recover_time;
    o_seed = p.seed;
    o_pad = uvec2(p.pad0, p.pad1);
    EmitVertex();
    EndPrimitive();
}
#endif

/* up = growth; right = (cos a, 0, sin a) made orthogonal to up, or
 * (-sin a, 0, cos a) when the first is (nearly) along a horizontal up
 * (it would normalise a zero vector). Twin: bb_point_frame. */
void bb_frame(bb_point p, out vec3 right, out vec3 up)
{
    up = p.growth;
    vec3 t = vec3(cos(p.angle), 0.0, sin(p.angle));
    vec3 r = t - up * dot(t, up);
    if (dot(r, r) < 1e-6) {
        t = vec3(-sin(p.angle), 0.0, cos(p.angle));
        r = t - up * dot(t, up);
    }
    right = r * (1.0 / sqrt(dot(r, r)));
}

/* The bottom corners a, b and wind-posed top corners ta, tb of plain
 * billboard p (bb_wind_vertex with h = 1 on the rest quad's top edge). */
void bb_plain_corners(bb_point p, vec3 right, vec3 up, bb_wind wind, float time, out vec3 a, out vec3 b,
                      out vec3 ta, out vec3 tb)
{
    a = p.position - 0.5 * p.size.x * right;
    b = p.position + 0.5 * p.size.x * right;
    ta = bb_wind_vertex(wind, a + p.size.y * up, p.position, 1.0, time);
    tb = bb_wind_vertex(wind, b + p.size.y * up, p.position, 1.0, time);
}

/* Surface normal of a plain quad with root corners a, b and top corners
 * ta, tb (wind pose and slope shift applied): the quad as drawn, so its
 * shading leans with it as a deformed mesh's does (bb_mesh_normal). */
vec3 bb_plain_normal(vec3 a, vec3 b, vec3 ta, vec3 tb)
{
    return normalize(cross(b - a, 0.5 * (ta + tb) - 0.5 * (a + b)));
}

/* True when billboard p lies wholly nearer than the hybrid fade band
 * (fade_end <= 0: no band), where blades stand instead. */
bool bb_fade_dropped(bb_point p, vec3 camera, float fade_start, float fade_end)
{
    return fade_end > 0.0 && grass_distance(p.position, camera) + 0.5 * length(p.size) < fade_start;
}

/* True when billboard p lies wholly beyond the canopy's fade (far_end > 0),
 * where the ground canopy stands for it. */
bool bb_far_dropped(bb_point p, vec3 camera, float far_end)
{
    return far_end > 0.0 && grass_distance(p.position, camera) - 0.5 * length(p.size) > far_end;
}

/* bb_mesh_init_quad into bb_rest. */
void bb_build_rest(bb_point p, vec3 right, vec3 up)
{
    for (int j = 0; j < BB_M; j++) {
        for (int i = 0; i < BB_N; i++) {
            float x = p.size.x * (float(i) / float(BB_N - 1) - 0.5);
            float y = p.size.y * float(j) / float(BB_M - 1);
            bb_rest[j * BB_N + i] = p.position + x * right + y * up;
        }
    }
}

#endif

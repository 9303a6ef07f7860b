#version 450
/* bb_render.geom: billboard rendering of Orthmann et al. 2009. A plain
 * billboard, thinned with distance (bb_lod.glsl: culled, or drawn wider),
 * becomes a quad whose two upper vertices follow the procedural
 * wind (bb_wind_vertex, h = 1); a deformed one (pool slot set) draws its
 * stored N x M mesh as M-1 triangle strips with normals from central
 * differences. Billboards wholly nearer than the hybrid fade band are
 * dropped here. Plain quads and deformed meshes take the handed-over slope
 * of their cell (bb_slope.glsl). With BB_GI each vertex takes the global
 * illumination's ambient light (bb_vertex_ambient, Orthmann et al. sec. 6.1). */
#define BB_NO_GENERATE
#include "common/bb.glsl"
#define BB_POINTS_IN
#include "billboard/bb_points.glsl"
#include "billboard/bb_pool.glsl"
#include "billboard/bb_slope.glsl"
#include "billboard/bb_lod.glsl"
#include "common/grass_shade.glsl"

layout(points) in;
layout(triangle_strip, max_vertices = BB_RENDER_VERTS) out;

uniform mat4 u_viewproj;
uniform vec3 u_camera;
uniform float u_time;
uniform float u_fade_start;
uniform float u_fade_end;
uniform float u_far_end;
uniform bb_wind u_wind;

out vec3 g_world;
out vec3 g_normal;
out vec3 g_uvl; /* u, v (0 at the top of the clump image), layer */
flat out float g_tint;
flat out float g_card; /* 1: plain quad, 0: deformed mesh (bb_render.frag) */
flat out uint g_overlay; /* debug overlay, packUnorm4x8 (u_overlay 1: colliding red, recovering yellow);
                          one component: the vertex is 16 (bb.c checks the GPU's limit) */
#ifdef BB_GI
out vec3 g_amb_front; /* the vertex's global illumination (bb_vertex_ambient): 6 more */
out vec3 g_amb_back;
#endif
uniform int u_overlay;

void put(vec3 pos, vec3 n, float u, float h, float layer)
{
    g_world = pos;
    g_normal = n;
#ifdef BB_GI
    bb_vertex_ambient(pos, n, g_amb_front, g_amb_back);
#endif
    g_uvl = vec3(u, 1.0 - h, layer);
    gl_Position = u_viewproj * vec4(pos, 1.0);
    EmitVertex();
}

void main()
{
    bb_point p = bb_load_point();
    float k;
    if (!bb_lod_thin(p, u_camera, k)) return;
    if (bb_fade_dropped(p, u_camera, u_fade_start, u_fade_end) || bb_far_dropped(p, u_camera, u_far_end)) return;
    vec3 right, up;
    bb_frame(p, right, up);
    float layer = float(p.layer);
    g_tint = bb_tint(p);
    g_overlay = packUnorm4x8(u_overlay != 1 ? vec4(0.0)
                           : (p.state == BB_STATE_COLLIDING ? vec4(1.0, 0.1, 0.1, 0.75)
                                                            : (p.state == BB_STATE_RECOVERING ? vec4(1.0, 0.85, 0.1, 0.75)
                                                                                              : vec4(0.0))));
    if (p.pad0 == BB_NO_SLOT) {
        vec3 a, b, c, d;
        bb_plain_corners(p, right, up, u_wind, u_time, a, b, c, d);
        vec3 shift = bb_slope_shift(p, c, d);
        c = c + shift;
        d = d + shift;
        vec3 n = bb_plain_normal(a, b, c, d);
        g_card = 1.0;
        put(a, n, 0.0, 0.0, layer);
        put(b, n, 1.0, 0.0, layer);
        put(c, n, 0.0, 1.0, layer);
        put(d, n, 1.0, 1.0, layer);
        EndPrimitive();
        return;
    }
    bb_load_mesh(p.pad0);
    bb_lod_mesh(p.position, right, k);
    g_card = 0.0;
    if (u_slope_on != 0) {
        vec3 a, b, ta, tb;
        bb_plain_corners(p, right, up, u_wind, u_time, a, b, ta, tb);
        bb_slope_mesh(p, ta, tb);
    }
    vec3 nrm[BB_N * BB_M];
    for (int j = 0; j < BB_M; j++)
        for (int i = 0; i < BB_N; i++) nrm[j * BB_N + i] = bb_mesh_normal(i, j, cross(right, up));
    for (int j = 0; j < BB_M - 1; j++) {
        for (int i = 0; i < BB_N; i++) {
            float u = float(i) / float(BB_N - 1);
            put(bb_pos[j * BB_N + i], nrm[j * BB_N + i], u, float(j) / float(BB_M - 1), layer);
            put(bb_pos[(j + 1) * BB_N + i], nrm[(j + 1) * BB_N + i], u, float(j + 1) / float(BB_M - 1), layer);
        }
        EndPrimitive();
    }
}

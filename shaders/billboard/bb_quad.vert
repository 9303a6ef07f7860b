#version 450
/* bb_quad.vert: the plain billboards of idle octree leaves without a
 * geometry shader (vertex pulling): six vertices per billboard read the
 * point from the points buffer and build the same wind-animated quad as
 * bb_render.geom (two upper vertices moved by bb_wind_vertex). Idle leaves
 * hold no deformed billboard; a point that does, that its thinning with
 * distance culls (bb_lod.glsl; else it is drawn wider) or that lies wholly
 * nearer than the hybrid fade band, is emitted degenerate. The top edge takes the
 * handed-over slope of its cell (bb_slope.glsl); the normal is the moved
 * quad's (bb_plain_normal); with BB_GI the vertex takes the global
 * illumination's ambient light (bb_vertex_ambient, Orthmann et al. sec.
 * 6.1). Outputs match bb_render.frag's inputs. */
#define BB_NO_GENERATE
#include "common/bindings_billboard.glsl"
#include "common/bb.glsl"
#include "billboard/bb_points.glsl"
#include "billboard/bb_slope.glsl"
#include "billboard/bb_lod.glsl"
#include "common/grass_shade.glsl"

layout(std430, binding = BB_BIND_POINTS) readonly buffer Points { bb_point points[]; };

uniform mat4 u_viewproj;
uniform vec3 u_camera;
uniform float u_time;
uniform float u_fade_start;
uniform float u_fade_end;
uniform float u_far_end;
uniform bb_wind u_wind;

out vec3 g_world;
out vec3 g_normal;
out vec3 g_uvl;
flat out float g_tint;
flat out float g_card; /* always 1: a plain quad */
flat out uint g_overlay; /* packUnorm4x8; idle leaves: never tinted */
#ifdef BB_GI
out vec3 g_amb_front;
out vec3 g_amb_back;
#endif

void main()
{
    bb_point p = points[gl_VertexID / 6];
    const int corners[6] = int[](0, 1, 2, 2, 1, 3);
    int c = corners[gl_VertexID % 6];
    float k;
    bool culled = !bb_lod_thin(p, u_camera, k);
    bool near = bb_fade_dropped(p, u_camera, u_fade_start, u_fade_end) || bb_far_dropped(p, u_camera, u_far_end);
    if (p.pad0 != BB_NO_SLOT || culled || near) {
        g_world = vec3(0.0);
        g_normal = vec3(0.0, 1.0, 0.0);
        g_uvl = vec3(0.0);
        g_tint = 0.0;
        g_card = 1.0;
        g_overlay = 0u;
#ifdef BB_GI
        g_amb_front = g_amb_back = vec3(0.0);
#endif
        gl_Position = vec4(0.0, 0.0, 2.0, 1.0); /* beyond the far plane */
        return;
    }
    vec3 right, up;
    bb_frame(p, right, up);
    vec3 a, b, ta, tb;
    bb_plain_corners(p, right, up, u_wind, u_time, a, b, ta, tb);
    vec3 shift = bb_slope_shift(p, ta, tb);
    ta += shift;
    tb += shift;
    vec3 pos = c == 0 ? a : (c == 1 ? b : (c == 2 ? ta : tb));
    g_tint = bb_tint(p);
    g_card = 1.0;
    g_overlay = 0u;
    g_world = pos;
    g_normal = bb_plain_normal(a, b, ta, tb);
#ifdef BB_GI
    bb_vertex_ambient(pos, g_normal, g_amb_front, g_amb_back);
#endif
    g_uvl = vec3(float(c & 1), 1.0 - float(c >> 1), float(p.layer));
    gl_Position = u_viewproj * vec4(pos, 1.0);
}

#version 450
/* tiles_slope_resolve.comp: turns the fixed-point sums of the slope cells
 * of the listed tiles into cells (hybrid_slope_resolve: means, written at
 * u_time) and zeroes the sums for the next hand-over. Invocation i: tile
 * list[i / (C * C)].y, cell i % (C * C) of it (C = u_cells_per_tile). */
#include "common/slope.glsl"
#include "common/bindings_blade.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BLADE_TILES_BIND_LIST) readonly buffer List { uvec2 list[]; };
layout(std430, binding = HYBRID_BIND_SLOPE_MAP) buffer Map { SlopeCell cells[]; };
layout(std430, binding = HYBRID_BIND_SLOPE_SUMS) buffer Sums { SlopeSum sums[]; };

uniform uint u_count; /* entries * C * C */
uniform int u_cells_per_tile;
uniform int u_tiles_x;
uniform float u_time;

void main()
{
    uint i = gl_GlobalInvocationID.x;
    if (i >= u_count) return;
    uint per = uint(u_cells_per_tile * u_cells_per_tile);
    uint tile = list[i / per].y;
    int local = int(i % per);
    int ci = (int(tile) % u_tiles_x) * u_cells_per_tile + local % u_cells_per_tile;
    int cj = (int(tile) / u_tiles_x) * u_cells_per_tile + local / u_cells_per_tile;
    if (ci >= u_slope_dims.x || cj >= u_slope_dims.y) return;
    int c = cj * u_slope_dims.x + ci;
    SlopeSum s = sums[c];
    SlopeCell r;
    r.a = vec4(0.0);
    r.b = vec4(u_time, 0.0, 0.0, 0.0);
    if (s.b.x > 0u) {
        float k = 1.0 / (float(s.b.x) * SLOPE_FIXED);
        r.a = vec4(s.a) * k;
        r.b.y = float(s.b.x);
    }
    cells[c] = r;
    sums[c].a = ivec4(0);
    sums[c].b = uvec4(0u);
}

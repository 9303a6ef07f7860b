#version 450
/* bb_ring_gen.comp: one cell of the billboard ring on a world terrain
 * (src/billboard/bb_ring.c, docs/WORLD.md): the generation rule of
 * Orthmann et al. 2009 (bb_generate, twin of bb_layout_sample) over the
 * cell's K x K candidates, one thread per candidate, written straight into
 * the cell's slot [u_first, u_first + K^2) of the points buffer. Point
 * order: generation tiles (BB_TILE x BB_TILE candidates) row by row,
 * candidates row by row within a tile, the order of the heightfield's
 * generation. Every candidate writes one point, so a cell fills its slot
 * exactly: an accepted one its billboard with the root on the world's
 * height function (world_height), a rejected one or one outside the world
 * square a dead point (size 0, 1e6 m below the ground: culled by every
 * path). Each point depends on its candidate alone, so a cell generated
 * again is bit-identical. */
#include "common/hash.glsl"
#include "common/bindings_billboard.glsl"
#include "common/world_height.glsl"
#include "common/bb.glsl"
#include "billboard/bb_points.glsl"

layout(local_size_x = 64) in;

layout(std430, binding = BB_BIND_POINTS) writeonly buffer Points { bb_point points[]; };
layout(binding = BB_TEX_EXTENT) uniform sampler2D u_extent;
layout(binding = BB_TEX_DIRECTION) uniform sampler2D u_direction;
layout(binding = BB_TEX_MESSINESS) uniform sampler2D u_messiness;
uniform bb_gen u_gen;
uniform ivec2 u_cell0;    /* the cell's first candidate (ix, iz) */
uniform int u_cand;       /* K: candidates per cell side */
uniform uint u_first;     /* the slot's first point */
uniform ivec2 u_cells;    /* candidate cells of the world square */
uniform vec2 u_field_max; /* the world square's far corner (x, z) */

void main()
{
    int i = int(gl_GlobalInvocationID.x);
    if (i >= u_cand * u_cand) return;
    const int per_tile = BB_TILE * BB_TILE;
    int tile = i / per_tile, r = i % per_tile, per_row = u_cand / BB_TILE;
    int ix = u_cell0.x + (tile % per_row) * BB_TILE + r % BB_TILE;
    int iz = u_cell0.y + (tile / per_row) * BB_TILE + r / BB_TILE;
    bb_point p;
    bool live = ix >= 0 && iz >= 0 && ix < u_cells.x && iz < u_cells.y &&
                bb_generate(u_extent, u_direction, u_messiness, u_gen, ix, iz, p) &&
                p.position.x <= u_field_max.x && p.position.z <= u_field_max.y;
    if (live) {
        p.position.y = world_height(p.position.xz);
    } else {
        p = bb_point(vec3(0.0), 0.0, vec3(0.0, 1.0, 0.0), 0.0, vec2(0.0), 0u, 0u, 0.0, 0u, 0u, 0u);
        p.position = vec3(u_gen.origin.x + (float(ix) + 0.5) * u_gen.spacing, -1.0e6,
                          u_gen.origin.y + (float(iz) + 0.5) * u_gen.spacing);
    }
    p.pad0 = BB_NO_SLOT;
    points[u_first + uint(i)] = p;
}

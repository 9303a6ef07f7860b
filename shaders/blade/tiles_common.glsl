/* tiles_common.glsl: shared by the tiled blade field shaders (Fan et al.
 * 2015 tiles over Jahrmann & Wimmer 2017 blades; src/blade/blade_tiles.h).
 *   tiles_rest   template blade k placed in tile `tile`: the template and
 *                the symmetry of the square (4 rotations x mirror) from
 *                a hash of the world tile coordinates, root on the heightfield by the
 *                barycentric interpolation of terrain_height_at, up the
 *                interpolated vertex normal, rest pose v1 = v2 = v0 + up h.
 *                Roots outside the field and template padding get h = 0.
 *   tiles_pose   the procedural pose: quasi-static equilibrium of eq. 3-16
 *                (eta = 0) under gravity (eq. 4-6) and the wind of u_time
 *                (eq. 7-8), by relaxed fixed-point iteration
 *                v2 <- validate(v2 + 0.7 (v0 + up h + (g + w(v2)) / s - v2)),
 *                then steps of the physics' gain 1 - exp(-s dt) (at most
 *                0.7); s below BLADE_STIFFNESS_MIN counts as that minimum.
 * Twins on the CPU: blade_tiles_root / blade_tiles_instance. Bindings:
 * SSBO 0 templates, 3 winds; texture unit 0 the ground (xyz normal, w
 * height per grid vertex), or with TILES_WORLD the world's height function
 * (world_height.glsl, its uniforms set by blade_tiles.c).
 * Tile index -> field tile coordinates: row-major over the field, or in a
 * window (u_window > 0, hybrid.h) the one in [base, base + W) congruent to
 * the index, base + (i + shift) mod W with shift = -base mod W. */
#ifndef TILES_COMMON_GLSL
#define TILES_COMMON_GLSL

#include "common/switch.glsl"
#include "common/bindings_blade.glsl"
#include "common/blade.glsl"
#include "common/hash.glsl"
#ifdef TILES_WORLD
#include "common/world_height.glsl"
#else
#include "common/heightfield.glsl"
#endif

#define TILES_POSE_ITERATIONS 6
#define TILES_POSE_RELAX 0.7
#define TILES_POSE_STEPS 24
#define TILES_NO_SLOT 0xffffffffu

layout(std430, binding = BLADE_TILES_BIND_TEMPLATES) readonly buffer Templates { Blade templates[]; };
layout(std430, binding = BLADE_TILES_BIND_WINDS) readonly buffer Winds { BladeWind winds[]; };
layout(binding = BLADE_TILES_TEX_GROUND) uniform sampler2D u_ground;

uniform uint u_template_blades;  /* padded blades per template */
uniform uint u_template_count;
uniform uint u_seed_hash;
uniform int u_tiles_x;
uniform ivec2 u_tile_offset;     /* world tile coordinates of field tile (0, 0) */
uniform int u_window;            /* tiles per side of the window, 0: the whole field */
uniform ivec2 u_window_base;     /* field tile coordinates of the window's first corner */
uniform ivec2 u_window_shift;    /* -u_window_base mod u_window */
uniform float u_tile_size;
uniform float u_half;            /* heightfield half size (centred on the origin) */
uniform int u_grid_res;
uniform float u_time;
uniform vec4 u_gravity;          /* xyz unit direction, w magnitude (0: off) */
uniform vec4 u_gravity_centre;   /* xyz centre, w mix t */
uniform int u_wind_count;
uniform int u_length_mode;
uniform float u_pose_dt;         /* the physics step the pose settles for */

/* Field tile coordinates of a tile index (see the banner). */
ivec2 tiles_cell(uint tile)
{
    ivec2 c = ivec2(int(tile) % u_tiles_x, int(tile) / u_tiles_x);
    if (u_window > 0) c = u_window_base + (c + u_window_shift) % u_window;
    return c;
}

/* Hash of the tile's world coordinates (field tile + u_tile_offset), so a
 * world tile looks the same in fields of any size. */
void tiles_instance(uint tile, out uint tmpl, out uint sym)
{
    ivec2 c = tiles_cell(tile);
    int wi = c.x + u_tile_offset.x, wj = c.y + u_tile_offset.y;
    uint h = hash_u32(uint(wi) * 0x8da6b343u ^ hash_u32(uint(wj) ^ u_seed_hash));
    tmpl = h % u_template_count;
    sym = (h >> 8) & 7u;
}

/* Ground height and interpolated normal at (x, z), as terrain_height_at. */
float tiles_ground(float x, float z, out vec3 n)
{
#ifdef TILES_WORLD
    n = world_normal(vec2(x, z));
    return world_height(vec2(x, z));
#else
    vec4 r = heightfield_at(u_ground, u_grid_res, u_half, vec2(x, z));
    n = blade_safe_normalize(r.xyz);
    return r.w;
#endif
}

Blade tiles_rest(uint tile, uint k)
{
    uint tmpl, sym;
    tiles_instance(tile, tmpl, sym);
    Blade t = templates[tmpl * u_template_blades + k];
    Blade b;
    float half_tile = 0.5 * u_tile_size;
    float x = t.v0.x - half_tile, z = t.v0.z - half_tile;
    float a = t.v0.w;
    for (uint r = 0u; r < (sym & 3u); r++) {
        float nx = -z;
        z = x;
        x = nx;
        a = a + 1.57079633;
    }
    if ((sym & 4u) != 0u) {
        x = -x;
        a = 3.14159265 - a;
    }
    ivec2 c = tiles_cell(tile);
    x = x + half_tile + (-u_half + float(c.x) * u_tile_size);
    z = z + half_tile + (-u_half + float(c.y) * u_tile_size);
    float h = t.v1.w;
    if (x > u_half || z > u_half) h = 0.0;
    vec3 up;
    float y = tiles_ground(x, z, up);
    b.v0 = vec4(x, y, z, a);
    vec3 tip = b.v0.xyz + up * h;
    b.v1 = vec4(tip, h);
    b.v2 = vec4(tip, t.v2.w);
    b.up = vec4(up, t.up.w);
    return b;
}

vec3 tiles_wind_sum(vec3 p)
{
    vec3 wi = vec3(0.0);
    for (int k = 0; k < u_wind_count; k++) wi = wi + blade_wind_field(winds[k], p, u_time);
    return wi;
}

/* b in the rest pose (tiles_rest); returns the procedural pose. */
Blade tiles_pose(Blade b)
{
    if (b.v1.w <= 0.0) return b;
    vec3 wi = tiles_wind_sum(b.v0.xyz);
    vec3 g = blade_gravity(b, u_gravity, u_gravity_centre);
    vec3 iv2 = b.v0.xyz + b.up.xyz * b.v1.w;
    float s = max(b.up.w, BLADE_STIFFNESS_MIN);
    float inv_s = 1.0 / s;
    float relax_step = min(1.0 - exp(-s * u_pose_dt), TILES_POSE_RELAX);
    for (int it = 0; it < TILES_POSE_ITERATIONS + TILES_POSE_STEPS; it++) {
        vec3 target = iv2 + (g + blade_wind(b, wi)) * inv_s;
        b.v2.xyz = b.v2.xyz + (target - b.v2.xyz) * (it < TILES_POSE_ITERATIONS ? TILES_POSE_RELAX : relax_step);
        blade_validate(b, u_length_mode);
    }
    return b;
}

#endif

/* terrain_world: the procedural open-world terrain (terrain.type "world"), a
 * height function of (x, z) and nothing else: no vertices are held, so the
 * memory does not grow with the world's size. Value noise from
 * core_hash_u32 on integer lattices in four layers:
 *   macro   3 octaves, wavelengths 1024/512/256 m: the large shape;
 *   valleys 2 octaves, 128/64 m, smooth |n|: ridges and V-ish valleys
 *           along the zero lines of the noise;
 *   detail  3 octaves, 64/32/16 m: small bumps;
 *   flat    1 octave, 512 m, smoothstep: the meadow mask, 1 where the
 *           ground is only the (gentle) macro shape plus faint detail.
 * h/height = mix(0.5 macro + 0.35 valleys + 0.15 detail,
 *                0.5 macro + 0.03 detail, flat), within [-1, 1].
 * All wavelengths are powers of two (exact reciprocals), so C and GLSL see
 * the same lattice cells; the normal is analytic (derivatives of the same
 * expressions). shaders/common/world_height.glsl is the GLSL twin
 * (world_height, world_normal), configured only by its uniforms
 * (terrain_world_gpu), so one compiled program serves every world size
 * and seed. The world is centred on the origin, the square
 * [-size/2, size/2]^2; the function is defined (and continuous) beyond it.
 * GL-free. */
#ifndef MEADOW_TERRAIN_WORLD_H
#define MEADOW_TERRAIN_WORLD_H

#include <stddef.h>
#include <stdint.h>

#include <cglm/cglm.h>

#define TERRAIN_WORLD_SIZE_MAX 8192.0f /* terrain.size limit of type world (m) */

typedef struct terrain_world_t {
    float size;       /* side of the world square (m) */
    float height;     /* amplitude: heights in [-height, height] (m) */
    uint32_t seed[2]; /* seed words: low and high 32 bits of the seed */
} terrain_world_t;

struct terrain_desc_t;

/* Parameters from the desc's size and height (zero fields resolved by
 * terrain_desc_defaults) and the seed. */
terrain_world_t terrain_world_make(const struct terrain_desc_t *desc, uint64_t seed);

/* Height at (x, z) in [-height, height] and the unit analytic normal there
 * (normal_out may be NULL). */
float terrain_world_height(const terrain_world_t *w, float x, float z, vec3 normal_out);

/* Noise layers of the height function (macro 0-2, valleys 3-4, detail
 * 5-7, flat 8): world_height.glsl's WORLD_LAYERS. */
#define TERRAIN_WORLD_LAYERS 9

/* What world_height.glsl's uniforms hold: u_world_keys, the hash key of
 * each noise layer (from the seed words), and u_world_height, the
 * amplitude (m). */
typedef struct terrain_world_gpu_t {
    uint32_t keys[TERRAIN_WORLD_LAYERS];
    float height;
} terrain_world_gpu_t;

terrain_world_gpu_t terrain_world_gpu(const terrain_world_t *w);

#endif

/* bindings_ground.glsl: the binding numbers of the ground's shaders
 * (shaders/ground), included as they are by ground.c and terrain.frag;
 * only #define lines and comments, so valid C and GLSL
 * (docs/DESIGN.md "Layout"). */
#ifndef BINDINGS_GROUND_GLSL
#define BINDINGS_GROUND_GLSL

/* terrain.frag: the grass extent map that thins the ground canopy */
#define GROUND_TEX_EXTENT 0
/* terrain.frag: the soil-and-turf noise's lattice (GROUND_NOISE_SIZE^2
 * hashes, repeating) */
#define GROUND_TEX_NOISE 1
#define GROUND_NOISE_SIZE 256
/* terrain.vert, terrain_world.vert: the ground canopy's table
 * (common/canopy.glsl, blade_canopy_pack) */
#define GROUND_TEX_CANOPY 2
/* canopy_match.comp: the frame's colour (its samples) and the opaque depth
 * under the grass (one sample) */
#define GROUND_TEX_MATCH_COLOR 3
#define GROUND_TEX_MATCH_DEPTH 4
/* canopy_match.comp on a heightfield: the tiles' ground texture, the
 * terrain's vertex normals and heights (common/heightfield.glsl) */
#define GROUND_TEX_MATCH_GRID 5
/* The canopy match's state (ground.c's match buffer): canopy_match.comp and
 * canopy_match_update.comp write it as a storage buffer, the terrain's
 * vertex shaders read its gain as a uniform block */
#define GROUND_BIND_MATCH 0
#define GROUND_UBO_MATCH 0
/* Its fixed point: a linear-light channel of one pixel summed as
 * round(value GROUND_MATCH_FIXED) (a window of 1080p holds about 10^5
 * pixels: 4 10^8, within a uint) */
#define GROUND_MATCH_FIXED 4096

#endif

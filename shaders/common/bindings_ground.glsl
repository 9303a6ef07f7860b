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

#endif

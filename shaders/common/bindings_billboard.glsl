/* bindings_billboard.glsl: the billboard module's binding numbers, for
 * the C of src/billboard (through bb_local.h) and for shaders/billboard
 * (each file that names one includes this); only #define lines and
 * comments, valid in both languages (docs/DESIGN.md "Layout"). The
 * hand-over's slope buffers are hybrid's (bindings_hybrid.glsl). */
#ifndef BINDINGS_BILLBOARD_GLSL
#define BINDINGS_BILLBOARD_GLSL

/* Storage: the field's buffers (bb_pool.glsl, render, raster, recovery) */
#define BB_BIND_POOL 1   /* free-slot stack of the deformed meshes */
#define BB_BIND_MESHES 2 /* the deformed meshes */
#define BB_BIND_POINTS 3 /* one bb_point per billboard */
#define BB_BIND_RANGES 4 /* bb_recover.comp: the leaves' ranges */
/* Storage: generation (bb_generate.geom, bb_gen_leaves.glsl) */
#define BB_BIND_LEAF_COUNTS 0
#define BB_BIND_GEN_ENTRIES 1
#define BB_BIND_GEN_TRIS 2
/* Uniform buffer: bb_collide.geom's colliders of one batch */
#define BB_UBO_OBJECTS 0

/* Texture units */
#define BB_TEX_CLUMPS 0    /* render, raster: the clump atlas */
#define BB_TEX_CUBES 0     /* collide: the colliders' depth cube maps */
#define BB_TEX_EXTENT 0    /* generate: the layout maps */
#define BB_TEX_DIRECTION 1
#define BB_TEX_MESSINESS 2
#define BB_TEX_HEIGHTS 3   /* bb_ground.glsl (generate, collide) */

#endif

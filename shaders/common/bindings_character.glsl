/* bindings_character.glsl: the character module's binding numbers, read
 * by character.c and by skin.comp / character.frag through the same
 * #include; only #define lines and comments, valid C and GLSL
 * (docs/DESIGN.md "Layout"). */
#ifndef BINDINGS_CHARACTER_GLSL
#define BINDINGS_CHARACTER_GLSL

/* skin.comp: bind-pose vertices and the pose's matrices in, skinned out */
#define CHARACTER_BIND_VERTICES 0
#define CHARACTER_BIND_BONES 1
#define CHARACTER_BIND_SKINNED 2
/* character.frag: the model's diffuse texture */
#define CHARACTER_TEX_DIFFUSE 0

#endif

/* gi: the GL half of the global illumination (gi_volume.h): uploads the
 * ambient-occlusion and irradiance volumes as 3-D textures and binds them
 * for the shaders of common/gi.glsl, on the texture units of
 * shaders/common/bindings_gi.glsl (fixed in the shader: layout(binding)),
 * so a program needs no sampler uniforms. A draw desc carries a gi_bind_t:
 * zero is GI off (the hemispheric ambient of common/lighting.glsl). */
#ifndef MEADOW_GI_H
#define MEADOW_GI_H

#include "gfx/gfx.h"
#include "gi/gi_volume.h"

/* The volumes on the GPU: ao R16F, irr[3] RGBA16F (the 12 floats of a
 * cell, 4 per texture), all res[0] x res[1] x res[2], linear, clamped. */
typedef struct gi_gpu_t {
    gfx_texture_t ao, irr[3];
    float lo[3], hi[3], bounce[3];
} gi_gpu_t;

/* What a draw needs: the textures (ao 0: GI off), the box and the bounce. */
typedef struct gi_bind_t {
    GLuint ao, irr[3];
    float lo[3], inv_size[3], bounce[3];
} gi_bind_t;

/* False (logged, nothing kept) when a texture cannot be made. */
bool gi_gpu_make(gi_gpu_t *g, const gi_volume_t *v);
void gi_gpu_destroy(gi_gpu_t *g);
/* The bind of g (zero when g is NULL or not made). */
gi_bind_t gi_gpu_bind(const gi_gpu_t *g);
/* Sets u_gi_on, u_gi_lo, u_gi_inv_size and u_gi_bounce of program p (in
 * use) and, when b is on, binds its textures (b NULL: off). */
void gi_set_uniforms(GLuint p, const gi_bind_t *b);

#endif

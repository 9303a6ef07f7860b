/* raster: grass drawn by compute shaders instead of the hardware rasterizer.
 *
 * On the H100 the vertex/tessellation/fragment stages run on a small part of
 * the chip while compute runs on every SM, so millions of tiny grass
 * triangles rasterize far faster in compute (issue 14; docs/RASTER.md).
 * This module owns the visibility buffer (one 64-bit word per sample, 4
 * samples per pixel in the 4x MSAA pattern: depth high, RGBA8 colour low,
 * kept by atomicMin), its start from the opaque
 * depth, and the resolve + composite into the frame's target. The grass
 * modules only say what to draw: each has a compute shader that includes
 * shaders/raster/raster.glsl, made with raster_program_make and run with
 * raster_draw, which binds their buffers and uniforms through a callback.
 *
 * A frame:
 *   opaque scene drawn by the hardware into the target
 *   raster_begin(r, target)      fills every sample with the target's opaque depth
 *   bb_field_raster / blade_gpu_raster / blade_tiles_raster   (raster_draw)
 *   raster_end(r, target)        composites colour, coverage and depth
 *   (or raster_end_color: colour alone, in compute)
 *
 * Without GL_NV_shader_atomic_int64 (Mesa llvmpipe, CI) the buffer is two
 * uints per sample and each draw runs twice (nearest depth, then colour
 * where its depth won): same images, twice the work. */
#ifndef MEADOW_RASTER_H
#define MEADOW_RASTER_H

#include <stdbool.h>
#include <stdint.h>

#include "gfx/gfx.h"

#define RASTER_QUEUE_LAYERS 16
typedef struct raster_desc_t {
    int w, h;               /* target pixels, required */
    int samples;            /* per pixel: 4 (default; the standard 4x MSAA pattern) or 1 (the centre) */
    int small_samples;      /* a triangle whose box covers up to this many samples is scanned
                               by its primitive's thread at once; default 64 */
    int medium_samples;     /* up to this it is queued and scanned one per thread among
                               similar ones, beyond it by a work group; default 4096 */
    int queue_capacity;     /* queued triangles per list (medium, large) per draw; default RASTER_QUEUE_LAYERS
                               layers of small_samples-sample triangles over the target, at least 1 << 20 */
    bool no_atomic64;       /* force the two-pass 32-bit variant (tests); default: 64-bit
                               atomics when the GL has GL_NV_shader_atomic_int64 */
    const char *label;      /* default "raster" */
} raster_desc_t;

typedef struct raster_stats_t {
    uint32_t medium, large; /* queued by the last draw: medium triangles, bands of large ones */
    uint32_t overflow;      /* of those, beyond queue_capacity (not drawn; logged) */
} raster_stats_t;

typedef struct raster_t {
    raster_desc_t desc;     /* resolved */
    bool atomic64;
    gfx_buffer_t vis;       /* 8 bytes per sample */
    gfx_buffer_t queue;     /* large and medium counts and overflows, the large list, the medium list */
    gfx_buffer_t args;      /* two glDispatchComputeIndirect argument triples */
    gfx_texture_t opaque_depth; /* r32f, the farthest opaque sample of each pixel, written by raster_begin:
                                   what occlusion culling reads in this path */
    gfx_program_t init, init_ms, args_prog, composite;
    gfx_program_t composite_cs, composite_cs_ms; /* raster_end_color, single-sample and MSAA targets */
    int image_samples;                           /* GL_MAX_IMAGE_SAMPLES */
    GLuint empty_vao;
    raster_stats_t stats;
    bool warned_overflow;
} raster_t;

/* A grass module's compute rasterization shader, in two variants: one
 * thread per primitive, and RASTER_BIG (the queued medium triangles one per
 * thread, the large ones one per work group). */
typedef struct raster_program_t {
    gfx_program_t prim, big;
    bool atomic64;    /* made for a one-pass (64-bit atomic) raster_t */
    uint32_t defines; /* hash of the defines it was made with */
} raster_program_t;

/* True when the current context has 64-bit atomics for the one-pass buffer. */
bool raster_has_atomic64(void);
/* Fills defaults; false (and one log line) when w or h is not positive or a
 * field is out of range. */
bool raster_desc_resolve(const raster_desc_t *in, raster_desc_t *out);

bool raster_make(raster_t *r, const raster_desc_t *desc);
void raster_destroy(raster_t *r);

/* Compiles `cs` (path under shaders/) with `defines` for the raster
 * variant of `r` (atomic64 or not). id 0 on failure (logged). */
raster_program_t raster_program_make(const raster_t *r, const char *cs, const char *defines, const char *label);
void raster_program_destroy(raster_program_t *p);
/* Starts compiling what raster_program_make(r, cs, defines, ...) will
 * build for a raster_t made from desc (gfx_programs_prefetch), so it
 * compiles while the caller makes other things. */
void raster_program_prefetch(const raster_desc_t *desc, const char *cs, const char *defines);
/* *p made for r's variant: (re)made from cs/defines when it is missing or
 * was made for the other variant. False when it cannot be made (logged). */
bool raster_program_ensure(const raster_t *r, raster_program_t *p, const char *cs, const char *defines,
                           const char *label);

/* What a draw covers: `count` primitives, or (count_buffer.id != 0) the
 * uint at word `count_index` of count_buffer, at most `count_max`. */
typedef struct raster_items_t {
    uint32_t count;
    gfx_buffer_t count_buffer;
    uint32_t count_index;
    uint32_t count_max;
    /* This draw's work split (0: the desc's). Pixel-rate shaders with a
     * texture fetch per fragment (billboards) run best without a medium
     * list (medium_samples = small_samples) and a larger small one. */
    uint32_t small_samples, medium_samples;
} raster_items_t;

/* Binds the grass module's buffers, textures and uniforms on `prog`
 * (already in use); called before every dispatch of a draw. */
typedef void (*raster_bind_fn)(gfx_program_t prog, void *user);

/* Starts a frame: fills the visibility buffer from `target`'s depth
 * texture, per sample (raster_init.comp, no resolve blit), and writes
 * opaque_depth. The target must have r's size. */
void raster_begin(raster_t *r, const gfx_target_t *target);
/* Runs a grass module's program over `items` (both passes without 64-bit
 * atomics): threads per primitive, then the triangles they queued. */
void raster_draw(raster_t *r, const raster_program_t *p, const raster_items_t *items, raster_bind_fn bind,
                 void *user);
/* Composites the grass into `target`, colour and depth (binds its FBO;
 * a full-screen fragment pass, raster_composite.frag): for frames whose
 * depth is read back. */
void raster_end(raster_t *r, const gfx_target_t *target);
/* The same colour as raster_end, by a compute pass (raster_composite.comp)
 * that blends into the target's RGBA8 colour texture; its depth keeps the
 * opaque scene. 0.40 -> 0.04 ms on the H100 (world hybrid, 1080p, 4x).
 * raster_end where the colour is not RGBA8 or the GL cannot store to an
 * image of its samples. */
void raster_end_color(raster_t *r, const gfx_target_t *target);

/* Queued-triangle counts of the last draw (blocking read: tests, summaries). */
void raster_read_stats(raster_t *r, raster_stats_t *out);

#endif

/* gfx: the only layer that creates and destroys GL objects. Every object
 * gets a debug label and is tracked, so shutdown can release everything and
 * tests can count what is still alive. Also: shader programs from the
 * sources built into the library (or a folder) with #include, file:line
 * errors and a program-binary cache, FBOs with MSAA resolve, per-pass GPU timer
 * queries read back without stalling, fenced readback rings, screenshots and
 * a text HUD. */
#ifndef MEADOW_GFX_H
#define MEADOW_GFX_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/core.h"

/* ---- lifetime ------------------------------------------------------------ */
/* What gfx_init_desc takes; a zero field takes its default. The strings
 * are copied. */
typedef struct gfx_desc_t {
    const char *shader_dir;   /* read shader files from this folder (paths as under shaders/) instead
                                 of the table built into the library; default: $MEADOW_SHADER_DIR
                                 when set and not empty, else the built-in table */
    const char *shader_cache; /* program-binary cache folder (created when missing); default:
                                 $MEADOW_SHADER_CACHE when set and not empty, else no cache */
    bool poison;              /* fill buffers made uninitialized (gfx_buffer_desc_t) with 0xff bytes
                                 (NaN floats, 0xffffffff uints) and new targets' colour with magenta,
                                 so a kernel or frame that leaves part of one unwritten shows in a
                                 test (the GL tests' contexts); default: $MEADOW_GFX_POISON set,
                                 not empty and not "0" */
} gfx_desc_t;
/* The desc with its defaults filled in (the environment read). */
gfx_desc_t gfx_desc_defaults(const gfx_desc_t *desc);
/* Starts gfx in the current GL context. desc may be NULL (all defaults).
 * A cache folder that cannot be written is one warning, then no cache. */
bool gfx_init_desc(const gfx_desc_t *desc);
/* gfx_init_desc(NULL). */
bool gfx_init(void);
/* Every gfx call works on the current context: the live objects, the
 * programs and their uniform cache, the timers and counters, the upload
 * ring. A process starts with a default one (what gfx_init starts);
 * another GL context, or a library that must not share the host's state,
 * makes its own and binds it around its calls. */
typedef struct gfx_ctx_t gfx_ctx_t;
/* A context for the GL context current on this thread (gfx_init_desc in
 * it); the current context stays as it was. NULL when out of memory. */
gfx_ctx_t *gfx_ctx_make(const gfx_desc_t *desc);
/* Makes c current (NULL: the default context). */
void gfx_ctx_bind(gfx_ctx_t *c);
gfx_ctx_t *gfx_ctx_current(void);
/* gfx_shutdown in c, then frees it; the current context stays current,
 * or the default one when c was current. The default context is not freed. */
void gfx_ctx_destroy(gfx_ctx_t *c, bool report_leaks);
/* Releases every object still alive (logging each label in debug builds when
 * `report_leaks`), then the gfx-internal objects. */
void gfx_shutdown(bool report_leaks);
/* Number of live GL objects created through gfx (user objects only). */
int gfx_live_objects(void);
/* GL objects created through gfx since gfx_init (released or not): what a
 * test reads to see that nothing was remade. */
long gfx_objects_made(void);
/* Bytes of buffer and texture storage those objects hold (textures:
 * texels x format size x samples, +1/3 with mipmaps). */
size_t gfx_memory_bytes(void);
/* The GL's limits that decide what a scene may ask (admit), and the
 * GPU memory free now (GL_NVX_gpu_memory_info or GL_ATI_meminfo; 0 when the
 * GL tells neither, as llvmpipe, whose storage is host memory). */
typedef struct gfx_limits_t {
    GLint max_texture_size, max_renderbuffer_size;
    GLint max_gs_vertices, max_gs_components, max_compute_groups;
    double gpu_bytes;
} gfx_limits_t;
gfx_limits_t gfx_limits(void);
/* Returns the number of GL errors seen by glGetError since the last call,
 * logging each with `where`. Cheap enough for tests, not for the frame. */
int gfx_check_errors(const char *where);

/* ---- buffers -------------------------------------------------------------- */
typedef struct gfx_buffer_t {
    GLuint id;
    size_t size;
    void *mapped; /* persistent mapping, when desc.persistent */
    bool readable; /* desc.readable */
} gfx_buffer_t;

typedef struct gfx_buffer_desc_t {
    size_t size;        /* bytes, required */
    const void *data;   /* initial contents, optional (default: zeros) */
    bool uninitialized; /* without data: no zero fill, for a store the GPU writes whole before
                           any read (clearing blade mode's 660 MB blade buffer on meadow_large
                           took 0.65 s of the H200's start-up) */
    bool dynamic;       /* GL_DYNAMIC_STORAGE_BIT (glNamedBufferSubData) */
    bool persistent;    /* mapped coherent for the buffer's life: for writing, or for
                           reading when readable (gfx_readback) */
    bool readable;      /* GL_MAP_READ_BIT: a small buffer the CPU reads (readback rings, staging).
                           Never on a buffer the GPU uses every frame: on the H100 such buffers
                           can be placed where every GPU access crosses PCIe. */
    const char *label;  /* required: debug label */
} gfx_buffer_desc_t;

/* Returns id 0 and logs (naming the label and size) on failure, including
 * GL_OUT_OF_MEMORY. */
gfx_buffer_t gfx_buffer_make(const gfx_buffer_desc_t *desc);
void gfx_buffer_destroy(gfx_buffer_t *buf);
/* Copies `data` into the buffer in order with the commands around it: the
 * bytes go through gfx's upload ring (8 MB, persistently mapped) and a GPU
 * copy, so commands queued before the call still see the old contents, even
 * without frame pacing (see gfx.c "uploads"). A persistent buffer is written
 * directly through its mapping (the caller keeps the GPU off those bytes). */
void gfx_buffer_update(gfx_buffer_t buf, size_t offset, size_t size, const void *data);
/* Times the upload ring had to wait for the GPU since gfx_init (a whole ring
 * of uploads queued ahead of the GPU). */
long gfx_upload_waits(void);
/* Blocking read (tests, summaries, one-off): glGetNamedBufferSubData on a
 * readable buffer; any other buffer is read through a temporary readable
 * copy (4 MB chunks). A direct read of a buffer the GPU keeps using made the
 * H100 driver move it, once and for good, to memory every GPU access then
 * reached over PCIe (the billboard points, 25 MB, read once after
 * generation: billboard recovery 0.34 -> 4.9 ms, rendering 12.3 -> 15.9 ms
 * on meadow_large). False when the copy cannot be made (logged; out is
 * then untouched). */
bool gfx_buffer_read(gfx_buffer_t buf, size_t offset, size_t size, void *out);

/* ---- textures ------------------------------------------------------------- */
typedef struct gfx_texture_t {
    GLuint id;
    GLenum target;
    int w, h, layers, samples;
    GLenum format;
} gfx_texture_t;

typedef struct gfx_texture_desc_t {
    GLenum target;        /* default GL_TEXTURE_2D; GL_TEXTURE_2D_ARRAY, GL_TEXTURE_2D_MULTISAMPLE,
                             GL_TEXTURE_3D */
    int w, h;             /* required */
    int layers;           /* arrays: default 1; 3-D textures: the depth */
    int samples;          /* multisample: default 4 */
    GLenum format;        /* sized internal format, default GL_RGBA8 */
    int mip_levels;       /* default 1; -1 = full chain (generated after upload) */
    GLenum filter;        /* default GL_LINEAR (GL_LINEAR_MIPMAP_LINEAR with mips) */
    GLenum wrap;          /* default GL_CLAMP_TO_EDGE */
    const void *data;     /* optional; upload_format/type describe it */
    GLenum upload_format; /* default GL_RGBA */
    GLenum upload_type;   /* default GL_UNSIGNED_BYTE */
    const char *label;    /* required */
} gfx_texture_desc_t;

gfx_texture_t gfx_texture_make(const gfx_texture_desc_t *desc);
void gfx_texture_destroy(gfx_texture_t *tex);

/* ---- render targets ------------------------------------------------------- */
/* An MSAA colour + depth FBO and a single-sample resolve FBO. With samples
 * == 1 the draw FBO is already single-sample and resolve is a no-op copy. */
typedef struct gfx_target_t {
    int w, h, samples;
    GLuint fbo, resolve_fbo;
    gfx_texture_t color, depth, resolve_color, resolve_depth;
} gfx_target_t;

typedef struct gfx_target_desc_t {
    int w, h;            /* required */
    int samples;         /* default 4; 1 = no MSAA */
    GLenum color_format; /* default GL_RGBA8 */
    bool no_depth;       /* default: depth attachment present */
    /* default GL_DEPTH_COMPONENT24: as precise as DEPTH32F under a standard
     * (not reversed) depth range, whose values lie near 1 where a float
     * keeps 24 bits, and 0.7 ms cheaper per 1080p 4x MSAA frame on an
     * H200 (meadow_large, hardware path: clear, terrain and blades) */
    GLenum depth_format;
    const char *label;   /* required */
} gfx_target_desc_t;

gfx_target_t gfx_target_make(const gfx_target_desc_t *desc);
/* The samples a target asking for `requested` gets (0: the default 4),
 * at most GL_MAX_SAMPLES (read once per gfx_init). */
int gfx_target_samples(int requested);
void gfx_target_destroy(gfx_target_t *t);
void gfx_target_bind(const gfx_target_t *t); /* binds fbo and sets viewport */
/* Resolves colour (and depth, for occlusion culling) into the resolve FBO. */
void gfx_target_resolve(const gfx_target_t *t);
/* Depth only (occlusion culling, the compute rasterizer's start). */
void gfx_target_resolve_depth(const gfx_target_t *t);
/* Reads the resolved colour as RGBA8, row 0 at the top, alpha 255 (opaque). */
bool gfx_target_read(const gfx_target_t *t, core_image_t *out);
/* Reads the resolved depth (window depth in [0, 1], 1 where nothing was
 * drawn) as w * h floats, row 0 at the top; false when the target has no
 * depth. */
bool gfx_target_read_depth(const gfx_target_t *t, float *out);
/* As gfx_target_read_depth, but each pixel's nearest depth sample instead
 * of the one sample the resolve blit keeps (gfx_depth.c): the distance to
 * the nearest surface anything in the pixel shows, alike for grass drawn
 * per sample by the hardware and per pixel by the compute rasterizer's
 * composite. False when the target has no depth or the pass fails. */
bool gfx_target_read_depth_nearest(const gfx_target_t *t, float *out);
/* Resolve + read + write PNG (atomic). */
bool gfx_target_screenshot(const gfx_target_t *t, const char *path);

/* A framebuffer over every layer of `color` (a GL_TEXTURE_2D_ARRAY, not
 * owned) with a DEPTH32F array of as many layers (owned): a geometry
 * shader picks the layer each primitive goes to (gl_Layer). */
typedef struct gfx_layered_target_t {
    GLuint fbo;
    gfx_texture_t depth;
} gfx_layered_target_t;

gfx_layered_target_t gfx_layered_target_make(gfx_texture_t color, const char *label);
void gfx_layered_target_destroy(gfx_layered_target_t *t);

/* ---- programs ------------------------------------------------------------- */
/* Paths are relative to shaders/. The sources come from the table every
 * file under shaders/ was built into (src/gfx/embed_shaders.cmake), or
 * from gfx_desc_t.shader_dir when set: no file is read from the working
 * directory. Sources may `#include "common/x.glsl"` (relative to
 * shaders/). Compile and link errors are logged as
 * "shaders/<file>:<line>: <message>" and give id 0.
 * With a cache folder (gfx_desc_t.shader_cache) and a driver that offers
 * program binary formats, a linked program's binary is stored there under
 * a hash of its preprocessed stage sources, defines, transform feedback
 * outputs and the GL's vendor, renderer and version; a later make with
 * the same key loads it with glProgramBinary instead of compiling. An
 * entry that is truncated, corrupt or refused by the driver is compiled
 * instead and rewritten. */
typedef struct gfx_program_desc_t {
    const char *vs, *tcs, *tes, *gs, *fs, *cs;
    const char *defines;            /* inserted after #version, e.g. "#define N 4\n" */
    const char *const *tf_varyings; /* transform feedback outputs, NULL-terminated */
    bool tf_separate;               /* default interleaved */
    const char *label;              /* default: first stage's path */
} gfx_program_desc_t;

typedef struct gfx_program_t {
    GLuint id;
} gfx_program_t;

gfx_program_t gfx_program_make(const gfx_program_desc_t *desc);
/* n programs built side by side: every compile and link is issued before
 * any is waited for (GL_KHR_parallel_shader_compile's threads, turned on
 * here, build them at once: on the H100 8 programs took 2.2 s instead of
 * 15 s one by one). out[i] gets descs[i]'s program, id 0 where it failed
 * (logged as gfx_program_make does); returns true when all were made. */
bool gfx_programs_make(int n, const gfx_program_desc_t *descs, gfx_program_t *out);
/* Starts building n programs that a later gfx_program_make or
 * gfx_programs_make with an equal desc (the same stages, defines and
 * transform feedback; the label may differ) takes instead of building
 * them again, so what the caller does in between overlaps the driver's
 * compiles. Nothing is checked here: the make that takes a program checks
 * it. At most 32 wait at a time; one past that, or one already waiting,
 * is left to the make. */
void gfx_programs_prefetch(int n, const gfx_program_desc_t *descs);
/* Deletes the prefetched programs no make took; returns how many. */
int gfx_programs_prefetch_drop(void);
void gfx_program_destroy(gfx_program_t *p);
/* Programs made since the start (gfx_program_make and gfx_programs_make,
 * successful or not): their count, the wall clock spent compiling and
 * linking them (the status checks wait for the driver), the binary
 * cache's counts and the slowest five makes (a batch as "first
 * label+N"). */
#define GFX_PROGRAM_SLOWEST 5
typedef struct gfx_program_stats_t {
    int count;
    double ms;
    int prefetched, taken; /* issued by gfx_programs_prefetch; of those, taken by a make */
    bool cache_on;         /* a cache folder is in use (named, writable, the driver has binary formats) */
    int cache_hits;        /* programs loaded from the cache */
    int cache_misses;      /* programs compiled with the cache on (no entry, or one refused) */
    int cache_refused;     /* of the misses: entries found but truncated, corrupt or refused by the driver */
    int cache_stored;      /* entries written */
    struct {
        char label[64];
        double ms;
    } slowest[GFX_PROGRAM_SLOWEST]; /* slowest first; ms 0 where fewer */
} gfx_program_stats_t;
gfx_program_stats_t gfx_program_stats(void);
/* glGetUniformLocation, cached per (program, name) after the first ask
 * (names of up to 47 characters; -1 for a name the program lacks). */
GLint gfx_uniform(gfx_program_t p, const char *name);
/* Sets the uniforms of shaders/common/world_height.glsl on p (unbound is
 * fine; p keeps them): u_world_keys, the hash key of each of the `layers`
 * noise layers, and u_world_height, the amplitude (m); the values of
 * terrain_world_gpu (terrain/terrain_world.h), so gfx needs no scene type.
 * Every program that includes world_height.glsl takes it once after it
 * is made (the ground's, the billboard ring's, the tiles' on a world). */
void gfx_world_height_uniforms(gfx_program_t p, const uint32_t *keys, int layers, float height);
/* The preprocessed source of a file (tests): #include expanded with #line.
 * A file that is neither in the table nor in the shader folder gives NULL
 * and err "shaders/<file>: cannot read: ...". */
char *gfx_shader_preprocess(const char *rel_path, const char *defines, char *err, size_t err_size);

/* ---- vertex arrays, queries ---------------------------------------------- */
GLuint gfx_vertex_array_make(const char *label);
void gfx_vertex_array_destroy(GLuint *vao);
GLuint gfx_query_make(GLenum target, const char *label);
void gfx_query_destroy(GLuint *q);
GLuint gfx_transform_feedback_make(const char *label);
void gfx_transform_feedback_destroy(GLuint *tf);

/* ---- readback rings ----------------------------------------------------------
 * `depth` buffers of `size` bytes that GPU data is copied into, one slot per
 * frame: gfx_readback_copy (any number of copies into the slot being
 * written), then gfx_readback_fence (a fence sync after them; the slot is
 * pending until read). Later frames read pending slots whose fence has
 * passed, without stalling unless `wait`, through the buffers' persistent
 * read mapping (no GL call). The buffers are labelled "<label>". */
#define GFX_READBACK_MAX_DEPTH 8
typedef struct gfx_readback_t {
    gfx_buffer_t buf[GFX_READBACK_MAX_DEPTH];
    GLsync fence[GFX_READBACK_MAX_DEPTH]; /* after the slot's copies; 0 once passed */
    bool pending[GFX_READBACK_MAX_DEPTH]; /* fenced and not read yet */
    int depth, next;                      /* next: the slot being written (the oldest) */
} gfx_readback_t;

/* depth 1..GFX_READBACK_MAX_DEPTH. On failure (logged by gfx_buffer_make)
 * returns a ring with depth 0; gfx_readback_destroy accepts either. */
gfx_readback_t gfx_readback_make(size_t size, int depth, const char *label);
void gfx_readback_destroy(gfx_readback_t *r);
/* The slot being written is still pending: copying into it now would drop a
 * copy nobody has read (callers that must not lose one skip the frame). */
bool gfx_readback_busy(const gfx_readback_t *r);
/* glCopyNamedBufferSubData from src into the slot being written. */
void gfx_readback_copy(gfx_readback_t *r, gfx_buffer_t src, size_t src_offset, size_t dst_offset, size_t size);
/* Fences the slot being written, moves on to the next and returns the fenced
 * slot's index (for the caller's per-slot bookkeeping). */
int gfx_readback_fence(gfx_readback_t *r);
/* The oldest pending slot if its fence has passed (wait: blocks until it
 * has), marked read; -1 when none. Call until -1 to take every completed
 * slot in order. */
int gfx_readback_poll(gfx_readback_t *r, bool wait);
/* The newest pending slot whose fence has passed (wait: the newest pending
 * slot, blocking), or -1; every pending slot is marked read. */
int gfx_readback_latest(gfx_readback_t *r, bool wait);
/* Copies bytes of a slot returned by poll or latest to out. */
void gfx_readback_read(const gfx_readback_t *r, int slot, size_t offset, size_t size, void *out);

/* ---- GPU timers ------------------------------------------------------------
 * Passes of a kind (gfx_pass_t) timed with GL_TIME_ELAPSED queries. Results are read
 * GFX_TIMER_LATENCY frames later, only when available: no stall. Passes may
 * not nest. Each pass also runs the work-counter queries (see below). */
/* The kinds of pass a frame times (gfx_timer_begin) and counts (gfx_count):
 * every GPU pass of meadow is one of these, named by gfx_pass_name in
 * summary.txt, the frame log and the bench. */
typedef enum gfx_pass_t {
    GFX_PASS_TERRAIN,
    GFX_PASS_COLLIDERS,
    GFX_PASS_CHARACTER_SKIN,
    GFX_PASS_CHARACTER_DRAW,
    GFX_PASS_BB_CUBEMAPS,
    GFX_PASS_BB_COLLIDE,
    GFX_PASS_BB_RECOVER,
    GFX_PASS_BB_OCCLUSION,
    GFX_PASS_BB_RING,
    GFX_PASS_BB_RENDER,
    GFX_PASS_BB_RASTER,
    GFX_PASS_BLADE_PHYSICS,
    GFX_PASS_BLADE_CULL,
    GFX_PASS_BLADE_DRAW,
    GFX_PASS_BLADE_RASTER,
    GFX_PASS_TILES_PHYSICS,
    GFX_PASS_TILES_CULL,
    GFX_PASS_TILES_DRAW,
    GFX_PASS_TILES_RASTER,
    GFX_PASS_RASTER_INIT,
    GFX_PASS_RASTER_COMPOSITE,
    GFX_PASS_CANOPY_MATCH,   /* the canopy match's measure and step (ground_match) */
    GFX_PASS_TARGET_CLEAR,   /* the frame's target cleared (world_frame) */
    GFX_PASS_DEPTH_RESOLVE,  /* a multisampled depth resolved for occlusion culling */
    GFX_PASS_TEST,
    GFX_PASS_KINDS
} gfx_pass_t;
/* "terrain", "colliders", "character.skin", ..., "raster.composite",
 * "target.clear", "depth.resolve", "test" (tests' own passes). */
const char *gfx_pass_name(gfx_pass_t kind);
#define GFX_TIMER_MAX_PASSES 32
_Static_assert(GFX_PASS_KINDS <= GFX_TIMER_MAX_PASSES, "every pass kind has a timer");
#define GFX_TIMER_LATENCY 4
void gfx_timer_frame_begin(void);
void gfx_timer_begin(gfx_pass_t pass);
void gfx_timer_end(void);
int gfx_timer_count(void);
const char *gfx_timer_name(int i);
double gfx_timer_last_ms(int i);  /* latest available result */
double gfx_timer_cpu_ms(int i);   /* CPU wall ms between the pass's begin and end calls since the
                                     latest gfx_timer_frame_begin (the driver's time in its calls,
                                     blocking ones included) */
int gfx_timer_frames_since(int i); /* frames begun since the pass last ran (0: this frame) */
double gfx_timer_avg_ms(int i);   /* mean over every result so far */
double gfx_timer_max_ms(int i);   /* largest result so far */
double gfx_timer_median_ms(int i); /* median of the last 256 results */
/* Frame pacing without glFinish: puts a fence after the frame's commands,
 * then waits until at most `in_flight` frames (this one included) are
 * unfinished on the GPU, as a swap chain does; 1 waits for this frame.
 * Returns the seconds spent waiting, or -1 (logged, with the passes of the
 * frame) when a frame has not finished after 30 s: a hung GPU or a lost
 * context, which the caller should treat as fatal. */
double gfx_frame_end(int in_flight);
/* Drains all outstanding timer and counter queries (blocking). For
 * end-of-run summaries. */
void gfx_timer_flush(void);
void gfx_timer_reset_stats(void);
/* True when MEADOW_TIMER_SYNC=1: every pass begins after glFinish, so no
 * pass is charged for earlier work still in flight (profiling only). */
bool gfx_timer_sync(void);
/* Without waiting: clears the statistics and leaves out the results of the
 * frames begun so far (warm-up: first-use compiles, lazy allocations). */
void gfx_timer_skip_warmup(void);

/* ---- work counters ---------------------------------------------------------
 * Counts of work that do not depend on timing (gfx_count.c), for run
 * summaries and the CI baseline of test_work_counters. Per pass (the
 * gfx_timer pass open at the time, else "(untimed)"): draw calls, the draws
 * they stand for (a glMultiDrawArrays of n ranges counts 1 call, n ranges),
 * compute dispatches and their work groups (indirect dispatches add no
 * groups: the CPU does not know them), and the results of a
 * GL_PRIMITIVES_GENERATED and a GL_TRANSFORM_FEEDBACK_PRIMITIVES_WRITTEN
 * query that run with every timer pass (timer passes may therefore not
 * contain queries of those two targets). Query results are read when
 * available, never dropped; gfx_count_flush waits for the rest. Modules add
 * items they process by name with gfx_count_add (for example "bb.collided",
 * billboards the collide pass read). Totals run from gfx_count_reset;
 * gfx_timer_frame_begin counts frames. */
enum {
    GFX_COUNT_DRAWS,
    GFX_COUNT_DRAW_RANGES,
    GFX_COUNT_DISPATCHES,
    GFX_COUNT_GROUPS,
    GFX_COUNT_PRIMITIVES,
    GFX_COUNT_TF_WRITTEN,
    GFX_COUNT_KINDS
};
#define GFX_COUNT_MAX 64 /* passes, and items */
void gfx_count_draw(GLsizei ranges);
void gfx_count_dispatch(uint64_t groups);
void gfx_count_add(const char *item, double n);
void gfx_count_flush(void);
void gfx_count_reset(void); /* flushes, then zeroes every total and the frame count */
int gfx_count_frames(void);
int gfx_count_pass_count(void);
const char *gfx_count_pass_name(int i);
double gfx_count_pass_total(int i, int kind);
int gfx_count_item_count(void);
const char *gfx_count_item_name(int i);
double gfx_count_item_total(int i);

/* Every draw and dispatch entry point the project calls goes through a
 * counting wrapper: epoxy's macros are replaced here, so call sites stay
 * plain GL. A new entry point gets a wrapper beside these. */
static inline void gfx_counted_draw_arrays(GLenum mode, GLint first, GLsizei count)
{
    gfx_count_draw(1);
    epoxy_glDrawArrays(mode, first, count);
}
static inline void gfx_counted_draw_arrays_indirect(GLenum mode, const void *indirect)
{
    gfx_count_draw(1);
    epoxy_glDrawArraysIndirect(mode, indirect);
}
static inline void gfx_counted_draw_elements(GLenum mode, GLsizei count, GLenum type, const void *indices)
{
    gfx_count_draw(1);
    epoxy_glDrawElements(mode, count, type, indices);
}
static inline void gfx_counted_draw_arrays_instanced(GLenum mode, GLint first, GLsizei count, GLsizei instances)
{
    gfx_count_draw(1);
    epoxy_glDrawArraysInstanced(mode, first, count, instances);
}
static inline void gfx_counted_draw_elements_instanced(GLenum mode, GLsizei count, GLenum type, const void *indices,
                                                       GLsizei instances)
{
    gfx_count_draw(1);
    epoxy_glDrawElementsInstanced(mode, count, type, indices, instances);
}
static inline void gfx_counted_multi_draw_arrays(GLenum mode, const GLint *first, const GLsizei *count,
                                                 GLsizei drawcount)
{
    gfx_count_draw(drawcount);
    epoxy_glMultiDrawArrays(mode, first, count, drawcount);
}
static inline void gfx_counted_dispatch_compute(GLuint x, GLuint y, GLuint z)
{
    gfx_count_dispatch((uint64_t)x * y * z);
    epoxy_glDispatchCompute(x, y, z);
}
static inline void gfx_counted_dispatch_compute_indirect(GLintptr indirect)
{
    gfx_count_dispatch(0);
    epoxy_glDispatchComputeIndirect(indirect);
}
#undef glDrawArrays
#undef glDrawArraysIndirect
#undef glDrawElements
#undef glDrawArraysInstanced
#undef glDrawElementsInstanced
#undef glMultiDrawArrays
#undef glDispatchCompute
#undef glDispatchComputeIndirect
#define glDrawArrays gfx_counted_draw_arrays
#define glDrawArraysIndirect gfx_counted_draw_arrays_indirect
#define glDrawElements gfx_counted_draw_elements
#define glDrawArraysInstanced gfx_counted_draw_arrays_instanced
#define glDrawElementsInstanced gfx_counted_draw_elements_instanced
#define glMultiDrawArrays gfx_counted_multi_draw_arrays
#define glDispatchCompute gfx_counted_dispatch_compute
#define glDispatchComputeIndirect gfx_counted_dispatch_compute_indirect

/* ---- text HUD (stb_easy_font) ----------------------------------------------
 * Draws text in pixels from the top-left of the current viewport. */
void gfx_text_draw(const char *text, float x, float y, float scale, const float rgba[4]);

/* ---- fullscreen helpers ------------------------------------------------------ */
/* Blits the resolved target to the default framebuffer (window mode). */
void gfx_target_present(const gfx_target_t *t, int win_w, int win_h);

#endif

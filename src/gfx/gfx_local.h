/* gfx_local: what the gfx files share (private): the context that holds
 * every file's state, the live-object registry's calls. */
#ifndef MEADOW_GFX_LOCAL_H
#define MEADOW_GFX_LOCAL_H

#include "gfx/gfx.h"

/* kind is the glObjectLabel identifier: GL_BUFFER, GL_TEXTURE, GL_PROGRAM,
 * GL_FRAMEBUFFER, GL_VERTEX_ARRAY, GL_QUERY, GL_TRANSFORM_FEEDBACK. */
void gfx_track(GLenum kind, GLuint id, const char *label);
void gfx_untrack(GLenum kind, GLuint id);
void gfx_delete_object(GLenum kind, GLuint id);
/* Drops gfx_uniform's cached locations of program `prog` (0: of all). */
void gfx_uniforms_forget(GLuint prog);
/* Locations gfx_uniform holds for program `prog` (tests). */
int gfx_uniforms_cached(GLuint prog);
/* The shader table built into the library (gfx_shaders_embedded.c,
 * written at build time by embed_shaders.cmake): every file under
 * shaders/, by its path relative to shaders/, sorted by path. */
typedef struct gfx_shader_file_t {
    const char *path;
    size_t size;
    const char *text;
} gfx_shader_file_t;
extern const gfx_shader_file_t gfx_shader_files[];
extern const int gfx_shader_file_count;
/* gfx_shader: takes a resolved desc's shader folder and cache folder (in
 * the current context: reads its binary formats and driver strings). */
void gfx_shader_setup(const gfx_desc_t *desc);
/* The cache entry a make of d would read and write (tests). False when no
 * cache folder was named or d's sources cannot be read. */
bool gfx_shader_cache_path(const gfx_program_desc_t *d, char *out, size_t out_size);
/* A cache entry's check (GL-free): the magic, the key, the length and the
 * checksum of the binary. True with the driver's format and the binary's
 * bytes inside data. */
#define GFX_CACHE_HEADER 48
bool gfx_shader_cache_entry_check(const void *data, size_t size, const uint64_t key[2], GLenum *format,
                                  const void **binary, size_t *len);
/* Writes an entry's header for a binary of len bytes into head
 * (GFX_CACHE_HEADER bytes). */
void gfx_shader_cache_entry_header(void *head, const uint64_t key[2], GLenum format, const void *binary, size_t len);
void gfx_timer_shutdown(void);
/* gfx_count: the timer pass queries, the frame count, shutdown. */
void gfx_count_pass_begin(const char *pass);
void gfx_count_pass_end(void);
void gfx_count_frame(void);
void gfx_count_shutdown(void);
void gfx_text_shutdown(void);
void gfx_depth_shutdown(void);
/* gfx_buffer_update's ring upload for a raw buffer name (also gfx_text's
 * vertex buffer). */
void gfx_upload_raw(GLuint buffer, size_t offset, size_t size, const void *data);

/* ---- the context (gfx.c): every gfx file's state for one GL context ---- */
typedef struct gfx_obj_t {
    GLenum kind;
    GLuint id;
    size_t bytes; /* buffers and textures: storage allocated */
    char label[64];
} gfx_obj_t;


typedef struct gfx_registry_t {
    gfx_obj_t *objs;
    int count, cap;
    long made;       /* objects tracked since gfx_init */
    int max_samples; /* GL_MAX_SAMPLES, read once (0: not yet) */
    bool poison;     /* gfx_desc_t.poison */
} gfx_registry_t;


#define GFX_UPLOAD_SEGMENTS 16 /* the upload ring's fenced segments (gfx.c) */
typedef struct gfx_upload_ring_t {
    GLuint id;
    uint8_t *map;
    size_t head; /* next free byte */
    int seg;     /* segment holding head */
    GLsync fence[GFX_UPLOAD_SEGMENTS];
    bool failed; /* the ring could not be made: direct glNamedBufferSubData */
    long waits;
} gfx_upload_ring_t;


typedef struct gfx_counter_t {
    char name[32];
    double total[GFX_COUNT_KINDS];
} gfx_counter_t;


typedef struct gfx_query_pair_t {
    GLuint q[2]; /* primitives generated, transform-feedback primitives written */
    int pass;
} gfx_query_pair_t;


typedef struct gfx_count_state_t {
    gfx_counter_t passes[GFX_COUNT_MAX], items[GFX_COUNT_MAX];
    int pass_count, item_count;
    int open;           /* pass of the running queries, or -1 */
    gfx_query_pair_t running;
    gfx_query_pair_t *pending;
    int pending_count, pending_cap;
    gfx_query_pair_t *spare; /* read pairs, ready for reuse */
    int spare_count, spare_cap;
    int frames;
    bool warned_full;
} gfx_count_state_t;
#define GFX_COUNT_INITIAL {.pass_count = 1, .passes = {{.name = "(untimed)"}}, .open = -1}

typedef struct gfx_depth_state_t {
    GLuint prog;
    bool failed;
} gfx_depth_state_t;


typedef struct gfx_text_state_t {
    GLuint prog, vao, vbo;
    bool failed;
} gfx_text_state_t;


#define GFX_TIMER_HISTORY 256 /* samples a pass keeps for its median (gfx_timer.c) */

typedef struct gfx_timer_pass_t {
    char name[32];
    GLuint q[GFX_TIMER_LATENCY];
    bool pending[GFX_TIMER_LATENCY];
    int frame_of[GFX_TIMER_LATENCY]; /* frame each slot's query ran in */
    int last_frame;                  /* frame the pass last began in */
    double last, sum, max;
    long n;
    double hist[GFX_TIMER_HISTORY];
    int hist_n, hist_i;
    double cpu_ms, cpu_t0; /* CPU wall ms inside the pass this frame; its latest begin (s) */
} gfx_timer_pass_t;

typedef struct gfx_timer_state_t {
    gfx_timer_pass_t passes[GFX_TIMER_MAX_PASSES];
    int count;
    int frame;
    int open;
    int cpu_open; /* the pass between begin and end on the CPU clock, else -1 */
    int first_frame; /* samples of earlier frames are not recorded */
    GLsync fences[GFX_TIMER_LATENCY]; /* gfx_frame_end, oldest first */
    int fence_count;
    int sync; /* -1 unread, else MEADOW_TIMER_SYNC */
} gfx_timer_state_t;
#define GFX_TIMER_INITIAL {.open = -1, .cpu_open = -1, .sync = -1}

#define GFX_SHADER_FORMATS_MAX 16 /* program-binary formats read (gfx_shader.c) */

/* gfx_shader_setup's settings. */
typedef struct gfx_shader_state_t {
    char dir[CORE_PATH_MAX];   /* the shader folder; "" = the built-in table */
    char cache[CORE_PATH_MAX]; /* the cache folder; "" = none named */
    bool cache_on;             /* named, writable and the driver has binary formats */
    GLint formats[GFX_SHADER_FORMATS_MAX];
    int nformats;
    uint64_t driver[2]; /* hash of GL_VENDOR, GL_RENDERER, GL_VERSION */
} gfx_shader_state_t;


typedef struct pending_t pending_t; /* a program being built (gfx_shader.c) */
#define GFX_PREFETCH_MAX 32 /* programs issued ahead by gfx_programs_prefetch */
typedef struct gfx_prefetch_state_t {
    int count;
    char *key[GFX_PREFETCH_MAX];
    pending_t *pd[GFX_PREFETCH_MAX];
} gfx_prefetch_state_t;

#define GFX_UNIFORM_SLOTS 4096 /* a power of 2 */
#define GFX_UNIFORM_NAME_MAX 48 /* gfx_uniform caches names shorter than this */
typedef struct gfx_uniform_slot_t {
    GLuint prog; /* 0: never used */
    bool dead;   /* its program was deleted: skipped by searches, reused by inserts */
    GLint loc;
    char name[GFX_UNIFORM_NAME_MAX];
} gfx_uniform_slot_t;

typedef struct gfx_uniform_cache_t {
    gfx_uniform_slot_t slot[GFX_UNIFORM_SLOTS];
    int taken; /* slots with prog != 0 or dead */
} gfx_uniform_cache_t;


struct gfx_ctx_t {
    gfx_registry_t registry;     /* gfx.c: the live objects */
    gfx_upload_ring_t upload;    /* gfx.c */
    gfx_count_state_t count;     /* gfx_count.c */
    gfx_depth_state_t depth;     /* gfx_depth.c */
    gfx_text_state_t text;       /* gfx_text.c */
    gfx_timer_state_t timer;     /* gfx_timer.c */
    gfx_shader_state_t shader;   /* gfx_shader.c: settings */
    gfx_prefetch_state_t prefetch;
    gfx_uniform_cache_t uniforms;
    gfx_program_stats_t program_stats;
};
/* A context as it starts (gfx_ctx_make, the default one). */
#define GFX_CTX_INITIAL {.count = GFX_COUNT_INITIAL, .timer = GFX_TIMER_INITIAL}
/* The context every gfx call works on (gfx_ctx_bind). */
extern gfx_ctx_t *gfx_cur;

#endif

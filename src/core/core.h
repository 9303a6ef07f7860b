/* core: logging, seeded RNG, stateless hashes, file I/O with atomic writes,
 * growable buffers, 8-bit RGBA images, small geometry helpers and the one
 * per-frame view every grass driver draws with. GL-free; every other module
 * may use it. */
#ifndef MEADOW_CORE_H
#define MEADOW_CORE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* ---- logging ------------------------------------------------------------
 * One line per call on stderr, prefixed "meadow: " and the level.
 * core_log_set_quiet(true) drops info lines (tests, benchmarks). */
void core_log_info(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void core_log_warn(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void core_log_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
void core_log_set_quiet(bool quiet);
/* Every line to sink (severity 0 info, 1 warning, 2 error; the text
 * without prefix or newline) instead of stderr; NULL: stderr again.
 * Process-wide. */
typedef void (*core_log_sink_fn)(int severity, const char *line, void *user);
void core_log_set_sink(core_log_sink_fn sink, void *user);
/* Number of warnings/errors logged so far (tests assert on these). */
int core_log_warn_count(void);
int core_log_error_count(void);

/* ---- random numbers -----------------------------------------------------
 * PCG32: deterministic for a given seed on every platform. */
typedef struct core_rng_t {
    uint64_t state;
    uint64_t inc;
} core_rng_t;

void core_rng_seed(core_rng_t *rng, uint64_t seed, uint64_t stream);
uint32_t core_rng_u32(core_rng_t *rng);
float core_rng_float(core_rng_t *rng);                  /* [0,1) */
float core_rng_range(core_rng_t *rng, float lo, float hi); /* [lo,hi) */

/* Stateless integer hash (lowbias32). The GLSL twin is hash_u32() in
 * shaders/common/hash.glsl; both give identical bits. */
uint32_t core_hash_u32(uint32_t x);
/* Hash to [0,1) using the top 24 bits: exact in float on CPU and GPU. */
float core_hash_float(uint32_t x);
/* FNV-1a over bytes, for state hashes in determinism tests. */
uint64_t core_hash_bytes(const void *data, size_t size, uint64_t h);

/* ---- parallel loops ---------------------------------------------------------
 * fn(user, begin, end) over [0, n) split into contiguous bands, one per
 * thread (at most CORE_PARALLEL_MAX, the machine's cores), the caller's
 * thread taking the first; returns when every band is done. fn must only
 * write what its band owns. Falls back to one call when threads cannot be
 * made. */
#define CORE_PARALLEL_MAX 8
void core_parallel_for(int n, void (*fn)(void *user, int begin, int end), void *user);

/* ---- geometry --------------------------------------------------------------
 * Squared distance from p to the axis-aligned box [lo, hi] (0 inside it). */
float core_box_dist2(const float p[3], const float lo[3], const float hi[3]);

/* ---- files ---------------------------------------------------------------
 * core_fs_read reads a whole file into a malloc'd, NUL-terminated buffer,
 * at most CORE_FS_READ_MAX bytes (a larger file is refused, not read until
 * memory runs out). Only regular files are read: a FIFO, socket or device
 * (/dev/zero) is refused without blocking in open(2). On failure it returns
 * NULL and writes a reason into err (if non-NULL). */
#define CORE_FS_READ_MAX ((size_t)64 << 20)
/* Bytes of a path the program keeps (--scene, --out, ...), the NUL
 * included: the options refuse longer ones (app_cli.c). */
#define CORE_PATH_MAX 1024
char *core_fs_read(const char *path, size_t *size, char *err, size_t err_size);
/* Writes to "<path>.tmp.<pid>" then renames into place, so an interrupted
 * run never leaves a truncated file. Returns false and logs on failure. */
bool core_fs_write_atomic(const char *path, const void *data, size_t size);
/* mkdir -p. Returns false and logs on failure. */
bool core_fs_mkdirs(const char *path);
/* Creates dir (mkdir -p) and proves it is writable by writing and removing a
 * probe file. Returns false with a reason in err. */
bool core_fs_check_writable_dir(const char *dir, char *err, size_t err_size);
/* Claims dir for this process until it exits: an exclusive flock(2) on
 * dir/CORE_FS_LOCK_NAME (which then holds the process id), released by the
 * kernel when the process ends, however it ends. A folder this process
 * already holds is fine. Returns false with a reason in err when another
 * process holds it (two runs writing one folder mixed their files). */
#define CORE_FS_LOCK_NAME ".meadow.lock"
bool core_fs_lock_dir(const char *dir, char *err, size_t err_size);
/* Resolves a repository-relative path (e.g. "scenes/lawn.json") by trying,
 * in order: $MEADOW_ROOT/rel, ./rel, the compiled-in source dir/rel, the
 * installed data dir/rel (share/meadow). Writes the first that exists into
 * out. Returns false if none exists. */
bool core_fs_resolve(const char *rel, char *out, size_t out_size);

/* ---- growable buffers ------------------------------------------------------
 * Bytes or text appended in memory, then written atomically. Zero-initialise
 * (core_buf_t b = {0}); data stays NUL-terminated once anything was added
 * (NULL before). Out of memory: logged, then abort(). */
typedef struct core_buf_t {
    char *data;
    size_t len, cap;
} core_buf_t;

void core_buf_put(core_buf_t *b, const void *data, size_t size);
void core_buf_printf(core_buf_t *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
/* The text so far; "" when nothing was added. */
const char *core_buf_str(const core_buf_t *b);
/* core_fs_write_atomic of the contents (an empty file when nothing was added). */
bool core_buf_write(const core_buf_t *b, const char *path);
void core_buf_free(core_buf_t *b);

/* ---- images --------------------------------------------------------------
 * Tightly packed 8-bit images, row 0 at the top. */
typedef struct core_image_t {
    int w, h, channels; /* channels: 1..4 */
    uint8_t *px;
} core_image_t;

bool core_image_alloc(core_image_t *img, int w, int h, int channels);
void core_image_free(core_image_t *img);
/* Loads PNG/JPG/TGA via stb_image, forcing `channels` (0 keeps the file's).
 * Refuses (logged) what is not a regular file, a file over
 * CORE_FS_READ_MAX, and an image of more than CORE_IMAGE_MAX_PIXELS (a
 * small PNG can declare 2^24 x 2^24 pixels). */
#define CORE_IMAGE_MAX_PIXELS (8192.0 * 8192.0)
bool core_image_load(core_image_t *img, const char *path, int channels);
/* Decodes a PNG/JPG/TGA file held in memory, forcing `channels`. Logs
 * nothing: on failure returns false with the reason in err. */
bool core_image_decode(core_image_t *img, const void *data, size_t size, int channels, char *err, size_t err_size);
/* Writes PNG atomically (tmp + rename). */
bool core_image_write_png(const core_image_t *img, const char *path);
/* Writes an RGB JPEG atomically, box-filtered down by the smallest integer
 * factor that brings the width to at most max_width (0: full size);
 * quality 0 means 85. For images committed to docs/ (kept under 500 KB). */
bool core_image_write_jpg(const core_image_t *img, const char *path, int max_width, int quality);

/* Copies src (any channels, expanded to RGBA) into dst (RGBA) at (x, y),
 * clipped. */
void core_image_blit(core_image_t *dst, const core_image_t *src, int x, int y);
/* Fills a rectangle of an RGBA image, clipped. */
void core_image_fill(core_image_t *img, int x, int y, int w, int h, const uint8_t rgba[4]);
/* Draws text (stb_easy_font glyphs, `scale` pixels per font unit) into an
 * RGBA image with its top-left at (x, y). */
void core_image_text(core_image_t *img, int x, int y, int scale, const char *text, const uint8_t rgba[4]);

#endif

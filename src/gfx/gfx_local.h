/* gfx_local: the live-object registry shared by the gfx files (private). */
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

#endif

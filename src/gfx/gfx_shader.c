/* gfx_shader: GLSL programs from the shader sources built into the
 * library (gfx_shader_files, generated from shaders/ at build time by
 * embed_shaders.cmake) or from a folder named at gfx_init
 * (MEADOW_SHADER_DIR). Sources may `#include "path"` (relative to
 * shaders/); the preprocessor emits `#line <line> <file-index>` so compiler
 * messages (Mesa "0:12(3)" and NVIDIA "0(12)" forms) are rewritten to
 * "shaders/<file>:<line>: ...".
 * gfx_programs_make issues every program's compiles and link before it
 * waits for any, so a driver with GL_KHR_parallel_shader_compile builds
 * them side by side. With a cache folder (MEADOW_SHADER_CACHE), a program
 * whose key (preprocessed sources, defines, transform feedback, driver
 * strings) has an entry there is loaded with glProgramBinary instead; a
 * refused entry is compiled and rewritten. */
#include "gfx/gfx_local.h"

/* This file's state in the current context (gfx_local.h). */
#define SH (gfx_cur->shader)
#define PREFETCH (gfx_cur->prefetch)
#define UNI (gfx_cur->uniforms)
#define STATS (gfx_cur->program_stats)

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>


/* The text of shaders/<rel>: from the shader folder, else the built-in
 * table. NULL with a reason in why. */
static char *source_read(const char *rel, char *why, size_t why_size)
{
    if (SH.dir[0]) {
        char path[CORE_PATH_MAX + 256];
        snprintf(path, sizeof path, "%s/%s", SH.dir, rel);
        return core_fs_read(path, NULL, why, why_size);
    }
    for (int i = 0; i < gfx_shader_file_count; i++) {
        const gfx_shader_file_t *f = &gfx_shader_files[i];
        if (strcmp(f->path, rel) != 0) continue;
        char *text = malloc(f->size + 1);
        if (!text) {
            snprintf(why, why_size, "out of memory");
            return NULL;
        }
        memcpy(text, f->text, f->size + 1);
        return text;
    }
    snprintf(why, why_size, "not among the %d shaders built into the library (MEADOW_SHADER_DIR names a folder "
             "to read instead)", gfx_shader_file_count);
    return NULL;
}

#define MAX_FILES 32
#define MAX_DEPTH 8

typedef struct pp_t {
    char files[MAX_FILES][128];
    int nfiles;
    char *err;
    size_t err_size;
} pp_t;

static bool pp_file(pp_t *pp, core_buf_t *out, const char *rel, const char *defines, int depth)
{
    if (depth > MAX_DEPTH) {
        snprintf(pp->err, pp->err_size, "shaders/%s: #include nested deeper than %d", rel, MAX_DEPTH);
        return false;
    }
    if (pp->nfiles == MAX_FILES) {
        snprintf(pp->err, pp->err_size, "shaders/%s: more than %d included files", rel, MAX_FILES);
        return false;
    }
    int idx = pp->nfiles++;
    snprintf(pp->files[idx], sizeof pp->files[idx], "%s", rel);
    char why[256];
    char *src = source_read(rel, why, sizeof why);
    if (!src) {
        snprintf(pp->err, pp->err_size, "shaders/%s: cannot read: %s", rel, why);
        return false;
    }
    int line = 1;
    bool ok = true;
    for (char *p = src; *p && ok;) {
        char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p);
        const char *q = p;
        while (q < p + len && isspace((unsigned char)*q)) q++;
        if (depth == 0 && strncmp(q, "#version", 8) == 0) {
            core_buf_put(out, p, len);
            core_buf_put(out, "\n", 1);
            if (defines) core_buf_put(out, defines, strlen(defines));
            core_buf_printf(out, "#line %d %d\n", line + 1, idx);
        } else if (strncmp(q, "#include", 8) == 0) {
            const char *a = strchr(q, '"'), *b = a ? strchr(a + 1, '"') : NULL;
            if (!a || !b || b > p + len) {
                snprintf(pp->err, pp->err_size, "shaders/%s:%d: malformed #include", rel, line);
                ok = false;
                break;
            }
            char inc[128];
            snprintf(inc, sizeof inc, "%.*s", (int)(b - a - 1), a + 1);
            core_buf_printf(out, "#line 1 %d\n", pp->nfiles);
            ok = pp_file(pp, out, inc, NULL, depth + 1);
            core_buf_printf(out, "#line %d %d\n", line + 1, idx);
        } else {
            core_buf_put(out, p, len);
            core_buf_put(out, "\n", 1);
        }
        line++;
        p = eol ? eol + 1 : p + len;
    }
    free(src);
    return ok;
}

static char *preprocess(pp_t *pp, const char *rel, const char *defines, char *err, size_t err_size)
{
    memset(pp, 0, sizeof *pp);
    pp->err = err;
    pp->err_size = err_size;
    core_buf_t out = {0};
    if (!pp_file(pp, &out, rel, defines, 0)) {
        core_buf_free(&out);
        return NULL;
    }
    return out.data;
}

char *gfx_shader_preprocess(const char *rel_path, const char *defines, char *err, size_t err_size)
{
    pp_t pp;
    return preprocess(&pp, rel_path, defines, err, err_size);
}

/* Rewrites driver log lines to shaders/<file>:<line>: <message>. */
static void log_shader_errors(const pp_t *pp, const char *log, const char *what)
{
    for (const char *p = log; *p;) {
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p);
        int file = 0, line = 0, col = 0, used = 0;
        char msg[1024];
        if (len == 0) {
            p = eol ? eol + 1 : p + len;
            continue;
        }
        snprintf(msg, sizeof msg, "%.*s", (int)len, p);
        if ((sscanf(msg, "%d:%d(%d): %n", &file, &line, &col, &used) == 3 && used) ||
            (sscanf(msg, "%d(%d) : %n", &file, &line, &used) == 2 && used)) {
            const char *name = file >= 0 && file < pp->nfiles ? pp->files[file] : "?";
            core_log_error("shaders/%s:%d: %s", name, line, msg + used);
        } else {
            core_log_error("%s: %s", what, msg);
        }
        p = eol ? eol + 1 : p + len;
    }
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

/* One make (a batch counts its programs, under its first label +N). */
static void stats_add(const char *label, int programs, double ms)
{
    STATS.count += programs;
    STATS.ms += ms;
    int at = GFX_PROGRAM_SLOWEST;
    while (at > 0 && STATS.slowest[at - 1].ms < ms) at--;
    if (at == GFX_PROGRAM_SLOWEST) return;
    memmove(&STATS.slowest[at + 1], &STATS.slowest[at], (GFX_PROGRAM_SLOWEST - 1 - at) * sizeof STATS.slowest[0]);
    snprintf(STATS.slowest[at].label, sizeof STATS.slowest[at].label, "%s", label);
    STATS.slowest[at].ms = ms;
}

gfx_program_stats_t gfx_program_stats(void) { return STATS; }

/* d's stage files in pipeline order (NULL: no such stage); returns the
 * first, NULL when there is none. */
static const char *stage_paths(const gfx_program_desc_t *d, const char *paths[6])
{
    const char *all[6] = {d->vs, d->tcs, d->tes, d->gs, d->fs, d->cs};
    const char *first = NULL;
    for (int i = 0; i < 6; i++) {
        paths[i] = all[i];
        if (!first) first = all[i];
    }
    return first;
}

/* What d's program is called in messages and statistics. */
static const char *desc_label(const gfx_program_desc_t *d)
{
    const char *paths[6];
    const char *first = stage_paths(d, paths);
    return d->label ? d->label : first ? first : "?";
}

/* A program being built: its stages' shaders and their files' #line
 * tables (for mapping the compiler's messages). */
typedef struct pending_t {
    GLuint prog;
    GLuint shaders[6];
    pp_t pp[6];
    bool ok;       /* every stage preprocessed */
    bool keyed;    /* the cache is on: key holds the program's key */
    bool cached;   /* loaded from the cache (no shaders) */
    uint64_t key[2];
} pending_t;

/* What identifies d's program apart from its sources: every field but the
 * label (the prefetch table's key). */
static char *desc_key(const gfx_program_desc_t *d)
{
    core_buf_t b = {0};
    const char *parts[7] = {d->vs, d->tcs, d->tes, d->gs, d->fs, d->cs, d->defines};
    for (int i = 0; i < 7; i++) core_buf_printf(&b, "%s\x1f", parts[i] ? parts[i] : "");
    for (int i = 0; d->tf_varyings && d->tf_varyings[i]; i++) core_buf_printf(&b, "%s\x1e", d->tf_varyings[i]);
    core_buf_printf(&b, "%s", d->tf_separate ? "s" : "i");
    return b.data;
}

/* ---- program-binary cache ------------------------------------------------
 * An entry, <cache>/<key as 32 hex digits>.bin, is a GFX_CACHE_HEADER-byte
 * header (magic, the driver's binary format, the key, the binary's length
 * and FNV-1a checksum, in the machine's byte order) then the binary. The
 * key is two FNV-1a hashes (from two bases) of the driver strings, the
 * desc (stage paths, defines, transform feedback) and the preprocessed
 * stage sources. Entries are written atomically and never evicted. */
static const char cache_magic[8] = {'M', 'D', 'W', 'P', 'R', 'O', 'G', '1'};
typedef struct cache_head_t {
    char magic[8];
    uint32_t format, unused;
    uint64_t key[2];
    uint64_t len, sum;
} cache_head_t;
_Static_assert(sizeof(cache_head_t) == GFX_CACHE_HEADER, "cache entry header size");

void gfx_shader_cache_entry_header(void *head, const uint64_t key[2], GLenum format, const void *binary, size_t len)
{
    cache_head_t h = {.format = format, .key = {key[0], key[1]}, .len = len, .sum = core_hash_bytes(binary, len, 0)};
    memcpy(h.magic, cache_magic, sizeof h.magic);
    memcpy(head, &h, sizeof h);
}

bool gfx_shader_cache_entry_check(const void *data, size_t size, const uint64_t key[2], GLenum *format,
                                  const void **binary, size_t *len)
{
    cache_head_t h;
    if (size <= sizeof h) return false;
    memcpy(&h, data, sizeof h);
    const char *bin = (const char *)data + sizeof h;
    if (memcmp(h.magic, cache_magic, sizeof h.magic) != 0 || h.key[0] != key[0] || h.key[1] != key[1] ||
        h.len != size - sizeof h || h.sum != core_hash_bytes(bin, size - sizeof h, 0))
        return false;
    *format = h.format;
    *binary = bin;
    *len = size - sizeof h;
    return true;
}

/* Adds a string (NULL differs from "") to both hashes of a key. */
static void key_add(uint64_t key[2], const char *str)
{
    size_t n = str ? strlen(str) + 1 : 0;
    key[0] = core_hash_bytes(str ? str : "", n, key[0]);
    key[1] = core_hash_bytes(str ? str : "", n, key[1]);
}

void gfx_shader_setup(const gfx_desc_t *desc)
{
    memset(&SH, 0, sizeof SH);
    STATS.cache_on = false;
    snprintf(SH.dir, sizeof SH.dir, "%s", desc->shader_dir ? desc->shader_dir : "");
    if (SH.dir[0]) core_log_info("gfx: shaders read from %s instead of the built-in table", SH.dir);
    if (!desc->shader_cache) return;
    snprintf(SH.cache, sizeof SH.cache, "%s", desc->shader_cache);
    SH.driver[1] = 0x9e3779b97f4a7c15ull;
    key_add(SH.driver, "meadow program cache 1");
    const GLenum strings[3] = {GL_VENDOR, GL_RENDERER, GL_VERSION};
    for (int i = 0; i < 3; i++) key_add(SH.driver, (const char *)glGetString(strings[i]));
    GLint n = 0;
    glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &n);
    if (n <= 0) {
        core_log_info("gfx: program cache %s unused: the driver offers no program binary formats", SH.cache);
        return;
    }
    char err[512];
    if (!core_fs_check_writable_dir(SH.cache, err, sizeof err)) {
        core_log_warn("gfx: program cache: %s; running without it", err);
        return;
    }
    GLint *all = calloc((size_t)n, sizeof *all);
    if (!all) return;
    glGetIntegerv(GL_PROGRAM_BINARY_FORMATS, all);
    SH.nformats = n < GFX_SHADER_FORMATS_MAX ? n : GFX_SHADER_FORMATS_MAX;
    memcpy(SH.formats, all, (size_t)SH.nformats * sizeof *all);
    free(all);
    SH.cache_on = STATS.cache_on = true;
}

/* d's key from its preprocessed stage sources. */
static void cache_key(const gfx_program_desc_t *d, char *const srcs[6], uint64_t key[2])
{
    key[0] = SH.driver[0];
    key[1] = SH.driver[1];
    char *dk = desc_key(d);
    key_add(key, dk);
    free(dk);
    for (int i = 0; i < 6; i++) key_add(key, srcs[i]);
}

static void entry_path(const uint64_t key[2], char *out, size_t size)
{
    snprintf(out, size, "%s/%016llx%016llx.bin", SH.cache, (unsigned long long)key[0], (unsigned long long)key[1]);
}

static bool format_known(GLenum format)
{
    for (int i = 0; i < SH.nformats; i++)
        if ((GLenum)SH.formats[i] == format) return true;
    return false;
}

/* Loads pd's program from its entry (keying pd). False on no entry or a
 * refused one: pd->prog is then a fresh program to compile into. */
static bool cache_load(pending_t *pd, const gfx_program_desc_t *d, char *const srcs[6])
{
    cache_key(d, srcs, pd->key);
    pd->keyed = true;
    char path[CORE_PATH_MAX + 64], why[256];
    entry_path(pd->key, path, sizeof path);
    size_t size = 0;
    char *data = core_fs_read(path, &size, why, sizeof why);
    if (!data) {
        STATS.cache_misses++;
        return false;
    }
    GLenum format = 0;
    const void *bin = NULL;
    size_t len = 0;
    GLint linked = 0;
    if (gfx_shader_cache_entry_check(data, size, pd->key, &format, &bin, &len) && format_known(format)) {
        glProgramBinary(pd->prog, format, bin, (GLsizei)len);
        glGetProgramiv(pd->prog, GL_LINK_STATUS, &linked);
    }
    free(data);
    if (linked) {
        STATS.cache_hits++;
        pd->cached = true;
        return true;
    }
    STATS.cache_misses++;
    STATS.cache_refused++;
    core_log_info("gfx: program cache entry %s refused (truncated, corrupt or not this driver's); compiling %s",
                  path, desc_label(d));
    glDeleteProgram(pd->prog);
    pd->prog = glCreateProgram();
    return false;
}

/* Writes pd's linked program to its entry; a failed write turns the
 * cache off (logged by core_fs_write_atomic). */
static void cache_store(const pending_t *pd)
{
    GLint len = 0;
    glGetProgramiv(pd->prog, GL_PROGRAM_BINARY_LENGTH, &len);
    char *buf = len > 0 ? malloc(GFX_CACHE_HEADER + (size_t)len) : NULL;
    if (!buf) return;
    GLsizei got = 0;
    GLenum format = 0;
    glGetProgramBinary(pd->prog, len, &got, &format, buf + GFX_CACHE_HEADER);
    char path[CORE_PATH_MAX + 64];
    entry_path(pd->key, path, sizeof path);
    gfx_shader_cache_entry_header(buf, pd->key, format, buf + GFX_CACHE_HEADER, (size_t)got);
    if (got > 0 && core_fs_write_atomic(path, buf, GFX_CACHE_HEADER + (size_t)got)) STATS.cache_stored++;
    else if (got > 0) SH.cache_on = STATS.cache_on = false;
    free(buf);
}

/* Preprocesses d's stages into srcs (NULL where d has no stage); logs and
 * returns false when one fails (the others are kept). */
static bool stages_preprocess(const gfx_program_desc_t *d, pp_t pp[6], char *srcs[6])
{
    const char *paths[6];
    stage_paths(d, paths);
    bool ok = true;
    for (int i = 0; i < 6; i++) {
        srcs[i] = NULL;
        if (!paths[i]) continue;
        char err[512];
        srcs[i] = preprocess(&pp[i], paths[i], d->defines, err, sizeof err);
        if (!srcs[i]) core_log_error("%s", err);
        ok = ok && srcs[i];
    }
    return ok;
}

bool gfx_shader_cache_path(const gfx_program_desc_t *d, char *out, size_t out_size)
{
    if (!SH.cache[0]) return false;
    pp_t *pp = calloc(6, sizeof *pp);
    char *srcs[6] = {0};
    bool ok = pp && stages_preprocess(d, pp, srcs);
    uint64_t key[2];
    if (ok) cache_key(d, srcs, key);
    if (ok) entry_path(key, out, out_size);
    for (int i = 0; i < 6; i++) free(srcs[i]);
    free(pp);
    return ok;
}

/* Issues stage compiles and the link without waiting for either (a driver
 * with GL_KHR_parallel_shader_compile builds on its own threads), or loads
 * the program from the cache. */
static void program_issue(pending_t *pd, const gfx_program_desc_t *d)
{
    static const GLenum stage[6] = {GL_VERTEX_SHADER,   GL_TESS_CONTROL_SHADER, GL_TESS_EVALUATION_SHADER,
                                    GL_GEOMETRY_SHADER, GL_FRAGMENT_SHADER,     GL_COMPUTE_SHADER};
    char *srcs[6];
    pd->prog = glCreateProgram();
    pd->ok = stages_preprocess(d, pd->pp, srcs);
    bool loaded = pd->ok && SH.cache_on && cache_load(pd, d, srcs);
    for (int i = 0; i < 6 && !loaded; i++) {
        if (!srcs[i]) continue;
        pd->shaders[i] = glCreateShader(stage[i]);
        glShaderSource(pd->shaders[i], 1, (const GLchar *const *)&srcs[i], NULL);
        glCompileShader(pd->shaders[i]);
        glAttachShader(pd->prog, pd->shaders[i]);
    }
    for (int i = 0; i < 6; i++) free(srcs[i]);
    if (!pd->ok || loaded) return;
    if (d->tf_varyings) {
        int n = 0;
        while (d->tf_varyings[n]) n++;
        glTransformFeedbackVaryings(pd->prog, n, (const GLchar *const *)d->tf_varyings,
                                    d->tf_separate ? GL_SEPARATE_ATTRIBS : GL_INTERLEAVED_ATTRIBS);
    }
    if (pd->keyed) glProgramParameteri(pd->prog, GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
    glLinkProgram(pd->prog);
}

static char *info_log(GLuint obj, bool program)
{
    GLint n = 0;
    if (program) glGetProgramiv(obj, GL_INFO_LOG_LENGTH, &n);
    else glGetShaderiv(obj, GL_INFO_LOG_LENGTH, &n);
    char *log = calloc(1, (size_t)n + 1);
    if (log && program) glGetProgramInfoLog(obj, n, NULL, log);
    else if (log) glGetShaderInfoLog(obj, n, NULL, log);
    return log;
}

/* Waits for the link; on failure logs each stage that did not compile
 * (shaders/<file>:<line>: ...) or the link's message. d: the desc it was
 * issued from, or one with an equal key (a prefetched program). */
static gfx_program_t program_check(pending_t *pd, const gfx_program_desc_t *d)
{
    const char *paths[6];
    const char *first = stage_paths(d, paths);
    GLint linked = 0;
    if (pd->ok) glGetProgramiv(pd->prog, GL_LINK_STATUS, &linked);
    bool compiled = true;
    for (int i = 0; i < 6; i++) {
        if (!pd->shaders[i]) continue;
        GLint ok = 1;
        if (!linked) glGetShaderiv(pd->shaders[i], GL_COMPILE_STATUS, &ok);
        if (!ok) {
            char *log = info_log(pd->shaders[i], false);
            char what[300];
            snprintf(what, sizeof what, "shaders/%s", paths[i]);
            log_shader_errors(&pd->pp[i], log ? log : "", what);
            free(log);
            compiled = false;
        }
        glDetachShader(pd->prog, pd->shaders[i]);
        glDeleteShader(pd->shaders[i]);
    }
    if (pd->ok && compiled && !linked) {
        char *log = info_log(pd->prog, true);
        core_log_error("shaders/%s: link failed: %s", first ? first : "?", log ? log : "");
        free(log);
    }
    if (!linked) {
        glDeleteProgram(pd->prog);
        return (gfx_program_t){0};
    }
    if (pd->keyed && !pd->cached && SH.cache_on) cache_store(pd);
    gfx_track(GL_PROGRAM, pd->prog, desc_label(d));
    return (gfx_program_t){pd->prog};
}

static void threads_on(void)
{
    static bool set;
    if (set) return;
    set = true;
    if (epoxy_has_gl_extension("GL_KHR_parallel_shader_compile")) glMaxShaderCompilerThreadsKHR(0xffffffffu);
    else if (epoxy_has_gl_extension("GL_ARB_parallel_shader_compile")) glMaxShaderCompilerThreadsARB(0xffffffffu);
}

/* Programs issued by gfx_programs_prefetch, by their desc's key (every
 * field but the label). */

void gfx_programs_prefetch(int n, const gfx_program_desc_t *descs)
{
    threads_on();
    for (int i = 0; i < n; i++) {
        char *key = desc_key(&descs[i]);
        bool have = false;
        for (int k = 0; k < PREFETCH.count && !have; k++) have = key && strcmp(PREFETCH.key[k], key) == 0;
        pending_t *pd = have || !key || PREFETCH.count == GFX_PREFETCH_MAX ? NULL : calloc(1, sizeof *pd);
        if (!pd) { /* already issued, or no room: the make builds it then */
            free(key);
            continue;
        }
        program_issue(pd, &descs[i]);
        STATS.prefetched++;
        PREFETCH.key[PREFETCH.count] = key;
        PREFETCH.pd[PREFETCH.count++] = pd;
    }
}

/* The prefetched program with d's key, taken out of the table (NULL: none). */
static pending_t *prefetch_take(const gfx_program_desc_t *d)
{
    if (!PREFETCH.count) return NULL;
    char *key = desc_key(d);
    pending_t *pd = NULL;
    for (int k = 0; k < PREFETCH.count && key && !pd; k++) {
        if (strcmp(PREFETCH.key[k], key) != 0) continue;
        pd = PREFETCH.pd[k];
        free(PREFETCH.key[k]);
        PREFETCH.count--;
        PREFETCH.key[k] = PREFETCH.key[PREFETCH.count];
        PREFETCH.pd[k] = PREFETCH.pd[PREFETCH.count];
    }
    free(key);
    return pd;
}

int gfx_programs_prefetch_drop(void)
{
    int n = PREFETCH.count;
    for (int k = 0; k < n; k++) {
        pending_t *pd = PREFETCH.pd[k];
        for (int i = 0; i < 6; i++)
            if (pd->shaders[i]) glDeleteShader(pd->shaders[i]);
        glDeleteProgram(pd->prog);
        free(pd);
        free(PREFETCH.key[k]);
    }
    PREFETCH.count = 0;
    return n;
}

bool gfx_programs_make(int n, const gfx_program_desc_t *descs, gfx_program_t *out)
{
    threads_on();
    pending_t *pd = calloc((size_t)n, sizeof *pd);
    if (!pd) {
        core_log_error("gfx_programs_make: out of memory for %d programs", n);
        for (int i = 0; i < n; i++) out[i] = (gfx_program_t){0};
        return false;
    }
    double t0 = now_ms();
    for (int i = 0; i < n; i++) {
        pending_t *taken = prefetch_take(&descs[i]);
        if (taken) {
            pd[i] = *taken;
            free(taken);
            STATS.taken++;
        } else {
            program_issue(&pd[i], &descs[i]);
        }
    }
    bool ok = true;
    for (int i = 0; i < n; i++) ok = (out[i] = program_check(&pd[i], &descs[i])).id != 0 && ok;
    free(pd);
    const char *label = desc_label(&descs[0]);
    char batch[64];
    if (n > 1) snprintf(batch, sizeof batch, "%s+%d", label, n - 1);
    stats_add(n > 1 ? batch : label, n, now_ms() - t0);
    return ok;
}

gfx_program_t gfx_program_make(const gfx_program_desc_t *d)
{
    gfx_program_t p;
    gfx_programs_make(1, d, &p);
    return p;
}

void gfx_program_destroy(gfx_program_t *p)
{
    if (!p->id) return;
    gfx_untrack(GL_PROGRAM, p->id);
    gfx_delete_object(GL_PROGRAM, p->id);
    p->id = 0;
}

/* ---- uniform locations --------------------------------------------------
 * glGetUniformLocation is a string search in the driver, and the modules
 * ask for about 350 locations a frame (the world hybrid). An open-addressed
 * table of (program, name) -> location answers every ask after the first;
 * deleting a program drops its entries (program names are reused), and a
 * table three-quarters full or a shutdown starts it afresh. */

GLint gfx_uniform(gfx_program_t p, const char *name)
{
    size_t len = strlen(name);
    if (!p.id || len >= GFX_UNIFORM_NAME_MAX) return glGetUniformLocation(p.id, name);
    uint64_t h64 = core_hash_bytes(name, len, core_hash_bytes(&p.id, sizeof p.id, 0));
    uint32_t h = (uint32_t)(h64 ^ h64 >> 32);
    int insert = -1;
    for (uint32_t i = 0; i < GFX_UNIFORM_SLOTS; i++) {
        int k = (int)((h + i) & (GFX_UNIFORM_SLOTS - 1));
        gfx_uniform_slot_t *s = &UNI.slot[k];
        if (s->dead) {
            if (insert < 0) insert = k;
        } else if (!s->prog) {
            if (insert < 0) insert = k;
            break;
        } else if (s->prog == p.id && strcmp(s->name, name) == 0) {
            return s->loc;
        }
    }
    GLint loc = glGetUniformLocation(p.id, name);
    if (insert < 0 || (!UNI.slot[insert].dead && UNI.taken >= GFX_UNIFORM_SLOTS / 4 * 3)) {
        memset(&UNI, 0, sizeof UNI);
        insert = (int)(h & (GFX_UNIFORM_SLOTS - 1));
    }
    gfx_uniform_slot_t *s = &UNI.slot[insert];
    if (!s->dead) UNI.taken++;
    *s = (gfx_uniform_slot_t){.prog = p.id, .loc = loc};
    snprintf(s->name, sizeof s->name, "%s", name);
    return loc;
}

void gfx_uniforms_forget(GLuint prog)
{
    if (!prog) {
        memset(&UNI, 0, sizeof UNI);
        return;
    }
    for (int k = 0; k < GFX_UNIFORM_SLOTS; k++)
        if (UNI.slot[k].prog == prog) UNI.slot[k] = (gfx_uniform_slot_t){.dead = true};
}

int gfx_uniforms_cached(GLuint prog)
{
    int n = 0;
    for (int k = 0; k < GFX_UNIFORM_SLOTS; k++) n += prog && UNI.slot[k].prog == prog;
    return n;
}

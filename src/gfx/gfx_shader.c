/* gfx_shader: GLSL programs from files under shaders/. Sources may
 * `#include "path"` (relative to shaders/); the preprocessor emits
 * `#line <line> <file-index>` so compiler messages (Mesa "0:12(3)" and NVIDIA
 * "0(12)" forms) are rewritten to "shaders/<file>:<line>: ...". */
#include "gfx/gfx_local.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    char rel_path[256], path[1024], why[256];
    snprintf(rel_path, sizeof rel_path, "shaders/%s", rel);
    core_fs_resolve(rel_path, path, sizeof path);
    char *src = core_fs_read(path, NULL, why, sizeof why);
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

static GLuint compile(GLenum stage, const char *rel, const char *defines)
{
    pp_t pp;
    char err[512];
    char *src = preprocess(&pp, rel, defines, err, sizeof err);
    if (!src) {
        core_log_error("%s", err);
        return 0;
    }
    GLuint sh = glCreateShader(stage);
    const char *srcs[1] = {src};
    glShaderSource(sh, 1, srcs, NULL);
    glCompileShader(sh);
    free(src);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        GLint n = 0;
        glGetShaderiv(sh, GL_INFO_LOG_LENGTH, &n);
        char *log = calloc(1, (size_t)n + 1);
        glGetShaderInfoLog(sh, n, NULL, log);
        char what[300];
        snprintf(what, sizeof what, "shaders/%s", rel);
        log_shader_errors(&pp, log, what);
        free(log);
        glDeleteShader(sh);
        return 0;
    }
    return sh;
}

gfx_program_t gfx_program_make(const gfx_program_desc_t *d)
{
    struct {
        GLenum stage;
        const char *path;
    } stages[6] = {{GL_VERTEX_SHADER, d->vs},          {GL_TESS_CONTROL_SHADER, d->tcs},
                   {GL_TESS_EVALUATION_SHADER, d->tes}, {GL_GEOMETRY_SHADER, d->gs},
                   {GL_FRAGMENT_SHADER, d->fs},         {GL_COMPUTE_SHADER, d->cs}};
    GLuint prog = glCreateProgram();
    GLuint shaders[6] = {0};
    const char *first = NULL;
    bool ok = true;
    for (int i = 0; i < 6; i++) {
        if (!stages[i].path) continue;
        if (!first) first = stages[i].path;
        shaders[i] = compile(stages[i].stage, stages[i].path, d->defines);
        if (!shaders[i]) ok = false;
        else glAttachShader(prog, shaders[i]);
    }
    if (ok && d->tf_varyings) {
        int n = 0;
        while (d->tf_varyings[n]) n++;
        glTransformFeedbackVaryings(prog, n, (const GLchar *const *)d->tf_varyings,
                                    d->tf_separate ? GL_SEPARATE_ATTRIBS : GL_INTERLEAVED_ATTRIBS);
    }
    if (ok) {
        glLinkProgram(prog);
        GLint linked = 0;
        glGetProgramiv(prog, GL_LINK_STATUS, &linked);
        if (!linked) {
            GLint n = 0;
            glGetProgramiv(prog, GL_INFO_LOG_LENGTH, &n);
            char *log = calloc(1, (size_t)n + 1);
            glGetProgramInfoLog(prog, n, NULL, log);
            core_log_error("shaders/%s: link failed: %s", first ? first : "?", log);
            free(log);
            ok = false;
        }
    }
    for (int i = 0; i < 6; i++) {
        if (!shaders[i]) continue;
        glDetachShader(prog, shaders[i]);
        glDeleteShader(shaders[i]);
    }
    if (!ok) {
        glDeleteProgram(prog);
        return (gfx_program_t){0};
    }
    gfx_track(GL_PROGRAM, prog, d->label ? d->label : first);
    return (gfx_program_t){prog};
}

void gfx_program_destroy(gfx_program_t *p)
{
    if (!p->id) return;
    gfx_untrack(GL_PROGRAM, p->id);
    gfx_delete_object(GL_PROGRAM, p->id);
    p->id = 0;
}

GLint gfx_uniform(gfx_program_t p, const char *name) { return glGetUniformLocation(p.id, name); }

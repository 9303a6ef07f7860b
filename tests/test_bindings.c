/* test_bindings: the binding numbers stay defined once (GL-free). Every
 * buffer, texture and image binding is a name from
 * shaders/common/bindings_<module>.glsl, a file C and GLSL both include
 * (docs/DESIGN.md "Layout"). Fails when
 *   - a shader outside those files writes `binding = <digit>`;
 *   - a C file under src/ or tests/ passes a digit as the binding of
 *     glBindBufferBase/Range (storage, uniform), glBindTextureUnit or
 *     glBindImageTexture;
 *   - a bindings file holds a line other than blank, comment, #ifndef /
 *     #define / #endif (so it stays valid in both languages), defines a
 *     name another file defines too, or a name no shader uses.
 * The matchers are first run on made-up lines, so a broken pattern fails
 * instead of passing everything. Run from the source directory. */
#include "test.h"

#include <dirent.h>
#include <regex.h>
#include <string.h>
#include <sys/stat.h>

#include "core/core.h"

#define MAX_NAMES 256

typedef struct scan_t {
    regex_t shader_literal, c_literal, define_line, other_line;
    char names[MAX_NAMES][64];
    char owner[MAX_NAMES][512];
    int nnames, files;
    core_buf_t shader_text; /* every shader outside the bindings files */
} scan_t;

static bool ends_with(const char *s, const char *tail)
{
    size_t n = strlen(s), m = strlen(tail);
    return n >= m && strcmp(s + n - m, tail) == 0;
}

static bool is_bindings_file(const char *path)
{
    const char *base = strrchr(path, '/');
    return strstr(path, "shaders/common/") && base && strncmp(base + 1, "bindings_", 9) == 0;
}

/* Each line of text matching re, reported as path:line. */
static int count_matches(const regex_t *re, const char *path, const char *text)
{
    int found = 0, line = 1;
    for (const char *p = text; *p; line++) {
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p);
        char buf[1024];
        snprintf(buf, sizeof buf, "%.*s", (int)(len < sizeof buf ? len : sizeof buf - 1), p);
        if (regexec(re, buf, 0, NULL, 0) == 0) {
            fprintf(stderr, "%s:%d: literal binding: %s\n", path, line, buf);
            found++;
        }
        p = eol ? eol + 1 : p + len;
    }
    return found;
}

/* Remembers a defined name; 1 (reported) when another file has it. */
static int add_name(scan_t *s, const char *name, const char *path, int line)
{
    for (int k = 0; k < s->nnames; k++) {
        if (strcmp(s->names[k], name) != 0) continue;
        fprintf(stderr, "%s:%d: %s is also defined in %s\n", path, line, name, s->owner[k]);
        return 1;
    }
    if (s->nnames == MAX_NAMES) {
        fprintf(stderr, "%s:%d: more than %d binding names\n", path, line, MAX_NAMES);
        return 1;
    }
    snprintf(s->names[s->nnames], sizeof s->names[0], "%s", name);
    snprintf(s->owner[s->nnames++], sizeof s->owner[0], "%s", path);
    return 0;
}

/* A bindings file: only blank, comment and preprocessor lines, each
 * #define NAME VALUE remembered with its file. */
static int check_bindings_file(scan_t *s, const char *path, const char *text)
{
    int bad = 0, line = 1;
    bool in_comment = false;
    for (const char *p = text; *p; line++) {
        const char *eol = strchr(p, '\n');
        size_t len = eol ? (size_t)(eol - p) : strlen(p);
        char buf[512];
        snprintf(buf, sizeof buf, "%.*s", (int)(len < sizeof buf ? len : sizeof buf - 1), p);
        regmatch_t m[2];
        bool comment_line = in_comment || strncmp(buf, "/*", 2) == 0;
        if (comment_line) {
            in_comment = !strstr(buf, "*/");
        } else if (regexec(&s->define_line, buf, 2, m, 0) == 0) {
            char name[64];
            snprintf(name, sizeof name, "%.*s", (int)(m[1].rm_eo - m[1].rm_so), buf + m[1].rm_so);
            bad += add_name(s, name, path, line);
        } else if (regexec(&s->other_line, buf, 0, NULL, 0) != 0) {
            fprintf(stderr, "%s:%d: not valid in both C and GLSL: %s\n", path, line, buf);
            bad++;
        }
        p = eol ? eol + 1 : p + len;
    }
    return bad;
}

static bool is_shader(const char *path)
{
    static const char *const ext[] = {".glsl", ".vert", ".frag", ".geom", ".comp", ".tesc", ".tese"};
    for (size_t k = 0; k < sizeof ext / sizeof ext[0]; k++)
        if (ends_with(path, ext[k])) return true;
    return false;
}

static int check_file(scan_t *s, const char *path)
{
    bool c_source = ends_with(path, ".c") || ends_with(path, ".h");
    if (!is_shader(path) && !c_source) return 0;
    s->files++;
    char why[256];
    char *text = core_fs_read(path, NULL, why, sizeof why);
    if (!text) {
        fprintf(stderr, "%s: cannot read: %s\n", path, why);
        return 1;
    }
    int bad = 0;
    if (is_bindings_file(path)) {
        bad = check_bindings_file(s, path, text);
    } else if (is_shader(path)) {
        bad = count_matches(&s->shader_literal, path, text);
        core_buf_put(&s->shader_text, text, strlen(text));
    } else {
        bad = count_matches(&s->c_literal, path, text);
    }
    free(text);
    return bad;
}

/* check_file on every file below dir. */
static int walk(scan_t *s, const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) {
        fprintf(stderr, "%s: cannot open\n", dir);
        return 1;
    }
    int bad = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        char path[512];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        struct stat st;
        if (stat(path, &st) != 0) continue;
        if (S_ISDIR(st.st_mode)) {
            bad += walk(s, path);
        } else {
            bad += check_file(s, path);
        }
    }
    closedir(d);
    return bad;
}

static bool matches(const regex_t *re, const char *line)
{
    return regexec(re, line, 0, NULL, 0) == 0;
}

/* The matchers on made-up lines (split so this file does not match). */
static void check_matchers(const scan_t *s)
{
    CHECK(matches(&s->shader_literal, "layout(std430, binding" " = 3) buffer Points { uint p[]; };"));
    CHECK(matches(&s->shader_literal, "layout(binding" "=12) uniform sampler3D u_gi_ao;"));
    CHECK(!matches(&s->shader_literal, "layout(std430, binding = BB_BIND_POINTS) buffer Points"));
    CHECK(matches(&s->c_literal, "    glBindBufferBase" "(GL_SHADER_STORAGE_BUFFER, 4, t->spheres.id);"));
    CHECK(matches(&s->c_literal, "glBindBufferRange" "(GL_UNIFORM_BUFFER, 0, f->objects.id, 0, 64);"));
    CHECK(matches(&s->c_literal, "glBindTextureUnit" "(0, tex.id);"));
    CHECK(matches(&s->c_literal, "glBindImageTexture" "(0, img, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);"));
    CHECK(!matches(&s->c_literal, "glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BLADE_BIND_ETA, g->eta.id);"));
    CHECK(!matches(&s->c_literal, "glBindBufferBase(GL_TRANSFORM_FEEDBACK_BUFFER, 0, f->points.id);"));
    CHECK(matches(&s->define_line, "#define BB_BIND_POOL 1   /* free-slot stack */"));
    CHECK(!matches(&s->define_line, "const int BB_BIND_POOL = 1;"));
    CHECK(!matches(&s->other_line, "const int BB_BIND_POOL = 1;"));
    CHECK(matches(&s->other_line, "#ifndef BINDINGS_BB_GLSL"));
}

int main(void)
{
    static scan_t s;
    CHECK(regcomp(&s.shader_literal, "binding[[:space:]]*=[[:space:]]*[0-9]", REG_EXTENDED) == 0);
    CHECK(regcomp(&s.c_literal,
                  "glBind(BufferBase|BufferRange)\\([[:space:]]*GL_(SHADER_STORAGE|UNIFORM)_BUFFER,[[:space:]]*[0-9]|"
                  "glBind(TextureUnit|ImageTexture)\\([[:space:]]*[0-9]",
                  REG_EXTENDED) == 0);
    CHECK(regcomp(&s.define_line, "^#define ([A-Z][A-Z0-9_]*) [0-9]+( +/\\*.*\\*/)?$", REG_EXTENDED) == 0);
    CHECK(regcomp(&s.other_line, "^$|^#ifndef [A-Z0-9_]+$|^#define [A-Z0-9_]+$|^#endif$", REG_EXTENDED) == 0);
    if (test_failures) return 1;
    check_matchers(&s);

    int bad = 0;
    static const char *const roots[] = {"shaders", "src", "tests"};
    for (int r = 0; r < 3; r++) bad += walk(&s, roots[r]);
    CHECK_MSG(bad == 0, "%d problem(s) above", bad);
    CHECK_MSG(s.files > 100 && s.nnames > 50, "only %d files and %d names read: not the source directory?", s.files,
              s.nnames);
    for (int k = 0; k < s.nnames; k++)
        CHECK_MSG(strstr(core_buf_str(&s.shader_text), s.names[k]), "%s (%s) is used by no shader", s.names[k],
                  s.owner[k]);
    printf("%d files, %d binding names\n", s.files, s.nnames);
    core_buf_free(&s.shader_text);
    regfree(&s.shader_literal), regfree(&s.c_literal), regfree(&s.define_line), regfree(&s.other_line);
    TEST_END();
}

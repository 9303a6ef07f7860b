/* test_gfx_shader_embed: the shader table built into the library holds
 * every GLSL file under shaders/, byte for byte; from a working directory
 * that has no shaders/ (a temporary folder), programs made from the table
 * equal those made from MEADOW_SHADER_DIR=<source>/shaders (link result,
 * active uniforms); a shader folder with a modified shader is honoured and
 * one missing a file fails cleanly; an unknown shader name is one error
 * naming shaders/<file> and id 0, not a crash. */
#include "test.h"
#include "test_gl.h"

#include "gfx/gfx_local.h"

#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define SHADERS MEADOW_SOURCE_DIR "/shaders"
#define NPROGS 4

/* GLSL files under dir/rel (the extensions embed_shaders.cmake takes). */
static int count_glsl(const char *dir, const char *rel)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, rel);
    DIR *d = opendir(path);
    if (!d) return 0;
    static const char *const exts[] = {".glsl", ".comp", ".vert", ".frag", ".geom", ".tesc", ".tese"};
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        char sub[1024];
        snprintf(sub, sizeof sub, "%s%s%s", rel, rel[0] ? "/" : "", e->d_name);
        const char *dot = strrchr(e->d_name, '.');
        bool glsl = false;
        for (size_t k = 0; dot && k < sizeof exts / sizeof exts[0]; k++) glsl = glsl || strcmp(dot, exts[k]) == 0;
        n += glsl ? 1 : count_glsl(dir, sub);
    }
    closedir(d);
    return n;
}

/* Every entry of the table against its file. */
static void check_table(void)
{
    CHECK(gfx_shader_file_count == count_glsl(SHADERS, ""));
    for (int i = 0; i < gfx_shader_file_count; i++) {
        const gfx_shader_file_t *f = &gfx_shader_files[i];
        char path[2048];
        snprintf(path, sizeof path, SHADERS "/%s", f->path);
        size_t size = 0;
        char *text = core_fs_read(path, &size, NULL, 0);
        CHECK_MSG(text && size == f->size && strlen(f->text) == f->size && memcmp(text, f->text, size) == 0,
                  "embedded %s differs from %s", f->path, path);
        CHECK(i == 0 || strcmp(gfx_shader_files[i - 1].path, f->path) < 0);
        free(text);
    }
}

/* What a program is, as far as a caller can tell: linked, and its active
 * uniforms (name, type, size, location) in the driver's order. */
typedef struct shape_t {
    bool linked;
    char uniforms[2048];
} shape_t;

static shape_t program_shape(const gfx_program_desc_t *d)
{
    shape_t s = {0};
    gfx_program_t p = gfx_program_make(d);
    s.linked = p.id != 0;
    GLint n = 0;
    if (p.id) glGetProgramiv(p.id, GL_ACTIVE_UNIFORMS, &n);
    size_t at = 0;
    for (GLint i = 0; i < n && at < sizeof s.uniforms - 128; i++) {
        char name[96];
        GLint size = 0;
        GLenum type = 0;
        glGetActiveUniform(p.id, (GLuint)i, sizeof name, NULL, &size, &type, name);
        at += (size_t)snprintf(s.uniforms + at, sizeof s.uniforms - at, "%s:%x:%d@%d;", name, type, size,
                               glGetUniformLocation(p.id, name));
    }
    gfx_program_destroy(&p);
    return s;
}

static const gfx_program_desc_t progs[NPROGS] = {
    {.vs = "tests/tri.vert", .fs = "tests/tri.frag"},
    {.cs = "tests/uniforms.comp", .defines = "#define UNIFORMS_AB 1\n"},
    {.cs = "gfx/depth_nearest.comp"},
    {.vs = "gfx/text.vert", .fs = "gfx/text.frag"},
};

/* Makes d, which must fail, with stderr into path; returns what was
 * written there. */
static char *logged_make(const gfx_program_desc_t *d, const char *path)
{
    fflush(stderr);
    int saved = dup(2);
    FILE *f = fopen(path, "w");
    if (saved < 0 || !f || dup2(fileno(f), 2) < 0) return NULL;
    CHECK(gfx_program_make(d).id == 0);
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    fclose(f);
    char *text = core_fs_read(path, NULL, NULL, 0);
    fputs(text ? text : "", stderr);
    return text;
}

/* Restarts gfx with desc in the same context. */
static void restart(const gfx_desc_t *desc)
{
    gfx_shutdown(true);
    gfx_init_desc(desc);
}

/* A shader folder of tri.vert, its include, and a tri.frag with one more
 * uniform; no uniforms.comp. */
static void write_override(const char *dir)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/tests", dir);
    CHECK(core_fs_mkdirs(path));
    const char *copies[2] = {"tests/tri.vert", "tests/ok_include.glsl"};
    for (int i = 0; i < 2; i++) {
        char from[2048];
        size_t size = 0;
        snprintf(from, sizeof from, SHADERS "/%s", copies[i]);
        char *text = core_fs_read(from, &size, NULL, 0);
        CHECK(text != NULL);
        snprintf(path, sizeof path, "%s/%s", dir, copies[i]);
        CHECK(text && core_fs_write_atomic(path, text, size));
        free(text);
    }
    const char frag[] = "#version 450 core\n"
                        "out vec4 o_color;\n"
                        "uniform float u_override;\n"
                        "void main() { o_color = vec4(u_override, 0.0, 0.0, 1.0); }\n";
    snprintf(path, sizeof path, "%s/tests/tri.frag", dir);
    CHECK(core_fs_write_atomic(path, frag, sizeof frag - 1));
}

int main(void)
{
    check_table();
    unsetenv("MEADOW_SHADER_DIR");
    unsetenv("MEADOW_ROOT");
    char tmp[1024];
    snprintf(tmp, sizeof tmp, "%s/cwd-XXXXXX", test_out_dir());
    CHECK(mkdtemp(tmp) != NULL);
    CHECK(chdir(tmp) == 0);
    struct stat st;
    CHECK(stat("shaders", &st) != 0);

    test_gl_init();
    CHECK(gfx_desc_defaults(NULL).shader_dir == NULL);
    shape_t embedded[NPROGS];
    for (int i = 0; i < NPROGS; i++) {
        embedded[i] = program_shape(&progs[i]);
        CHECK_MSG(embedded[i].linked, "program %d from the table", i);
    }
    CHECK(strstr(embedded[1].uniforms, "u_a:") && strstr(embedded[1].uniforms, "u_b:"));

    /* An unknown shader: one error naming it, id 0; its include too. */
    int errs = core_log_error_count();
    CHECK(gfx_program_make(&(gfx_program_desc_t){.vs = "tests/no_such.vert", .fs = "tests/tri.frag"}).id == 0);
    CHECK(core_log_error_count() == errs + 1);
    char err[512];
    CHECK(gfx_shader_preprocess("tests/no_such.vert", NULL, err, sizeof err) == NULL);
    CHECK_MSG(strstr(err, "shaders/tests/no_such.vert: cannot read") && strstr(err, "built into"), "%s", err);
    CHECK(gfx_shader_preprocess("../shaders/tests/tri.vert", NULL, err, sizeof err) == NULL);

    /* The same programs from the source's shaders/ through the environment. */
    setenv("MEADOW_SHADER_DIR", SHADERS, 1);
    CHECK(gfx_desc_defaults(NULL).shader_dir && strcmp(gfx_desc_defaults(NULL).shader_dir, SHADERS) == 0);
    restart(NULL);
    for (int i = 0; i < NPROGS; i++) {
        shape_t dir = program_shape(&progs[i]);
        CHECK_MSG(dir.linked == embedded[i].linked && strcmp(dir.uniforms, embedded[i].uniforms) == 0,
                  "program %d: table '%s', folder '%s'", i, embedded[i].uniforms, dir.uniforms);
    }
    unsetenv("MEADOW_SHADER_DIR");

    /* A folder of our own (the desc field): its tri.frag is the one used;
     * a file it lacks is not taken from the table. */
    char over[1100];
    snprintf(over, sizeof over, "%s/override", tmp);
    write_override(over);
    restart(&(gfx_desc_t){.shader_dir = over});
    shape_t mod = program_shape(&progs[0]);
    CHECK_MSG(mod.linked && strstr(mod.uniforms, "u_override:"), "%s", mod.uniforms);
    errs = core_log_error_count();
    CHECK(!program_shape(&progs[1]).linked);
    CHECK(core_log_error_count() == errs + 1);
    CHECK(gfx_shader_preprocess("tests/uniforms.comp", NULL, err, sizeof err) == NULL);
    CHECK_MSG(strstr(err, "shaders/tests/uniforms.comp: cannot read"), "%s", err);

    /* Compile errors from the table still name shaders/<file>:<line>. */
    restart(NULL);
    char log_path[1100];
    snprintf(log_path, sizeof log_path, "%s/broken.log", tmp);
    char *log = logged_make(&(gfx_program_desc_t){.vs = "tests/tri.vert", .fs = "tests/broken.frag"}, log_path);
    CHECK_MSG(log && strstr(log, "shaders/tests/broken.frag:7: "), "%s", log ? log : "(no log)");
    free(log);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

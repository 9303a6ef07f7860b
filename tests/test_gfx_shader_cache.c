/* test_gfx_shader_cache: the program-binary cache. Without a folder it is
 * off. With one and a driver that has binary formats, a cold make writes an
 * entry per program, a second make (the same gfx, a prefetch, a fresh
 * gfx_init) loads it, and an entry that is corrupt, truncated, or well
 * formed but refused by the driver is compiled and rewritten; a folder
 * that cannot be written is one warning and no cache. The entry check is
 * also run on its own (GL-free). The test runs itself again with Mesa's
 * shader cache disabled (MESA_SHADER_CACHE_DISABLE: no binary formats on
 * llvmpipe) for the no-op path: no folder made, nothing read or written, a
 * corrupt entry ignored. */
#include "test.h"
#include "test_gl.h"

#include "gfx/gfx_local.h"
#include "common/bindings_tests.glsl"

#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static const gfx_program_desc_t progs[2] = {
    {.vs = "tests/tri.vert", .fs = "tests/tri.frag", .label = "cache.tri"},
    {.cs = "tests/uniforms.comp", .defines = "#define UNIFORMS_AB 1\n", .label = "cache.uniforms"},
};

/* Entries (*.bin) and leftovers (anything else) in dir. */
static int count_files(const char *dir, bool entries)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        if (e->d_name[0] == '.') continue;
        const char *dot = strrchr(e->d_name, '.');
        n += (dot && strcmp(dot, ".bin") == 0) == entries;
    }
    closedir(d);
    return n;
}

/* Makes both programs, checks they work (locations, a dispatch), destroys
 * them; returns the stats after. */
static gfx_program_stats_t make_both(void)
{
    gfx_program_t p[2];
    CHECK(gfx_programs_make(2, progs, p));
    CHECK(gfx_uniform(p[1], "u_a") == 2 && gfx_uniform(p[1], "u_b") == 3);
    GLint linked = 0;
    glGetProgramiv(p[0].id, GL_LINK_STATUS, &linked);
    CHECK(linked);
    float one = 0.0f;
    gfx_buffer_t out = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof one, .label = "cache.out"});
    glUseProgram(p[1].id);
    glUniform4f(gfx_uniform(p[1], "u_a"), 1.5f, 0.0f, 0.0f, 0.0f);
    glUniform1f(gfx_uniform(p[1], "u_b"), 2.0f);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_OUT, out.id);
    glDispatchCompute(1, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    CHECK(gfx_buffer_read(out, 0, sizeof one, &one) && one == 3.5f);
    glUseProgram(0);
    gfx_buffer_destroy(&out);
    for (int i = 0; i < 2; i++) gfx_program_destroy(&p[i]);
    return gfx_program_stats();
}

static void restart(const char *cache)
{
    gfx_shutdown(true);
    gfx_init_desc(&(gfx_desc_t){.shader_cache = cache});
}

static void write_file(const char *path, const void *data, size_t size)
{
    CHECK(core_fs_write_atomic(path, data, size));
}

/* The header and checksum checks alone. */
static void check_entry_format(void)
{
    const uint64_t key[2] = {0x1234, 0x5678}, other[2] = {0x1234, 0x5679};
    char e[GFX_CACHE_HEADER + 16];
    for (int i = 0; i < 16; i++) e[GFX_CACHE_HEADER + i] = (char)(i * 7);
    gfx_shader_cache_entry_header(e, key, 0x8740, e + GFX_CACHE_HEADER, 16);
    GLenum format = 0;
    const void *bin = NULL;
    size_t len = 0;
    CHECK(gfx_shader_cache_entry_check(e, sizeof e, key, &format, &bin, &len));
    CHECK(format == 0x8740 && bin == e + GFX_CACHE_HEADER && len == 16);
    CHECK(!gfx_shader_cache_entry_check(e, sizeof e, other, &format, &bin, &len));
    CHECK(!gfx_shader_cache_entry_check(e, sizeof e - 1, key, &format, &bin, &len));
    CHECK(!gfx_shader_cache_entry_check(e, GFX_CACHE_HEADER, key, &format, &bin, &len));
    CHECK(!gfx_shader_cache_entry_check(e, 10, key, &format, &bin, &len));
    e[GFX_CACHE_HEADER + 3] ^= 1;
    CHECK(!gfx_shader_cache_entry_check(e, sizeof e, key, &format, &bin, &len));
    e[GFX_CACHE_HEADER + 3] ^= 1;
    e[0] ^= 1;
    CHECK(!gfx_shader_cache_entry_check(e, sizeof e, key, &format, &bin, &len));
}

/* An entry the driver must refuse: the key and checksum right, the
 * binary garbage. */
static void write_refused_entry(const char *path)
{
    size_t size = 0;
    char *old = core_fs_read(path, &size, NULL, 0);
    CHECK(old && size > GFX_CACHE_HEADER);
    if (!old) return;
    uint64_t key[2];
    memcpy(key, old + 16, sizeof key);
    GLenum format = 0;
    const void *bin;
    size_t len;
    CHECK(gfx_shader_cache_entry_check(old, size, key, &format, &bin, &len));
    for (size_t i = GFX_CACHE_HEADER; i < size; i++) old[i] = (char)(i * 31 + 5);
    gfx_shader_cache_entry_header(old, key, format, old + GFX_CACHE_HEADER, size - GFX_CACHE_HEADER);
    write_file(path, old, size);
    free(old);
}

/* One way of spoiling entry 0, then a make: it is refused, compiled,
 * rewritten, and the next make takes it. */
static void check_spoiled(const char *what, const char *path, void (*spoil)(const char *path))
{
    spoil(path);
    gfx_program_stats_t a = gfx_program_stats();
    gfx_program_stats_t b = make_both();
    CHECK_MSG(b.cache_refused == a.cache_refused + 1 && b.cache_hits == a.cache_hits + 1 &&
                  b.cache_stored == a.cache_stored + 1,
              "%s: refused %d, hits %d, stored %d", what, b.cache_refused - a.cache_refused,
              b.cache_hits - a.cache_hits, b.cache_stored - a.cache_stored);
    gfx_program_stats_t c = make_both();
    CHECK_MSG(c.cache_hits == b.cache_hits + 2 && c.cache_refused == b.cache_refused, "%s: not rewritten", what);
}

static void flip_byte(const char *path)
{
    size_t size = 0;
    char *data = core_fs_read(path, &size, NULL, 0);
    CHECK(data && size > GFX_CACHE_HEADER + 8);
    if (!data) return;
    data[size - 8] ^= 0x40;
    write_file(path, data, size);
    free(data);
}

static void truncate_half(const char *path)
{
    size_t size = 0;
    char *data = core_fs_read(path, &size, NULL, 0);
    CHECK(data != NULL);
    if (data) write_file(path, data, size / 2);
    free(data);
}

/* The driver has binary formats: cold, warm, spoiled entries. */
static void check_cache(const char *dir)
{
    restart(dir);
    gfx_program_stats_t s0 = gfx_program_stats();
    CHECK(s0.cache_on);
    gfx_program_stats_t cold = make_both();
    CHECK(cold.cache_misses == s0.cache_misses + 2 && cold.cache_stored == s0.cache_stored + 2);
    CHECK(cold.cache_hits == s0.cache_hits);
    CHECK(count_files(dir, true) == 2 && count_files(dir, false) == 0);
    gfx_program_stats_t warm = make_both();
    CHECK(warm.cache_hits == cold.cache_hits + 2 && warm.cache_misses == cold.cache_misses);
    printf("cache: cold make %.1f ms, warm %.1f ms (two programs)\n", cold.ms - s0.ms, warm.ms - cold.ms);

    /* A prefetch loads from the cache too; a fresh gfx reads what the
     * last one wrote. */
    gfx_programs_prefetch(2, progs);
    gfx_program_stats_t pre = make_both();
    CHECK(pre.cache_hits == warm.cache_hits + 2 && pre.taken == warm.taken + 2);
    restart(dir);
    gfx_program_stats_t fresh = make_both();
    CHECK(fresh.cache_hits == pre.cache_hits + 2 && fresh.cache_misses == pre.cache_misses);

    /* Other defines: another entry. */
    gfx_program_desc_t other = progs[1];
    other.defines = "#define UNIFORMS_AB 1\n#define UNUSED 2\n";
    char a[2048], b[2048];
    CHECK(gfx_shader_cache_path(&progs[1], a, sizeof a) && gfx_shader_cache_path(&other, b, sizeof b));
    CHECK(strcmp(a, b) != 0);

    char path[2048];
    CHECK(gfx_shader_cache_path(&progs[0], path, sizeof path));
    check_spoiled("flipped byte", path, flip_byte);
    check_spoiled("truncated", path, truncate_half);
    check_spoiled("refused by the driver", path, write_refused_entry);
    CHECK(count_files(dir, true) == 2 && count_files(dir, false) == 0);
}

/* No binary formats: no folder made, nothing counted, a planted entry
 * ignored. */
static void check_noop(const char *dir)
{
    restart(dir);
    gfx_program_stats_t s0 = gfx_program_stats();
    CHECK(!s0.cache_on);
    struct stat st;
    CHECK(stat(dir, &st) != 0);
    char path[2048];
    CHECK(gfx_shader_cache_path(&progs[0], path, sizeof path));
    CHECK(core_fs_mkdirs(dir));
    write_file(path, "not a program binary", 20);
    gfx_program_stats_t s1 = make_both();
    CHECK(s1.cache_hits == s0.cache_hits && s1.cache_misses == s0.cache_misses && s1.cache_refused == s0.cache_refused);
    CHECK(s1.cache_stored == s0.cache_stored);
    CHECK(count_files(dir, true) == 1);
    size_t size = 0;
    char *data = core_fs_read(path, &size, NULL, 0);
    CHECK(data && size == 20);
    free(data);
}

/* Runs this test again with Mesa's shader cache off: what it reports. */
static int run_without_formats(void)
{
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid == 0) {
        setenv("MESA_SHADER_CACHE_DISABLE", "1", 1);
        execl("/proc/self/exe", "test_gfx_shader_cache", "--no-formats", (char *)NULL);
        _exit(127);
    }
    int status = 0;
    CHECK(pid > 0 && waitpid(pid, &status, 0) == pid);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128;
}

int main(int argc, char **argv)
{
    bool child = argc > 1 && strcmp(argv[1], "--no-formats") == 0;
    unsetenv("MEADOW_SHADER_CACHE");
    unsetenv("MEADOW_SHADER_DIR");
    check_entry_format();
    char dir[1024], base[900];
    snprintf(base, sizeof base, "%s/%s-%ld", test_out_dir(), child ? "noformats" : "cache", (long)getpid());
    snprintf(dir, sizeof dir, "%s/programs", base);
    test_gl_init();

    /* No folder: off, nothing counted. */
    gfx_program_stats_t s0 = gfx_program_stats();
    CHECK(!s0.cache_on && gfx_desc_defaults(NULL).shader_cache == NULL);
    gfx_program_stats_t s1 = make_both();
    CHECK(s1.cache_hits == 0 && s1.cache_misses == 0 && s1.cache_stored == 0);
    setenv("MEADOW_SHADER_CACHE", dir, 1);
    CHECK(gfx_desc_defaults(NULL).shader_cache && strcmp(gfx_desc_defaults(NULL).shader_cache, dir) == 0);
    unsetenv("MEADOW_SHADER_CACHE");

    GLint formats = 0;
    glGetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
    printf("%s: %d program binary format(s)\n", child ? "without Mesa's shader cache" : "driver", formats);
    if (formats > 0) check_cache(dir);
    else check_noop(dir);

    /* A folder that cannot be made (under a file): with formats, one
     * warning and no cache; programs still build. */
    char blocked[1100];
    snprintf(blocked, sizeof blocked, "%s/file", base);
    CHECK(core_fs_mkdirs(base));
    write_file(blocked, "x", 1);
    snprintf(blocked, sizeof blocked, "%s/file/programs", base);
    int warns = core_log_warn_count();
    restart(blocked);
    CHECK(core_log_warn_count() == warns + (formats > 0 ? 1 : 0));
    CHECK(!gfx_program_stats().cache_on);
    gfx_program_stats_t b0 = gfx_program_stats(), b1 = make_both();
    CHECK(b1.cache_hits == b0.cache_hits && b1.cache_misses == b0.cache_misses);
    CHECK(test_gl_shutdown() == 0);

    if (!child) {
        int rc = run_without_formats();
        CHECK_MSG(rc == 0, "the run without binary formats exited %d", rc);
    }
    TEST_END();
}

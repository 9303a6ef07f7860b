/* core_fs: whole-file reads, atomic writes (tmp + rename), directory checks
 * and locks, and lookup of repository files (shaders/, models/, textures/,
 * scenes/). */
#include "core.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

char *core_fs_read(const char *path, size_t *size, char *err, size_t err_size)
{
    /* Opened without blocking: open(2) of a FIFO waits for a writer, forever
     * and deaf to SIGINT (SA_RESTART); only regular files are read. */
    int fd = open(path, O_RDONLY | O_NONBLOCK | O_CLOEXEC);
    if (fd < 0) {
        if (err) snprintf(err, err_size, "%s", strerror(errno));
        return NULL;
    }
    struct stat st;
    const char *why = NULL;
    if (fstat(fd, &st) != 0) why = strerror(errno);
    else if (S_ISDIR(st.st_mode)) why = "is a directory";
    else if (!S_ISREG(st.st_mode)) why = "not a regular file";
    FILE *f = why || fcntl(fd, F_SETFL, 0) != 0 ? NULL : fdopen(fd, "rb");
    if (!f) {
        if (err) snprintf(err, err_size, "%s", why ? why : strerror(errno));
        close(fd);
        return NULL;
    }
    if ((uint64_t)st.st_size > CORE_FS_READ_MAX) {
        if (err) snprintf(err, err_size, "larger than %zu MiB, the most this program reads", CORE_FS_READ_MAX >> 20);
        fclose(f);
        return NULL;
    }
    size_t cap = (size_t)st.st_size + 1, len = 0;
    char *buf = malloc(cap);
    if (!buf) {
        if (err) snprintf(err, err_size, "out of memory (%zu bytes)", cap);
        fclose(f);
        return NULL;
    }
    for (;;) {
        size_t n = fread(buf + len, 1, cap - 1 - len, f);
        len += n;
        if (len < cap - 1) break;
        if (len >= CORE_FS_READ_MAX) {
            free(buf);
            fclose(f);
            if (err) snprintf(err, err_size, "more than %zu MiB, the most this program reads", CORE_FS_READ_MAX >> 20);
            return NULL;
        }
        char *grown = realloc(buf, cap * 2);
        if (!grown) {
            free(buf);
            fclose(f);
            if (err) snprintf(err, err_size, "out of memory");
            return NULL;
        }
        buf = grown;
        cap *= 2;
    }
    if (ferror(f)) {
        if (err) snprintf(err, err_size, "read error: %s", strerror(errno));
        free(buf);
        fclose(f);
        return NULL;
    }
    fclose(f);
    buf[len] = 0;
    if (size) *size = len;
    return buf;
}

bool core_fs_write_atomic(const char *path, const void *data, size_t size)
{
    char tmp[4096];
    snprintf(tmp, sizeof tmp, "%s.tmp.%ld", path, (long)getpid());
    FILE *f = fopen(tmp, "wb");
    if (!f) {
        core_log_error("%s: cannot write: %s", path, strerror(errno));
        return false;
    }
    bool ok = fwrite(data, 1, size, f) == size;
    ok = (fflush(f) == 0) && ok;
    ok = (fclose(f) == 0) && ok;
    if (!ok || rename(tmp, path) != 0) {
        core_log_error("%s: write failed: %s", path, strerror(errno));
        remove(tmp);
        return false;
    }
    return true;
}

bool core_fs_mkdirs(const char *path)
{
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", path);
    size_t n = strlen(buf);
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] == '/' || buf[i] == 0) {
            char c = buf[i];
            buf[i] = 0;
            if (mkdir(buf, 0755) != 0 && errno != EEXIST) {
                core_log_error("%s: cannot create directory: %s", buf, strerror(errno));
                return false;
            }
            buf[i] = c;
        }
    }
    return true;
}

bool core_fs_check_writable_dir(const char *dir, char *err, size_t err_size)
{
    struct stat st;
    if (stat(dir, &st) == 0 && !S_ISDIR(st.st_mode)) {
        snprintf(err, err_size, "%s exists and is not a directory", dir);
        return false;
    }
    char buf[4096];
    snprintf(buf, sizeof buf, "%s", dir);
    for (size_t i = 1, n = strlen(buf); i <= n; i++) {
        if (buf[i] == '/' || buf[i] == 0) {
            char c = buf[i];
            buf[i] = 0;
            if (mkdir(buf, 0755) != 0 && errno != EEXIST) {
                snprintf(err, err_size, "cannot create %s: %s", buf, strerror(errno));
                return false;
            }
            buf[i] = c;
        }
    }
    char probe[4200];
    snprintf(probe, sizeof probe, "%s/.meadow-probe.%ld", dir, (long)getpid());
    FILE *f = fopen(probe, "wb");
    if (!f) {
        snprintf(err, err_size, "%s is not writable: %s", dir, strerror(errno));
        return false;
    }
    char block[4096] = {0};
    bool ok = fwrite(block, 1, sizeof block, f) == sizeof block;
    ok = (fflush(f) == 0) && ok;
    ok = (fclose(f) == 0) && ok;
    remove(probe);
    if (!ok) {
        snprintf(err, err_size, "%s is full or not writable: %s", dir, strerror(errno));
        return false;
    }
    return true;
}

bool core_fs_lock_dir(const char *dir, char *err, size_t err_size)
{
    static struct {
        dev_t dev;
        ino_t ino;
    } held[16];
    static int held_count;
    struct stat st;
    if (stat(dir, &st) != 0) {
        snprintf(err, err_size, "%s: %s", dir, strerror(errno));
        return false;
    }
    for (int i = 0; i < held_count; i++)
        if (held[i].dev == st.st_dev && held[i].ino == st.st_ino) return true;
    char path[4200];
    snprintf(path, sizeof path, "%s/" CORE_FS_LOCK_NAME, dir);
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
        snprintf(err, err_size, "cannot create %s: %s", path, strerror(errno));
        return false;
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
        char pid[32] = "";
        ssize_t n = pread(fd, pid, sizeof pid - 1, 0);
        pid[n > 0 ? n : 0] = 0;
        pid[strcspn(pid, "\n")] = 0;
        snprintf(err, err_size, "%s is in use by another run (%s is locked%s%s); wait for it or choose another "
                 "folder", dir, path, pid[0] ? " by process " : "", pid);
        close(fd);
        return false;
    }
    char pid[32];
    int len = snprintf(pid, sizeof pid, "%ld\n", (long)getpid());
    if (ftruncate(fd, 0) != 0 || pwrite(fd, pid, (size_t)len, 0) != len)
        core_log_warn("%s: cannot note the process id: %s", path, strerror(errno));
    if (held_count < (int)(sizeof held / sizeof held[0])) {
        held[held_count].dev = st.st_dev;
        held[held_count++].ino = st.st_ino;
    }
    return true; /* fd stays open: the kernel releases the lock at exit */
}

bool core_fs_resolve(const char *rel, char *out, size_t out_size)
{
    const char *roots[4] = {getenv("MEADOW_ROOT"), ".", MEADOW_SOURCE_DIR, MEADOW_DATA_DIR};
    for (int i = 0; i < 4; i++) {
        if (!roots[i]) continue;
        int n = snprintf(out, out_size, "%s/%s", roots[i], rel);
        if (n >= 0 && (size_t)n < out_size && access(out, R_OK) == 0) return true; /* a cut path is not it */
    }
    snprintf(out, out_size, "%s", rel);
    return access(out, R_OK) == 0;
}

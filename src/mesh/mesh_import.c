/* mesh_import: guarded assimp import (see mesh_import.h). */
#include "mesh/mesh_import.h"

#include <assimp/cimport.h>
#include <assimp/scene.h>
#include <errno.h>
#include <math.h>
#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdint.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* Largest model or terrain mesh file imported (assimp holds it whole,
 * several times over, before meadow sees a vertex). */
#define MESH_IMPORT_MAX_BYTES (256 << 20)
/* Seconds the probe may take before the file is declared to hang assimp. */
#define MESH_IMPORT_PROBE_SECONDS 120

/* A file that assimp may read as PLY (whatever its extension: assimp tries
 * every importer whose signature matches when the first fails) must have
 * "end_header" at the start of a line, followed by white space, before any
 * NUL byte; otherwise assimp's header parser never returns. Only the first
 * 64 KiB are searched. */
static bool ply_header_ok(const char *path, char *err, size_t err_size)
{
    FILE *f = fopen(path, "rb");
    if (!f) return true; /* assimp reports the open error itself */
    static char buf[65536 + 1];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = 0;
    /* assimp's own PLY signature test: "ply" anywhere in the first 200
     * bytes, case-insensitive, NUL bytes removed. */
    char head[201];
    size_t h = 0;
    for (size_t i = 0; i < n && i < 200; i++)
        if (buf[i]) head[h++] = (char)(buf[i] >= 'A' && buf[i] <= 'Z' ? buf[i] + 32 : buf[i]);
    head[h] = 0;
    if (!strstr(head, "ply")) return true;
    size_t len = strlen(buf); /* stops at the first NUL */
    for (size_t i = 0; i + 10 < len; i++) {
        bool line_start = i == 0 || buf[i - 1] == '\n' || buf[i - 1] == '\r';
        char next = buf[i + 10];
        if (line_start && memcmp(buf + i, "end_header", 10) == 0 &&
            (next == '\n' || next == '\r' || next == ' ' || next == '\t'))
            return true;
    }
    snprintf(err, err_size, "malformed PLY header (no end_header line before the data)");
    return false;
}

static bool faces_ok(const struct aiScene *sc, char *err, size_t err_size)
{
    for (unsigned m = 0; m < sc->mNumMeshes; m++) {
        const struct aiMesh *am = sc->mMeshes[m];
        if (am->mNumVertices == 0 || am->mNumFaces == 0 || !am->mVertices) {
            snprintf(err, err_size, "mesh %u is empty (%u vertices, %u faces)", m, am->mNumVertices, am->mNumFaces);
            return false;
        }
        for (unsigned v = 0; v < am->mNumVertices; v++) {
            const struct aiVector3D *p = &am->mVertices[v];
            if (!isfinite(p->x) || !isfinite(p->y) || !isfinite(p->z)) {
                snprintf(err, err_size, "mesh %u vertex %u is not a finite number", m, v);
                return false;
            }
        }
        for (unsigned f = 0; f < am->mNumFaces; f++) {
            const struct aiFace *face = &am->mFaces[f];
            if (face->mNumIndices == 0 || !face->mIndices) {
                snprintf(err, err_size, "mesh %u face %u has no vertex indices", m, f);
                return false;
            }
            for (unsigned k = 0; k < face->mNumIndices; k++)
                if (face->mIndices[k] >= am->mNumVertices) {
                    snprintf(err, err_size, "mesh %u face %u uses vertex %u of %u", m, f, face->mIndices[k],
                             am->mNumVertices);
                    return false;
                }
        }
    }
    return true;
}

/* Imports the file once in a child process first. assimp 5.2 has crashes
 * and endless loops inside its readers that no check of ours can foresee
 * (fuzzing keeps finding new ones, e.g. a malformed glTF that dereferences
 * NULL in the glTF2 reader); a child that dies or runs past the time limit
 * costs only the child. The real import then runs in this process, which
 * assimp does deterministically the same way. */
static bool probe_in_child(const char *path, unsigned flags, char *err, size_t err_size)
{
    fflush(NULL);
    pid_t pid = fork();
    if (pid < 0) return true; /* cannot probe: import directly */
    if (pid == 0) {
        alarm(MESH_IMPORT_PROBE_SECONDS);
        const struct aiScene *sc = aiImportFile(path, 0);
        char why[8];
        bool ok = sc && faces_ok(sc, why, sizeof why);
        if (sc && ok) sc = aiApplyPostProcessing(sc, flags);
        _exit(sc && ok ? 0 : 3);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {}
    if (WIFEXITED(status) && (WEXITSTATUS(status) == 0 || WEXITSTATUS(status) == 3)) return true;
    if (WIFSIGNALED(status) && WTERMSIG(status) == SIGALRM)
        snprintf(err, err_size, "assimp did not finish reading the file within %d s (it hangs on this input)",
                 MESH_IMPORT_PROBE_SECONDS);
    else if (WIFSIGNALED(status))
        snprintf(err, err_size, "assimp crashed reading the file (signal %d); the file is malformed",
                 WTERMSIG(status));
    else
        snprintf(err, err_size, "assimp crashed reading the file (exit %d); the file is malformed",
                 WEXITSTATUS(status));
    return false;
}

const struct aiScene *mesh_import(const char *path, unsigned flags, char *err, size_t err_size)
{
    struct stat st;
    if (stat(path, &st) == 0 && (!S_ISREG(st.st_mode) || (uint64_t)st.st_size > MESH_IMPORT_MAX_BYTES)) {
        if (!S_ISREG(st.st_mode)) snprintf(err, err_size, "not a regular file");
        else snprintf(err, err_size, "larger than %d MiB, the most this program imports", MESH_IMPORT_MAX_BYTES >> 20);
        return NULL;
    }
    if (!ply_header_ok(path, err, err_size)) return NULL;
    if (!probe_in_child(path, flags, err, err_size)) return NULL;
    const struct aiScene *sc = aiImportFile(path, 0);
    if (!sc) {
        snprintf(err, err_size, "assimp: %s", aiGetErrorString());
        return NULL;
    }
    if (!faces_ok(sc, err, err_size)) {
        aiReleaseImport(sc);
        return NULL;
    }
    const struct aiScene *pp = aiApplyPostProcessing(sc, flags);
    if (!pp) {
        /* assimp has already released the scene. */
        snprintf(err, err_size, "assimp post-processing: %s", aiGetErrorString());
        return NULL;
    }
    return pp;
}

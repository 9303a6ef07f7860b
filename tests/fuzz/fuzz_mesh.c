/* fuzz_mesh: libFuzzer target for the assimp importers behind terrain meshes
 * (terrain_load_mesh) and, when built with MEADOW_FUZZ_CHARACTER, characters
 * (character_load). The first input byte picks the file extension (assimp
 * chooses the importer by extension first), the rest is written to a
 * temporary file which both loaders read. A successful load is then used the
 * way the program uses it: ground-height ray casts through the terrain grid;
 * clip sampling, skinning and capsule fitting for characters. A crash, an
 * ASan/UBSan report or a failure without a message is a finding. No paper
 * equations. */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <assimp/cimport.h>
#include <assimp/scene.h>

#include "core/core.h"
#include "scene/terrain.h"
#ifdef MEADOW_FUZZ_CHARACTER
#include "character/character_load.h"
#include "character/character_ref.h"
#endif

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char *const extensions[] = {"obj", "ply", "gltf", "glb", "stl"};
enum { EXT_COUNT = sizeof extensions / sizeof extensions[0] };
static char paths[EXT_COUNT][256];
/* MEADOW_FUZZ_UNFILTERED=1 turns the known-bug filters below off, so that
 * .ci/fuzz can replay tests/fuzz/known_bugs.txt and see which are fixed. */
static bool unfiltered;

static void remove_temp_files(void)
{
    for (int i = 0; i < EXT_COUNT; i++)
        if (paths[i][0]) unlink(paths[i]);
}

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    const char *dir = getenv("TMPDIR");
    if (!dir || !dir[0]) dir = "/tmp";
    for (int i = 0; i < EXT_COUNT; i++)
        snprintf(paths[i], sizeof paths[i], "%s/meadow_fuzz_mesh_%ld.%s", dir, (long)getpid(),
                 extensions[i]);
    atexit(remove_temp_files);
    core_log_set_quiet(true);
    const char *u = getenv("MEADOW_FUZZ_UNFILTERED");
    unfiltered = u && u[0] == '1';
    return 0;
}

static void use_terrain(const terrain_mesh_t *mesh)
{
    /* Rays through the AABB corners, centre and just outside it. */
    for (int i = 0; i <= 4; i++)
        for (int j = 0; j <= 4; j++) {
            float x = mesh->aabb_min[0] + (mesh->aabb_max[0] - mesh->aabb_min[0]) * (i - 0.5f) / 3.0f;
            float z = mesh->aabb_min[2] + (mesh->aabb_max[2] - mesh->aabb_min[2]) * (j - 0.5f) / 3.0f;
            vec3 n;
            terrain_height_at(mesh, x, z, n);
        }
    terrain_hash(mesh);
}

#ifdef MEADOW_FUZZ_CHARACTER
static void use_character(const character_model_t *model)
{
    character_pose_t pose;
    if (!character_pose_init(&pose, model)) return;
    float *pos = malloc(sizeof(float) * 3 * (size_t)(model->vertex_count + 1));
    float *nrm = malloc(sizeof(float) * 3 * (size_t)(model->vertex_count + 1));
    if (pos && nrm) {
        for (int c = 0; c < model->clip_count && c < 4; c++)
            for (int k = 0; k < 3; k++) {
                float t = model->clips[c].duration * (float)k * 0.6f;
                character_sample_clip(model, c, t, k == 2, &pose);
                character_pose_globals(model, &pose);
            }
        character_skin_cpu(model, &pose, pos, nrm);
        character_capsule_t caps[8];
        character_fit_capsules(model, &pose, pos, caps, 8);
        character_bounds_t b;
        character_bounds(model, pos, &b);
    }
    free(pos);
    free(nrm);
    character_pose_free(&pose);
}
#endif

/* Known bugs: inputs that hang or crash assimp 5.2.4 inside
 * terrain_load_mesh / character_load, which meadow does not guard against yet
 * (tests/fuzz/known_bugs.txt, docs/RELIABILITY.md). Skipping them lets the
 * fuzzer look for other bugs instead of finding the same ones again; remove a
 * filter once the loaders reject such files themselves.
 * - A PLY header that does not end with a line "end_header" (followed by a
 *   space or line end) before the end of the file or a NUL byte: the header
 *   parser loops forever at the end of its buffer
 *   (tests/data/fuzz_regressions/mesh_ply_*). Whatever the extension: when
 *   the importer the extension picks fails, assimp tries every importer whose
 *   signature matches, and PLY's is the token "ply" anywhere in the first 200
 *   bytes (case-insensitive, NULs removed). */
static bool known_assimp_hang(const uint8_t *data, size_t size)
{
    char head[201];
    size_t h = 0;
    for (size_t i = 0; i < size && i < 200; i++)
        if (data[i]) head[h++] = (char)(data[i] >= 'A' && data[i] <= 'Z' ? data[i] + 32 : data[i]);
    head[h] = 0;
    if (!strstr(head, "ply")) return false;

    static const char tag[] = "end_header";
    const size_t n = sizeof tag - 1;
    for (size_t i = 0; i < size && data[i] != 0; i++) {
        bool line_start = i == 0 || data[i - 1] == '\n' || data[i - 1] == '\r';
        if (line_start && size - i > n && memcmp(data + i, tag, n) == 0 &&
            strchr(" \t\r\n", data[i + n]) && data[i + n] != 0)
            return false;
    }
    return true;
}

/* - Faces whose vertex indices are out of range (a shifted binary PLY body,
 *   say): assimp's post-processing steps read out of bounds and crash
 *   (tests/data/fuzz_regressions/mesh_ply_face_index_out_of_range).
 * - Faces with no indices: TriangulateProcess.cpp:238 ai_assert aborts
 *   (tests/data/fuzz_regressions/mesh_ply_empty_face).
 * Both are checked on a raw import without post-processing, which is what
 * aiProcess_ValidateDataStructure would reject. */
static bool known_assimp_crash(const char *path)
{
    const struct aiScene *sc = aiImportFile(path, 0);
    if (!sc) return false;
    bool bad = false;
    for (unsigned m = 0; m < sc->mNumMeshes && !bad; m++) {
        const struct aiMesh *am = sc->mMeshes[m];
        for (unsigned f = 0; f < am->mNumFaces && !bad; f++) {
            if (am->mFaces[f].mNumIndices == 0) bad = true;
            for (unsigned k = 0; k < am->mFaces[f].mNumIndices; k++)
                if (am->mFaces[f].mIndices[k] >= am->mNumVertices) bad = true;
        }
    }
    aiReleaseImport(sc);
    return bad;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    if (!unfiltered && known_assimp_hang(data + 1, size - 1)) return 0;
    const char *path = paths[data[0] % EXT_COUNT];
    FILE *f = fopen(path, "wb");
    if (!f) abort();
    if (size > 1 && fwrite(data + 1, 1, size - 1, f) != size - 1) abort();
    if (fclose(f) != 0) abort();
    if (!unfiltered && known_assimp_crash(path)) return 0;

    char err[512] = "";
    terrain_mesh_t mesh;
    if (terrain_load_mesh(&mesh, path, 1.0f, err, sizeof err)) {
        use_terrain(&mesh);
        terrain_free(&mesh);
    } else if (!err[0]) {
        abort(); /* failures must say why */
    }

#ifdef MEADOW_FUZZ_CHARACTER
    err[0] = 0;
    character_model_t model;
    if (character_load(&model, path, err, sizeof err)) {
        use_character(&model);
        character_model_free(&model);
    } else if (!err[0]) {
        abort();
    }
#endif
    return 0;
}

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
#include "terrain/terrain.h"
#ifdef MEADOW_FUZZ_CHARACTER
#include "character/character_load.h"
#include "character/character_ref.h"
#endif

int LLVMFuzzerInitialize(int *argc, char ***argv);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char *const extensions[] = {"obj", "ply", "gltf", "glb", "stl"};
enum { EXT_COUNT = sizeof extensions / sizeof extensions[0] };
static char paths[EXT_COUNT][256];

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

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) return 0;
    const char *path = paths[data[0] % EXT_COUNT];
    FILE *f = fopen(path, "wb");
    if (!f) abort();
    if (size > 1 && fwrite(data + 1, 1, size - 1, f) != size - 1) abort();
    if (fclose(f) != 0) abort();

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

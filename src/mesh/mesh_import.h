/* mesh_import: the one way meadow calls assimp. Guards against inputs that
 * make assimp 5.2 hang or crash (found by fuzzing, see docs/RELIABILITY.md):
 * a PLY header without a proper end_header line (the parser loops forever),
 * and faces with no indices or indices past the vertex count (post-processing
 * asserts or reads out of bounds). The file is imported without
 * post-processing, checked, and only then post-processed. */
#ifndef MEADOW_MESH_IMPORT_H
#define MEADOW_MESH_IMPORT_H

#include <stddef.h>

struct aiScene;

/* Returns the post-processed scene (release with aiReleaseImport), or NULL
 * with the problem in err (without the path: callers prefix it). */
const struct aiScene *mesh_import(const char *path, unsigned post_process_flags, char *err, size_t err_size);

#endif

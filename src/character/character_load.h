/* character_load: imports skinned, animated characters through assimp into a
 * flat, GL-free model: one merged vertex array, a bone list in
 * parent-before-child order, and animation clips with per-bone key tracks.
 * Inconsistent files are repaired with a warning rather than rejected
 * (aiProcess_ValidateDataStructure is deliberately not used): unsorted, NaN
 * or negative key times, keys past the clip duration, zero quaternions,
 * NaN/negative weights, vertices with no weight. No paper equations here;
 * the sampling/skinning maths is in character_ref.h. */
#ifndef MEADOW_CHARACTER_LOAD_H
#define MEADOW_CHARACTER_LOAD_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#define CHARACTER_MAX_INFLUENCES 4

/* Interleaved vertex (56 bytes), usable as-is as a GL vertex buffer.
 * pos/normal are the bind pose in model space. weights sum to 1; unused
 * slots have weight 0 and joint 0. */
typedef struct character_vertex_t {
    float pos[3];
    float normal[3];
    float uv[2];
    uint16_t joints[CHARACTER_MAX_INFLUENCES];
    float weights[CHARACTER_MAX_INFLUENCES];
} character_vertex_t;

/* One node of the flattened hierarchy. Every scene node becomes a bone (so
 * non-joint nodes such as an armature root are animated too); a rigid file
 * collapses to one bone named "root". Matrices are column-major 4x4. */
typedef struct character_bone_t {
    char *name;
    int parent;               /* -1 for a root; always smaller than own index */
    float inverse_bind[16];   /* model space -> bone space at bind pose */
    float bind_t[3];          /* local bind transform as TRS */
    float bind_r[4];          /* quaternion x, y, z, w */
    float bind_s[3];
    float bind_local[16];     /* the same as a matrix (exact, incl. shear) */
} character_bone_t;

/* A key: time in seconds; v = x,y,z for translation/scale, x,y,z,w for a
 * rotation quaternion. */
typedef struct character_key_t {
    float time;
    float v[4];
} character_key_t;

typedef struct character_track_t {
    int count;
    character_key_t *keys; /* sorted by time after loading */
} character_track_t;

/* Empty tracks keep the bone's bind value. */
typedef struct character_channel_t {
    character_track_t pos, rot, scale;
} character_channel_t;

typedef struct character_clip_t {
    char *name;
    float duration;          /* seconds, > 0 */
    float ticks_per_second;  /* the file's timeline rate (frame ranges) */
    bool still;              /* a single frame: no keys, or all at time 0 with no duration stated */
    character_channel_t *channels; /* bone_count entries */
    int morph_count;         /* the model's morph_count (0 without morph targets) */
    character_track_t *morph; /* per morph target its weight track (v[0]); empty: the default weight */
    float cut[2];            /* ticks a..b of clip 0 this clip was cut from (character_clip_range); 0, 0: the file's */
} character_clip_t;

/* A morph target (blend shape) of one mesh instance: assimp's aiAnimMesh,
 * driven by the aiMeshMorphAnim channels named after its node. A vertex v
 * of the range [first, first + count) is drawn at
 * pos + sum_k weight_k * delta_k[v - first] (normals likewise) before
 * skinning; deltas are in the same space as the vertices. */
typedef struct character_morph_t {
    int node;             /* bone (node) whose morph channel drives it */
    int target;           /* index among that node's targets (aiMeshMorphKey mValues) */
    int first, count;     /* the mesh instance's vertices */
    float weight;         /* default weight (the mesh's, glTF mesh.weights) */
    float max_weight;     /* largest |weight| over the default and every key */
    float (*delta)[6];    /* count entries: position delta xyz, normal delta xyz */
} character_morph_t;

/* What the file states about its units and axes (assimp's scene metadata:
 * UnitScaleFactor or OriginalUnitScaleFactor, UpAxis/UpAxisSign,
 * FrontAxis/FrontAxisSign), read by character_import. Axis codes as in
 * character_import.h: +-1 x, +-2 y, +-3 z; 0 = not stated. */
typedef struct character_file_info_t {
    float unit_metres; /* metres per file unit; 0 = not stated (FBX: cm per unit / 100) */
    int up, front;
    char format[16];   /* lower-case file extension, e.g. "b3d" */
} character_file_info_t;

/* An embedded texture (aiScene mTextures, referenced as "*N" or by name):
 * either a compressed image file (png, jpg...) in memory (height 0, size
 * bytes) or raw BGRA texels (width x height). */
typedef struct character_image_t {
    unsigned char *data;
    size_t size;
    int width, height; /* height 0: data is a compressed file */
} character_image_t;

typedef struct character_model_t {
    character_vertex_t *vertices;
    int vertex_count;
    uint32_t *indices; /* triangles */
    int index_count;
    character_bone_t *bones;
    int bone_count;
    character_clip_t *clips;
    int clip_count;
    character_morph_t *morphs;
    int morph_count;
    float base_color[4];      /* from the first mesh's material; default 0.8 grey */
    char texture_path[1024];  /* diffuse/base-colour texture file, "" when none */
    character_image_t texture_embedded; /* data NULL when none; wins over texture_path */
    character_file_info_t file;
    bool rigid;               /* no skin and no animation: one bone */
} character_model_t;

/* Loads `path`. On failure returns false, logs one error line and writes the
 * reason into err. Repairs are logged with core_log_warn. The model must be
 * released with character_model_free. */
bool character_load(character_model_t *model, const char *path, char *err, size_t err_size);
void character_model_free(character_model_t *model);

/* The part of a path after its last '/' or '\\' (Windows paths stored in
 * files). */
const char *character_path_basename(const char *path);
/* Finds the texture file `ref` that a material of model_path names, trying
 * in turn: ref itself (absolute) or beside the model (relative, with its
 * folders); its file name beside the model; in textures/ beside the model;
 * in ../textures/ (Minetest's layout). Writes the first readable one into
 * out and returns true; otherwise lists the candidates in tried. */
bool character_texture_find(const char *model_path, const char *ref, char *out, size_t out_size, char *tried,
                            size_t tried_size);

/* Bone index by exact name, or -1. */
int character_bone_find(const character_model_t *model, const char *name);

/* Clip selection. spec may be:
 *   NULL or ""     the first clip
 *   a name         exact match, then case-insensitive, then the part after
 *                  the last '|' (assimp writes "Armature|walk" for FBX);
 *                  clips cut by character_clip_range are not matched by
 *                  name (another character's named range stays its own)
 *   "N"            clip index N
 *   "A:B"          frames/ticks A..B of the first clip (files with a single
 *                  timeline): character_clip_range(model, spec, A, B)
 * Returns the clip index, or -1 (nothing logged: the caller names the
 * available clips with character_clip_list, or a bad range's reason with
 * character_clip_range_check). */
int character_clip_find(character_model_t *model, const char *spec);
/* "A:B" with two numbers into a and b; false when spec is not of that form. */
bool character_clip_parse_range(const char *spec, double *a, double *b);
/* Whether ticks a..b lie on clip 0's timeline: 0 <= a < b <= its ticks
 * (duration * ticks_per_second). False with the reason in why ("start -1
 * is negative", "end 3 is not after start 5", "end 40 is past the
 * timeline's 25 ticks", "the model has no clips"). */
bool character_clip_range_check(const character_model_t *model, double a, double b, char *why, size_t why_size);
/* A clip called name holding ticks a..b of clip 0 (a named range of one long
 * clip, or "A:B"), appended once per name and range, which may move
 * model->clips (re-read pointers after). -1 when the range fails
 * character_clip_range_check or memory runs out (logged). */
int character_clip_range(character_model_t *model, const char *name, double a, double b);
/* The clip to play for `clip`: itself unless it is still (a duration of 0,
 * or no keys), else the next clip after it (wrapping) that is not; itself
 * when none is. */
int character_clip_playable(const character_model_t *model, int clip);
/* `meadow --list-clips`: loads the (repository-relative or absolute) model
 * and prints each clip's index, name, duration (s), key count and timeline
 * ticks (for A:B ranges) to out. false after one error line. */
bool character_print_clips(const char *path, FILE *out);
/* Keys of a clip over all tracks (bones' and morph weights'). */
int character_clip_keys(const character_clip_t *clip, int bone_count);
/* "0 'walk' (1 s), 1 'idle' (2 s), or a range A:B of clip 0's 25 ticks"
 * into buf (truncated to size). Returns the length written. */
size_t character_clip_list(const character_model_t *model, char *buf, size_t size);

/* Repairs one clip in place (its bone tracks and its clip->morph_count
 * morph weight tracks): drops keys with NaN time or value and zero
 * quaternions, clamps negative times to 0, sorts keys by time, normalises
 * quaternions, and extends the duration to cover the last key (a duration
 * <= 0 becomes the last key time, or 1 s if that is 0 too). Logs one warning
 * per kind of repair naming `context`. Returns the number of repairs. */
int character_clip_fixup(character_clip_t *clip, int bone_count, const char *context);

#endif

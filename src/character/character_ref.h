/* character_ref: GL-free reference for character animation and skinning.
 * Clip sampling (lerp for translation/scale, shortest-path normalised slerp
 * for rotations), the bone hierarchy (global = parent_global * local),
 * skinning matrices (global * inverse_bind), linear blend skinning
 * (p' = sum_i w_i * S_i * p), collision capsules fitted per bone and bounds.
 * The GPU skinning path is compared against this. No paper equations: the
 * grass papers (Orthmann 2009, Jahrmann & Wimmer 2017) take the character as
 * a set of collision proxies, which is what character_fit_capsules makes. */
#ifndef MEADOW_CHARACTER_REF_H
#define MEADOW_CHARACTER_REF_H

#include "character/character_load.h"

#include <stdbool.h>

/* Pose of every bone. Matrices are column-major 4x4 (cglm mat4 layout). */
typedef struct character_pose_t {
    int bone_count;
    float (*t)[3];       /* local translation */
    float (*r)[4];       /* local rotation quaternion x, y, z, w */
    float (*s)[3];       /* local scale */
    float (*global)[16]; /* model space */
    float (*skin)[16];   /* global * inverse_bind */
    int morph_count;
    float *morph;        /* weight of each morph target (character_morph_t) */
} character_pose_t;

/* Allocates a pose for model and sets it to the bind pose (globals
 * included). Returns false (and logs) when out of memory. */
bool character_pose_init(character_pose_t *pose, const character_model_t *model);
void character_pose_free(character_pose_t *pose);
/* Locals = bind TRS, morph weights = their defaults. Call
 * character_pose_globals afterwards. */
void character_pose_bind(const character_model_t *model, character_pose_t *pose);

/* Samples clip at time (seconds) into the locals and the morph weights
 * (lerped). loop wraps time into [0, duration); otherwise it is clamped to
 * [0, duration]. Bones without keys in a track keep their bind value,
 * morph targets without keys their default weight. Call
 * character_pose_globals next. */
void character_sample_clip(const character_model_t *model, int clip, float time, bool loop,
                           character_pose_t *pose);
/* globals (parents first) and skinning matrices from the locals. */
void character_pose_globals(const character_model_t *model, character_pose_t *pose);

/* Samples one track at time (seconds, clamped to the key range). is_rotation
 * selects slerp and a quaternion result; otherwise lerp of xyz. An empty
 * track leaves out untouched. */
void character_track_sample(const character_track_t *track, float time, bool is_rotation, float out[4]);
/* Shortest-path spherical interpolation of unit quaternions (x,y,z,w);
 * falls back to normalised lerp when they are nearly parallel. */
void character_quat_slerp(const float a[4], const float b[4], float t, float out[4]);
/* Column-major matrix from translation, quaternion and scale. */
void character_trs_matrix(const float t[3], const float r[4], const float s[3], float out[16]);
/* out = a * b (out may alias a or b). */
void character_mat4_mul(const float a[16], const float b[16], float out[16]);
/* General inverse; false (out untouched) when singular. */
bool character_mat4_invert(const float m[16], float out[16]);
/* out = m * (p, 1), xyz. */
void character_mat4_point(const float m[16], const float p[3], float out[3]);

/* Linear blend skinning of every vertex: out_positions and out_normals hold
 * 3 * vertex_count floats. The morph targets come first: a vertex is
 * pos + sum_k pose.morph[k] * delta_k (normals likewise), then skinned.
 * Normals use the blended matrix's upper 3x3 and are renormalised (exact
 * for rotations and uniform scale). out_normals may be NULL. */
void character_skin_cpu(const character_model_t *model, const character_pose_t *pose, float *out_positions,
                        float *out_normals);

/* The model's vertices with the pose's morph weights applied (the input
 * of the GPU skinning when the model has morph targets): out holds
 * vertex_count entries; normals are not renormalised (skinning does it). */
void character_morph_apply(const character_model_t *model, const character_pose_t *pose, character_vertex_t *out);
/* The farthest vertex v can move from its bind position through the morph
 * targets at any weight the file uses (sum_k max_weight_k |delta_k|). */
float character_morph_reach(const character_model_t *model, int v);

/* A capsule: segment a-b and radius, in model space for the pose it was
 * fitted in, plus the same end points in the space of `bone` so that
 * skin-free callers can move it with pose.global[bone] on later frames. */
typedef struct character_capsule_t {
    float a[3], b[3];
    float radius;
    float local_a[3], local_b[3];
    int bone;         /* bone whose vertices (and merged ones) it covers */
    int vertex_count; /* vertices it was fitted to */
} character_capsule_t;

/* Fits one capsule per bone that dominates (largest weight) at least one
 * vertex: axis = principal axis of those skinned vertices, radius = their
 * largest distance from the axis, end points pulled in as far as containment
 * of every vertex allows. When there are more such bones than max, the
 * capsule with the fewest vertices is merged into its nearest surviving
 * ancestor's (or, for a root, the nearest capsule's) and refitted, until max
 * remain. Returns the number written (<= max). */
int character_fit_capsules(const character_model_t *model, const character_pose_t *pose,
                           const float *skinned_positions, character_capsule_t *capsules_out, int max);
/* Distance from p to the capsule's segment minus its radius (<= 0 inside). */
float character_capsule_distance(const character_capsule_t *capsule, const float p[3]);

typedef struct character_bounds_t {
    float center[3], radius; /* sphere centred on the AABB centre */
    float min[3], max[3];
} character_bounds_t;

/* Bounds of the skinned positions (3 * vertex_count floats). */
void character_bounds(const character_model_t *model, const float *skinned_positions, character_bounds_t *out);

#endif

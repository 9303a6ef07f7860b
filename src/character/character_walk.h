/* character_walk: GL-free helpers behind character.h (private to the
 * character module and its tests): playback rate from the clip's stride,
 * placement on the walk path and terrain, spheres along a capsule. */
#ifndef MEADOW_CHARACTER_WALK_H
#define MEADOW_CHARACTER_WALK_H

#include <stdbool.h>
#include <stdint.h>

#include "character/character.h"

/* Strides slower than this (m/s) are "no stride": the clip plays at rate 1. */
#define CHARACTER_MIN_STRIDE_SPEED 1e-3f

/* Stance feet slower than this many heights per second say nothing about
 * where a model faces. */
#define CHARACTER_FACING_MIN_SPEED 0.05f

/* Where a model faces, judged from its walk: over every clip, the one whose
 * stance feet (character_clip_stride) move fastest; they move backwards, so
 * the model faces the opposite way, snapped to +X (1), -X (-1), +Z (3) or
 * -Z (-3) when that axis is at least twice the other component. 0: no clip
 * moves its feet at CHARACTER_FACING_MIN_SPEED * height (m/s) or more, or
 * the direction is diagonal. */
int character_walk_facing(const character_model_t *model, float height);

/* The walk's say on where an imported model faces: unless the scene chose
 * the forward axis or a rotation (yaw != 0), a model whose walk
 * (character_walk_facing) runs along X or -Z is imported again turned to
 * face +Z, and a walk along +Z confirms the forward found; both make the
 * evidence "walk". im is updated (forward, its evidence and confidence,
 * the drawn box). false with a reason in err when the import fails. */
bool character_walk_face(character_model_t *model, const char *path, float yaw, character_import_t *im, char *err,
                         size_t err_size);

/* Clip seconds per second of walking: speed / (natural_speed * scale),
 * negative for clips that walk backwards in model space (played in
 * reverse); 1 when the clip has no stride. */
float character_walk_rate(const character_stride_t *stride, float speed, float scale);

/* Position on the walk at `time` (scene_walk_eval), y from the terrain under
 * the root (0 without terrain or off a mesh terrain), walking direction,
 * world-from-model matrix T(position) Ry(yaw) S(scale) with the model's +Z
 * along dir, and the clip time: distance walked / speed * rate (frozen when
 * a non-looping walk has ended; `time` itself when there is no path). */
void character_walk_place(const scene_character_t *c, const terrain_mesh_t *terrain, float rate, float time,
                          float *clip_time, float position[3], float dir[2], float model[16]);

/* Number of spheres laid along a capsule: ceil(length / radius) + 1, so the
 * spacing is at most the radius. */
int character_capsule_sphere_count(const character_capsule_t *c);
/* n spheres from a to b whose union contains the capsule (a, b, radius):
 * radii are inflated to sqrt(radius^2 + (spacing/2)^2). */
void character_capsule_spheres(const float a[3], const float b[3], float radius, int n, float (*out)[4]);

/* Animation level of detail (character_set_view): the updates between
 * two poses of a character `distance` m from the camera, 1 within
 * lod_distance and one more per lod_distance beyond it, at most
 * CHARACTER_POSE_STEP_MAX; 1 when lod_distance <= 0 (off). */
#define CHARACTER_POSE_STEP_MAX 8
int character_pose_step(float distance, float lod_distance);
/* Whether character `index` is posed at update number `update` with step
 * `step`: every step-th update, the characters staggered by index so that
 * the far ones' poses spread evenly over the updates. */
bool character_pose_due(uint64_t update, int index, int step);

#endif

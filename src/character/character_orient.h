/* character_orient: where a loaded model's up and front lie, judged from
 * what is drawn (GL-free). The drawn pose is the first frame of the clip a
 * character plays (the walk clip, else the first clip that moves), skinned
 * with every node transform; without clips the bind pose. Evidence, each a
 * signed axis of the file (codes as in character_import.h):
 *   skeleton  the mean of the head/neck/spine bones minus the mean of the
 *             leg/foot bones (by name) points up; toe minus heel/ankle/foot
 *             points forward, else left bones minus right bones is the
 *             model's left and left x up points forward;
 *   geometry  a model stands on its feet: along the true up axis the
 *             vertices within 3% of the bottom spread over more of the
 *             model's horizontal box than along any other axis (a side or
 *             an end touches the ground in a strip or a point); the area
 *             centroid breaks a tie between the two ends of an axis;
 *   body      a model that lies along a horizontal axis (a quadruped, a
 *             spider) is mirror-symmetric across the other one (its left
 *             and right), and its head is the end of its length that holds
 *             more vertices (eyes, mouth, horns, fangs: where a modeller
 *             spends them; the bulk is no guide, a bull's big end is its
 *             head, a spider's its abdomen).
 * character_import weighs these against the file's metadata and the format
 * (docs/CHARACTERS.md, "Import: units, axes, height"). */
#ifndef MEADOW_CHARACTER_ORIENT_H
#define MEADOW_CHARACTER_ORIENT_H

#include "character/character_load.h"
#include "character/character_ref.h"

/* Bone evidence counts below this angle from an axis (degrees). */
#define CHARACTER_ORIENT_MAX_ANGLE 35.0f

/* The clip whose first frame is drawn: a clip named like "walk" (any
 * case), else the first clip with keys that is not still
 * (character_clip_t.still), else the first clip; -1 without clips. */
int character_orient_pose_clip(const character_model_t *model);

/* Skins the drawn pose of `clip` (-1: bind) into positions (3 floats per
 * vertex), leaving the pose in `pose` (initialised by the caller). */
void character_orient_pose(const character_model_t *model, int clip, character_pose_t *pose, float *positions);

/* Box (min, max per axis) of the drawn pose of `clip` (-1: bind); false
 * (the box empty) when out of memory. */
bool character_orient_box(const character_model_t *model, int clip, float lo[3], float hi[3]);

/* Up from the skeleton: an axis code, or 0 when the bone names give no top
 * and bottom or their difference is farther than CHARACTER_ORIENT_MAX_ANGLE
 * from every axis. *cos_out: cosine to the axis chosen. */
int character_orient_skeleton_up(const character_model_t *model, const character_pose_t *pose, float *cos_out);
/* Forward from the feet (toe minus heel, ankle or foot), perpendicular to
 * `up`; without toes and heels from the sides (left x up, the left being
 * the mean of the bones named left minus that of those named right); 0
 * when the names give none or the direction is diagonal. */
int character_orient_skeleton_forward(const character_model_t *model, const character_pose_t *pose, int up);

/* Up from the geometry (see the banner). *margin: the winning support over
 * the best support of another axis (>= 1; 1 = no preference, a cube). */
int character_orient_geometry_up(const character_model_t *model, const float *positions, float *margin);

/* A horizontal axis counts as the body's left-right when mirroring the
 * drawn surface across the box's middle along it leaves at most this
 * fraction of the surface's cells unmatched; the body's length must leave
 * at least twice this fraction unmatched. */
#define CHARACTER_ORIENT_MIRROR 0.2f

/* Forward from the body (see the banner), perpendicular to `up`: the
 * horizontal axis the model is not mirror-symmetric along, when the other
 * one is (CHARACTER_ORIENT_MIRROR) and the model is at least as long along
 * it as it is tall, towards the end whose vertices' mean lies at least 3%
 * of the length beyond the middle; 0 otherwise (a standing figure, a box,
 * a sphere, a sheet) or when out of memory. */
int character_orient_body_forward(const character_model_t *model, const float *positions, int up);

#endif

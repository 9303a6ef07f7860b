/* character_import: brings a loaded model (character_load, file units and
 * axes) into meadow's model space: metres, +Y up, facing +Z, the bind pose
 * standing on y = 0. The conversion is one similarity transform
 * p' = s R p + t baked into the vertices, the inverse bind matrices, the root
 * bones' bind values and their animation keys, so skinning, stride
 * estimation and capsules all see the converted model. GL-free.
 *
 * Where each part comes from, first match wins (docs/CHARACTERS.md,
 * "Import: units, axes, height"):
 *   up:      desc.up; the file's metadata (UpAxis/UpAxisSign); +Z for formats
 *            that are Z-up by convention and that assimp leaves so (3ds, ase,
 *            blend, mdl, md2, smd); +Y.
 *   forward: desc.forward; the skeleton; the metadata
 *            (FrontAxis/FrontAxisSign); the body (a quadruped's or a
 *            spider's head end, character_orient_body_forward); +X for
 *            Quake/Valve formats (mdl, md2, md3, md5mesh, smd); -Z for b3d
 *            (left-handed, mirrored by assimp); -Y for 3ds, ase and blend;
 *            +Z (glTF's convention).
 *   scale:   desc.height / bind height; the metadata's unit (UnitScaleFactor,
 *            else OriginalUnitScaleFactor); 1 (metres) when the bind pose is
 *            CHARACTER_IMPORT_MIN..MAX_HEIGHT tall; otherwise fitted to
 *            CHARACTER_IMPORT_FIT_HEIGHT with a warning. A metadata unit that
 *            gives a height outside that window also warns. */
#ifndef MEADOW_CHARACTER_IMPORT_H
#define MEADOW_CHARACTER_IMPORT_H

#include "character/character_load.h"

#include <stdbool.h>
#include <stddef.h>

#define CHARACTER_IMPORT_MIN_HEIGHT 0.25f /* m: plausible character sizes */
#define CHARACTER_IMPORT_MAX_HEIGHT 3.0f
#define CHARACTER_IMPORT_FIT_HEIGHT 1.75f /* m: a humanoid, when units are unknown */
#define CHARACTER_IMPORT_MAX_FIT 1000.0f  /* m: largest accepted desc.height */

/* Axis codes: +1/-1 = +X/-X, +2/-2 = +Y/-Y, +3/-3 = +Z/-Z; 0 = automatic.
 * Zero means default throughout. */
typedef struct character_import_desc_t {
    float height;  /* bind-pose height to fit (m), (0, CHARACTER_IMPORT_MAX_FIT]; 0 = automatic */
    int up;        /* the file's up axis; 0 = automatic */
    int forward;   /* the file's forward axis (where the face looks); 0 = automatic */
    float yaw;     /* degrees about +Y after the axes, counter-clockwise seen
                      from above (+Z turns towards +X); default 0 */
} character_import_desc_t;

/* What was applied, for messages and summary.txt. */
typedef struct character_import_t {
    float scale;          /* metres per file unit (s) */
    float height;         /* bind-pose height after import (m) */
    float file_height;    /* bind-pose height in file units, along the up axis */
    int up, forward;      /* file axes used (codes above) */
    const char *scale_from, *up_from, *forward_from; /* "scene", "skeleton", "geometry", "metadata",
                                                        "walk", "format", "default", ... */
    float up_confidence, forward_confidence; /* 0..1 per evidence (character_import_confidence) */
    int pose_clip;        /* the clip whose first frame was measured (character_orient_pose_clip); -1: bind */
    float box_min[3], box_max[3]; /* that drawn pose after the import (m, model space: +Y up, +Z forward) */
} character_import_t;

/* Below this, character_import_report warns and names the keys that
 * override. */
#define CHARACTER_IMPORT_LOW_CONFIDENCE 0.5f

/* Axis code from "+x", "-y", "z" (= "+z"), ...; 0 for anything else. */
int character_axis_parse(const char *s);
/* "+x", "-z", ...; "auto" for 0. */
const char *character_axis_name(int code);

/* Converts model in place (see above). `path` prefixes warnings. Returns
 * false with one line in err (not logged) when desc is inconsistent (up
 * parallel to forward, height out of range) or the model has no extent along
 * its up axis. */
bool character_import(character_model_t *model, const char *path, const character_import_desc_t *desc,
                      character_import_t *out, char *err, size_t err_size);

/* The confidence of one kind of evidence ("scene" 1, "skeleton, geometry"
 * 0.95, "walk" 0.9, ..., "default" 0.2; 0 for an unknown name). */
float character_import_evidence(const char *from);
/* The smaller of the up and forward confidences. */
float character_import_confidence(const character_import_t *import);
/* One warning when the confidence is low, naming what was guessed and the
 * scene keys (characters[].up, .forward, .rotation) that override it.
 * Returns whether it warned. */
bool character_import_report(const char *path, const character_import_t *import);

/* The similarity transform of the last step as a column-major matrix: p' =
 * m p. Exposed for tests: build_matrix(scale, up, forward, yaw, lift). */
void character_import_matrix(float scale, int up, int forward, float yaw_deg, float lift, float out[16]);

#endif

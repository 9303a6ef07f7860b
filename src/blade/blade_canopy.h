/* blade_canopy: the far field's third representation, after Qiu et al.:
 * the ground itself shaded as a grass canopy, its coverage and colour and
 * their change with the view elevation measured on the blade model
 * (GL-free; the GLSL twin that shades with the table is
 * shaders/common/canopy.glsl).
 *
 * A periodic square patch of blades, seeded as blade_seed seeds them and
 * settled under gravity by the blade physics (blade_ref_step_one,
 * eq. 3-16; the rest pose: no wind), is ray-cast orthographically at `rows` view
 * elevations (row i at 90 i / (rows - 1) degrees, row 0 at 1 degree), the
 * hits of `patches` such patches pooled. Each blade is `segments` quads of
 * blade_ref_surface (eq. 21 with the scene's shape). Per row the table
 * keeps the cover (rays that meet a blade before the ground) and the
 * means of the ambient-occlusion and sun terms of blade_shade over the
 * points met, in the ground's frame (blades grow along the ground's
 * normal, so on a slope the canopy is the flat one rotated), from which
 * the mean colour is exact on any slope and for any sun; thinned by the
 * extent map to a fraction E, the ground shows through as (1 - cover)^E.
 * The same rays also give the rows cut at BLADE_CANOPY_CUTS heights: the
 * cover and means of each ray's first hit below the cut, the ray reaching
 * it unobstructed; just past the hybrid's switch the drawn blades' overhang
 * takes the part above (blade_canopy_overhang).
 * Under wind (desc.wind > 0) the table has BLADE_CANOPY_POSES poses: the
 * rest pose, and the patch settled under a uniform wind of BLADE_CANOPY_WIND_STEPS
 * magnitudes at BLADE_CANOPY_WIND_AZIMUTHS azimuths from the viewer; a
 * point's wind picks them (blade_canopy_color). Blades bent towards the
 * viewer show their undersides: seen at 7.5 degrees, the mean luminance
 * 0.265 at rest falls to 0.150 under a wind of 0.5 towards the viewer and
 * rises to 0.347 under one away (test_blade_canopy).
 * The table's terms and the colour formula:
 * docs/HYBRID.md ("Ground canopy"). */
#ifndef MEADOW_BLADE_CANOPY_H
#define MEADOW_BLADE_CANOPY_H

#include <stdbool.h>
#include <stdint.h>

#include "blade/blade_population.h"

#define BLADE_CANOPY_MAX_ROWS 32
#define BLADE_CANOPY_AZIMUTHS 9
#define BLADE_CANOPY_SUNS 14            /* sun elevations over the ground */
#define BLADE_CANOPY_SUN_STEP 0.2617994f /* between them: 15 degrees */
#define BLADE_CANOPY_SEGMENTS 8
#define BLADE_CANOPY_MAX_SEGMENTS 64
#define BLADE_CANOPY_PATCHES 4
/* Cut k at top 2^(k - BLADE_CANOPY_CUTS), halving down from top / 2: at a
 * low view the cover below a cut rises within centimetres (at 7.5 degrees
 * to 0.5 by top / 32). */
#define BLADE_CANOPY_CUTS 5
/* Wind poses: azimuths k 90 degrees from t towards s (k = 0..3), each at
 * magnitudes wind (m + 1) / BLADE_CANOPY_WIND_STEPS; pose 0 is the rest
 * pose, pose 1 + m BLADE_CANOPY_WIND_AZIMUTHS + k the wind's. */
#define BLADE_CANOPY_WIND_AZIMUTHS 4
#define BLADE_CANOPY_WIND_STEPS 2
#define BLADE_CANOPY_POSES (1 + BLADE_CANOPY_WIND_AZIMUTHS * BLADE_CANOPY_WIND_STEPS)

/* Zero means default. */
#define BLADE_CANOPY_PATCH_BLADES 2048.0f
typedef struct blade_canopy_desc_t {
    blade_population_t population; /* the blades (blade_population.h; the scene's): density,
                                       ranges, shape, and the gravity they settle under; the
                                       albedo is not used (blade_canopy_color takes it) */
    uint32_t seed;      /* any value (0 included) */
    int rows;           /* view elevations, default 16, at most BLADE_CANOPY_MAX_ROWS */
    int rays;           /* rays per row, default 4096 */
    float patch;        /* side of the periodic patch, m, default 2, smaller where
                           the density puts more than BLADE_CANOPY_PATCH_BLADES in it */
    float sun[3];       /* towards the sun over flat ground, required (unit: normalised
                           here): one of the table's sun elevations is its elevation */
    int segments;       /* quads along a blade, default BLADE_CANOPY_SEGMENTS, at most
                           BLADE_CANOPY_MAX_SEGMENTS: the drawn blades' level of detail
                           where the canopy takes over (blade_tiles_segments_at) */
    int patches;        /* independent patches (seeds) whose hits are pooled, sharing the
                           rays, default BLADE_CANOPY_PATCHES: one patch's blades moved
                           the mean colour by 0.9 L* (sd over seeds, 7.5 degrees) */
    float wind;         /* the largest wind force the blades meet (the sum of the scene's
                           wind strengths; blade_wind_wave), default 0: the rest pose alone */
    int wind_rays;      /* rays per row of each wind pose, default rays / 4, times 1,024 /
                           the patch's blades past 1,024 (at least 64): bent blades are
                           dearer to cast (their triangles span more of a strip), and at the
                           rest pose's rays the 8 poses made the table 10 times as slow */
} blade_canopy_desc_t;
blade_canopy_desc_t blade_canopy_desc_defaults(const blade_canopy_desc_t *desc);

/* A row's moments are over the points met, their normal n (flipped to the
 * viewer) in the ground's frame: n = (n_t, n_g, n_s) along the horizontal
 * direction towards the viewer t, the ground normal g and the side s = g x t. */
typedef struct blade_canopy_row_t {
    float cover;
    float ao[4];   /* E[ao], E[n_t ao], E[n_g ao], E[n_s ao] */
    float v_ao[4]; /* the same times v */
    float sun[BLADE_CANOPY_SUNS][BLADE_CANOPY_AZIMUTHS][2]; /* E[D], E[v D] */
} blade_canopy_row_t;

/* One pose's rows: the whole column, and the first hits below cut k, at
 * height top 2^(k - BLADE_CANOPY_CUTS). */
typedef struct blade_canopy_pose_t {
    blade_canopy_row_t row[BLADE_CANOPY_MAX_ROWS];
    blade_canopy_row_t below[BLADE_CANOPY_MAX_ROWS][BLADE_CANOPY_CUTS];
} blade_canopy_pose_t;

typedef struct blade_canopy_t {
    int rows;
    float elevation[BLADE_CANOPY_MAX_ROWS]; /* radians, the rays' (row 0: 1 degree) */
    float sun0; /* radians, the first sun elevation (<= -pi / 2); sun elevation k is
                   sun0 + k BLADE_CANOPY_SUN_STEP, the desc's sun one of them */
    blade_canopy_row_t row[BLADE_CANOPY_MAX_ROWS]; /* the rest pose's whole column */
    /* the rest pose's first hits below cut k, at height top 2^(k - BLADE_CANOPY_CUTS) */
    blade_canopy_row_t below[BLADE_CANOPY_MAX_ROWS][BLADE_CANOPY_CUTS];
    float top; /* m, the tallest blade point of the patches at rest */
    int blades; /* in a patch */
    float wind; /* the desc's: the wind poses' largest magnitude (0: none) */
    float gravity; /* the population's (resolved): what pulls blades on a slope downhill
                      (blade_canopy_slope_lean) */
    int poses;  /* 1, or BLADE_CANOPY_POSES with wind */
    blade_canopy_pose_t *windy; /* poses 1.. (poses - 1 of them; NULL without wind) */
} blade_canopy_t;

/* Measures the table. False (and logs) on bad input or out of memory.
 * With wind it takes about BLADE_CANOPY_POSES times as long. */
bool blade_canopy_make(blade_canopy_t *out, const blade_canopy_desc_t *desc);
/* Releases the wind poses (the table itself is the caller's). */
void blade_canopy_free(blade_canopy_t *c);

/* The rest pose's row at elevation e (radians, clamped to [0, pi / 2]),
 * linear between rows spaced pi / (2 (rows - 1)) apart: the lookup
 * canopy.glsl does. */
blade_canopy_row_t blade_canopy_at(const blade_canopy_t *c, float elevation);

/* The same of the hits below height `cut` (m over the ground; 0: no cut,
 * the whole column), between cut levels: level 0 a cut at 0 (cover 0, the
 * means of level 1), level k in 1..BLADE_CANOPY_CUTS the cut at h_k = top
 * 2^(k - 1 - BLADE_CANOPY_CUTS), the last the whole column (at the top and
 * above); at level q = cut / h_1 below h_1, 1 + log2(cut / h_1) above,
 * linear in q between levels; of pose p (0: at rest). */
blade_canopy_row_t blade_canopy_at_cut(const blade_canopy_t *c, int pose, float elevation, float cut);

/* The poses a wind of force `wind` at azimuth psi (radians from t, towards
 * the sun's side: blade_canopy_view_t) takes and their weights: out[p] for
 * pose p (BLADE_CANOPY_POSES of them, summing to 1): linear in the
 * magnitude between the rest pose and the steps (clamped to the largest),
 * and along the azimuths the trigonometric interpolation through the four
 * (exact for 1, cos, sin and cos 2 of psi; weights may be negative).
 * Without wind poses, out[0] = 1. */
void blade_canopy_wind_weights(const blade_canopy_t *c, float wind, float psi, float out[BLADE_CANOPY_POSES]);

/* The table as canopy.glsl's texture takes it (RGBA32F, texelFetch):
 * texel (x, row + (level + pose BLADE_CANOPY_LEVELS) rows), the row at cut
 * level `level` (blade_canopy_at_cut's) of pose `pose`, is (cover, 0, 0, 0)
 * at x 0, the row's ao at 1, v_ao at 2, and (E[D], E[v D], 0, 0) of sun
 * elevation k and azimuth j at 3 + k BLADE_CANOPY_AZIMUTHS + j. */
#define BLADE_CANOPY_TEXELS (3 + BLADE_CANOPY_SUNS * BLADE_CANOPY_AZIMUTHS)
#define BLADE_CANOPY_LEVELS (BLADE_CANOPY_CUTS + 2)
typedef struct blade_canopy_texture_t {
    int rows;  /* texels high: rows BLADE_CANOPY_LEVELS poses */
    int poses; /* the table's */
    float sun0, top, wind, gravity;
    float texel[BLADE_CANOPY_POSES * BLADE_CANOPY_LEVELS * BLADE_CANOPY_MAX_ROWS][BLADE_CANOPY_TEXELS][4];
} blade_canopy_texture_t;
void blade_canopy_pack(const blade_canopy_t *c, blade_canopy_texture_t *out);

/* The terms of common/lighting.glsl's shade() the mean colour uses. */
#define BLADE_CANOPY_SUN_DIFFUSE 0.85f
#define BLADE_CANOPY_SUN_COLOR {1.0f, 0.95f, 0.85f}
#define BLADE_CANOPY_AMBIENT_DOWN {0.18f, 0.17f, 0.14f}
#define BLADE_CANOPY_AMBIENT_UP {0.35f, 0.42f, 0.55f}

/* Where a canopy point is seen from and lit from, in its ground's frame
 * (blade_canopy_row_t): the view's elevation over the ground, the sun's
 * elevation over it (radians, clamped to the table's) and azimuth in
 * [0, pi] from t, and world up (t.y, g.y, s.y). Flat ground: up (0, 1, 0).
 * cut: only the hits below this height count (m, blade_canopy_at_cut;
 * 0: the whole column). */
typedef struct blade_canopy_view_t {
    float elevation, sun_elevation, azimuth;
    float up[3];
    float cut;
    float wind, wind_azimuth; /* the wind force's magnitude along the ground and its azimuth
                                 from t, towards the sun's side (radians; the sun's side is s's
                                 when the sun's azimuth in the ground is in [0, pi] from t
                                 towards s, otherwise -s's: the mirror image) */
} blade_canopy_view_t;

/* The lean of the blades on ground of unit normal n, as a wind force
 * (world) to add to the wind at the point: the part of their gravity
 * (c->gravity along -y) along the ground, c->gravity (n.y n - y), of
 * magnitude gravity sin(slope), downhill. The table settles its blades on
 * flat ground, gravity along the normal; the tiles' blades grow along the
 * normal and their gravity pulls straight down, so on a slope they lean
 * downhill like blades in a wind (the wind poses pick it up; without wind
 * poses the canopy has no lean). The C twin of canopy_slope_lean in
 * common/canopy.glsl, which canopy_view adds to its wind. */
void blade_canopy_slope_lean(const blade_canopy_t *c, const float n[3], float out[3]);

/* The canopy's mean colour (unfogged) and cover seen and lit as v, blades
 * of albedo mix(root, tip, v): the C twin of canopy_table_color in
 * common/canopy.glsl (linear in the view elevation, the sun's elevation and
 * its azimuth; the poses mixed by blade_canopy_wind_weights, the cover
 * clamped to [0, 1]). */
void blade_canopy_color(const blade_canopy_t *c, const blade_canopy_view_t *v, const float root[3],
                        const float tip[3], float rgb[3], float *cover);

/* The canopy that stands for the blades past the hybrid's switch under
 * the overhang of those drawn before it, thinned to `kept` of the field
 * (blade_lod_coverage; 1: all drawn): full and cut are (colour, cover) of
 * the whole column and of the column cut at the overhang's height
 * (blade_canopy_color). The cut's hits, and of the hits above the cut
 * (transmittance (1 - full) / (1 - cut)) the share of the blades not
 * drawn, 1 - kept, in front: out = (colour, cover). kept 1: the cut; cut
 * cover 0: the whole column thinned to 1 - kept (blade_canopy_under's
 * cover with e 1). */
void blade_canopy_overhang(const float full[4], const float cut[4], float kept, float out[4]);

/* Cover of the canopy thinned to a fraction e in [0, 1] of its density:
 * 1 - max(1 - cover, 1e-6)^e (a gap of 0 would make e = 0 undefined in
 * GLSL's pow). */
float blade_canopy_thinned(float cover, float e);

/* Grass-shaded ground under thinned blades: of the ground a thinned field
 * shows (1 - the cover of `kept` of it, kept = blade_lod_coverage), the
 * share the removed blades covered, (C - C_kept) / (1 - C_kept) with C =
 * blade_canopy_thinned(cover, e) over the extent map's fraction e and
 * C_kept the same at e * kept: the ground mixed towards the canopy's colour
 * by this keeps the full field's mean colour. kept 1: 0 (the ground as it
 * is); kept 0: C (the canopy beyond the grass). */
float blade_canopy_under(float cover, float e, float kept);

#endif

/* scene: the scene description (JSON files in scenes/) that drives every run:
 * terrain, grass parameters for the billboard (Orthmann et al. 2009), blade
 * (Jahrmann & Wimmer 2017) and hybrid renderers, camera, wind, analytic
 * colliders and walking characters. GL-free.
 *
 * Parsing is strict: unknown keys, wrong types, out-of-range values, too many
 * entries and malformed JSON are errors of the form
 *     scenes/x.json:12: field "grass.density": expected number, got string
 * (file, line, field path, reason). Limits are never capped silently.
 *
 * Every field is optional; absent or 0 means the default written below (the
 * meadow "zero means default" rule; an explicit 0 therefore also selects the
 * default). Ranges in [] are the accepted JSON values. Keys, ranges and
 * defaults come from one table, scene_fields.c (constants in
 * scene_fields.h, shared with the modules' descs); docs/SCENES.md is its
 * rendering (`meadow --scene-keys`). File paths inside a
 * scene (terrain.mesh, characters[].model) are repository-relative and are
 * resolved by the consumer with core_fs_resolve. */
#ifndef MEADOW_SCENE_H
#define MEADOW_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include <cglm/cglm.h>

#include "blade/blade_lod.h"
#include "blade/blade_population.h"
#include "collide/collide_shape.h"
#include "scene/camera.h"
#include "scene/path.h"
#include "terrain/terrain.h"

/* The blade physics's wind fields (BLADE_MAX_WINDS; world.c asserts it). */
#define SCENE_MAX_WIND 8
#define SCENE_MAX_COLLIDERS 128
#define SCENE_MAX_CHARACTERS 16
/* Paths (camera.path, colliders[].path, characters[].path) hold at most
 * SCENE_MAX_PATH_KEYS (64) keys or waypoints; see path.h. */
#define SCENE_PATH_MAX 256 /* bytes of a file path, including the NUL */
#define SCENE_NAME_MAX 64  /* bytes of a clip name, including the NUL */
#define SCENE_MAX_CLIP_RANGES 8 /* named ranges per character ("clips") */

typedef enum scene_mode_t {
    SCENE_MODE_HYBRID = 0, /* "hybrid" (default): blades near, billboards far */
    SCENE_MODE_BILLBOARD,  /* "billboard": Orthmann et al. 2009 only */
    SCENE_MODE_BLADE,      /* "blade": Jahrmann & Wimmer 2017 only */
} scene_mode_t;

/* How grass is rasterized (docs/RASTER.md). */
typedef enum scene_raster_t {
    SCENE_RASTER_AUTO = 0, /* "auto" (default): the faster of the two, measured at start-up
                              (bench and compare sessions draw hw unless --raster says
                              otherwise; --raster auto measures there too) */
    SCENE_RASTER_HW,       /* "hw": the hardware pipeline, the papers' reference path
                              (tessellation / geometry shaders, alpha-to-coverage) */
    SCENE_RASTER_COMPUTE,  /* "compute": compute shaders into a visibility buffer (src/raster) */
} scene_raster_t;

/* How the hardware path draws blades (docs/BLADES.md). */
typedef enum scene_blade_render_t {
    SCENE_BLADE_RENDER_PULL = 0, /* "pull" (default): instanced triangle strips, vertex pulling */
    SCENE_BLADE_RENDER_TESS,     /* "tess": one patch per blade through blade.tesc / blade.tese */
} scene_blade_render_t;

/* What the hybrid draws between the blades and the ground canopy on a
 * world terrain (docs/WORLD.md). */
typedef enum scene_hybrid_billboards_t {
    SCENE_HYBRID_BILLBOARDS_RING = 0, /* "ring" (default): the streamed billboard ring */
    SCENE_HYBRID_BILLBOARDS_NONE,     /* "none": the canopy from the switch distance */
} scene_hybrid_billboards_t;

/* grass.canopy_match: where the blades end in the ground canopy, its colour
 * matched to theirs by the frame's own means (ground/ground_match.h). Off
 * by default: against blades drawn across the band it made meadow_large's
 * worst frames worse (docs/HYBRID.md "Canopy match"). */
typedef enum scene_canopy_match_t {
    SCENE_CANOPY_MATCH_OFF = 0, /* "off" (default): the table's colour as it is */
    SCENE_CANOPY_MATCH_ON,      /* "on" */
} scene_canopy_match_t;

/* Clearings of the extent map (bb_layout.h, bb_extent_desc_t): where both
 * grass models leave the ground bare. */
typedef enum scene_clearings_type_t {
    SCENE_CLEARINGS_NOISE = 0, /* "noise" (default): bare blobs where a fBm field dips */
    SCENE_CLEARINGS_NONE,      /* "none": full coverage everywhere (a lawn) */
    SCENE_CLEARINGS_IMAGE,     /* "image": a grey image over the terrain, white grass, black bare */
} scene_clearings_type_t;

/* "grass.clearings" object. Noise keys: type, fraction, size. Image keys:
 * type, image. None keys: type. */
typedef struct scene_clearings_desc_t {
    scene_clearings_type_t type;
    float fraction; /* noise: share of the ground left bare [0, 1]; default 0: the noise's own
                       threshold, whose bare share varies with the seed */
    float size;     /* noise: blob scale m [0, 10000] (the coarsest noise octave's cell);
                       default 0: a quarter of the field's side */
    char image[SCENE_PATH_MAX]; /* image: grey image file, repository-relative; required */
} scene_clearings_desc_t;

/* "grass" object. */
typedef struct scene_grass_desc_t {
    blade_population_t population; /* keys density [0, 10000], height [min, max] each [0, 10],
                                      width each [0, 1], stiffness each (0, 100], shape; albedo
                                      and gravity are not keys (left 0: the defaults of
                                      blade_population.h) */
    float billboard_density; /* billboards per m^2 [0, 1000]; default 6 */
    vec2 billboard_size;     /* billboard [w, h] m, each [0, 20]; default [1.0, 0.6] */
    float switch_distance;   /* hybrid blade->billboard distance m [0, 1000]; default 12 */
    float canopy_distance;   /* hybrid billboard->ground canopy distance m [0, 1e5]; default 60 */
    float tile_size;         /* grass tile side m [0, 1000]; default 4 */
    scene_blade_render_t blade_render; /* default pull */
    float displacement;      /* eq. 23 as printed, times this [0, 4]; default 0 (off) */
    float width_correction;  /* eq. 24 step (this project's reading) [0, 1]; default 0 (off) */
    vec2 width_printed;      /* eq. 24 as printed: [w_min, w_span] px, each [0, 100]; w_span 0: off
                                (default [0, 0]) */
    int subdiv[2];           /* billboard mesh subdivision [N, M], each 0 or [2, 8]; default [4, 4] */
    int spring_iterations;   /* billboard spring relaxation iterations [0, 64]; default 2 */
    int deformed_pool;       /* billboards' deformed-mesh pool slots [0, 262144]; default 4096 */
    int tile_pool;           /* hybrid: tiles simulated at once (state slots) [0, 1024]; default 64 */
    int cube_resolution;     /* collision cube-map resolution [0, 4096]; default 32 */
    float cube_texel;        /* largest cube-map texel m [0, 10]: the resolution rises above
                                cube_resolution until 2 r / res <= cube_texel for the largest
                                collider; default 0 (off: cube_resolution for all) */
    float recover_time;      /* seconds to stand up after a push [0, 3600]; default 3 */
    float blade_distance;    /* blade mode: blades drawn up to this distance m [0, 1e6]; default 0:
                                as far as grass is visible (scene_blade_distance) */
    blade_lod_t lod;         /* "lod": thinning with distance (blade_lod.h); defaults there */
    scene_clearings_desc_t clearings; /* default noise */
    bool gi;                 /* Orthmann sec. 6.1 global illumination volumes; default false */
    bool bb_occlusion;       /* occlusion queries per billboard leaf batch (Orthmann sec. 6);
                                default false */
    bool bb_lod;             /* billboard cards thinned by grass.lod's rule, the kept ones
                                widened (billboard/bb_lod.h); default false */
    float bb_lod_width_px;   /* with bb_lod: the width rule's width_px for the cards;
                                default 0: grass.lod.width_px */
    scene_hybrid_billboards_t billboards; /* hybrid on a world terrain; default ring */
    scene_canopy_match_t canopy_match;    /* default off */
    char lod_table[SCENE_PATH_MAX]; /* hybrid: switch distances measured by the bench for a GL
                                       renderer (scene_lod.h), repository-relative; default "": the
                                       scene's switch_distance and canopy_distance */
} scene_grass_desc_t;
/* For [min, max] pairs, [0, 0] (or absent) means default; otherwise
 * min <= max is required. */

/* "camera" object. position/target each component [-1e6, 1e6]; when both are
 * zero the camera sits at (0, 8, 24) looking at the origin. */
typedef struct scene_camera_desc_t {
    vec3 position;
    vec3 target;
    float fov;       /* vertical degrees [0, 179]; default 60 */
    float near;      /* m [0, 1e4]; default 0.1 */
    float far;       /* m [0, 1e6]; default 200; must exceed near */
    cam_path_t path; /* "path": [{"t", "position", "target"}...], t strictly increasing */
} scene_camera_desc_t;

typedef enum scene_wind_type_t {
    SCENE_WIND_DIRECTIONAL = 0, /* "directional" (default) */
    SCENE_WIND_POINT,           /* "point" */
} scene_wind_type_t;

/* "wind" array entry. Directional keys: type, direction, strength,
 * wavelength, speed. Point keys: type, position, strength, radius. */
typedef struct scene_wind_t {
    scene_wind_type_t type;
    vec2 direction;   /* directional: (x, z), normalised on load; default (1, 0) */
    float strength;   /* [0, 100]; default 1 */
    float wavelength; /* directional: gust wavelength m [0, 1e4]; default 10 */
    float speed;      /* directional: gust speed m/s [0, 1000]; default 2 */
    vec3 position;    /* point: centre, components [-1e6, 1e6] */
    float radius;     /* point: falloff radius m [0, 1e4]; default 5 */
} scene_wind_t;

typedef enum scene_collider_type_t {
    SCENE_COLLIDER_SPHERE = 0, /* "sphere" (default); keys radius */
    SCENE_COLLIDER_CAPSULE,    /* "capsule"; keys radius, length (vertical axis) */
    SCENE_COLLIDER_BOX,        /* "box"; keys half_extents (axis aligned) */
} scene_collider_type_t;

/* "colliders" array entry. Common keys: type, position, path, loop.
 * On heightfield terrains the program reads y as the height of the centre
 * above the ground under it; on mesh terrains y is absolute.
 * "position": [x,y,z] is a static collider (stored as a one-key path);
 * "path": [{"t", "position"}...] moves it (scene_path_eval); not both. */
typedef struct scene_collider_t {
    scene_collider_type_t type;
    float radius;      /* sphere/capsule m [0, 100]; default 0.5 (sphere), 0.3 (capsule) */
    float length;      /* capsule segment length m [0, 100]; default 1 */
    vec3 half_extents; /* box m, each [0, 100]; default (0.5, 0.5, 0.5) */
    scene_path_t path; /* centre over time */
    bool loop;         /* default false; see scene_path_eval */
} scene_collider_t;

/* The collider's shape as the grass's collision takes it (collide_shape.h). */
collide_shape_t scene_collider_shape(const scene_collider_t *c);

/* A named range of frames of a model's first clip ("clips": {"walk": [1, 14]}):
 * ticks of that clip's timeline (frames for frame-based formats; what
 * `meadow --list-clips` prints), start < end, each in [0, 1e7]. Whether the
 * range lies on the model's timeline is checked when the model is loaded. */
typedef struct scene_clip_range_t {
    char name[SCENE_NAME_MAX]; /* not empty, not an index ("3") nor a range ("1:2") */
    float range[2];            /* start, end */
} scene_clip_range_t;

/* "characters" array entry. Keys: model (required), clip, clips, speed,
 * scale, height, up, forward, rotation, path, loop. up and forward are
 * SCENE_AXIS_* indices into "auto", "+x", "-x", "+y", "-y", "+z", "-z"
 * (scene_axis_code turns them into character_import's axis codes). */
typedef struct scene_character_t {
    char model[SCENE_PATH_MAX];    /* model file, e.g. "models/humanoid.gltf" */
    char clip_name[SCENE_NAME_MAX]; /* "clip": "walk" -> name, clip_index = -1 */
    int clip_index;                /* "clip": 2 -> index [0, 1000]; default 0 (first clip) */
    int clip_range_count;          /* "clips": named ranges, at most SCENE_MAX_CLIP_RANGES */
    scene_clip_range_t clip_ranges[SCENE_MAX_CLIP_RANGES];
    float speed;                   /* walking speed m/s [0, 100]; default 1.2 */
    float scale;                   /* uniform scale on top of the import [0, 1000]; default 1 */
    float height;                  /* fit the bind pose to this height m [0, 1000]; 0 = automatic */
    int up, forward;               /* the file's axes; 0 = automatic */
    float rotation;                /* yaw after import, degrees [-360, 360]; default 0 */
    int waypoint_count;            /* "path": [[x, z], ...]; none = stands at the origin */
    vec2 waypoints[SCENE_MAX_PATH_KEYS];
    bool loop;                     /* closed walk, default false; see scene_walk_eval */
} scene_character_t;

/* Axis code of an up/forward index: 0 (auto), +1/-1 x, +2/-2 y, +3/-3 z. */
static inline int scene_axis_code(int index) { return index <= 0 ? 0 : ((index + 1) / 2) * (index % 2 ? 1 : -1); }

/* The whole scene. Top-level keys: seed, frames, dt, size, msaa, mode,
 * terrain, grass, camera, wind, colliders, characters.
 * "terrain" keys: type ("heightfield" | "mesh"), size [0, 10000],
 * resolution [0, 4096], height [0, 1000], mesh (required for type mesh),
 * scale [0, 1e6]; defaults in terrain.h (40 m, 64 cells, 1.5 m, scale 1). */
typedef struct scene_desc_t {
    uint32_t seed;        /* [0, 2^32-1]; default 0 (a valid seed) */
    int frames;           /* frames of a headless run [0, 1e7]; default 300 */
    float dt;             /* fixed timestep s [0, 1]; default 1/60 */
    int size[2];          /* framebuffer [w, h] px, each [0, 16384]; default [1280, 720] */
    int msaa;             /* samples, one of 0, 1, 2, 4, 8, 16 (1 = off); default 4 */
    scene_mode_t mode;    /* default hybrid */
    scene_raster_t raster; /* "raster": "hw" (default) | "compute" | "auto" */
    int raster_samples;   /* compute rasterizer samples per pixel, 1 or 4; default 4 */
    terrain_desc_t terrain;
    scene_grass_desc_t grass;
    scene_camera_desc_t camera;
    int wind_count;
    scene_wind_t wind[SCENE_MAX_WIND];
    int collider_count;
    scene_collider_t colliders[SCENE_MAX_COLLIDERS];
    int character_count;
    scene_character_t characters[SCENE_MAX_CHARACTERS];
} scene_desc_t;

/* Replaces every zero field (including those of the first *_count entries of
 * wind, colliders and characters) with its default, in place. */
void scene_desc_defaults(scene_desc_t *d);

/* Reads and parses a scene file. On failure: err gets the message (also
 * logged with core_log_error), *out is zeroed, returns false. */
bool scene_load(scene_desc_t *out, const char *path, char *err, size_t err_size);
/* Parses scene JSON text; name_for_errors prefixes messages (a file name).
 * On success *out is fully resolved (scene_desc_defaults applied). */
bool scene_parse(scene_desc_t *out, const char *text, const char *name_for_errors, char *err,
                 size_t err_size);
/* Releases the desc. It owns no heap memory today; this clears it so a freed
 * desc never looks valid. */
void scene_free(scene_desc_t *d);

/* Camera at t = 0 from a resolved desc: position/target/fov/near/far, aspect
 * from size, then the camera path (if any) evaluated at 0. */
void scene_camera_init(const scene_desc_t *d, cam_t *cam);

/* The focal length (px per unit tangent) of the scene's view: its target
 * height and vertical field of view (blade_lod_focal's measure); what the
 * tiles' draw buffer is sized for (a taller window drops far blades,
 * counted and logged: blade_tiles_desc_t.draw_capacity). */
float scene_focal(const scene_desc_t *s);

/* Blade mode's cull distance (m) for a camera at cam_pos with far plane
 * `far` over grass in the box [field_min, field_max]: grass.blade_distance
 * when positive, else the distance from the camera to the box's farthest
 * corner or `far`, whichever is nearer (every blade of the field that the
 * far plane leaves visible). */
float scene_blade_distance(const scene_grass_desc_t *g, const float cam_pos[3], float far, const float field_min[3],
                           const float field_max[3]);

/* Names used in scene files, for logs and UIs. */
const char *scene_mode_name(scene_mode_t mode);
const char *scene_raster_name(scene_raster_t raster);
/* "hw", "compute" or "auto" into *out; false for anything else. */
bool scene_raster_parse(const char *name, scene_raster_t *out);
const char *scene_blade_shape_name(blade_shape_t shape);

#endif

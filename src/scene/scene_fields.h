/* scene_fields: the one source of the scene's defaults and bounds.
 *
 * - The SCENE_DEFAULT_* and SCENE_*_MIN / _MAX constants below are the
 *   program's values. The modules that take a scene knob (bb, blade_tiles,
 *   hybrid, terrain, camera) resolve their zero desc fields to these same
 *   constants, so a module test run with a zero desc behaves as the program
 *   (test_scene_defaults checks every pair). The blades' keys (density,
 *   height, width, stiffness, shape) fill a blade_population_t, whose
 *   defaults are BLADE_DEFAULT_* of blade/blade_population.h.
 * - scene_fields[] (scene_fields.c) lists every scene key with its type,
 *   accepted range, default and a doc line. scene.c takes its bounds checks,
 *   its unknown-key lists and scene_desc_defaults from it, and
 *   scene_keys_markdown renders it as docs/SCENES.md (`meadow --scene-keys`;
 *   test_scene_json fails when the committed file differs).
 *
 * GL-free and free of includes beyond <stdbool.h> and <stddef.h>. */
#ifndef MEADOW_SCENE_FIELDS_H
#define MEADOW_SCENE_FIELDS_H

#include <stdbool.h>
#include <stddef.h>

#include "billboard/bb_defaults.h"
#include "hybrid/hybrid.h"

/* ---- defaults and bounds shared with the modules ------------------------ */

/* Top level. */
#define SCENE_DEFAULT_FRAMES 300
#define SCENE_DEFAULT_DT (1.0f / 60.0f)
#define SCENE_DEFAULT_WIDTH 1280
#define SCENE_DEFAULT_HEIGHT 720
#define SCENE_DEFAULT_MSAA 4
#define SCENE_DEFAULT_RASTER_SAMPLES 4

/* "terrain": TERRAIN_DEFAULT_* of terrain/terrain.h. */

/* "grass": blades: BLADE_DEFAULT_* of blade/blade_population.h. */
/* "grass": billboards: BB_DEFAULT_* of billboard/bb_defaults.h; the hybrid's
 * tiles: HYBRID_DEFAULT_* of hybrid/hybrid.h. */
#define SCENE_DEFAULT_CANOPY_DISTANCE 60.0f
/* recover_time drives the billboards' recovery, the blades' collision decay
 * and the hand-over memory: one default. */
#define SCENE_DEFAULT_RECOVER_TIME BB_DEFAULT_RECOVER_TIME

/* "camera" (cam_defaults). */
#define SCENE_DEFAULT_FOV 60.0f
#define SCENE_DEFAULT_NEAR 0.1f
#define SCENE_DEFAULT_FAR 200.0f
#define SCENE_DEFAULT_CAMERA_Y 8.0f  /* position (0, 8, 24) when position and */
#define SCENE_DEFAULT_CAMERA_Z 24.0f /* target are both zero */

/* "wind" entries. */
#define SCENE_DEFAULT_WIND_STRENGTH 1.0f
#define SCENE_DEFAULT_WIND_WAVELENGTH 10.0f
#define SCENE_DEFAULT_WIND_SPEED 2.0f
#define SCENE_DEFAULT_WIND_RADIUS 5.0f

/* "colliders" entries. */
#define SCENE_DEFAULT_SPHERE_RADIUS 0.5f
#define SCENE_DEFAULT_CAPSULE_RADIUS 0.3f
#define SCENE_DEFAULT_CAPSULE_LENGTH 1.0f
#define SCENE_DEFAULT_HALF_EXTENT 0.5f

/* Coordinates (positions, targets, directions, waypoints): each in
 * [-SCENE_COORD_MAX, SCENE_COORD_MAX]. */
#define SCENE_COORD_MAX 1e6

/* "characters" entries. */
#define SCENE_DEFAULT_WALK_SPEED 1.2f
#define SCENE_DEFAULT_CHARACTER_SCALE 1.0f

/* ---- the table of keys -------------------------------------------------- */

/* Where a key lives: the object it is a member of. */
typedef enum scene_section_t {
    SCENE_SEC_ROOT = 0,      /* scene_desc_t */
    SCENE_SEC_TERRAIN,       /* terrain_desc_t */
    SCENE_SEC_GRASS,         /* scene_grass_desc_t */
    SCENE_SEC_CLEARINGS,     /* scene_clearings_desc_t */
    SCENE_SEC_LOD,           /* blade_lod_t (grass.lod) */
    SCENE_SEC_CAMERA,        /* scene_camera_desc_t */
    SCENE_SEC_CAMERA_KEY,    /* cam_path_key_t */
    SCENE_SEC_WIND,          /* scene_wind_t */
    SCENE_SEC_COLLIDER,      /* scene_collider_t */
    SCENE_SEC_COLLIDER_KEY,  /* scene_path_key_t */
    SCENE_SEC_CHARACTER,     /* scene_character_t */
    SCENE_SEC_COUNT
} scene_section_t;

typedef enum scene_field_type_t {
    SCENE_FIELD_INT = 0, /* int */
    SCENE_FIELD_U32,     /* uint32_t, read as an integral double */
    SCENE_FIELD_FLOAT,   /* float */
    SCENE_FIELD_INTS,    /* int[n]; defaults per component */
    SCENE_FIELD_FLOATS,  /* float[n]; defaults per component */
    SCENE_FIELD_RANGE,   /* float[2] [min, max], min <= max; [0, 0] means default */
    SCENE_FIELD_ENUM,    /* an enum stored as int; names[0] is the default */
    SCENE_FIELD_BOOL,    /* bool */
    SCENE_FIELD_STRING,  /* char[size] */
    SCENE_FIELD_OBJECT,  /* a section: parsed by scene.c */
    SCENE_FIELD_ARRAY,   /* entries (at most hi): parsed by scene.c */
    SCENE_FIELD_CUSTOM,  /* parsed by scene.c (doc says how) */
} scene_field_type_t;

enum {
    SCENE_FIELD_REQUIRED = 1 << 0, /* missing is an error */
    SCENE_FIELD_ZERO_OK = 1 << 1,  /* 0 (the default) is accepted besides [lo, hi] */
    SCENE_FIELD_POW2 = 1 << 2,     /* integer, 0 or a power of two */
    SCENE_FIELD_NO_DEFAULT = 1 << 3, /* 0 is a value: never replaced (or replaced by scene.c) */
    SCENE_FIELD_ABOVE_LO = 1 << 4,   /* the range is (lo, hi]: lo itself is refused */
    SCENE_FIELD_ENDS = 1 << 5,       /* only lo or hi (raster_samples: 1 or 4) */
};

typedef struct scene_field_t {
    scene_section_t section;
    const char *key;
    unsigned variants;        /* entry types (bit per enum value of the entry's
                                 "type") that accept the key; 0: all */
    scene_field_type_t type;
    int n;                    /* components of INTS / FLOATS */
    double lo, hi;            /* accepted range (ARRAY: hi is the maximum count) */
    float def[3];             /* default (per component) */
    int flags;                /* SCENE_FIELD_* */
    const char *const *names; /* ENUM: the accepted strings, NULL-terminated */
    const char *limit;        /* ARRAY: the constant naming hi, for messages */
    size_t offset, size;      /* member offset and size in the section's struct */
    const char *doc;          /* one line (markdown) */
    const char *type_doc;     /* the reference's type column when not derived from type */
    const char *def_doc;      /* the reference's default column when not derived from def */
} scene_field_t;

extern const scene_field_t scene_fields[];
extern const int scene_field_count;

/* "grass", "camera.path[]", ...: a section's key path prefix. */
const char *scene_section_name(scene_section_t section);
/* The row of section.key; NULL when there is none. */
const scene_field_t *scene_field_find(scene_section_t section, const char *key);
/* Whether number x is a value row f accepts (its range and flags; not the
 * integer check, which is the type's). The scene parser and the command
 * line's options that set a scene value (--frames, --size, --seed,
 * --raster-samples) both ask this. False with why = "<x> is out of range
 * [lo, hi]" or "<x> is not ..." when not. */
bool scene_field_accepts(const scene_field_t *f, double x, char *why, size_t why_size);
/* The key reference (docs/SCENES.md) as markdown, malloc'd (caller frees);
 * NULL when out of memory. */
char *scene_keys_markdown(void);

#endif

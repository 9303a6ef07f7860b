/* hybrid: the tiled field shared by both grass models (GL-free).
 * - Representation per tile: blades within switch_distance of the camera
 *   (the eye distance to the tile's box, the one switch distance of
 *   shaders/common/switch.glsl), billboards beyond, with hysteresis so a tile near the boundary does not
 *   flip every frame.
 * - Activation per tile (Fan et al. 2015): a tile is ACTIVE while an object
 *   touches it, RECOVERING after the last object left until its measured
 *   motion died down (or recover_timeout passed), then IDLE. Only ACTIVE and
 *   RECOVERING tiles hold per-blade simulation state, taken from a
 *   preallocated pool of slots; when the pool is exhausted the tile is
 *   reported (hybrid_stats_t.pool_denied and a warning), never dropped
 *   silently.
 * - Hand-over (after Qiu et al.; the data path is hybrid_slope.h): a
 *   RECOVERING tile drawn as billboards gives its blade state to the
 *   billboards' slope cells and frees its slot (handover_slot names the
 *   slot for that one update); a tile drawn as blades that has no slot but
 *   may still carry deformation (memory_left > 0: touched, or handed over,
 *   less than `memory` seconds ago) takes a slot to be seeded from the
 *   slope cells (seed, for that one update) and turns RECOVERING.
 * - Per-tile object lists, built every update: every object that touches
 *   a tile is listed, however many (a crowd): the lists lie end to end in
 *   one array of the grid (hybrid_grid_t.objects, tile i's from
 *   object_first, a prefix sum over the tiles' counts) that grows to the
 *   step's total, so nothing is left out.
 * - Window (desc.window > 0, the open world, docs/WORLD.md): the grid is a
 *   W x W square of tiles that follows the camera over a field of any size.
 *   Field tile (gi, gj) lives at index (gj mod W) W + (gi mod W) while it
 *   is inside the window; its index is reused by the tile entering opposite
 *   (stats.streamed), with a new epoch. A tile leaving with a slot keeps
 *   it away from the camera (stats.detached): it recovers with no objects
 *   until its motion dies down (hybrid_grid_settle_away) or recover_timeout
 *   passes, then frees the slot, unless it comes back first
 *   and takes its slot and state again (stats.reattached). Memory and the
 *   per-update loop depend on W and the pool, not on the field. */
#ifndef MEADOW_HYBRID_H
#define MEADOW_HYBRID_H

#include <stdbool.h>
#include <stdint.h>

/* The tiles' defaults (what a zero hybrid_desc_t field takes, and the
 * scene keys' defaults, scene/scene_fields.h). */
#define HYBRID_DEFAULT_TILE_SIZE 4.0f        /* m (grass.tile_size) */
#define HYBRID_DEFAULT_SWITCH_DISTANCE 12.0f /* m (grass.switch_distance) */
#define HYBRID_DEFAULT_POOL_SLOTS 64         /* tiles with per-blade state (grass.tile_pool) */
#define HYBRID_DEFAULT_MEMORY 3.0f           /* s a trail is remembered (grass.recover_time) */
/* Not a scene key: the motion (m) below which a RECOVERING tile goes IDLE
 * (hybrid_desc_t, blade_tiles_desc_t). */
#define HYBRID_DEFAULT_MOTION_EPSILON 2e-3f

typedef enum hybrid_state_t {
    HYBRID_IDLE = 0,
    HYBRID_ACTIVE,
    HYBRID_RECOVERING,
} hybrid_state_t;

typedef enum hybrid_rep_t {
    HYBRID_REP_BILLBOARD = 0,
    HYBRID_REP_BLADE,
} hybrid_rep_t;

typedef struct hybrid_tile_t {
    float min[3], max[3];   /* AABB: ground extent, y grown by grass height */
    hybrid_state_t state;
    hybrid_rep_t rep;
    float recover_left;     /* seconds until forced IDLE while RECOVERING */
    float motion;           /* last measured motion (m), from the simulation */
    int slot;               /* pool slot of its simulation state, -1 = none */
    float memory_left;      /* s it may still carry deformation without a slot */
    int handover_slot;      /* slot handed over to billboards this update, else -1 */
    int32_t coord[2];       /* field tile coordinates (gi, gj): the tile's place in the field's grid */
    uint32_t epoch;         /* bumped each time the index takes a new field tile (window) */
    bool present;           /* inside the field (window tiles beyond its edge are not) */
    bool reattached;        /* window: took back the slot it kept away, this update */
    bool seed;              /* slot taken this update, to be seeded from the slope cells */
    int object_first;       /* its list's first entry in hybrid_grid_t.objects */
    int object_count;       /* objects touching it this update: its list's length */
} hybrid_tile_t;

/* Zero means default; (scene) marks HYBRID_DEFAULT_* above, which the scene
 * keys share. */
typedef struct hybrid_desc_t {
    float min_x, min_z;       /* field origin (m); required */
    float size_x, size_z;     /* field extent (m); required */
    float min_y, max_y;       /* ground height range (m) */
    float tile_size;          /* default 4 m (scene, grass.tile_size) */
    float grass_height;       /* AABB growth above the ground; default 1 m */
    float switch_distance;    /* blade/billboard boundary; default 12 m (scene) */
    float hysteresis;         /* half width of the dead band; default 1 m */
    float recover_timeout;    /* default 5 s */
    float motion_epsilon;     /* RECOVERING -> IDLE below this; default 2 mm (scene) */
    int pool_slots;           /* simulation-state slots; default 64 */
    float memory;             /* s a tile carries deformation after its last touch
                                 or hand-over (the billboards' recover time);
                                 default 3 s (scene, grass.recover_time) */
    bool keep_state;          /* false (default): hand over (see the banner);
                                 true: RECOVERING tiles keep their slot whatever
                                 their representation, nothing is handed over */
    int window;               /* tiles per side of the window that follows the
                                 camera; 0 (default): the grid covers the field */
    /* Window only: the ground height range under a tile entering the
     * window (y_out[0] lowest, y_out[1] highest); NULL: min_y..max_y. */
    void (*tile_range)(void *user, const float min_xz[2], const float max_xz[2], float y_out[2]);
    void *range_user;
} hybrid_desc_t;

hybrid_desc_t hybrid_desc_defaults(const hybrid_desc_t *d);

typedef struct hybrid_stats_t {
    int tiles, blade_tiles, billboard_tiles;
    int idle, active, recovering;
    int slots_used, slots_total;
    int pool_denied;        /* tiles that wanted a slot this update and got none */
    int rep_switches;       /* representation changes this update */
    int handovers;          /* tiles handed from blades to billboards this update */
    int seeded;             /* tiles taking a slot to be seeded from billboards this update */
    int listed;             /* entries of all the tiles' object lists this update */
    int streamed;           /* window: tiles that entered the window this update */
    int detached;           /* window: tiles that left it holding a slot, this update */
    int reattached;         /* window: tiles that came back to the slot they kept, this update */
    int away;               /* window: tiles recovering outside it now */
} hybrid_stats_t;

/* A tile that left the window holding a slot: it recovers there. */
typedef struct hybrid_away_t {
    int32_t coord[2];
    int slot;
    float recover_left;
    float memory_left;
} hybrid_away_t;

typedef struct hybrid_grid_t {
    hybrid_desc_t desc;
    int nx, nz;             /* tiles held: the field's, or W x W in a window */
    int field_nx, field_nz; /* tiles of the field */
    int base[2];            /* window: field tile coordinates of its first corner */
    hybrid_away_t *away;    /* window: tiles recovering outside it (at most pool_slots) */
    int away_count;
    hybrid_tile_t *tiles;
    int *free_slots;
    int free_count;
    uint32_t *objects;      /* the tiles' object lists end to end (object indices, ascending per tile) */
    int object_capacity;    /* entries objects holds; grown (doubled) to each update's total */
    bool warned_pool;
    hybrid_stats_t stats;
} hybrid_grid_t;

/* A bounding sphere of a moving object: xyz centre, w radius. */
typedef struct hybrid_object_t {
    float sphere[4];
} hybrid_object_t;

/* The most tiles a grid holds (its CPU table, slope cells and tile lists
 * grow with them): grass.tile_size is refused below what this allows. */
#define HYBRID_MAX_TILES (1 << 20)

bool hybrid_grid_make(hybrid_grid_t *g, const hybrid_desc_t *desc);
void hybrid_grid_free(hybrid_grid_t *g);
/* One update: representation from the camera (eye distance to the tile's box,
 * its nearest point), object lists (every touching object; out of memory:
 * logged, then abort(), as core's growable buffers) and activation. `motion` (may be NULL) gives
 * the measured motion per tile from the last simulation step. */
void hybrid_grid_update(hybrid_grid_t *g, const float camera[3], const hybrid_object_t *objects, int count,
                        const float *motion, float dt);
/* Window: tiles away from it whose slot's latest measured motion
 * (slot_motion[slot], m) is below motion_epsilon end their recovery at the
 * next update, as tiles in the window do. */
void hybrid_grid_settle_away(hybrid_grid_t *g, const float *slot_motion);
/* Tile index of a world position, -1 outside the field (or the window). */
int hybrid_tile_at(const hybrid_grid_t *g, float x, float z);
/* Independent brute-force activity test (tests): does any object touch
 * tile i? */
bool hybrid_tile_touched_brute(const hybrid_grid_t *g, int i, const hybrid_object_t *objects, int count);

#endif

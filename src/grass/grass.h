/* grass: responsive grass for a host's own frame. One grass_t holds a
 * field (its terrain, population, mode and LOD from a scene file), is
 * stepped with the host's colliders and drawn into the host's framebuffer
 * with the host's view. docs/LIBRARY.md is the reference: lifecycle,
 * threading, GL state, units and costs.
 *
 * Units: metres, seconds, y up, right-handed; matrices column-major with
 * GL's clip conventions. Threading: every call on the thread whose GL 4.5
 * core context is current. GL state: grass_draw leaves as it found them
 * the framebuffer bindings, viewport, program, vertex array, the generic
 * buffer bindings (array, indirect, storage, uniform, atomic, pixel, copy
 * read), the 2D, array, 3D, cube and multisample textures of units 0-15
 * and the active unit, the enables (depth, blend, cull, alpha to coverage,
 * scissor, stencil, polygon offset, multisample, rasterizer discard,
 * point size), depth function and mask, blend function and equation,
 * polygon mode and colour mask. It leaves changed: indexed buffer
 * bindings, image units, samplers, and the uniforms of its own programs. */
#ifndef MEADOW_GRASS_H
#define MEADOW_GRASS_H

#include <stdbool.h>
#include <stdint.h>

#include "grass_view.h" /* src/grass_view in the tree, beside grass.h when installed */

typedef struct grass_t grass_t;
struct grass_host_t; /* in-tree hosts only (grass_harness.h) */

/* Fills v from the host's view and proj (column-major), the target's
 * width x height pixels and the draw's time: the rest of grass_view_t. */
void grass_view_make(grass_view_t *v, const float view[16], const float proj[16], int width, int height, float time);

/* Where the tiles of a world terrain draw blades in blade mode when the
 * scene sets no grass.blade_distance (m). */
#define GRASS_BLADE_DISTANCE 80.0f
/* The reference (grass_host_t.reference, the image error's) on a world,
 * which has no field of vertices to seed every blade from: the tiles
 * drawn to this distance (m), no thinning, 16 segments at the camera
 * falling to 4 here, no orientation or occlusion culling, their templates
 * seeded by the placement seed; the ground canopy beyond. It bounds what
 * the image error compares on a world: past it, canopy against canopy. */
#define GRASS_REFERENCE_REACH 100.0f
/* Half width (m) of the hybrid's cross-fade around grass.switch_distance. */
#define GRASS_SWITCH_FADE 1.0f
/* Half width (m) of the ground canopy's band around grass.canopy_distance. */
#define GRASS_CANOPY_FADE 4.0f

typedef enum grass_mode_t {
    GRASS_MODE_SCENE = 0, /* the scene's "mode" */
    GRASS_MODE_BILLBOARD,
    GRASS_MODE_BLADE,
    GRASS_MODE_HYBRID,
} grass_mode_t;

/* What the library asks of its host; zero: stderr, malloc and stdio. */
typedef struct grass_io_t {
    void (*log)(int level, const char *line, void *user); /* level 0 info, 1 warning, 2 error */
    void *user;
} grass_io_t;

/* Zero means default throughout. */
typedef struct grass_desc_t {
    const char *scene;     /* a scene file (docs/SCENES.md): terrain, grass, wind, lod; a relative path is
                              also looked for in the installed share/meadow; default scenes/meadow.json */
    uint32_t seed;         /* 0: the scene's */
    grass_mode_t mode;
    int raster;            /* 0: the scene's, 1 hardware, 2 compute rasterizer */
    int width, height;     /* the largest target grass_draw gets (admission); default the scene's size */
    float collider_radius; /* the largest collider's bounding radius (m; sizes the cube maps); default 2 */
    int max_colliders;     /* colliders per step that bend billboards (cube maps); default 8 */
    grass_io_t io;
    const struct grass_host_t *host; /* in-tree hosts: a resolved scene and terrain (grass_harness.h) */
} grass_desc_t;

/* The host's framebuffer and the textures attached to it (GL_RGBA8
 * colour, depth; MSAA ones with samples > 1). Without both textures (0:
 * renderbuffers) the grass takes the hardware path. Grass reads a
 * single-sample depth texture as it is and resolves a copy of any other. */
typedef struct grass_target_t {
    uint32_t fbo, color_texture, depth_texture;
    int width, height, samples;
} grass_target_t;

/* One collider of a step, in the order the host keeps from step to step
 * (the previous step's collider at the same index gives the sweep). A step
 * takes the first GRASS_MAX_COLLIDERS into its collide set (billboards'
 * cube maps, sweeps); the blades alone feel the rest, as sphere proxies
 * without a sweep, and grass_update warns through io.log once each time
 * the count past the limit changes. */
#define GRASS_MAX_COLLIDERS 128
typedef enum grass_shape_t {
    GRASS_SHAPE_SPHERE,  /* radius */
    GRASS_SHAPE_CAPSULE, /* radius, length between the end centres, along y */
    GRASS_SHAPE_BOX,     /* half_extents, axis-aligned */
    GRASS_SHAPE_SPHERES, /* spheres[sphere_count] in the world, e.g. a skinned character's proxies */
} grass_shape_t;
typedef struct grass_collider_t {
    grass_shape_t shape;
    float position[3]; /* the shape's centre; GRASS_SHAPE_SPHERES: its bounding sphere's */
    float radius, length, half_extents[3];
    const float (*spheres)[4]; /* xyz centre, w radius (m, world) */
    int sphere_count;
    float bound_radius; /* GRASS_SHAPE_SPHERES: of all its spheres about position */
    /* The object as the billboards' cube maps draw it: a vertex array with
     * vec3 position at attribute 0 and normal at 1, drawn with
     * glDrawElements(GL_TRIANGLES, index_count, index_type, 0) under model
     * (rigid, uniform scale; centre: the bounding sphere's in the model's
     * space). vao 0: the blades alone feel the collider. */
    uint32_t vao, index_type;
    int32_t index_count;
    float model[16], centre[3];
} grass_collider_t;

/* A new field and its GPU resources; NULL after one error line (bad scene
 * file, a field the GL cannot hold, a shader that does not build);
 * grass_last_error says which. */
grass_t *grass_make(const grass_desc_t *desc);
/* 0 after success, 1 out of memory or GL, 2 bad input: of the last
 * grass_make on this thread. */
int grass_last_error(void);
void grass_destroy(grass_t *g);
/* The library's version, "major.minor.patch". */
const char *grass_version(void);

/* One step of dt s ending at time t: the colliders move, the grass bends
 * and recovers. Steers by the views drawn since the previous step (the
 * union of their cameras; before any draw, the scene's camera). */
void grass_update(grass_t *g, const grass_collider_t *colliders, int count, float t, float dt);
/* Draws the ground and the grass into target after the host's opaque
 * objects (their depth occludes the grass). */
void grass_draw(grass_t *g, const grass_view_t *view, const grass_target_t *target);
/* grass_draw in two parts: the ground (terrain and sky) first, so that it
 * occludes the host's objects drawn next, then the grass over both. */
typedef enum grass_part_t { GRASS_PART_ALL = 0, GRASS_PART_GROUND = 1, GRASS_PART_GRASS = 2 } grass_part_t;
void grass_draw_part(grass_t *g, const grass_view_t *view, const grass_target_t *target, grass_part_t part);

/* Switches the mode or the rasterizer at run time, keeping the state. */
void grass_set_mode(grass_t *g, grass_mode_t mode);
void grass_set_raster(grass_t *g, bool compute);

typedef struct grass_stats_t {
    grass_mode_t mode;
    bool compute;         /* the compute rasterizer draws the grass */
    bool canopy;          /* the ground is shaded as grass where blades are thinned or end */
    float reach;          /* m from the camera within which colliders bend grass; 0: everywhere */
    double update_ms[3];  /* CPU wall ms of the last grass_update: billboards, sphere proxies, blades */
    double make_ms[3];    /* wall ms of grass_make: ground (and GI), billboards, blades or tiles */
    const char *lod_note; /* grass.lod_table: what was chosen and why; "" without one */
} grass_stats_t;
grass_stats_t grass_stats(const grass_t *g);

#endif

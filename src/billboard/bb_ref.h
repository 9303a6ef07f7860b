/* bb_ref: GL-free reference of the billboard collision model of Orthmann,
 * Rezk-Salama & Kolb 2009, "GPU-based Responsive Grass": the collision of a
 * refined billboard mesh with depth cube maps (the cube maps, inside test,
 * eq. 1-3, and push-out, eq. 4-5, are collide/collide_cube.h), spring
 * relaxation (eq. 6-7), recovery towards the wind pose (eq. 8) and the
 * procedural wind pose. shaders/common/bb.glsl mirrors every function here
 * line by line. */
#ifndef MEADOW_BB_REF_H
#define MEADOW_BB_REF_H

#include <cglm/cglm.h>
#include <stdbool.h>
#include <stdint.h>

#include "collide/collide_cube.h"

/* ---- billboard mesh ------------------------------------------------------
 * N columns x M rows, vertex (i,j) at index j*N + i, row j = 0 the roots
 * (fixed). rest holds the undeformed quad; spring rest lengths come from it. */
typedef struct bb_mesh_t {
    int n, m;
    vec3 *pos;   /* current positions, world space */
    vec3 *rest;  /* rest positions (the undeformed quad) */
} bb_mesh_t;

/* Quad of width x height centred on root_centre along `right`, rising along
 * `up` (both normalised here). n, m >= 2. Returns false on allocation failure. */
bool bb_mesh_init_quad(bb_mesh_t *mesh, const vec3 root_centre, const vec3 right,
                       const vec3 up, float width, float height, int n, int m);
void bb_mesh_free(bb_mesh_t *mesh);

/* Eq. 6-7: `iterations` Gauss-Seidel sweeps over, in this order, horizontal
 * structural springs (row by row), vertical structural springs (column by
 * column), then shear springs (both diagonals of each cell, "/" then "\").
 * A spring a-b with rest length l0 and current length l has correction
 * c = (l - l0)/l * (b - a): free ends move a += r/2 c, b -= r/2 c; if a is
 * a root only b moves, b -= r c (and vice versa). r = r1 structural, r2 shear. */
void bb_ref_relax_springs(bb_mesh_t *mesh, float r1, float r2, int iterations);
/* Bend limit (departure from the paper; issue 17), one Gauss-Seidel sweep:
 * along each column (bottom up), then along each row (left to right), a
 * joint a between segments b-a and a-v is kept from bending by more than
 * about acos(BB_REF_BEND_COS) (75 degrees): (v - a) . t >= BB_REF_BEND_COS
 * l0, t the unit direction b -> a (a root's rest column direction for row
 * 1), l0 the rest length a-v. A violated joint is projected along the
 * constraint's gradients (position-based dynamics, roots fixed), so the
 * segment below leans into the bend rather than the joint creasing. The
 * margin below 90 degrees absorbs what the push-out after it bends back
 * (docs/BILLBOARDS.md, bend limit). */
#define BB_REF_BEND_COS 0.25f
void bb_ref_bend_limit(bb_mesh_t *mesh);
/* Mean |l - l0| / l0 over all structural and shear springs. */
float bb_ref_spring_error(const bb_mesh_t *mesh);

typedef struct bb_collide_desc_t {
    float r1;       /* structural responsiveness, default 1.0 */
    float r2;       /* shear responsiveness, default 0.5 */
    int iterations; /* relaxation sweeps K, default 4 */
    /* Terrain height at (x, z), or NULL (no ground). Departure from the
     * paper: after each push-out every non-root vertex is raised to the
     * ground, since a push along a downward normal (a ball sunk into the
     * ground over the roots) would leave it under the terrain; a vertex so
     * raised back into an object then leaves it sideways (the push's
     * horizontal part, pen / |n_h|, at most 4 pen). GPU twin: the field's
     * height texture (shaders/billboard/bb_ground.glsl). */
    float (*ground)(const void *user, float x, float z);
    const void *ground_user;
    /* Swept collision (departure from the paper; issue 17): per cube, the
     * world translation from the object's current to its previous position
     * (the capsule the step swept), or NULL (default): the object where it
     * is. A vertex is tested against the object moved back along its sweep
     * to the point nearest the vertex (t = clamp((p - c).s / s.s, 0, 1), c
     * the cube centre in world space), so the step's whole path pushes, as
     * blade_ref's swept spheres. GPU twin: bb_push_mesh's sweep. */
    const float (*sweep)[3];
    /* The paper's collision as printed (the stability suite's paper
     * variant): the push-out of eq. 4-5 alone (no slide, no ground), then K
     * relaxation sweeps (eq. 6-7) with no bend limit and no push after
     * them. Default false. */
    bool paper;
} bb_collide_desc_t;
bb_collide_desc_t bb_collide_desc_defaults(const bb_collide_desc_t *desc);

/* Push every non-root vertex out of each cube (eq. 4-5), then K times: the
 * bend limit (bb_ref_bend_limit), one relaxation sweep (eq. 6-7), another
 * push-out. Departure from
 * the paper, which relaxes once after the push-out: re-projecting after each
 * sweep keeps springs from pulling vertices back inside the object. Second
 * departure: a pushed vertex slides, on the plane across the push through
 * its target, to its rest row length from the vertex below it, and that
 * point is pushed again (bb_ref.c bb_slide), so a column turns out of the
 * object instead of being shortened by it.
 * world_to_cube[k] maps world space into cube k's space. desc may be NULL. */
void bb_ref_collide(bb_mesh_t *mesh, const collide_cubemap_t *cubes, const mat4 *world_to_cube,
                    int count, const bb_collide_desc_t *desc);

/* Eq. 8: v <- (1 - t^3) w + t^3 v for every vertex, t = remaining recover
 * time / recover duration, clamped to [0,1]. */
void bb_ref_recover(bb_mesh_t *mesh, const vec3 *wind_pose, float t);

/* ---- procedural wind ------------------------------------------------------
 * For a vertex with rest position p, billboard root r (rest row-0 centre),
 * height fraction h = j/(M-1), wind direction d (xz, normalised):
 *   ph   = k * dot(r.xz, d)
 *   s    = 0.6 sin(ph - w t) + 0.3 sin(1.7 ph - 2.3 w t + 1.3)
 *        + 0.1 sin(2.9 ph - 5.1 w t + 0.7)
 *   bend = strength * h^2 * (0.4 + 0.6 s)
 *   out  = p + bend * (d.x, 0, d.y)
 * Only the upper vertices move (h = 0 at the roots); the displacement is
 * horizontal, so the vertical springs stretch slightly under strong wind. */
typedef struct bb_wind_desc_t {
    float dir[2];      /* xz direction, normalised here; default (1, 0) */
    float strength;    /* metres of tip displacement, default 0.1 */
    float omega;       /* angular frequency w (rad/s), default 1.5 */
    float wavenumber;  /* k (rad/m), default 0.4 */
} bb_wind_desc_t;
bb_wind_desc_t bb_wind_desc_defaults(const bb_wind_desc_t *desc);
/* The billboards' wind for the blades' wave field blade_wind_wave(dir_x,
 * dir_z, strength, wavelength, speed) (blade_ref.h): the same direction,
 * k = 2 pi / wavelength and w = 2 pi speed / wavelength, so both sway in
 * phase (the wave's crest, where the blades bend most, is where s peaks),
 * and 0.08 m of tip displacement per unit of strength (the blades' bend
 * under it: about 0.1 m on 0.5 m blades of stiffness 8-12). wavelength > 0. */
bb_wind_desc_t bb_wind_from_wave(float dir_x, float dir_z, float strength, float wavelength, float speed);

/* One vertex of the formula above (wind must be resolved by the defaults). */
void bb_ref_wind_vertex(const bb_wind_desc_t *wind, const vec3 rest, const vec3 root,
                        float h, float time, vec3 out);
/* Wind pose of the whole mesh into out[n*m]. desc may be NULL. */
void bb_ref_wind_pose(const bb_mesh_t *mesh, const bb_wind_desc_t *desc, float time, vec3 *out);

/* ---- stored billboard ------------------------------------------------------
 * One generated billboard (a point in the billboard buffer). Mirrors
 * struct bb_point in shaders/common/bb.glsl (std430, 64 bytes); used both as
 * an SSBO element and as a vertex buffer with the attribute layout listed
 * there. */
enum { BB_STATE_IDLE = 0, BB_STATE_COLLIDING = 1, BB_STATE_RECOVERING = 2 };

typedef struct bb_point_t {
    float position[3];   /* root centre, world space (y = terrain height)  offset 0 */
    float angle;         /* rotation of the quad about `growth`, radians       12 */
    float growth[3];     /* growth direction (unit), from the direction map    16 */
    float messiness;     /* 0..1 from the messiness map                        28 */
    float size[2];       /* width, height in metres                            32 */
    uint32_t layer;      /* clump texture array layer                          40 */
    uint32_t state;      /* BB_STATE_*                                         44 */
    float recover_time;  /* seconds of recovery left                           48 */
    uint32_t seed;       /* per-billboard hash                                 52 */
    uint32_t pad[2];     /*                                                    56 */
} bb_point_t;

#endif

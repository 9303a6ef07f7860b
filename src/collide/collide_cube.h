/* collide_cube: depth cube maps of collision objects, the representation of
 * Orthmann, Rezk-Salama & Kolb 2009 ("GPU-based Responsive Grass", sec. 5)
 * shared by both grass models: the billboards collide against them
 * (billboard/bb_ref.h adds the springs and recovery, eq. 6-8) and so can the
 * blades (blade/blade_ref.h, beyond both papers). Here: the cube map, its face table and texel
 * addressing, CPU rasterisation of analytic shapes, the nearest-texel
 * lookup, the inside test (eq. 1-3) and the push-out (eq. 4-5). GL-free;
 * shaders/common/bb.glsl mirrors the lookup, inside test and push-out
 * (collide_lookup_texel -> bb_lookup, collide_test_inside -> bb_inside,
 * collide_push_out -> bb_push_out) line by line. The texel layout both
 * sides share is written above collide_cubemap_t; the method and its
 * departures: docs/BILLBOARDS.md. */
#ifndef MEADOW_COLLIDE_CUBE_H
#define MEADOW_COLLIDE_CUBE_H

#include <cglm/cglm.h>
#include <stdbool.h>

enum {
    COLLIDE_FACE_PX,
    COLLIDE_FACE_NX,
    COLLIDE_FACE_PY,
    COLLIDE_FACE_NY,
    COLLIDE_FACE_PZ,
    COLLIDE_FACE_NZ,
    COLLIDE_FACE_COUNT
};

/* Depth cube map convention (shared with the GPU side).
 * A cube map surrounds an object's bounding cube [centre-half, centre+half]^3
 * given in the object's local ("cube") space. Face f (0..5 = +X,-X,+Y,-Y,+Z,-Z)
 * is the plane at centre + half*outward; its camera looks inward. Texel (i,j)
 * of face f (i along u, j along v, j = 0 at v = -half, i.e. GL's bottom row
 * when rendered with an orthographic camera whose right = u and up = v) has
 * its centre at face-local (u,v) = -half + (i+0.5, j+0.5) * 2*half/res.
 *
 *   face | outward | u  | v  | inward
 *   -----+---------+----+----+-------
 *   0 +X |   +X    | -Z | +Y |  -X
 *   1 -X |   -X    | +Z | +Y |  +X
 *   2 +Y |   +Y    | +X | -Z |  -Y
 *   3 -Y |   -Y    | +X | +Z |  +Y
 *   4 +Z |   +Z    | +X | +Y |  -Z
 *   5 -Z |   -Z    | -X | +Y |  +Z
 *   (u x v = outward for every face.)
 *
 * texels[((f*res + j)*res + i)*4 + k], k = 0: distance from the face plane
 * along `inward` to the first surface hit, k = 1..3: the object's outward
 * surface normal there (cube space). No hit: distance = 2*half (the far face;
 * chosen over +infinity so GPU float textures never hold inf), normal =
 * outward of the face. On the GPU this is a 2D array texture, layer = face.
 *
 * A point q (cube space) projects on face f to (u,v) = ((q-c).u, (q-c).v) and
 * to the projected depth d_f = (q-c).inward + half (0 on the face plane, 2*half
 * on the opposite face). Lookups are NEAREST texel (no bilinear filtering), so
 * the GPU side can use texelFetch and match bit for bit. */
typedef struct collide_cubemap_t {
    int res;        /* texels per face side */
    float *texels;  /* 6*res*res*4 floats: distance, nx, ny, nz */
    vec3 centre;    /* cube centre, cube space */
    float half;     /* half edge length */
} collide_cubemap_t;

/* Allocates the texels and clears every texel to "no hit". */
bool collide_init_cubemap(collide_cubemap_t *cube, int res, const vec3 centre, float half);
void collide_free_cubemap(collide_cubemap_t *cube);
/* Resets every texel to "no hit" (distance 2*half, normal = face outward). */
void collide_clear_cubemap(collide_cubemap_t *cube);
/* The table above: u, v and inward unit axes of face f. */
void collide_get_face_basis(int face, vec3 axis_u, vec3 axis_v, vec3 inward);
/* Cube-space centre of texel (i,j) on face f's plane (the ray origin). */
void collide_get_texel_origin(const collide_cubemap_t *cube, int face, int i, int j, vec3 out);

/* CPU rasterisation: one ray per texel centre from the face plane inward.
 * Each call depth-tests (keeps the nearer hit), so several calls build the
 * union of shapes (e.g. the capsules of a character proxy). A shape poking
 * out through a face plane gives distance 0 there, normal = face outward.
 * Shape parameters are in cube space. */
void collide_render_sphere(collide_cubemap_t *cube, const vec3 centre, float radius);
void collide_render_capsule(collide_cubemap_t *cube, const vec3 a, const vec3 b, float radius);
/* Axis-aligned box (cube space) given by centre and half extents. */
void collide_render_box(collide_cubemap_t *cube, const vec3 centre, const vec3 half_extents);

/* Nearest-texel lookup of q (cube space) on face f. Writes the stored texel
 * (distance, normal) to texel and returns the projected depth d_f of q. */
float collide_lookup_texel(const collide_cubemap_t *cube, int face, const vec3 q, vec4 texel);
/* Eq. 1-3: q is inside the object iff q lies in the cube and, on every face,
 * its projected depth exceeds the stored distance (d_f > D_f). */
bool collide_test_inside(const collide_cubemap_t *cube, const vec3 q);
/* Eq. 4-5: if q is inside, pick the face with the smallest penetration
 * p_f = d_f - D_f and move q along that texel's stored normal by p_f; else
 * return q unchanged. Returns true if q was moved. */
bool collide_push_out(const collide_cubemap_t *cube, const vec3 q, vec3 out);

/* A placed cube map (a "cube proxy"), 160 bytes, std430; mirrors `struct
 * BladeCube` in shaders/common/blade.glsl and bb_local.h's bb_object_gpu_t:
 *   w2c    world -> cube space (column-major), c2w its inverse
 *   cube   xyz cube centre (cube space), w half edge length
 *   sphere xyz world centre, w radius of a sphere holding the whole cube
 *          (broad phase: points farther are not tested); w <= 0: the
 *          object is skipped
 * Object k's faces are layers 6k .. 6k+5 of a cube texture (CPU: cubes[k]). */
typedef struct collide_cube_proxy_t {
    float w2c[16];
    float c2w[16];
    float cube[4];
    float sphere[4];
} collide_cube_proxy_t;

/* The proxy of a cube map of centre `centre` and half edge `half` (cube
 * space) placed by `model` (cube -> world, column-major, rigid with uniform
 * scale): w2c = model^-1, sphere = model * centre with radius
 * half * sqrt(3) * (largest column norm of model's 3x3). */
void collide_make_cube_proxy(const float model[16], const float centre[3], float half,
                             collide_cube_proxy_t *out);

#endif

/* collide_set: the colliders of one simulation step. The app builds one set
 * per step from the scene's colliders and the characters (collide_begin_set,
 * collide_add_object, then the sphere and cube proxies) and every grass
 * system takes it: the billboard field its objects (bb_field_update), the
 * blades its spheres and cube proxies (blade_gpu_update, blade_ref_step),
 * the tiles its spheres (blade_tiles_update). GL-free: GL object names are
 * carried as plain integers for the GL systems, never used here. A zeroed
 * set is empty. */
#ifndef MEADOW_COLLIDE_SET_H
#define MEADOW_COLLIDE_SET_H

#include <stdint.h>

#include "collide/collide_cube.h"

#define COLLIDE_MAX_OBJECTS 128 /* colliders and characters per step */
/* Sphere proxies per step: 16 characters (a scene's most) of 256 each, or
 * one capsule 4095 radii long; admission (admit.h) refuses a scene that
 * packs more. The blade physics' buffers grow to the step's count
 * (blade_gpu_update), so a set this full costs only its 128 KiB here. */
#define COLLIDE_MAX_SPHERES 4096
#define COLLIDE_MAX_CUBES 16 /* cube proxies per step */

/* One collider or character this step. The builder fills model, centre,
 * radius and the mesh; collide_add_object fills position, prev_position
 * and velocity. */
typedef struct collide_object_t {
    float model[16];        /* object -> world (column-major), rigid with uniform scale */
    float centre[3];        /* bounding sphere in object space: centre and radius; */
    float radius;           /* a cube map of the object covers centre +- radius */
    float position[3];      /* world centre of the bounding sphere (model * centre) */
    float prev_position[3]; /* position at the previous step (swept tests); = position on
                               the first step and after a step with dt <= 0 */
    float velocity[3];      /* (position - prev_position) / dt; 0 when dt <= 0 */
    /* Mesh drawn into GPU cube maps: a GL vertex array with attribute 0 =
     * vec3 position and 1 = vec3 normal (object space), drawn with
     * glDrawElements(GL_TRIANGLES, index_count, index_type, 0). vao 0: no
     * mesh (a CPU cube map stands in, bb_field_set_cube). */
    uint32_t vao;
    int32_t index_count;
    uint32_t index_type;
} collide_object_t;

/* A sphere proxy, 32 bytes, std430: centre_radius xyz centre, w radius
 * (world); sweep xyz = previous centre - centre (this step's travel,
 * backwards), w 0. A zero sweep (resting, first step, or left zero by a
 * `{{x, y, z, r}}` initialiser) is the plain sphere; otherwise the proxy is
 * the capsule swept by the sphere during the step (swept collision, see
 * blade_ref.h). Mirrors `struct BladeSphere` in shaders/common/blade.glsl. */
typedef struct collide_sphere_t {
    float centre_radius[4];
    float sweep[4];
} collide_sphere_t;

typedef struct collide_set_t {
    collide_object_t objects[COLLIDE_MAX_OBJECTS]; /* colliders, then characters */
    int object_count;
    int prev_count; /* object_count of the previous step (collide_begin_set) */
    /* Sphere proxies of the objects for the blade physics (colliders by
     * collide_pack_spheres, characters by their capsules). */
    collide_sphere_t spheres[COLLIDE_MAX_SPHERES];
    int sphere_count;
    /* Cube proxies for the blade physics: cubes[k]'s faces are layers
     * 6k .. 6k+5 of cube_texture (RGBA32F GL_TEXTURE_2D_ARRAY of cube_res^2
     * faces; not owned) on the GPU and cube_maps[k] on the CPU (the
     * reference; NULL when only the GPU takes the set). */
    collide_cube_proxy_t cubes[COLLIDE_MAX_CUBES];
    int cube_count;
    uint32_t cube_texture;
    int cube_res;
    const collide_cubemap_t *cube_maps;
} collide_set_t;

/* Starts the next step: empties the set, keeping this step's object
 * positions for collide_add_object's prev_position. */
void collide_begin_set(collide_set_t *set);
/* Appends obj (model, centre, radius, mesh) and fills its position,
 * prev_position (the previous step's object at the same index) and
 * velocity over dt. Returns the stored object, NULL when the set holds
 * COLLIDE_MAX_OBJECTS already (the caller reports it). */
collide_object_t *collide_add_object(collide_set_t *set, const collide_object_t *obj, float dt);

#endif

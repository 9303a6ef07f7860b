/* grass_character: a skinned, animated character that walks waypoints over
 * a field's ground, for a host with none of its own: the library's assimp
 * loader, GPU skinning and proxy spheres (src/character). Each step hand
 * grass_character_collider's result to grass_update with the host's other
 * colliders; draw it among the host's opaque objects. Calls on the thread
 * of the field's GL context. docs/LIBRARY.md. */
#ifndef MEADOW_GRASS_CHARACTER_H
#define MEADOW_GRASS_CHARACTER_H

#include "grass/grass.h"

typedef struct grass_character_t grass_character_t;

/* Zero means default. */
typedef struct grass_character_desc_t {
    const char *model; /* a file assimp reads (glTF, FBX, ...); a relative path is also looked for
                          in the installed share/meadow (models/humanoid.gltf); required */
    const char *clip;  /* clip name; default the first clip */
    float height;      /* m the character is fitted to; default the file's */
    float speed;       /* m/s along the waypoints; default 1.2 */
    const float (*waypoints)[2]; /* (x, z) on the ground; none: it stands at the origin */
    int waypoint_count;
    bool loop; /* from the last waypoint back to the first */
} grass_character_desc_t;

/* A character on g's ground, in g's GL state; NULL after one error line
 * (a model that cannot be read, a clip it lacks). */
grass_character_t *grass_character_make(grass_t *g, const grass_character_desc_t *desc);
/* Walks and poses it at time t, dt after the previous step. */
void grass_character_update(grass_character_t *c, float t, float dt);
/* It as this step's collider: its proxy spheres and its skinned mesh
 * (valid until its next update). */
grass_collider_t grass_character_collider(const grass_character_t *c);
/* Lit draw into the bound framebuffer, with the host's depth test. */
void grass_character_draw(const grass_character_t *c, const grass_view_t *view);
void grass_character_destroy(grass_character_t *c);

#endif

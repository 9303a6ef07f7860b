/* character: the GPU half of the character module. Skinned, animated
 * characters (models loaded with character_load) walk along the scene's
 * waypoint paths over the terrain; linear blend skinning runs in a compute
 * shader (shaders/character/skin.comp) into a vertex buffer that the lit
 * draw (shaders/character/character.vert/.frag) and other systems (the
 * billboard collision depth cube maps of Orthmann et al. 2009) read through one
 * VAO. Each frame also produces collision proxies: spheres along fitted
 * capsules for the sphere collisions of the blade physics (Jahrmann &
 * Wimmer 2017) and {vao, model matrix, bounding sphere} objects for the
 * billboards. The clip plays at the rate that matches the walking speed
 * (character_clip_stride); see docs/CHARACTERS.md "GPU skinning and walking".
 */
#ifndef MEADOW_CHARACTER_H
#define MEADOW_CHARACTER_H

#include <stdbool.h>
#include <stdint.h>

#include "character/character_import.h"
#include "character/character_load.h"
#include "character/character_ref.h"
#include "gfx/gfx.h"
#include "scene/scene.h"
#include "terrain/terrain.h"

#define CHARACTER_DEFAULT_CAPSULES 16
#define CHARACTER_MAX_FEET 8

/* A skinned object as the billboard module consumes it: draw
 * glDrawElements(GL_TRIANGLES, index_count, index_type, 0) with `vao`
 * (attribute 0 = vec3 model-space position, attribute 1 = vec3 normal) and
 * `model` (column-major, world from model). centre/radius: world-space
 * bounding sphere of the skinned mesh this frame. */
typedef struct character_object_t {
    GLuint vao;
    GLsizei index_count;
    GLenum index_type;
    float model[16];
    float centre[3];
    float radius;
} character_object_t;

/* Skinned vertex written by skin.comp (std430, 32 bytes): model space. */
typedef struct character_skinned_vertex_t {
    float pos[4];    /* xyz, w = 1 */
    float normal[4]; /* xyz unit, w = 0 */
} character_skinned_vertex_t;

/* Natural stride of a clip, estimated from the animation (GL-free).
 * Feet: bones that dominate at least one vertex, have no children, and whose
 * bind-pose origin lies in the lowest quarter of the mesh's height. Each
 * foot's bone origin is sampled at CHARACTER_STRIDE_SAMPLES times over one
 * loop in model space; its ground-contact phase is the contiguous run of
 * samples around its lowest sample that stay within 25% of its height range
 * above that lowest point. The natural speed is the mean backward (-Z:
 * models face +Z) velocity of the feet during contact: the sum over feet of
 * -(z_end - z_begin) divided by the sum of the contact durations. Negative
 * means the clip walks backwards in model space (stance feet move forward);
 * played in reverse it walks forward. */
#define CHARACTER_STRIDE_SAMPLES 256
typedef struct character_stride_t {
    int foot_count;
    int feet[CHARACTER_MAX_FEET];
    /* contact phase of each foot as a fraction of the clip, begin in [0, 1),
     * end in [begin, begin + 1] (past 1 wraps into the next loop) */
    float contact_begin[CHARACTER_MAX_FEET], contact_end[CHARACTER_MAX_FEET];
    float natural_speed;                 /* model units per clip second, signed; 0 = no stride */
    float contact_motion[2];             /* sum over feet of the (x, z) moved during contact (units) */
    float contact_time;                  /* sum of the contact durations (s) */
} character_stride_t;

void character_clip_stride(const character_model_t *model, int clip, character_stride_t *out);

/* One model file on the GPU, shared by every instance that uses it. */
typedef struct character_asset_t {
    char path[1024];
    character_import_desc_t import_desc; /* assets are shared by path and import */
    character_import_t import;           /* what character_import applied */
    character_model_t model;
    gfx_buffer_t vertices; /* character_vertex_t array: SSBO for skinning, uv source */
    gfx_buffer_t indices;  /* uint32 triangles */
    gfx_texture_t texture; /* id 0 when the model has none */
    float (*bone_spheres)[4]; /* per bone: centre (bind model space) + radius of
                                 its influenced vertices; radius < 0 if none */
} character_asset_t;

/* One walking character. Everything is in world space unless noted. */
typedef struct character_instance_t {
    scene_character_t desc; /* resolved copy; model/clip overrides applied */
    int asset;              /* index into the set's assets */
    int clip;
    character_stride_t stride;
    float rate;       /* clip seconds per second of walking at desc.speed */
    float clip_time;  /* this frame (signed, unwrapped) */
    float position[3];
    float dir[2];     /* walking direction (x, z), unit */
    float model[16];  /* world from model: T(position) Ry(yaw) S(scale) */
    character_pose_t pose;
    gfx_buffer_t bones;   /* pose.skin, bone_count mat4 */
    gfx_buffer_t skinned; /* character_skinned_vertex_t per vertex */
    character_vertex_t *morphed;  /* models with morph targets: the bind vertices */
    gfx_buffer_t morph_vertices;  /* with this pose's weights (character_morph_apply), skin.comp's input */
    GLuint vao;
    GLsizei index_count;
    int capsule_count;
    character_capsule_t *capsules; /* fitted at the bind pose, follow pose.global */
    int sphere_count;
    int *capsule_first_sphere;     /* capsule_count + 1 offsets into spheres */
    float (*spheres)[4];           /* this frame's proxies (swept, see update) */
    float (*sphere_now)[4];        /* unswept spheres at this frame's pose */
    bool have_previous;
    float centre[3], radius;       /* bounding sphere */
    float centre_model[3];         /* its centre in model space at the last pose */
    bool posed;                    /* posed (and skinned) by the last update */
} character_instance_t;

/* Zero means default. */
typedef struct character_set_desc_t {
    const scene_character_t *characters; /* resolved scene entries (scene_desc_defaults) */
    int count;                           /* any number; 0 with model_override makes one */
    const terrain_mesh_t *terrain;       /* ground; NULL = flat ground at y = 0 */
    int capsules;                        /* capsules per character; default 16 */
    const char *model_override;          /* --character PATH: replaces every model */
    const char *clip_override;           /* --clip SPEC: name, index or "A:B" frames */
    float height_override;               /* --character-height M: every character's height; 0 = none */
} character_set_desc_t;

character_set_desc_t character_set_desc_defaults(const character_set_desc_t *d);

typedef struct character_set_t {
    character_asset_t *assets;
    int asset_count;
    character_instance_t *items;
    int count;
    const terrain_mesh_t *terrain;
    int capsules;
    gfx_program_t skin_prog, draw_prog;
    float view_camera[3]; /* character_set_view */
    float lod_distance;   /* 0: every character posed at every update */
    uint64_t updates;     /* character_set_update calls so far */
} character_set_t;

/* Loads every distinct model once, creates GPU buffers, fits capsules and
 * estimates strides, then places everyone at time 0. A missing or bad model
 * file or an unknown clip: one error line, everything released, false. */
bool character_set_make(character_set_t *set, const character_set_desc_t *desc);
/* Walks, animates, skins on the GPU (timer "character.skin") and rebuilds
 * the proxies. dt is the step since the previous update (for the swept
 * spheres); dt <= 0 resets the sweep. */
void character_set_update(character_set_t *set, float time, float dt);
/* Animation level of detail for the updates after this call: a character
 * whose root is more than lod_distance m from `camera` horizontally (in
 * x and z, as the grass's reaches are) is posed and
 * skinned only every character_pose_step-th update (2 up to twice the
 * distance, one more per lod_distance, at most 8), staggered over the
 * characters; its place, model matrix and bounding sphere follow its walk
 * at every update, drawn in its last pose (character_set_make's first
 * update poses all; counter character.posed). Its proxy spheres stay at that
 * pose and the next pose does not sweep from them, so lod_distance must
 * exceed every reach in which the proxies or the cube maps are used.
 * lod_distance <= 0 (the default): every character at every update. */
void character_set_view(character_set_t *set, const float camera[3], float lod_distance);
/* Lit draw into the bound framebuffer (timer "character.draw"). */
void character_set_draw(const character_set_t *set, const float viewproj[16], const float camera[3],
                        const float sun[3]);
void character_set_destroy(character_set_t *set);

/* Blade proxies of one character: spheres (xyz centre, radius) compatible
 * with blade_sphere_t. Writes at most max and returns the number needed;
 * every call that needs more than max logs a warning and adds what it left
 * out to the count "character.spheres_dropped" (gfx_count_add). */
int character_proxy_spheres(const character_instance_t *inst, float (*out)[4], int max);
/* The same for every character of the set, concatenated. */
int character_set_spheres(const character_set_t *set, float (*out)[4], int max);
/* The same for the characters whose bounding sphere comes within `reach`
 * of centre horizontally (the open world's tile window; reach <= 0 or
 * centre NULL: every character). */
int character_set_spheres_near(const character_set_t *set, const float centre[3], float reach, float (*out)[4],
                               int max);
/* One line per character for summary.txt: model, fitted height (m, scale
 * included) and scale (metres per file unit times the scene's scale), and
 * where units and axes came from. Returns the characters written. */
int character_set_describe(const character_set_t *set, char *buf, size_t size);
/* Characters in the set. */
int character_set_count(const character_set_t *set);
/* Billboard proxy of one character. */
void character_bb_object(const character_instance_t *inst, character_object_t *out);
/* Every character's object; writes at most max, returns set->count (logs
 * when max is smaller). */
int character_set_objects(const character_set_t *set, character_object_t *out, int max);

#endif

/* test_character_thirdparty: third-party rigged models from Debian packages
 * (.ci/packages installs them; nothing is committed) loaded as a user would,
 * with no flags: character_load + character_import with a zero desc. For
 * each: the fitted height lies in the range expected of the figure, and
 * while it walks a path (character_walk_place, the walk clip sampled and
 * skinned on the CPU with character_ref) its face looks along the walking
 * direction, its head is up and its feet are on the ground.
 *
 * The face is found independently of the import's conventions: the
 * triangles whose texture coordinates lie in the skin's face region (the
 * Minetest skin layout puts the head's front at u 8..16/64, v 8..16/32),
 * seen from the centre of the vertices of the bone that carries them.
 * A missing package is a failure that names it, never a skip. */
#include "character/character_import.h"
#include "character/character_walk.h"
#include "core/core.h"
#include "test.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef struct thirdparty_t {
    const char *package, *path, *walk; /* walk: the clip spec of the walk cycle */
    float face_uv[4];                  /* u0, u1, v0, v1 of the face (v from the top) */
    float height_lo, height_hi;        /* expected fitted height (m) */
} thirdparty_t;

static const thirdparty_t models[] = {
    {"minetest-data", "/usr/share/games/minetest/games/minetest_game/mods/player_api/models/character.b3d",
     "168:187", {0.125f, 0.25f, 0.25f, 0.5f}, 1.6f, 2.0f},
    {"minetest-mod-3d-armor", "/usr/share/games/minetest/mods/3d_armor/3d_armor/models/3d_armor_character.b3d",
     "168:187", {0.125f, 0.25f, 0.25f, 0.5f}, 1.6f, 2.0f},
    /* a maid robot, 1.5 units: taken as metres */
    {"minetest-mod-maidroid", "/usr/share/games/minetest/mods/maidroid/maidroid/models/maidroid.b3d", "168:187",
     {0.6f, 0.8f, 0.82f, 1.0f}, 1.3f, 1.8f},
};

static int dominant(const character_vertex_t *v)
{
    int best = 0;
    for (int k = 1; k < CHARACTER_MAX_INFLUENCES; k++)
        if (v->weights[k] > v->weights[best]) best = k;
    return v->joints[best];
}

/* Marks the face's vertices and the vertices of the bone that carries them
 * (the head). Returns the face vertex count. */
static int find_face(const character_model_t *m, const float uv[4], bool *face, bool *head)
{
    int n = 0, bone = -1;
    for (int t = 0; t + 2 < m->index_count; t += 3) {
        float u = 0.0f, v = 0.0f;
        for (int k = 0; k < 3; k++) {
            u += m->vertices[m->indices[t + k]].uv[0] / 3.0f;
            v += (1.0f - m->vertices[m->indices[t + k]].uv[1]) / 3.0f;
        }
        if (u < uv[0] || u > uv[1] || v < uv[2] || v > uv[3]) continue;
        for (int k = 0; k < 3; k++) {
            n += !face[m->indices[t + k]];
            face[m->indices[t + k]] = true;
            bone = dominant(&m->vertices[m->indices[t + k]]);
        }
    }
    for (int v = 0; v < m->vertex_count; v++) head[v] = bone >= 0 && dominant(&m->vertices[v]) == bone;
    return n;
}

/* Walks the model along +X (and then +Z) and checks the face, head and
 * feet at a few times of the walk. */
static void check_walk(const thirdparty_t *tp, character_model_t *m, float height)
{
    bool *face = calloc((size_t)m->vertex_count, sizeof *face), *head = calloc((size_t)m->vertex_count, sizeof *head);
    float *p = malloc(sizeof(float) * 3 * (size_t)m->vertex_count);
    int clip = character_clip_find(m, tp->walk);
    character_pose_t pose;
    CHECK_MSG(clip >= 0, "%s: no walk clip %s", tp->path, tp->walk);
    if (!face || !head || !p || clip < 0 || !character_pose_init(&pose, m)) goto done;
    CHECK_MSG(find_face(m, tp->face_uv, face, head) >= 3, "%s: no face triangles in the skin's face region", tp->path);
    static const float paths[2][2][2] = {{{0, 0}, {20, 0}}, {{0, 0}, {0, 20}}};
    for (int w = 0; w < 2; w++) {
        scene_character_t c = {.speed = 1.2f, .scale = 1.0f, .waypoint_count = 2};
        memcpy(c.waypoints, paths[w], sizeof paths[w]);
        for (int i = 0; i < 8; i++) {
            float clip_time, pos[3], dir[2], model[16];
            character_walk_place(&c, NULL, 1.0f, 0.5f + 0.37f * (float)i, &clip_time, pos, dir, model);
            character_sample_clip(m, clip, clip_time, true, &pose);
            character_pose_globals(m, &pose);
            character_skin_cpu(m, &pose, p, NULL);
            double fc[3] = {0}, hc[3] = {0}, nf = 0, nh = 0, low = DBL_MAX;
            for (int v = 0; v < m->vertex_count; v++) {
                float q[3];
                character_mat4_point(model, p + 3 * v, q);
                low = fmin(low, q[1]);
                for (int k = 0; k < 3; k++) fc[k] += face[v] ? q[k] : 0.0, hc[k] += head[v] ? q[k] : 0.0;
                nf += face[v], nh += head[v];
            }
            double look[2] = {fc[0] / nf - hc[0] / nh, fc[2] / nf - hc[2] / nh};
            double len = sqrt(look[0] * look[0] + look[1] * look[1]);
            double cosine = len > 0 ? (look[0] * dir[0] + look[1] * dir[1]) / len : -1.0;
            CHECK_MSG(cosine > 0.9, "%s walking (%g, %g): the face looks (%g, %g), cos %g", tp->path, (double)dir[0],
                      (double)dir[1], look[0], look[1], cosine);
            CHECK_MSG(hc[1] / nh > 0.7 * height, "%s: head centre at %g m of %g m", tp->path, hc[1] / nh,
                      (double)height);
            CHECK_MSG(fabs(low) < 0.08 * height, "%s: lowest point %g m off the ground", tp->path, low);
        }
    }
    character_pose_free(&pose);
done:
    free(face), free(head), free(p);
}

static void check_model(const thirdparty_t *tp)
{
    if (access(tp->path, R_OK) != 0) {
        CHECK_MSG(false, "%s is missing: install the Debian package %s (it is listed in .ci/packages: "
                         "xargs -a .ci/packages apt-get install -y --no-install-recommends)", tp->path, tp->package);
        return;
    }
    character_model_t m;
    character_import_t o;
    char err[512] = "";
    if (!character_load(&m, tp->path, err, sizeof err)) {
        CHECK_MSG(false, "%s: %s", tp->path, err);
        return;
    }
    bool ok = character_import(&m, tp->path, &(character_import_desc_t){0}, &o, err, sizeof err);
    CHECK_MSG(ok, "%s: %s", tp->path, err);
    CHECK_MSG(o.height >= tp->height_lo && o.height <= tp->height_hi, "%s: fitted height %g m, expected %g-%g m",
              tp->path, (double)o.height, (double)tp->height_lo, (double)tp->height_hi);
    printf("%s (%s): %g units -> %.3f m (scale %g, %s), up %s (%s), forward %s (%s)\n", tp->path, tp->package,
           (double)o.file_height, (double)o.height, (double)o.scale, o.scale_from, character_axis_name(o.up), o.up_from,
           character_axis_name(o.forward), o.forward_from);
    if (ok) check_walk(tp, &m, o.height);
    character_model_free(&m);
}

int main(void)
{
    core_log_set_quiet(true);
    for (size_t i = 0; i < sizeof models / sizeof models[0]; i++) check_model(&models[i]);
    TEST_END();
}

/* test_character_load: the assimp loader's repairs and fallbacks: the
 * deliberately inconsistent fixture tests/data/models/broken.gltf (written by
 * meadow_gen_models), the morph and clip fixture tests/data/models/clips.gltf
 * (morph targets through assimp, a clip without duration), rigid OBJ
 * objects checked against their analytic surfaces, a file without
 * vertices, missing/present textures. */
#include "character/character_ref.h"
#include "core/core.h"
#include "test.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979

static const char *out_dir(void)
{
    const char *d = getenv("MEADOW_TEST_OUT");
    return d ? d : "/tmp/meadow-test_character_load";
}

static void write_text(const char *path, const char *text)
{
    CHECK(core_fs_write_atomic(path, text, strlen(text)));
}

static void test_broken_fixture(void)
{
    char path[1024], err[256];
    CHECK(core_fs_resolve("tests/data/models/broken.gltf", path, sizeof path));
    character_model_t m;
    int warns = core_log_warn_count();
    CHECK(character_load(&m, path, err, sizeof err));
    /* zero-weight vertex, NaN key, zero quaternion, negative time, unsorted */
    CHECK_MSG(core_log_warn_count() - warns >= 5, "warnings=%d", core_log_warn_count() - warns);
    CHECK(!m.rigid && m.clip_count == 1 && m.vertex_count == 4 && m.index_count == 6);
    int root = character_bone_find(&m, "root"), arm = character_bone_find(&m, "arm");
    int quad = character_bone_find(&m, "quad");
    CHECK(root >= 0 && arm > root && quad >= 0);
    if (root < 0 || arm < 0 || quad < 0 || m.clip_count != 1) {
        if (m.bone_count) character_model_free(&m);
        return;
    }
    CHECK(m.bones[arm].parent == root);
    CHECK(character_clip_find(&m, "bend") == 0);
    const character_track_t *rt = &m.clips[0].channels[arm].rot;
    CHECK(rt->count == 3);
    for (int i = 1; i < rt->count; i++) CHECK(rt->keys[i].time > rt->keys[i - 1].time);
    const character_track_t *tt = &m.clips[0].channels[root].pos;
    CHECK(tt->count == 2 && tt->keys[0].time == 0.0f);
    CHECK_NEAR(m.clips[0].duration, 2.0, 1e-6);
    /* keys after repair: rotation 0 -> 90 -> 180 deg about Z at 0, 0.5, 1 s;
     * root translation (0,0,0) at 0 s -> (0,2,0) at 2 s */
    character_pose_t pose;
    CHECK(character_pose_init(&pose, &m));
    character_sample_clip(&m, 0, 0.25f, false, &pose);
    CHECK_NEAR(2.0 * atan2(pose.r[arm][2], pose.r[arm][3]) * 180.0 / PI, 45.0, 1e-3);
    character_sample_clip(&m, 0, 1.0f, false, &pose);
    CHECK_NEAR(pose.t[root][1], 1.0, 1e-5);
    /* the zero-weight vertex (0,1,0) is bound rigidly to its mesh node */
    bool found = false;
    for (int v = 0; v < m.vertex_count; v++) {
        const character_vertex_t *vx = &m.vertices[v];
        float s = vx->weights[0] + vx->weights[1] + vx->weights[2] + vx->weights[3];
        CHECK_NEAR(s, 1.0, 1e-6);
        if (fabsf(vx->pos[0]) < 1e-6f && fabsf(vx->pos[1] - 1.0f) < 1e-6f) {
            found = true;
            CHECK(vx->joints[0] == quad && vx->weights[0] == 1.0f);
        }
    }
    CHECK(found);
    /* at bind, skinning reproduces the vertices */
    character_pose_bind(&m, &pose);
    character_pose_globals(&m, &pose);
    float p[12];
    character_skin_cpu(&m, &pose, p, NULL);
    for (int v = 0; v < 4; v++)
        for (int k = 0; k < 3; k++) CHECK_NEAR(p[3 * v + k], m.vertices[v].pos[k], 1e-6);
    character_pose_free(&pose);
    character_model_free(&m);
}

/* The skinned box's extent along x and y (width, height). */
static void extent_xy(const float *p, int n, float *w, float *h)
{
    float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
    for (int v = 0; v < n; v++)
        for (int k = 0; k < 2; k++) lo[k] = fminf(lo[k], p[3 * v + k]), hi[k] = fmaxf(hi[k], p[3 * v + k]);
    *w = hi[0] - lo[0], *h = hi[1] - lo[1];
}

/* tests/data/models/clips.gltf: a 1 x 1 quad whose morph targets lift the
 * top edge (target 0) and move the right edge (target 1) by 0.5; clip 0
 * "pose" has no duration, clip 1 "grow" weighs (0,0) -> (1,0) -> (0,1) over
 * 2 s, through assimp's aiAnimMesh and aiMeshMorphAnim. */
static void test_clips_fixture(void)
{
    char path[1024], err[256];
    CHECK(core_fs_resolve("tests/data/models/clips.gltf", path, sizeof path));
    character_model_t m;
    CHECK(character_load(&m, path, err, sizeof err));
    CHECK(!m.rigid && m.vertex_count == 4 && m.morph_count == 2 && m.clip_count == 2);
    if (m.morph_count != 2 || m.clip_count != 2 || m.vertex_count != 4) {
        if (m.bone_count) character_model_free(&m);
        return;
    }
    CHECK(!strcmp(m.clips[0].name, "pose") && m.clips[0].still && !m.clips[1].still);
    CHECK(character_clip_playable(&m, 0) == 1 && character_clip_playable(&m, 1) == 1);
    CHECK(m.morphs[0].target == 0 && m.morphs[1].target == 1 && m.morphs[0].max_weight == 1.0f);
    CHECK(m.clips[1].morph_count == 2 && m.clips[1].morph[0].count == 3 && m.clips[1].morph[1].count == 3);
    CHECK_NEAR(m.clips[1].duration, 2.0, 1e-6);
    character_pose_t pose;
    CHECK(character_pose_init(&pose, &m));
    float p[12], w, h;
    /* t (s), weights, width, height */
    const float want[4][5] = {{0, 0, 0, 1, 1}, {0.5f, 0.5f, 0, 1, 1.25f}, {1, 1, 0, 1, 1.5f}, {1.5f, 0.5f, 0.5f, 1.25f, 1.25f}};
    for (int i = 0; i < 4; i++) {
        character_sample_clip(&m, 1, want[i][0], false, &pose);
        character_pose_globals(&m, &pose);
        character_skin_cpu(&m, &pose, p, NULL);
        extent_xy(p, 4, &w, &h);
        CHECK_NEAR(pose.morph[0], want[i][1], 1e-6);
        CHECK_NEAR(pose.morph[1], want[i][2], 1e-6);
        CHECK_NEAR(w, want[i][3], 1e-6);
        CHECK_NEAR(h, want[i][4], 1e-6);
    }
    character_pose_free(&pose);
    character_model_free(&m);
}

static void test_rigid_objects(void)
{
    char path[1024], err[256];
    character_model_t m;
    CHECK(core_fs_resolve("models/torus.obj", path, sizeof path));
    CHECK(character_load(&m, path, err, sizeof err));
    CHECK(m.rigid && m.bone_count == 1 && m.clip_count == 0 && m.bones[0].parent == -1);
    CHECK(m.vertex_count > 500 && m.index_count > 3000 && m.index_count % 3 == 0);
    /* every vertex lies on the torus: distance from the major circle (radius
     * 2 in the XZ plane) equals the minor radius 0.8; normals point away */
    double worst = 0.0;
    for (int v = 0; v < m.vertex_count; v++) {
        const float *q = m.vertices[v].pos;
        double rho = sqrt(q[0] * q[0] + q[2] * q[2]);
        double d = sqrt((rho - 2.0) * (rho - 2.0) + q[1] * q[1]);
        worst = fmax(worst, fabs(d - 0.8));
        double cx = q[0] * 2.0 / rho, cz = q[2] * 2.0 / rho;
        const float *n = m.vertices[v].normal;
        double dot = (n[0] * (q[0] - cx) + n[1] * q[1] + n[2] * (q[2] - cz)) / 0.8;
        CHECK(dot > 0.99);
        CHECK(m.vertices[v].weights[0] == 1.0f && m.vertices[v].joints[0] == 0);
    }
    CHECK_MSG(worst < 1e-4, "torus surface error %g", worst);
    for (int i = 0; i < m.index_count; i++) CHECK(m.indices[i] < (uint32_t)m.vertex_count);
    character_model_free(&m);

    CHECK(core_fs_resolve("models/sphere.obj", path, sizeof path));
    CHECK(character_load(&m, path, err, sizeof err));
    CHECK(m.rigid && m.bone_count == 1);
    worst = 0.0;
    for (int v = 0; v < m.vertex_count; v++) {
        const float *q = m.vertices[v].pos;
        worst = fmax(worst, fabs(sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) - 2.0));
    }
    CHECK_MSG(worst < 1e-4, "sphere surface error %g", worst);
    character_model_free(&m);
}

static void test_errors_and_textures(void)
{
    char dir[1024], path[1100], err[256] = "";
    snprintf(dir, sizeof dir, "%s", out_dir());
    CHECK(core_fs_mkdirs(dir));
    character_model_t m;

    /* vertices but no faces: a clear error */
    snprintf(path, sizeof path, "%s/empty.obj", dir);
    write_text(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    int errors = core_log_error_count();
    CHECK(!character_load(&m, path, err, sizeof err));
    CHECK(core_log_error_count() == errors + 1);
    CHECK_MSG(strstr(err, "empty (3 vertices, 0 faces)") != NULL, "err='%s'", err);

    /* missing file */
    snprintf(path, sizeof path, "%s/does_not_exist.gltf", dir);
    err[0] = 0;
    CHECK(!character_load(&m, path, err, sizeof err));
    CHECK(err[0] != 0);

    /* missing texture: warning, plain colour from Kd */
    snprintf(path, sizeof path, "%s/tex_missing.mtl", dir);
    write_text(path, "newmtl red\nKd 0.9 0.1 0.2\nmap_Kd missing.png\n");
    snprintf(path, sizeof path, "%s/tex_missing.obj", dir);
    write_text(path, "mtllib tex_missing.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                     "usemtl red\nf 1/1 2/2 3/3\n");
    int warns = core_log_warn_count();
    CHECK(character_load(&m, path, err, sizeof err));
    CHECK(core_log_warn_count() > warns);
    CHECK(m.texture_path[0] == 0);
    CHECK_NEAR(m.base_color[0], 0.9, 1e-6); CHECK_NEAR(m.base_color[1], 0.1, 1e-6);
    CHECK(m.rigid && m.vertex_count == 3 && m.index_count == 3);
    character_model_free(&m);

    /* present texture: path resolved next to the model */
    core_image_t img;
    CHECK(core_image_alloc(&img, 2, 2, 4));
    memset(img.px, 200, 16);
    snprintf(path, sizeof path, "%s/present.png", dir);
    CHECK(core_image_write_png(&img, path));
    core_image_free(&img);
    snprintf(path, sizeof path, "%s/tex_present.mtl", dir);
    write_text(path, "newmtl t\nKd 1 1 1\nmap_Kd present.png\n");
    snprintf(path, sizeof path, "%s/tex_present.obj", dir);
    write_text(path, "mtllib tex_present.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n"
                     "usemtl t\nf 1/1 2/2 3/3\n");
    CHECK(character_load(&m, path, err, sizeof err));
    char expect[1200];
    snprintf(expect, sizeof expect, "%s/present.png", dir);
    CHECK_MSG(!strcmp(m.texture_path, expect), "texture_path='%s'", m.texture_path);
    character_model_free(&m);
}

int main(void)
{
    core_log_set_quiet(true);
    test_broken_fixture();
    test_clips_fixture();
    test_rigid_objects();
    test_errors_and_textures();
    TEST_END();
}

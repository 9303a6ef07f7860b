/* test_character_corpus: every rigged or animated model of Debian's
 * assimp-testmodels (.ci/packages; a missing package fails, never skips),
 * 17 formats, loaded as a user would (no flags: character_load,
 * character_import, character_walk_face). For each, on the CPU: the drawn
 * pose (the first frame of the clip measured, skinned) stands on the
 * ground (lowest point within 5 cm of y = 0); its height is the reported
 * one within 10 %, and 1.75 m within 10 % when 1.75 m is asked for; the
 * file's true up (judged once by looking at orthographic renders of the
 * drawn pose, the reason in the table) lands within 15 degrees of +Y;
 * where the model has a front (judged from the same renders, the reason
 * in the table), it lands within 25 degrees of +Z (the walking
 * direction); where it has a texture, the mean drawn albedo
 * (base colour times the texture at each triangle's centroid, area
 * weighted) is not near black. */
#include "character/character_import.h"
#include "character/character_orient.h"
#include "character/character_walk.h"
#include "core/core.h"
#include "test.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define CORPUS "/usr/share/assimp/models/"

typedef struct corpus_t {
    const char *path;  /* under CORPUS */
    int up;            /* the file's true up (axis code); 0: any (a box, a sphere, a flat sheet) */
    bool either_sign;  /* a cylinder or a strip: up or down alike */
    int front;         /* the file's true front; 0: none (a box, a symmetric object) */
    const char *why;   /* what the renders showed: up, then front */
} corpus_t;

static const corpus_t corpus[] = {
    {"X/Testwuson.X", 2, false, 3, "a bull on four hooves along +Y; head at +Z (side, top views), Wuson_Walk"},
    {"X/BCN_Epileptic.X", 2, false, 3, "a standing man; toes and nose at +Z (side view)"},
    {"X/anim_test.x", 2, true, 0, "a cylinder along Y; no front"},
    {"FBX/animation_with_skeleton.fbx", 2, false, 0, "a cube and a bent rod; the file is Y-up; no front"},
    {"FBX/huesitos.fbx", 2, false, 0, "a column of bones along +Y with an arm; no front"},
    {"MDL/MDL (HL1)/man.mdl", 2, false, 3, "a blocky man, head at +Y; hips across X; +Z: right bones at -X"},
    {"MDL/MDL (HL1)/unnamed_bones.mdl", 0, false, 0, "two slabs"},
    {"MDL/MDL (HL1)/chrome_sphere.mdl", 0, false, 0, "a sphere"},
    {"MDL/MDL (HL1)/alpha_test.mdl", 0, false, 0, "a box"},
    {"MDL/MDL (HL1)/blend_additive.mdl", 0, false, 0, "two quads"},
    {"MDL/MDL (HL1)/duplicate_bodyparts.mdl", 0, false, 0, "flat triangles"},
    {"MDL/MDL (HL1)/duplicate_submodels.mdl", 0, false, 0, "flat triangles"},
    {"MDL/MDL (HL1)/unnamed_bodyparts.mdl", 0, false, 0, "flat triangles"},
    {"MDL/MDL (HL1)/sequence_transitions.mdl", 0, false, 0, "a flat triangle"},
    {"MDL/MDL (HL1)/duplicate_sequences.mdl", 0, false, 0, "a flat triangle"},
    {"MDL/MDL (HL1)/unnamed_sequences.mdl", 0, false, 0, "a flat triangle"},
    {"MDL/MDL (HL1)/duplicate_sequence_groups/duplicate_sequence_groups.mdl", 0, false, 0, "a triangle"},
    {"MDL/MDL (HL1)/unnamed_sequence_groups/unnamed_sequence_groups.mdl", 0, false, 0, "a triangle"},
    {"BVH/01_01.bvh", 2, false, 3, "a T-posed skeleton; toes at +Z (side view)"},
    {"BVH/01_03.bvh", 2, false, 3, "a T-posed skeleton; toes at +Z (side view)"},
    {"BVH/Boxing_Toes.bvh", 2, false, -3, "a standing skeleton; toes at -Z (side view)"},
    {"CSM/ThomasFechten.csm", 3, false, -2, "a fencer's markers, head at +Z; shoulders across X; toe markers at -Y of the heels"},
    {"ASE/MotionCaptureROM.ase", 2, false, 3, "a T-posed figure of boxes, head at +Y; feet and nose at +Z (side view)"},
    {"ASE/anim.ASE", 0, false, 0, "boxes"},
    {"ASE/anim2.ASE", 0, false, 0, "boxes"},
    {"ASE/RotatingCube.ASE", 0, false, 0, "a box"},
    {"ASE/CameraRollAnim.ase", 0, false, 0, "a box"},
    {"ASE/CameraRollAnimWithChildObject.ase", 0, false, 0, "boxes"},
    {"ASE/TargetCameraAnim.ase", 0, false, 0, "a box"},
    {"Collada/anims_with_full_rotations_between_keys.DAE", 0, false, 0, "a row of cubes"},
    {"Collada/box_nested_animation.dae", 0, false, 0, "a box"},
    {"glTF2/simple_skin/simple_skin.gltf", 2, true, 0, "a flat strip along Y"},
    {"glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf", 0, false, 0, "a cube"},
    {"SMD/WusonSMD.smd", 3, false, 2, "a bull on four hooves along +Z; head at +Y (top, front views), not +X"},
    {"SMD/holy_grailref.smd", 3, false, 0, "a grail standing on its foot along +Z; round, no front"},
    {"SMD/triangle.smd", 0, false, 0, "a flat triangle"},
    {"3DS/RotatingCube.3DS", 0, false, 0, "a box"},
    {"3DS/CameraRollAnim.3ds", 0, false, 0, "a box"},
    {"3DS/CameraRollAnimWithChildObject.3ds", 0, false, 0, "boxes"},
    {"3DS/TargetCameraAnim.3ds", 0, false, 0, "a box"},
    {"LWS/move_x.lws", 0, false, 0, "a box"},
    {"LWS/move_xz_spline.lws", 0, false, 0, "a box"},
    {"MD2/faerie.md2", 2, false, 1, "a standing faerie; toes and face at +X (side and front views)"},
    {"MD2/sydney.md2", 2, false, 1, "a standing woman; toes and face at +X (side and front views)"},
    {"MDC/spider.mdc", 2, false, -1, "a spider on eight legs along +Y; head and fangs at -X (top view)"},
    {"IQM/mrfixit.iqm", 2, false, 1, "a T-posed man; toes and face at +X (side and front views)"},
    {"MD5/SimpleCube.md5mesh", 0, false, 0, "a cube"},
    {"B3D/WusonBlitz.b3d", 2, false, -3, "a bull on four hooves along +Y; head at -Z (side and top views)"},
    {"MS3D/Wuson.ms3d", 2, false, -3, "a bull on four hooves along +Y; head at -Z (side and top views)"},
};

static void axis_vec(int code, float v[3])
{
    v[0] = v[1] = v[2] = 0.0f;
    v[abs(code) - 1] = code < 0 ? -1.0f : 1.0f;
}

/* Where the import's rotation takes a file axis (model space). */
static void turn(const character_import_t *im, int axis, float out[3])
{
    float r[16], a[3];
    character_import_matrix(1.0f, im->up, im->forward, 0.0f, 0.0f, r);
    axis_vec(axis, a);
    for (int k = 0; k < 3; k++) out[k] = r[k] * a[0] + r[4 + k] * a[1] + r[8 + k] * a[2];
}

/* Mean albedo luminance of the drawn surface; -1 without a texture. */
static double mean_albedo(const character_model_t *m)
{
    core_image_t tex = {0};
    char why[256];
    const character_image_t *e = &m->texture_embedded;
    bool ok = false;
    if (e->data && e->height > 0) {
        ok = core_image_alloc(&tex, e->width, e->height, 4);
        for (int i = 0; ok && i < e->width * e->height; i++)
            for (int k = 0; k < 3; k++) tex.px[4 * i + k] = e->data[4 * i + 2 - k];
    } else if (e->data) {
        ok = core_image_decode(&tex, e->data, e->size, 4, why, sizeof why);
    } else if (m->texture_path[0]) {
        ok = core_image_load(&tex, m->texture_path, 4);
    } else {
        return -1.0;
    }
    if (!ok) return 0.0;
    double sum = 0.0, area = 0.0;
    for (int t = 0; t + 2 < m->index_count; t += 3) {
        const character_vertex_t *v[3] = {&m->vertices[m->indices[t]], &m->vertices[m->indices[t + 1]],
                                          &m->vertices[m->indices[t + 2]]};
        double e1[3], e2[3];
        for (int k = 0; k < 3; k++) e1[k] = v[1]->pos[k] - v[0]->pos[k], e2[k] = v[2]->pos[k] - v[0]->pos[k];
        double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        double w = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        float u = (v[0]->uv[0] + v[1]->uv[0] + v[2]->uv[0]) / 3.0f, vv = (v[0]->uv[1] + v[1]->uv[1] + v[2]->uv[1]) / 3.0f;
        u -= floorf(u), vv -= floorf(vv);
        int x = (int)(u * (float)tex.w) % tex.w, y = (int)((1.0f - vv) * (float)tex.h) % tex.h;
        const uint8_t *px = tex.px + 4 * ((size_t)y * (size_t)tex.w + (size_t)x);
        double lum = (0.2126 * m->base_color[0] * px[0] + 0.7152 * m->base_color[1] * px[1] +
                      0.0722 * m->base_color[2] * px[2]) / 255.0;
        sum += w * lum, area += w;
    }
    core_image_free(&tex);
    return area > 0.0 ? sum / area : 0.0;
}

static void check_model(const corpus_t *c, float fit)
{
    char path[1024], err[512];
    snprintf(path, sizeof path, CORPUS "%s", c->path);
    character_model_t m;
    character_import_t im;
    if (!character_load(&m, path, err, sizeof err)) {
        CHECK_MSG(false, "%s: %s", c->path, err);
        return;
    }
    bool ok = character_import(&m, path, &(character_import_desc_t){.height = fit}, &im, err, sizeof err) &&
              character_walk_face(&m, path, 0.0f, &im, err, sizeof err);
    CHECK_MSG(ok, "%s: %s", c->path, err);
    if (!ok) {
        character_model_free(&m);
        return;
    }
    float lo[3], hi[3], h;
    character_orient_box(&m, im.pose_clip, lo, hi);
    h = hi[1] - lo[1];
    CHECK_MSG(fabsf(lo[1]) <= 0.05f, "%s: lowest point %.3f m off the ground", c->path, (double)lo[1]);
    CHECK_MSG(fabsf(h - im.height) <= 0.1f * im.height, "%s: drawn %.3f m, reported %.3f m", c->path, (double)h,
              (double)im.height);
    if (fit > 0.0f) CHECK_MSG(fabsf(h - fit) <= 0.1f * fit, "%s: drawn %.3f m, asked %.3f m", c->path, (double)h, (double)fit);
    for (int k = 0; k < 3; k++)
        CHECK_MSG(fabsf(lo[k] - im.box_min[k]) <= 1e-3f * h && fabsf(hi[k] - im.box_max[k]) <= 1e-3f * h,
                  "%s: reported box axis %d differs from the drawn one", c->path, k);
    float v[3];
    if (c->up) {
        turn(&im, c->up, v);
        float cosine = c->either_sign ? fabsf(v[1]) : v[1];
        CHECK_MSG(cosine >= cosf(15.0f * 3.14159265f / 180.0f), "%s: true up %s lands at (%.2f %.2f %.2f); chose up %s (%s)",
                  c->path, character_axis_name(c->up), (double)v[0], (double)v[1], (double)v[2],
                  character_axis_name(im.up), im.up_from);
    }
    if (c->front) {
        turn(&im, c->front, v);
        bool faces = v[2] >= cosf(25.0f * 3.14159265f / 180.0f);
        CHECK_MSG(faces, "%s: true front %s lands at (%.2f %.2f %.2f); chose %s (%s)", c->path,
                  character_axis_name(c->front), (double)v[0], (double)v[1], (double)v[2],
                  character_axis_name(im.forward), im.forward_from);
    }
    double albedo = mean_albedo(&m);
    if (albedo >= 0.0) CHECK_MSG(albedo > 0.08, "%s: mean drawn albedo %.3f is near black", c->path, albedo);
    if (fit == 0.0f)
        printf("%-62s %-8s h %7.3f m  up %s (%s)  forward %s (%s)  conf %.2f%s\n", c->path, m.file.format,
               (double)h, character_axis_name(im.up), im.up_from, character_axis_name(im.forward), im.forward_from,
               (double)character_import_confidence(&im), albedo >= 0.0 ? "  textured" : "");
    character_model_free(&m);
}

int main(void)
{
    core_log_set_quiet(true);
    if (access(CORPUS, R_OK) != 0) {
        CHECK_MSG(false, "%s missing: install the Debian package assimp-testmodels (.ci/packages)", CORPUS);
        TEST_END();
    }
    int formats = 0;
    char seen[32][16];
    for (size_t i = 0; i < sizeof corpus / sizeof corpus[0]; i++) {
        check_model(&corpus[i], 0.0f);
        check_model(&corpus[i], 1.75f);
        const char *dot = strrchr(corpus[i].path, '.');
        char ext[16];
        size_t k = 0;
        for (const char *p = dot + 1; *p && k + 1 < sizeof ext; p++) ext[k++] = (char)(*p | 0x20);
        ext[k] = 0;
        bool known = false;
        for (int f = 0; f < formats; f++) known |= !strcmp(seen[f], ext);
        if (!known && formats < 32) snprintf(seen[formats++], sizeof seen[0], "%s", ext);
    }
    CHECK_MSG(formats >= 12, "%d formats", formats);
    printf("%zu models, %d formats\n", sizeof corpus / sizeof corpus[0], formats);
    TEST_END();
}

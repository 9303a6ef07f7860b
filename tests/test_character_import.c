/* test_character_import: character_import's units, axes and heights on the
 * generated humanoid (models/humanoid.gltf) turned into files of other
 * conventions (Z-up, centimetres, 17-unit Minetest-like sizes, b3d's -Z
 * forward), the skinned pose after import against C * (pose before), the
 * texture search (Windows paths, textures/, embedded data-URI images),
 * quad/ngon triangulation, and clip lookup and listing. GL-free. */
#include "character/character_import.h"
#include "character/character_orient.h"
#include "character/character_ref.h"
#include "core/core.h"
#include "test.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *out_dir(void)
{
    const char *d = getenv("MEADOW_TEST_OUT");
    return d ? d : "/tmp/meadow-test_character_import";
}

static void write_text(const char *path, const char *text)
{
    CHECK(core_fs_write_atomic(path, text, strlen(text)));
}

static bool load_humanoid(character_model_t *m)
{
    char path[1024], err[256];
    CHECK(core_fs_resolve("models/humanoid.gltf", path, sizeof path));
    bool ok = character_load(m, path, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    return ok;
}

/* Skinned positions of clip 0 at time t (3 * vertex_count floats). */
static float *skin_at(const character_model_t *m, float t)
{
    character_pose_t pose;
    float *p = malloc(sizeof(float) * 3 * (size_t)m->vertex_count);
    CHECK(p && character_pose_init(&pose, m));
    character_sample_clip(m, 0, t, true, &pose);
    character_pose_globals(m, &pose);
    character_skin_cpu(m, &pose, p, NULL);
    character_pose_free(&pose);
    return p;
}

static bool do_import(character_model_t *m, const character_import_desc_t *d, character_import_t *o)
{
    char err[256] = "";
    bool ok = character_import(m, "test", d, o, err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    return ok;
}

/* The generated humanoid is metres, +Y up, facing +Z: nothing changes. */
static void test_identity(void)
{
    character_model_t m;
    if (!load_humanoid(&m)) return;
    float *before = skin_at(&m, 0.3f);
    character_import_t o;
    int warns = core_log_warn_count();
    CHECK(do_import(&m, &(character_import_desc_t){0}, &o));
    CHECK(core_log_warn_count() == warns);
    CHECK(o.scale == 1.0f && o.up == 2 && o.forward == 3);
    CHECK(!strcmp(o.scale_from, "file (metres)") && !strcmp(o.up_from, "skeleton, geometry"));
    CHECK(o.height > 1.6f && o.height < 1.9f);
    float *after = skin_at(&m, 0.3f);
    CHECK(!memcmp(before, after, sizeof(float) * 3 * (size_t)m.vertex_count));
    free(before), free(after);
    character_model_free(&m);
}

/* A turned, scaled import moves every skinned vertex by the same
 * similarity (plus the lift that puts the feet on y = 0). */
static void test_similarity(void)
{
    character_model_t m;
    if (!load_humanoid(&m)) return;
    float *before = skin_at(&m, 0.3f);
    character_import_t o;
    CHECK(do_import(&m, &(character_import_desc_t){.height = 3.5f, .up = -3, .forward = 2, .yaw = 30.0f}, &o));
    CHECK(!strcmp(o.scale_from, "scene") && !strcmp(o.up_from, "scene") && !strcmp(o.forward_from, "scene"));
    CHECK_NEAR(o.height, 3.5, 1e-4);
    float *after = skin_at(&m, 0.3f);
    float c[16];
    character_import_matrix(o.scale, o.up, o.forward, 30.0f, 0.0f, c);
    double lift = 0.0, worst = 0.0;
    for (int v = 0; v < m.vertex_count; v++) {
        float e[3];
        character_mat4_point(c, before + 3 * v, e);
        if (v == 0) lift = after[1] - e[1];
        e[1] += (float)lift;
        worst = fmax(worst, test_dist3(e, after + 3 * v));
    }
    CHECK_MSG(worst < 1e-4, "skinned after import vs C * before: %g m", worst);
    float lo[3], hi[3];
    character_orient_box(&m, character_orient_pose_clip(&m), lo, hi);
    CHECK_NEAR(hi[1] - lo[1], 3.5, 1e-4);
    /* up -Z of the file: the model lay along -z; it stands on y = 0 now */
    CHECK(fabsf(lo[1]) < 0.01f * 3.5f);
    free(before), free(after);
    character_model_free(&m);
}

/* Converts the humanoid into a "file": Z-up, facing -Y, in centimetres
 * (import with up -Z and forward +Y is the inverse of up +Z forward -Y). */
static bool make_zup_cm(character_model_t *m)
{
    if (!load_humanoid(m)) return false;
    character_import_t o;
    float lo[3], hi[3];
    if (!do_import(m, &(character_import_desc_t){.height = 174.0f}, &o)) return false;
    character_orient_box(m, character_orient_pose_clip(m), lo, hi);
    /* the height along the source's up axis (-z) as it is: scale 1 */
    return do_import(m, &(character_import_desc_t){.height = hi[2] - lo[2], .up = -3, .forward = 2}, &o);
}

static void test_metadata(void)
{
    character_model_t m;
    if (!make_zup_cm(&m)) return;
    m.file.unit_metres = 0.01f, m.file.up = 3, m.file.front = -2;
    character_import_t o;
    int warns = core_log_warn_count();
    CHECK(do_import(&m, &(character_import_desc_t){0}, &o));
    CHECK(core_log_warn_count() == warns);
    /* the skeleton (head over feet) agrees with the metadata and wins; the
     * toes give the forward */
    CHECK(!strcmp(o.scale_from, "metadata") && o.up == 3 && o.forward == -2);
    CHECK_NEAR(o.height, 1.74, 0.01);
    character_model_t ref;
    if (load_humanoid(&ref)) {
        float lo[3], hi[3], rlo[3], rhi[3];
        character_orient_box(&m, character_orient_pose_clip(&m), lo, hi);
        character_orient_box(&ref, character_orient_pose_clip(&ref), rlo, rhi);
        /* the same figure up to the scale that fitted its drawn pose to
         * 174 units (a lift may have moved it along z) */
        float s = (hi[1] - lo[1]) / (rhi[1] - rlo[1]);
        for (int k = 0; k < 3; k++) CHECK_NEAR(hi[k] - lo[k], s * (rhi[k] - rlo[k]), 2e-3);
        CHECK_NEAR(lo[1], rlo[1], 2e-3);
        character_model_free(&ref);
    }
    character_model_free(&m);

    /* a metadata unit that makes a 174 m giant: kept, with a warning */
    if (!make_zup_cm(&m)) return;
    m.file.unit_metres = 1.0f, m.file.up = 3, m.file.front = -2;
    warns = core_log_warn_count();
    CHECK(do_import(&m, &(character_import_desc_t){0}, &o));
    CHECK(core_log_warn_count() == warns + 1);
    CHECK_NEAR(o.height, 174.0, 0.1);
    character_model_free(&m);
}

static void test_heuristics(void)
{
    character_model_t m;
    character_import_t o;
    /* 17 units, no unit stated (Minetest's player): fitted with a warning */
    if (!load_humanoid(&m)) return;
    CHECK(do_import(&m, &(character_import_desc_t){.height = 17.0f}, &o));
    int warns = core_log_warn_count();
    CHECK(do_import(&m, &(character_import_desc_t){0}, &o));
    CHECK(core_log_warn_count() == warns + 1);
    CHECK(!strcmp(o.scale_from, "fitted"));
    CHECK_NEAR(o.height, CHARACTER_IMPORT_FIT_HEIGHT, 1e-4);
    CHECK_NEAR(o.file_height, 17.0, 1e-3);
    character_model_free(&m);
    /* 1.5 units: taken as metres */
    if (!load_humanoid(&m)) return;
    CHECK(do_import(&m, &(character_import_desc_t){.height = 1.5f}, &o));
    warns = core_log_warn_count();
    CHECK(do_import(&m, &(character_import_desc_t){0}, &o));
    CHECK(core_log_warn_count() == warns && o.scale == 1.0f);
    character_model_free(&m);
    /* format conventions: b3d faces -Z (assimp mirrors its left-handed
     * Z), a 3ds is Z-up facing -Y; the humanoid's bones lose their names
     * (its left/right bones would otherwise say where it faces) */
    if (!load_humanoid(&m)) return;
    snprintf(m.file.format, sizeof m.file.format, "b3d");
    for (int b = 0; b < m.bone_count; b++) m.bones[b].name[0] = '\0';
    CHECK(do_import(&m, &(character_import_desc_t){0}, &o));
    CHECK(o.up == 2 && o.forward == -3 && !strcmp(o.forward_from, "format"));
    character_model_free(&m);
    if (!make_zup_cm(&m)) return;
    snprintf(m.file.format, sizeof m.file.format, "3ds");
    CHECK(do_import(&m, &(character_import_desc_t){.height = 1.74f}, &o));
    CHECK(o.up == 3 && o.forward == -2 && !strcmp(o.up_from, "skeleton, geometry"));
    float lo[3], hi[3];
    character_orient_box(&m, character_orient_pose_clip(&m), lo, hi);
    CHECK_NEAR(hi[1] - lo[1], 1.74, 1e-3);
    character_model_free(&m);
    /* inconsistent requests are errors, not guesses */
    if (!load_humanoid(&m)) return;
    char err[256] = "";
    CHECK(!character_import(&m, "test", &(character_import_desc_t){.up = 3, .forward = -3}, &o, err, sizeof err));
    CHECK_MSG(strstr(err, "lies along up") != NULL, "err='%s'", err);
    CHECK(!character_import(&m, "test", &(character_import_desc_t){.height = 2e4f}, &o, err, sizeof err));
    character_model_free(&m);
    CHECK(character_axis_parse("+x") == 1 && character_axis_parse("-Z") == -3 && character_axis_parse("y") == 2);
    CHECK(character_axis_parse("w") == 0 && character_axis_parse("+") == 0 && character_axis_parse("xx") == 0);
}

/* Blender's default OBJ export: quads and an ngon, no .mtl beside it. */
static void test_quads(void)
{
    char path[1100], err[256];
    snprintf(path, sizeof path, "%s/quads.obj", out_dir());
    write_text(path, "mtllib quads.mtl\no Cube\nv 1 1 -1\nv 1 -1 -1\nv 1 1 1\nv 1 -1 1\nv -1 1 -1\nv -1 -1 -1\n"
                     "v -1 1 1\nv -1 -1 1\nv 0 2 0\nvt 0 0\nvn 0 1 0\ns off\n"
                     "f 1/1/1 5/1/1 7/1/1 3/1/1\nf 4/1/1 3/1/1 7/1/1 8/1/1\nf 8/1/1 7/1/1 5/1/1 6/1/1\n"
                     "f 6/1/1 2/1/1 4/1/1 8/1/1\nf 2/1/1 1/1/1 3/1/1 4/1/1\nf 6/1/1 5/1/1 9/1/1 1/1/1 2/1/1\n");
    character_model_t m;
    int warns = core_log_warn_count(), errors = core_log_error_count();
    CHECK(character_load(&m, path, err, sizeof err));
    CHECK(core_log_error_count() == errors);
    CHECK_MSG(core_log_warn_count() == warns + 1, "the missing quads.mtl warns once");
    CHECK_MSG(m.index_count == 3 * (5 * 2 + 3), "triangles %d", m.index_count / 3);
    if (m.vertex_count) character_model_free(&m);
}

static void base64(const unsigned char *src, size_t n, char *out)
{
    static const char t[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    size_t o = 0;
    for (size_t i = 0; i < n; i += 3) {
        unsigned v = (unsigned)src[i] << 16 | (i + 1 < n ? (unsigned)src[i + 1] << 8 : 0) | (i + 2 < n ? src[i + 2] : 0);
        out[o++] = t[v >> 18 & 63], out[o++] = t[v >> 12 & 63];
        out[o++] = i + 1 < n ? t[v >> 6 & 63] : '=';
        out[o++] = i + 2 < n ? t[v & 63] : '=';
    }
    out[o] = 0;
}

/* A glTF whose image is a data URI: assimp hands it over as "*0". */
static void test_embedded_texture(const char *dir)
{
    core_image_t img;
    char path[1100], err[256];
    CHECK(core_image_alloc(&img, 2, 2, 4));
    memset(img.px, 77, 16);
    snprintf(path, sizeof path, "%s/embedded.png", dir);
    CHECK(core_image_write_png(&img, path));
    core_image_free(&img);
    size_t png_size = 0;
    char *png = core_fs_read(path, &png_size, err, sizeof err);
    float geo[9 + 6] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
    char png64[1024], geo64[128], *text = malloc(8192);
    if (!png || !text || png_size > 700) {
        CHECK(!"embedded png");
        free(png), free(text);
        return;
    }
    base64((const unsigned char *)png, png_size, png64);
    base64((const unsigned char *)geo, sizeof geo, geo64);
    snprintf(text, 8192,
             "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],"
             "\"meshes\":[{\"primitives\":[{\"attributes\":{\"POSITION\":0,\"TEXCOORD_0\":1},\"material\":0}]}],"
             "\"materials\":[{\"pbrMetallicRoughness\":{\"baseColorTexture\":{\"index\":0}}}],"
             "\"textures\":[{\"source\":0}],\"images\":[{\"uri\":\"data:image/png;base64,%s\"}],"
             "\"buffers\":[{\"byteLength\":60,\"uri\":\"data:application/octet-stream;base64,%s\"}],"
             "\"bufferViews\":[{\"buffer\":0,\"byteLength\":36},{\"buffer\":0,\"byteOffset\":36,\"byteLength\":24}],"
             "\"accessors\":[{\"bufferView\":0,\"componentType\":5126,\"count\":3,\"type\":\"VEC3\","
             "\"min\":[0,0,0],\"max\":[1,1,0]},{\"bufferView\":1,\"componentType\":5126,\"count\":3,\"type\":\"VEC2\"}]}",
             png64, geo64);
    snprintf(path, sizeof path, "%s/embedded.gltf", dir);
    write_text(path, text);
    character_model_t m;
    CHECK(character_load(&m, path, err, sizeof err));
    CHECK(m.texture_embedded.data != NULL && m.texture_path[0] == 0);
    if (m.texture_embedded.data) {
        CHECK(m.texture_embedded.height == 0 && m.texture_embedded.size == png_size);
        core_image_t dec;
        CHECK(core_image_decode(&dec, m.texture_embedded.data, m.texture_embedded.size, 4, err, sizeof err));
        CHECK(dec.w == 2 && dec.h == 2 && dec.px[0] == 77);
        core_image_free(&dec);
    }
    if (m.vertex_count) character_model_free(&m);
    free(png), free(text);
}

static void test_textures(void)
{
    char dir[1024], path[1100], want[1200], tried[2048], found[1024], err[256];
    snprintf(dir, sizeof dir, "%s/tex", out_dir());
    snprintf(path, sizeof path, "%s/textures", dir);
    CHECK(core_fs_mkdirs(path));
    snprintf(path, sizeof path, "%s/skin.png", dir);
    write_text(path, "x");
    snprintf(path, sizeof path, "%s/textures/body.png", dir);
    write_text(path, "x");
    snprintf(path, sizeof path, "%s/model.obj", dir);
    /* an absolute Windows path: the file name beside the model */
    CHECK(character_texture_find(path, "C:\\art\\chars\\skin.png", found, sizeof found, tried, sizeof tried));
    snprintf(want, sizeof want, "%s/skin.png", dir);
    CHECK_MSG(!strcmp(found, want), "found '%s'", found);
    /* a folder that does not exist: textures/ beside the model */
    CHECK(character_texture_find(path, "maps/body.png", found, sizeof found, tried, sizeof tried));
    snprintf(want, sizeof want, "%s/textures/body.png", dir);
    CHECK_MSG(!strcmp(found, want), "found '%s'", found);
    CHECK(!character_texture_find(path, "/nowhere/none.png", found, sizeof found, tried, sizeof tried));
    CHECK_MSG(strstr(tried, "/nowhere/none.png") && strstr(tried, "textures/none.png"), "tried '%s'", tried);

    /* through a material: found, and no error line for a missing one */
    snprintf(path, sizeof path, "%s/win.mtl", dir);
    write_text(path, "newmtl t\nKd 1 1 1\nmap_Kd D:\\work\\skin.png\n");
    snprintf(path, sizeof path, "%s/win.obj", dir);
    write_text(path, "mtllib win.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nusemtl t\nf 1/1 2/1 3/1\n");
    character_model_t m;
    int errors = core_log_error_count();
    CHECK(character_load(&m, path, err, sizeof err));
    snprintf(want, sizeof want, "%s/skin.png", dir);
    CHECK_MSG(!strcmp(m.texture_path, want), "texture_path '%s'", m.texture_path);
    if (m.vertex_count) character_model_free(&m);
    CHECK(core_log_error_count() == errors);

    /* a corrupt image decodes to a reason, not a log line */
    core_image_t img;
    CHECK(!core_image_decode(&img, "\x89PNG\r\n\x1a\nbroken", 14, 4, err, sizeof err) && err[0]);
    CHECK(core_log_error_count() == errors);
    test_embedded_texture(dir);
}

static void test_clips(void)
{
    character_model_t m;
    if (!load_humanoid(&m)) return;
    int warns = core_log_warn_count();
    CHECK(character_clip_find(&m, "walk") == 0 && character_clip_find(&m, "IDLE") == 1);
    CHECK(character_clip_find(&m, "run") == -1 && character_clip_find(&m, "7") == -1);
    CHECK(core_log_warn_count() == warns);
    char list[512];
    character_clip_list(&m, list, sizeof list);
    CHECK_MSG(strstr(list, "0 'walk' (1 s)") && strstr(list, "1 'idle' (2 s)") && strstr(list, "1000 ticks"),
              "list '%s'", list);
    CHECK(character_clip_keys(&m.clips[0], m.bone_count) > 100);
    character_model_free(&m);
}

int main(void)
{
    core_log_set_quiet(true);
    CHECK(core_fs_mkdirs(out_dir()));
    test_identity();
    test_similarity();
    test_metadata();
    test_heuristics();
    test_quads();
    test_textures();
    test_clips();
    TEST_END();
}

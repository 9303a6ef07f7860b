/* test_scene_json: scene files parse; every malformed input fails with
 * file:line and the field in the message; parsed values and defaults match
 * hand-written expectations; the JSON parser decodes escapes and rejects
 * non-JSON; docs/SCENES.md is the rendering of the key table. */
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/core.h"
#include "scene/scene.h"
#include "scene/scene_fields.h"
#include "test.h"

#define DATA MEADOW_SOURCE_DIR "/tests/data/scenes/"

static scene_desc_t desc; /* large: keep off the stack */

static void expect_parse_fail(const char *text, const char *what, const char *sub1, const char *sub2)
{
    char err[512] = "";
    bool ok = scene_parse(&desc, text, "inline.json", err, sizeof err);
    CHECK_MSG(!ok, "%s: parsed but should fail", what);
    CHECK_MSG(strstr(err, sub1) != NULL, "%s: \"%s\" not in \"%s\"", what, sub1, err);
    if (sub2) CHECK_MSG(strstr(err, sub2) != NULL, "%s: \"%s\" not in \"%s\"", what, sub2, err);
}

static void expect_load_fail(const char *file, const char *sub1, const char *sub2)
{
    char err[512] = "", path[1024];
    snprintf(path, sizeof path, DATA "%s", file);
    bool ok = scene_load(&desc, path, err, sizeof err);
    CHECK_MSG(!ok, "%s: loaded but should fail", file);
    CHECK_MSG(strstr(err, sub1) != NULL, "%s: \"%s\" not in \"%s\"", file, sub1, err);
    if (sub2) CHECK_MSG(strstr(err, sub2) != NULL, "%s: \"%s\" not in \"%s\"", file, sub2, err);
    printf("  %s -> %s\n", file, err);
}

static bool parse_ok(const char *text)
{
    char err[512] = "";
    bool ok = scene_parse(&desc, text, "inline.json", err, sizeof err);
    CHECK_MSG(ok, "should parse: %s: %s", text, err);
    return ok;
}

static void test_scene_files(void)
{
    DIR *dir = opendir(MEADOW_SOURCE_DIR "/scenes");
    CHECK(dir != NULL);
    if (!dir) return;
    int n = 0;
    struct dirent *e;
    while ((e = readdir(dir))) {
        size_t len = strlen(e->d_name);
        if (len < 5 || strcmp(e->d_name + len - 5, ".json") != 0) continue;
        char path[1024], err[512] = "";
        snprintf(path, sizeof path, MEADOW_SOURCE_DIR "/scenes/%s", e->d_name);
        CHECK_MSG(scene_load(&desc, path, err, sizeof err), "%s", err);
        n++;
    }
    closedir(dir);
    CHECK_MSG(n >= 5, "only %d scene files", n);

    char err[512];
    CHECK(scene_load(&desc, MEADOW_SOURCE_DIR "/scenes/meadow.json", err, sizeof err));
    CHECK(desc.mode == SCENE_MODE_HYBRID);
    CHECK(desc.terrain.type == TERRAIN_HEIGHTFIELD);
    CHECK_NEAR(desc.terrain.size, 40, 0);
    CHECK(desc.character_count == 2);
    CHECK(strcmp(desc.characters[0].model, "models/humanoid.gltf") == 0);
    CHECK(strcmp(desc.characters[1].model, "models/quadruped.gltf") == 0);
    CHECK(desc.characters[0].loop && desc.characters[1].loop);
    CHECK(desc.characters[0].waypoint_count >= 3);
    CHECK(desc.wind_count >= 1 && desc.wind[0].type == SCENE_WIND_DIRECTIONAL);
    CHECK(desc.camera.path.count >= 2);

    CHECK(scene_load(&desc, MEADOW_SOURCE_DIR "/scenes/billboards.json", err, sizeof err));
    CHECK(desc.mode == SCENE_MODE_BILLBOARD);
    CHECK(desc.collider_count >= 1 && desc.colliders[0].type == SCENE_COLLIDER_SPHERE);
    CHECK(desc.colliders[0].path.count >= 2);

    CHECK(scene_load(&desc, MEADOW_SOURCE_DIR "/scenes/blades.json", err, sizeof err));
    CHECK(desc.mode == SCENE_MODE_BLADE);
    CHECK(desc.collider_count >= 1 && desc.colliders[0].path.count >= 2);

    CHECK(scene_load(&desc, MEADOW_SOURCE_DIR "/scenes/closed_mesh.json", err, sizeof err));
    CHECK(desc.terrain.type == TERRAIN_MESH);
    CHECK(strcmp(desc.terrain.mesh, "models/torus.obj") == 0);

    CHECK(scene_load(&desc, MEADOW_SOURCE_DIR "/scenes/tiny.json", err, sizeof err));
    CHECK_NEAR(desc.terrain.size, 8, 0);
    CHECK(desc.grass.population.density <= 50);
}

static void test_bad_files(void)
{
    expect_load_fail("does_not_exist.json", "does_not_exist.json: cannot read", "No such file");
    expect_load_fail("bad_truncated.json", "bad_truncated.json:5:", "unexpected end of file");
    expect_load_fail("bad_truncated.json", "unclosed '[' from line 5", NULL);
    expect_load_fail("bad_malformed.json", "bad_malformed.json:5:", "expected ',' or '}'");
    expect_load_fail("bad_wrong_type.json",
                     "bad_wrong_type.json:4: field \"grass.density\": expected number, got string",
                     NULL);
    expect_load_fail("bad_unknown_key.json", "bad_unknown_key.json:5: field \"grass.densty\"",
                     "unknown key \"densty\"");
    expect_load_fail("bad_out_of_range.json", "bad_out_of_range.json:4: field \"camera.fov\"",
                     "200 is out of range [0, 179]");
    expect_load_fail("bad_too_many.json", "bad_too_many.json:2: field \"wind\"",
                     "17 entries, more than the maximum 8");
    expect_load_fail("bad_trailing.json", "bad_trailing.json:4:", "end of file after the top-level");
    expect_load_fail("bad_wrong_type_vec.json",
                     "bad_wrong_type_vec.json:5: field \"characters[0].path[1][1]\": expected number, "
                     "got string",
                     NULL);
    /* A failed load leaves nothing behind. */
    CHECK(desc.character_count == 0 && desc.frames == 0);
}

static void test_bad_inline(void)
{
    expect_parse_fail("", "empty", "inline.json:1:", "unexpected end of file");
    expect_parse_fail("[1, 2]", "top array", "inline.json:1:", "expected object, got array");
    expect_parse_fail("{\"seed\": 1,}", "trailing comma", "inline.json:1:", "string key after ','");
    expect_parse_fail("{\"seed\": 1,\n\"seed\": 2}", "duplicate", "inline.json:2:",
                      "duplicate key \"seed\" (first on line 1)");
    expect_parse_fail("{\"seed\": 01}", "leading zero", "inline.json:1:", "expected ',' or '}'");
    expect_parse_fail("{\"dt\": 1.}", "bare dot", "inline.json:1:", "digit after '.'");
    expect_parse_fail("{\"dt\": .5}", "leading dot", "inline.json:1:", "unexpected character '.'");
    expect_parse_fail("{\"dt\": +1}", "plus", "inline.json:1:", "unexpected character '+'");
    expect_parse_fail("{\"dt\": 1e}", "bad exponent", "inline.json:1:", "exponent digit");
    expect_parse_fail("{\"dt\": 1e999}", "huge", "inline.json:1:", "out of double range");
    expect_parse_fail("{\"msaa\": tru}", "literal", "inline.json:1:", "unexpected character 't'");
    expect_parse_fail("{\"msaa\": nulls}", "literal tail", "inline.json:1:", NULL);
    expect_parse_fail("{\"mode\": \"bla\nde\"}", "newline in string", "inline.json:1:",
                      "unterminated string");
    expect_parse_fail("{\"mode\": \"a\\qb\"}", "bad escape", "inline.json:1:", "invalid escape '\\q'");
    /* Invalid UTF-8 in strings: stray continuation, overlong, surrogate,
     * past U+10FFFF, cut short; well-formed text passes to the key check. */
    expect_parse_fail("{\n\"mode\": \"a\x80\"}", "stray continuation", "inline.json:2:",
                      "invalid UTF-8 in a string (byte 0x80 at offset 12)");
    expect_parse_fail("{\"mode\": \"\xc0\xaf\"}", "overlong", "inline.json:1:", "invalid UTF-8 in a string (byte 0xc0");
    expect_parse_fail("{\"mode\": \"\xed\xa0\x80\"}", "surrogate", "inline.json:1:", "invalid UTF-8");
    expect_parse_fail("{\"mode\": \"\xf4\x90\x80\x80\"}", "past U+10FFFF", "inline.json:1:", "invalid UTF-8");
    expect_parse_fail("{\"mode\": \"\xe2\x82\"}", "cut short", "inline.json:1:", "invalid UTF-8");
    expect_parse_fail("{\"mode\": \"caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x8c\xbf\"}", "valid UTF-8", "inline.json:1:",
                      "unknown value");
    expect_parse_fail("{\"mode\": \"\\ud800x\"}", "lone high surrogate", "inline.json:1:",
                      "not followed by a low surrogate");
    expect_parse_fail("{\"mode\": \"\\udc00\"}", "lone low surrogate", "inline.json:1:",
                      "lone low surrogate");
    expect_parse_fail("{\"mode\": \"\\u12\"}", "short \\u", "inline.json:1:", "4 hex digits");
    expect_parse_fail("{\"mode\": \"\\u0000\"}", "nul", "inline.json:1:", "\\u0000");
    expect_parse_fail("{\n// comment\n}", "comment", "inline.json:2:", "unexpected character '/'");
    expect_parse_fail("{\"a\" 1}", "no colon", "inline.json:1:", "':' after key");
    expect_parse_fail("{\"seed\": [1 2]}", "array comma", "inline.json:1:", "',' or ']'");
    expect_parse_fail("{\"mode\": \"abc", "eof in string", "inline.json:1:", "closing '\"'");
    {
        char deep[256] = "{\"grass\": ";
        for (int i = 0; i < 70; i++) strcat(deep, "[");
        expect_parse_fail(deep, "deep", "inline.json:1:", "nesting deeper than 64");
    }

    expect_parse_fail("{\n\"seed\": -1}", "negative seed", "inline.json:2: field \"seed\"",
                      "-1 is out of range [0, 4.29497e+09]");
    expect_parse_fail("{\n\"grass\": {\"stiffness\": [0, 10]}}", "stiffness 0", "inline.json:2: field \"grass.stiffness[0]\"",
                      "0 is out of range (0, 100]");
    expect_parse_fail("{\"frames\": 2.5}", "fraction", "field \"frames\": expected an integer, got 2.5",
                      NULL);
    expect_parse_fail("{\"msaa\": 3}", "msaa", "field \"msaa\"", "3 is not one of");
    expect_parse_fail("{\n\"raster_samples\": 2}", "raster_samples 2", "inline.json:2: field \"raster_samples\"",
                      "2 is not 1 or 4");
    expect_parse_fail("{\"size\": [8, 100]}", "size 8", "field \"size[0]\"", "8 is out of range [16, 16384]");
    {
        scene_desc_t d;
        char err[256];
        CHECK(scene_parse(&d, "{\"raster_samples\": 1}", "inline.json", err, sizeof err) && d.raster_samples == 1);
        CHECK(scene_parse(&d, "{}", "inline.json", err, sizeof err) && d.raster_samples == 4);
    }
    expect_parse_fail("{\"mode\": \"grass\"}", "mode", "field \"mode\": unknown value \"grass\"",
                      "billboard, blade");
    expect_parse_fail("{\"size\": [1, 2, 3]}", "size len", "field \"size\"",
                      "expected an array of 2 numbers, got 3 elements");
    expect_parse_fail("{\"grass\": {\"height\": [0.7, 0.35]}}", "min>max", "field \"grass.height\"",
                      "min 0.7 is greater than max 0.35");
    expect_parse_fail("{\"grass\": {\"shape\": \"round\"}}", "shape", "field \"grass.shape\"",
                      "dandelion");
    expect_parse_fail("{\"grass\": 5}", "grass type", "field \"grass\": expected object, got number",
                      NULL);
    expect_parse_fail("{\"terrain\": {\"type\": \"mesh\"}}", "mesh required", "field \"terrain.mesh\"",
                      "required");
    expect_parse_fail("{\"terrain\": {\"resolution\": 5000}}", "res range",
                      "field \"terrain.resolution\"", "[0, 4096]");
    expect_parse_fail("{\"camera\": {\"near\": 5, \"far\": 2}}", "far<near", "field \"camera.far\"",
                      "must be greater than near");
    expect_parse_fail("{\"camera\": {\"path\": [\n{\"t\": 1, \"position\": [0,0,0], \"target\": "
                      "[0,0,0]},\n{\"t\": 1, \"position\": [0,0,0], \"target\": [0,0,0]}]}}",
                      "t order", "inline.json:3: field \"camera.path[1].t\"", "strictly increasing");
    expect_parse_fail("{\"camera\": {\"path\": [{\"t\": 1, \"position\": [0,0,0]}]}}", "missing target",
                      "field \"camera.path[0].target\"", "required");
    expect_parse_fail("{\"wind\": [{\"type\": \"directional\",\n \"radius\": 3}]}", "wind key",
                      "inline.json:2: field \"wind[0].radius\"",
                      "unknown key \"radius\" for wind type \"directional\"");
    expect_parse_fail("{\"wind\": [{\"type\": \"gust\"}]}", "wind type", "field \"wind[0].type\"",
                      "unknown value \"gust\"");
    expect_parse_fail("{\"colliders\": [{\"type\": \"box\", \"radius\": 1}]}", "box radius",
                      "field \"colliders[0].radius\"", "for collider type \"box\"");
    expect_parse_fail("{\"colliders\": [{\"position\": [0,0,0], \"path\": []}]}", "pos+path",
                      "field \"colliders[0]\"", "not both");
    expect_parse_fail("{\"colliders\": [{\"half_extents\": [1, 1]}]}", "sphere half",
                      "field \"colliders[0].half_extents\"", "unknown key");
    expect_parse_fail("{\"characters\": [{\"clip\": 1}]}", "model required",
                      "field \"characters[0].model\": required", NULL);
    expect_parse_fail("{\"characters\": [{\"model\": \"m\", \"clip\": [1]}]}", "clip type",
                      "field \"characters[0].clip\": expected string or number, got array", NULL);
    expect_parse_fail("{\"characters\": [{\"model\": \"m\", \"loop\": 1}]}", "loop type",
                      "field \"characters[0].loop\": expected boolean, got number", NULL);
    {
        /* 65 waypoints: one more than SCENE_MAX_PATH_KEYS. */
        static char text[4096];
        strcpy(text, "{\"characters\": [{\"model\": \"m\", \"path\": [");
        for (int i = 0; i <= SCENE_MAX_PATH_KEYS; i++) strcat(text, i ? ",[0,0]" : "[0,0]");
        strcat(text, "]}]}");
        expect_parse_fail(text, "waypoints", "field \"characters[0].path\"",
                          "65 entries, more than the maximum 64 (SCENE_MAX_PATH_KEYS)");
    }
    {
        static char text[65536];
        strcpy(text, "{\"colliders\": [");
        for (int i = 0; i <= SCENE_MAX_COLLIDERS; i++) strcat(text, i ? ",{}" : "{}");
        strcat(text, "]}");
        expect_parse_fail(text, "colliders", "field \"colliders\"", "129 entries, more than the maximum 128");
        strcpy(text, "{\"characters\": [");
        for (int i = 0; i <= SCENE_MAX_CHARACTERS; i++) strcat(text, i ? ",{\"model\":\"m\"}" : "{\"model\":\"m\"}");
        strcat(text, "]}");
        expect_parse_fail(text, "characters", "field \"characters\"", "17 entries, more than the maximum 16");
    }
    {
        static char text[1024];
        strcpy(text, "{\"terrain\": {\"type\": \"mesh\", \"mesh\": \"");
        for (int i = 0; i < 300; i++) strcat(text, "a");
        strcat(text, "\"}}");
        expect_parse_fail(text, "long path", "field \"terrain.mesh\"", "longer than the maximum 255");
    }
}

static void test_good_full(void)
{
    char err[512] = "";
    bool ok = scene_load(&desc, DATA "good_full.json", err, sizeof err);
    CHECK_MSG(ok, "%s", err);
    if (!ok) return;
    CHECK(desc.seed == 4294967295u);
    CHECK(desc.frames == 42);
    CHECK_NEAR(desc.dt, 0.025, 1e-7);
    CHECK(desc.size[0] == 640 && desc.size[1] == 360);
    CHECK(desc.msaa == 8);
    CHECK(desc.mode == SCENE_MODE_BLADE);
    CHECK(desc.terrain.type == TERRAIN_MESH);
    CHECK(strcmp(desc.terrain.mesh, "models/torus.obj") == 0);
    CHECK_NEAR(desc.terrain.scale, 2.5, 0);
    const scene_grass_desc_t *g = &desc.grass;
    CHECK_NEAR(g->population.density, 55.5, 0);
    CHECK_NEAR(g->population.height[0], 0.1, 1e-7);
    CHECK_NEAR(g->population.height[1], 0.2, 1e-7);
    CHECK_NEAR(g->population.width[1], 0.03, 1e-7);
    CHECK_NEAR(g->population.stiffness[0], 2, 0);
    CHECK_NEAR(g->billboard_density, 3, 0);
    CHECK_NEAR(g->billboard_size[0], 0.8, 1e-7);
    CHECK_NEAR(g->switch_distance, 9, 0);
    CHECK_NEAR(g->tile_size, 2, 0);
    CHECK(g->population.shape == BLADE_SHAPE_TRIANGLE_TIP);
    CHECK(g->subdiv[0] == 6 && g->subdiv[1] == 3);
    CHECK(g->spring_iterations == 5 && g->cube_resolution == 64);
    CHECK_NEAR(g->recover_time, 1.5, 0);
    const scene_camera_desc_t *c = &desc.camera;
    CHECK(c->position[0] == 1 && c->position[2] == 3 && c->target[1] == 5);
    CHECK(c->fov == 45 && c->near == 0.5f && c->far == 50);
    CHECK(c->path.count == 2);
    CHECK_NEAR(c->path.keys[1].t, 2.5, 0);
    CHECK(c->path.keys[1].position[0] == 3 && c->path.keys[1].target[0] == 1);
    CHECK(desc.wind_count == 2);
    CHECK(desc.wind[0].type == SCENE_WIND_DIRECTIONAL);
    CHECK_NEAR(desc.wind[0].direction[0], 0.6, 1e-6); /* (3,4) normalised */
    CHECK_NEAR(desc.wind[0].direction[1], 0.8, 1e-6);
    CHECK(desc.wind[0].strength == 2 && desc.wind[0].wavelength == 7 && desc.wind[0].speed == 3);
    CHECK(desc.wind[1].type == SCENE_WIND_POINT);
    CHECK(desc.wind[1].position[2] == 3 && desc.wind[1].radius == 4);
    CHECK_NEAR(desc.wind[1].strength, 0.5, 0);
    CHECK(desc.collider_count == 2);
    CHECK(desc.colliders[0].type == SCENE_COLLIDER_BOX);
    CHECK(desc.colliders[0].half_extents[2] == 3);
    CHECK(desc.colliders[0].path.count == 1 && desc.colliders[0].path.keys[0].position[0] == 5);
    CHECK(desc.colliders[1].type == SCENE_COLLIDER_CAPSULE && desc.colliders[1].loop);
    CHECK_NEAR(desc.colliders[1].radius, 0.2, 1e-7);
    CHECK_NEAR(desc.colliders[1].length, 1.8, 1e-7);
    CHECK(desc.colliders[1].path.count == 2 && desc.colliders[1].path.keys[1].position[0] == 2);
    CHECK(desc.character_count == 2);
    CHECK_MSG(strcmp(desc.characters[0].model, "models/h\xc3\xa9\"q/x.gltf") == 0, "decoded: %s",
              desc.characters[0].model);
    CHECK(strcmp(desc.characters[0].clip_name, "walk") == 0 && desc.characters[0].clip_index == -1);
    CHECK(desc.characters[0].speed == 2 && desc.characters[0].scale == 0.5f);
    CHECK(desc.characters[0].waypoint_count == 3 && desc.characters[0].waypoints[2][1] == 2);
    CHECK(desc.characters[0].loop);
    CHECK(desc.characters[1].clip_index == 3 && desc.characters[1].clip_name[0] == 0);
    CHECK_NEAR(desc.characters[1].speed, 1.2, 1e-7); /* default */
    CHECK(!desc.characters[1].loop);
}

static void test_defaults_and_values(void)
{
    if (parse_ok("{}")) {
        CHECK(desc.seed == 0 && desc.frames == 300);
        CHECK_NEAR(desc.dt, 1.0 / 60.0, 1e-9);
        CHECK(desc.size[0] == 1280 && desc.size[1] == 720 && desc.msaa == 4);
        CHECK(desc.mode == SCENE_MODE_HYBRID);
        CHECK(desc.terrain.type == TERRAIN_HEIGHTFIELD && desc.terrain.size == 40);
        CHECK(desc.terrain.resolution == 64 && desc.terrain.height == 1.5f && desc.terrain.scale == 1);
        CHECK(desc.grass.population.density == 200 && desc.grass.billboard_density == 6);
        CHECK(desc.grass.population.height[0] == 0.35f && desc.grass.population.height[1] == 0.7f);
        CHECK(desc.grass.switch_distance == 12 && desc.grass.tile_size == 4);
        CHECK(desc.grass.population.shape == BLADE_SHAPE_QUADRATIC);
        CHECK(desc.grass.subdiv[0] == 4 && desc.grass.subdiv[1] == 4);
        CHECK(desc.grass.spring_iterations == 2 && desc.grass.cube_resolution == 32);
        CHECK(desc.grass.recover_time == 3);
        CHECK(desc.camera.fov == 60 && desc.camera.near == 0.1f && desc.camera.far == 200);
        CHECK(desc.camera.position[1] == 8 && desc.camera.position[2] == 24);
        CHECK(desc.wind_count == 0 && desc.collider_count == 0 && desc.character_count == 0);
        cam_t cam;
        scene_camera_init(&desc, &cam);
        CHECK_NEAR(cam.aspect, 1280.0 / 720.0, 1e-6);
        CHECK(cam.position[2] == 24 && cam.fov == 60);
    }
    /* Entry defaults, number grammar, explicit zero = default. */
    if (parse_ok("{\"msaa\": 0, \"dt\": 0, \"camera\": {\"position\": [-0.5e1, 1E2, 0.125], "
                 "\"target\": [-0, 0.0, 2e-1]},\n"
                 " \"wind\": [{}, {\"type\": \"point\"}], \"colliders\": [{}, {\"type\": \"capsule\"}],"
                 " \"characters\": [{\"model\": \"a\\u00e9\\ud83d\\ude00\\t\"}]}")) {
        CHECK(desc.msaa == 4);
        CHECK_NEAR(desc.dt, 1.0 / 60.0, 1e-9);
        CHECK(desc.camera.position[0] == -5 && desc.camera.position[1] == 100);
        CHECK(desc.camera.position[2] == 0.125f);
        CHECK_NEAR(desc.camera.target[2], 0.2, 1e-7);
        CHECK(desc.wind[0].direction[0] == 1 && desc.wind[0].strength == 1);
        CHECK(desc.wind[0].wavelength == 10 && desc.wind[0].speed == 2);
        CHECK(desc.wind[1].radius == 5);
        CHECK(desc.colliders[0].radius == 0.5f && desc.colliders[1].radius == 0.3f);
        CHECK(desc.colliders[0].path.count == 0);
        CHECK(strcmp(desc.characters[0].model, "a\xc3\xa9\xf0\x9f\x98\x80\t") == 0);
        CHECK(desc.characters[0].clip_index == 0 && desc.characters[0].scale == 1);
    }
    /* Whitespace and a trailing newline after the value are fine. */
    parse_ok(" \r\n\t{ \"seed\" : 7 }\n\n");
    CHECK(desc.seed == 7);
    CHECK(strcmp(scene_mode_name(SCENE_MODE_BLADE), "blade") == 0);
    CHECK(strcmp(scene_blade_shape_name(BLADE_SHAPE_DANDELION), "dandelion") == 0);
}

/* Every proper prefix of a real scene file is rejected with a line number
 * inside the file (no crash, no success on truncated input). */
static void test_all_truncations(void)
{
    char *text = core_fs_read(MEADOW_SOURCE_DIR "/scenes/meadow.json", NULL, NULL, 0);
    CHECK(text != NULL);
    if (!text) return;
    size_t len = strlen(text);
    int lines = 1;
    for (size_t i = 0; i < len; i++) lines += text[i] == '\n';
    int bad = 0;
    for (size_t cut = 0; cut + 1 < len; cut++) {
        char saved = text[cut], err[512] = "";
        text[cut] = 0;
        int line = 0;
        bool ok = scene_parse(&desc, text, "cut", err, sizeof err);
        if (ok || sscanf(err, "cut:%d:", &line) != 1 || line < 1 || line > lines) {
            if (bad++ < 3) fprintf(stderr, "prefix %zu: ok=%d err=%s\n", cut, ok, err);
        }
        text[cut] = saved;
    }
    CHECK_MSG(bad == 0, "%d of %zu prefixes misreported", bad, len - 1);
    free(text);
}

/* The billboard module's subdivision range is the scene's: 0 (default) or
 * [BB_SUBDIV_MIN, BB_SUBDIV_MAX]. */
static void test_subdiv_bounds(void)
{
    expect_parse_fail("{\"grass\": {\"subdiv\": [1, 4]}}", "subdiv 1", "field \"grass.subdiv[0]\"",
                      "1 is out of range [2, 8] (or 0 for the default)");
    expect_parse_fail("{\"grass\": {\"subdiv\": [4, 9]}}", "subdiv 9", "field \"grass.subdiv[1]\"",
                      "9 is out of range [2, 8]");
    if (parse_ok("{\"grass\": {\"subdiv\": [0, 8]}}"))
        CHECK(desc.grass.subdiv[0] == BB_DEFAULT_SUBDIV && desc.grass.subdiv[1] == BB_SUBDIV_MAX);
    if (parse_ok("{\"grass\": {\"subdiv\": [2, 2]}}")) CHECK(desc.grass.subdiv[0] == BB_SUBDIV_MIN);
}

/* docs/SCENES.md equals `meadow --scene-keys` (regenerate with
 * ./build/meadow --scene-keys > docs/SCENES.md). */
static void test_keys_doc(void)
{
    char *md = scene_keys_markdown();
    char *doc = core_fs_read(MEADOW_SOURCE_DIR "/docs/SCENES.md", NULL, NULL, 0);
    CHECK(md != NULL && doc != NULL);
    if (md && doc) {
        size_t i = 0;
        while (md[i] && md[i] == doc[i]) i++;
        CHECK_MSG(md[i] == doc[i], "docs/SCENES.md differs from scene_keys_markdown() at byte %zu: regenerate "
                                   "it with ./build/meadow --scene-keys > docs/SCENES.md", i);
    }
    /* Every row is well formed. */
    for (int i = 0; i < scene_field_count; i++) {
        const scene_field_t *f = &scene_fields[i];
        CHECK_MSG(f->doc && f->doc[0] && f->lo <= f->hi, "row %d (%s)", i, f->key);
        CHECK_MSG(scene_field_find(f->section, f->key) == f, "row %d (%s) is not unique", i, f->key);
        if (f->type == SCENE_FIELD_INTS || f->type == SCENE_FIELD_FLOATS)
            CHECK_MSG(f->n >= 1 && f->n <= 3 && f->size == (size_t)f->n * 4, "row %d (%s)", i, f->key);
    }
    free(md);
    free(doc);
}

/* grass.blade_distance and grass.clearings: defaults, values, errors, and
 * the blade distance resolved from the field's box and the far plane. */
static void test_grass_keys(void)
{
    if (parse_ok("{}")) {
        CHECK(desc.grass.blade_distance == 0 && desc.grass.clearings.type == SCENE_CLEARINGS_NOISE);
        CHECK(desc.grass.clearings.fraction == 0 && desc.grass.clearings.size == 0);
    }
    if (parse_ok("{\"grass\": {\"blade_distance\": 80, \"clearings\": {\"fraction\": 0.2, \"size\": 6}}}")) {
        CHECK(desc.grass.blade_distance == 80 && desc.grass.clearings.type == SCENE_CLEARINGS_NOISE);
        CHECK(desc.grass.clearings.fraction == 0.2f && desc.grass.clearings.size == 6);
    }
    if (parse_ok("{\"grass\": {\"clearings\": {\"type\": \"none\"}}}"))
        CHECK(desc.grass.clearings.type == SCENE_CLEARINGS_NONE);
    if (parse_ok("{\"grass\": {\"clearings\": {\"type\": \"image\", \"image\": \"tests/data/x.png\"}}}"))
        CHECK(desc.grass.clearings.type == SCENE_CLEARINGS_IMAGE &&
              strcmp(desc.grass.clearings.image, "tests/data/x.png") == 0);
    expect_parse_fail("{\n\"grass\": {\"blade_distance\": -1}}", "blade_distance < 0",
                      "inline.json:2: field \"grass.blade_distance\"", "-1 is out of range [0, 1e+06]");
    expect_parse_fail("{\"grass\": {\"blade_distance\": \"far\"}}", "blade_distance type",
                      "field \"grass.blade_distance\": expected number, got string", NULL);
    expect_parse_fail("{\"grass\": {\"clearings\": \"none\"}}", "clearings type",
                      "field \"grass.clearings\": expected object, got string", NULL);
    expect_parse_fail("{\"grass\": {\"clearings\": {\"type\": \"lawn\"}}}", "clearings kind",
                      "field \"grass.clearings.type\": unknown value \"lawn\"", "noise, none, image");
    expect_parse_fail("{\"grass\": {\"clearings\": {\n\"fraction\": 1.5}}}", "fraction > 1",
                      "inline.json:2: field \"grass.clearings.fraction\"", "1.5 is out of range [0, 1]");
    expect_parse_fail("{\"grass\": {\"clearings\": {\"size\": -6}}}", "size < 0",
                      "field \"grass.clearings.size\"", "out of range [0, 10000]");
    expect_parse_fail("{\"grass\": {\"clearings\": {\"size\": [6]}}}", "size type",
                      "field \"grass.clearings.size\": expected number, got array", NULL);
    expect_parse_fail("{\"grass\": {\"clearings\": {\"type\": \"none\", \"fraction\": 0.2}}}", "none + fraction",
                      "field \"grass.clearings.fraction\": unknown key \"fraction\" for clearings type \"none\"",
                      NULL);
    expect_parse_fail("{\"grass\": {\"clearings\": {\"type\": \"image\"}}}", "image missing",
                      "field \"grass.clearings.image\": required but missing", NULL);
    expect_parse_fail("{\"grass\": {\"clearings\": {\"type\": \"image\", \"image\": \"\"}}}", "image empty",
                      "field \"grass.clearings.image\": must not be empty", NULL);
    expect_parse_fail("{\"grass\": {\"clearings\": {\"image\": \"a.png\"}}}", "image for noise",
                      "unknown key \"image\" for clearings type \"noise\"", NULL);

    /* The camera 8 m up, 24 m behind a 40 m field: its farthest corner is
     * (+-20, -1.5, -20), sqrt(20^2 + 9.5^2 + 44^2) = 49.26 m away. */
    scene_grass_desc_t g = {0};
    const float cam[3] = {0, 8, 24}, lo[3] = {-20, -1.5f, -20}, hi[3] = {20, 1.5f, 20};
    float corner = sqrtf(20.0f * 20.0f + 9.5f * 9.5f + 44.0f * 44.0f);
    CHECK_NEAR(scene_blade_distance(&g, cam, 200.0f, lo, hi), corner, 1e-4);
    CHECK(scene_blade_distance(&g, cam, 30.0f, lo, hi) == 30.0f);
    g.blade_distance = 12.5f;
    CHECK(scene_blade_distance(&g, cam, 200.0f, lo, hi) == 12.5f);
    CHECK(scene_blade_distance(&g, cam, 5.0f, lo, hi) == 12.5f);
}

/* SCENES.md's rule about 0, against the table: every numeric key of the
 * non-array sections set to 0 parses exactly when its accepted column
 * allows 0 (scene_field_accepts, which renders that column), and then
 * holds its default (or 0 where 0 is a value of its own). */
static void test_zero_rule(void)
{
    static const char *const open[] = {[SCENE_SEC_ROOT] = "", [SCENE_SEC_TERRAIN] = "\"terrain\": {",
                                       [SCENE_SEC_GRASS] = "\"grass\": {",
                                       [SCENE_SEC_CLEARINGS] = "\"grass\": {\"clearings\": {",
                                       [SCENE_SEC_LOD] = "\"grass\": {\"lod\": {",
                                       [SCENE_SEC_CAMERA] = "\"camera\": {"};
    static const char *const close[] = {[SCENE_SEC_ROOT] = "", [SCENE_SEC_TERRAIN] = "}", [SCENE_SEC_GRASS] = "}",
                                        [SCENE_SEC_CLEARINGS] = "}}", [SCENE_SEC_LOD] = "}}",
                                        [SCENE_SEC_CAMERA] = "}"};
    int checked = 0;
    for (int i = 0; i < scene_field_count; i++) {
        const scene_field_t *f = &scene_fields[i];
        if (f->section > SCENE_SEC_CAMERA || f->type > SCENE_FIELD_RANGE || f->type == SCENE_FIELD_CUSTOM) continue;
        int n = f->type == SCENE_FIELD_RANGE ? 2 : (f->type == SCENE_FIELD_INTS || f->type == SCENE_FIELD_FLOATS) ? f->n : 1;
        char value[64] = "0", text[256], why[160];
        if (f->type >= SCENE_FIELD_INTS) snprintf(value, sizeof value, n == 2 ? "[0, 0]" : "[0, 0, 0]");
        char type[48] = ""; /* a key of some entry types only: the first of them */
        for (int v = 0; f->variants && v < 32; v++)
            if (f->variants & (1u << v)) {
                const char *name = scene_field_find(f->section, "type")->names[v];
                snprintf(type, sizeof type, "\"type\": \"%s\", %s", name,
                         strcmp(name, "mesh") == 0 && strcmp(f->key, "mesh") ? "\"mesh\": \"m.obj\", " : "");
                break;
            }
        snprintf(text, sizeof text, "{%s%s\"%s\": %s%s}", open[f->section], type, f->key, value, close[f->section]);
        scene_desc_t d;
        char err[256];
        bool allowed = scene_field_accepts(f, 0.0, why, sizeof why);
        bool parsed = scene_parse(&d, text, "zero.json", err, sizeof err);
        CHECK_MSG(parsed == allowed, "%s: 0 %s by the parser, %s by the table (%s)", text,
                  parsed ? "accepted" : "refused", allowed ? "allowed" : "not allowed", parsed ? "" : err);
        /* A value of its own that scene.c resolves (camera.position: its default column says how). */
        if (!parsed || !allowed || ((f->flags & SCENE_FIELD_NO_DEFAULT) && f->def_doc && strcmp(f->def_doc, "0")))
            continue;
        char *base = f->section == SCENE_SEC_TERRAIN ? (char *)&d.terrain
                     : f->section == SCENE_SEC_GRASS ? (char *)&d.grass
                     : f->section == SCENE_SEC_CLEARINGS ? (char *)&d.grass.clearings
                     : f->section == SCENE_SEC_LOD       ? (char *)&d.grass.lod
                     : f->section == SCENE_SEC_CAMERA ? (char *)&d.camera
                                                      : (char *)&d;
        for (int k = 0; k < n; k++) {
            bool ints = f->type == SCENE_FIELD_INT || f->type == SCENE_FIELD_INTS || f->type == SCENE_FIELD_U32;
            double got = f->type == SCENE_FIELD_U32 ? ((uint32_t *)(base + f->offset))[k]
                         : ints                      ? ((int *)(base + f->offset))[k]
                                                     : ((float *)(base + f->offset))[k];
            double want = (f->flags & SCENE_FIELD_NO_DEFAULT) ? 0.0 : f->def[k];
            CHECK_MSG(got == want, "%s: component %d is %g, want %g", text, k, got, want);
        }
        checked++;
    }
    CHECK_MSG(checked > 30, "only %d keys took 0", checked);
}

/* characters[].clips: named ranges (frames of the model's first clip) and
 * every bad one refused with its field. */
static void test_clip_ranges(void)
{
    if (parse_ok("{\"characters\": [{\"model\": \"m\", \"clip\": \"walk\", "
                 "\"clips\": {\"walk\": [1, 14], \"run\": [14.5, 30]}}, {\"model\": \"m\"}]}")) {
        const scene_character_t *c = &desc.characters[0];
        CHECK(c->clip_range_count == 2 && !strcmp(c->clip_ranges[0].name, "walk"));
        CHECK(c->clip_ranges[0].range[0] == 1 && c->clip_ranges[0].range[1] == 14);
        CHECK(!strcmp(c->clip_ranges[1].name, "run") && c->clip_ranges[1].range[0] == 14.5f);
        CHECK(!strcmp(c->clip_name, "walk") && desc.characters[1].clip_range_count == 0);
    }
    if (parse_ok("{\"characters\": [{\"model\": \"m\", \"clips\": {}}]}")) CHECK(desc.characters[0].clip_range_count == 0);
    const char *head = "{\"characters\": [{\"model\": \"m\",\n \"clips\": ";
    static const struct {
        const char *clips, *what, *sub1, *sub2;
    } bad[] = {
        {"{\"walk\": [14, 1]}", "reversed", "inline.json:2: field \"characters[0].clips.walk\"",
         "end 1 is not after start 14"},
        {"{\"walk\": [3, 3]}", "empty", "field \"characters[0].clips.walk\"", "end 3 is not after start 3"},
        {"{\"walk\": [-1, 14]}", "negative", "field \"characters[0].clips.walk[0]\"",
         "-1 is out of range [0, 1e+07]"},
        {"{\"walk\": [0, 2e7]}", "too far", "field \"characters[0].clips.walk[1]\"", "out of range [0, 1e+07]"},
        {"{\"walk\": [\"a\", 14]}", "not a number", "field \"characters[0].clips.walk[0]\"",
         "expected number, got string"},
        {"{\"walk\": [1, 14, 20]}", "three", "field \"characters[0].clips.walk\"", "expected an array of 2 numbers"},
        {"{\"walk\": 14}", "not an array", "field \"characters[0].clips.walk\"", "expected array, got number"},
        {"[[1, 14]]", "not an object", "field \"characters[0].clips\"", "expected object, got array"},
        {"{\"\": [1, 14]}", "no name", "field \"characters[0].clips.\"", "a range needs a name"},
        {"{\"2\": [1, 14]}", "index name", "field \"characters[0].clips.2\"", "reads as a clip index"},
        {"{\"1:4\": [1, 14]}", "range name", "field \"characters[0].clips.1:4\"", "reads as a clip range"},
        {"{\"a\": [0, 1], \"b\": [0, 1], \"c\": [0, 1], \"d\": [0, 1], \"e\": [0, 1], \"f\": [0, 1], "
         "\"g\": [0, 1], \"h\": [0, 1], \"i\": [0, 1]}",
         "too many names", "field \"characters[0].clips\"", "9 names, more than the maximum 8 (SCENE_MAX_CLIP_RANGES)"},
        {"{\"walk\": [1, 2], \"walk\": [3, 4]}", "twice", "duplicate key \"walk\"", NULL},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char text[512];
        snprintf(text, sizeof text, "%s%s}]}", head, bad[i].clips);
        expect_parse_fail(text, bad[i].what, bad[i].sub1, bad[i].sub2);
    }
    char text[512], name[80];
    memset(name, 'n', sizeof name - 1);
    name[sizeof name - 1] = 0;
    snprintf(text, sizeof text, "%s{\"%s\": [1, 2]}}]}", head, name);
    expect_parse_fail(text, "long name", "name of 79 bytes is longer than the maximum 63", NULL);
    /* the table's limit is the parser's */
    const scene_field_t *row = scene_field_find(SCENE_SEC_CHARACTER, "clips");
    CHECK(row && row->hi == 1e7 && !strcmp(row->limit, "SCENE_MAX_CLIP_RANGES") && strstr(row->doc, "at most 8 names"));
}

int main(void)
{
    core_log_set_quiet(true);
    test_scene_files();
    test_bad_files();
    test_bad_inline();
    test_good_full();
    test_defaults_and_values();
    test_grass_keys();
    test_all_truncations();
    test_subdiv_bounds();
    test_keys_doc();
    test_zero_rule();
    test_clip_ranges();
    TEST_END();
}

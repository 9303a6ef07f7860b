/* test_scene_lod: the bench's lod.json read back (scene_lod_read) and the
 * pick by renderer and path (scene_lod_choose): a table with both paths,
 * the path asked for, auto taking the cheaper one, another renderer
 * refused, a missing path, and malformed tables refused with the file and
 * what is wrong. */
#include "core/core.h"
#include "scene/scene_lod.h"
#include "test.h"

#include <string.h>

static const char *write_tmp(const char *name, const char *text)
{
    static char path[512];
    snprintf(path, sizeof path, "%s/%s", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp", name);
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    return path;
}

int main(void)
{
    core_log_set_quiet(true);
    const char *good = write_tmp("lod_good.json",
                                 "{\"renderer\": \"GPU X\", \"scene\": \"s.json\", \"paths\": {\n"
                                 " \"hw\": {\"switch_distance\": 25, \"canopy_distance\": 45, \"gpu_ms\": 6.5,"
                                 " \"image_error\": 0.5, \"budget\": 0.6, \"met\": true, \"label\": \"canopy45m\","
                                 " \"candidates\": 5},\n"
                                 " \"compute\": {\"switch_distance\": 20, \"canopy_distance\": 35, \"gpu_ms\": 2.5,"
                                 " \"image_error\": 0.7, \"budget\": 0.6, \"met\": false, \"candidates\": 5}}}\n");
    scene_lod_t t;
    char err[512];
    CHECK(scene_lod_read(&t, good, err, sizeof err));
    CHECK(strcmp(t.renderer, "GPU X") == 0);
    CHECK(t.path[0].present && t.path[1].present && t.path[0].met && !t.path[1].met);
    CHECK(t.path[0].switch_distance == 25.0f && t.path[0].canopy_distance == 45.0f);
    CHECK(strcmp(t.path[0].label, "canopy45m") == 0 && t.path[1].candidates == 5);
    bool compute = true;
    const scene_lod_pick_t *p = scene_lod_choose(&t, "GPU X", 0, &compute);
    CHECK(p == &t.path[0] && !compute);
    p = scene_lod_choose(&t, "GPU X", -1, &compute); /* auto: the cheaper path */
    CHECK(p == &t.path[1] && compute);
    CHECK(scene_lod_choose(&t, "GPU Y", 0, &compute) == NULL);
    CHECK(scene_lod_choose(&t, NULL, 1, &compute) == NULL);

    const char *hw_only = write_tmp("lod_hw.json", "{\"renderer\": \"GPU X\", \"paths\": {\"hw\": {"
                                                   "\"switch_distance\": 25, \"canopy_distance\": 45, \"gpu_ms\": 6,"
                                                   " \"image_error\": 0.5, \"budget\": 0.6, \"met\": true}}}");
    CHECK(scene_lod_read(&t, hw_only, err, sizeof err));
    CHECK(scene_lod_choose(&t, "GPU X", 1, &compute) == NULL);
    p = scene_lod_choose(&t, "GPU X", -1, &compute);
    CHECK(p == &t.path[0] && !compute);

    static const char *const bad[] = {
        "{\"renderer\": \"GPU X\"}",
        "{\"renderer\": \"GPU X\", \"paths\": {}}",
        "{\"renderer\": \"GPU X\", \"paths\": {\"hw\": {\"switch_distance\": 25}}}",
        "{\"renderer\": \"GPU X\", \"paths\": {\"hw\": {\"switch_distance\": 50, \"canopy_distance\": 45, "
        "\"gpu_ms\": 6, \"image_error\": 0.5, \"budget\": 0.6, \"met\": true}}}",
        "[1, 2",
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        const char *path = write_tmp("lod_bad.json", bad[i]);
        err[0] = 0;
        CHECK_MSG(!scene_lod_read(&t, path, err, sizeof err), "bad table %zu accepted", i);
        CHECK_MSG(strstr(err, "lod_bad.json") != NULL, "error '%s' does not name the file", err);
    }
    err[0] = 0;
    CHECK(!scene_lod_read(&t, "/nonexistent/lod.json", err, sizeof err) && strstr(err, "/nonexistent/lod.json"));
    TEST_END();
}

/* test_app_cli: option parsing accepts good values and rejects each bad one
 * with a message naming the option and the bound (for options that set a
 * scene value, the scene key's, from its table); the HUD's timing list
 * leaves out passes that no longer run. */
#include "app/app.h"
#include "test.h"

#include <string.h>

static int parse(app_options_t *o, char *err, int n, char **argv)
{
    return app_parse_args(n, argv, o, err, 256);
}

int main(void)
{
    app_options_t o;
    char err[256];
    char *good[] = {"meadow", "--headless", "--frames", "10", "--seed", "4294967295", "--size",
                    "640x480", "--out", "o", "--screenshot-every", "5", "--mode", "blade", "--scene", "s.json"};
    CHECK(parse(&o, err, 16, good) == 0);
    CHECK(o.headless && o.frames == 10 && o.frames_set && o.seed == 4294967295u && o.seed_set);
    CHECK(o.width == 640 && o.height == 480 && strcmp(o.out, "o") == 0 && o.screenshot_every == 5);
    CHECK(o.mode == APP_MODE_BLADE && strcmp(o.scene, "s.json") == 0);
    /* The harness's options are not the program's (src/bench parses them). */
    char *bench[] = {"meadow", "--quick"};
    CHECK(parse(&o, err, 2, bench) == 2 && strstr(err, "unknown option '--quick'"));

    struct {
        char *a, *b;
        const char *msg;
    } bad[] = {
        {"--frames", "0", "1..10000000 (scene key frames)"}, {"--frames", "10000001", "1..10000000"},
        {"--frames", "1e3", "--frames '1e3'"},   {"--size", "15x100", "16..16384 (scene key size)"},
        {"--size", "100x16385", "16..16384"},    {"--size", "100", "WxH"},
        {"--size", "100x100x", "WxH"},           {"--size", "0x100", "16..16384"},
        {"--seed", "-1", "0..4294967295 (scene key seed)"}, {"--seed", "4294967296", "0..4294967295"},
        {"--seed", "99999999999999999999", "0..4294967295"}, {"--raster-samples", "2", "expected 1 or 4"},
        {"--mode", "", "billboard, blade or hybrid"},
        {"--screenshot-every", "-1", "0..10000000"}, {"--out", "", "empty"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char *argv[] = {"meadow", bad[i].a, bad[i].b};
        err[0] = 0;
        CHECK_MSG(parse(&o, err, 3, argv) == 2 && strstr(err, bad[i].msg), "%s %s -> '%s'", bad[i].a, bad[i].b,
                  err);
    }
    char *missing[] = {"meadow", "--frames"};
    CHECK(parse(&o, err, 2, missing) == 2 && strstr(err, "needs a value"));
    /* HUD: after a switch from blade to billboard mode the blade passes
     * stop; past APP_HUD_STALE_FRAMES frames they leave the list. */
    app_hud_pass_t passes[] = {{"bb.draw", 0.5, 0}, {"blade.sim", 1.25, APP_HUD_STALE_FRAMES},
                               {"blade.draw", 2.0, APP_HUD_STALE_FRAMES + 1}, {"bb.generate", 9.0, 5000}};
    char hud[512];
    int len = app_hud_timings(passes, 4, hud, sizeof hud);
    CHECK_MSG(strstr(hud, "bb.draw") && strstr(hud, "0.500 ms") && strstr(hud, "blade.sim") &&
                  !strstr(hud, "blade.draw") && !strstr(hud, "bb.generate") && len == (int)strlen(hud),
              "hud:\n%s", hud);
    CHECK(app_hud_timings(passes + 2, 2, hud, sizeof hud) == 0 && hud[0] == 0);
    TEST_END();
}

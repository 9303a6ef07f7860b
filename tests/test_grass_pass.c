/* test_grass_pass: the frame's passes (grass_pass_list) for each mode, ground,
 * rasterizer and the reference, written out as the expected sequence of
 * pass names; GL-free. Also the rules alone: billboards never on a world
 * in the hybrid, tiles never for the reference, and the whole field
 * standing in for tiles the world could not make. */
#include "grass/grass_pass.h"
#include "grass/grass.h"
#include "test.h"

#include <string.h>

/* The list as "name name ...", compute grass passes marked with "*". */
static const char *listed(const grass_pass_desc_t *d)
{
    static char out[256];
    grass_pass_t p[GRASS_PASS_KINDS];
    int n = grass_pass_list(d, p);
    out[0] = '\0';
    for (int i = 0; i < n; i++) {
        strcat(out, i ? " " : "");
        strcat(out, grass_pass_name(p[i].kind));
        if (p[i].compute) strcat(out, "*");
    }
    return out;
}

/* Fails, naming the caller's line, when the list of d is not want. */
static void expect(grass_pass_desc_t d, const char *want, int line)
{
    const char *got = listed(&d);
    if (strcmp(got, want) == 0) return;
    fprintf(stderr, "line %d: got \"%s\", want \"%s\"\n", line, got, want);
    test_failures++;
}
#define CHECK_LIST(want, ...) expect((grass_pass_desc_t){__VA_ARGS__}, want, __LINE__)

#define ALL .have_tiles = true, .have_blades = true, .have_billboards = true

static void check_modes(void)
{
    /* Nothing made: the ground alone. */
    CHECK_LIST("ground", 0);
    CHECK_LIST("ground tiles billboards", .mode = SCENE_MODE_HYBRID, ALL);
    CHECK_LIST("ground raster_begin tiles* billboards* raster_end", .mode = SCENE_MODE_HYBRID, ALL, .compute = true);
    CHECK_LIST("ground billboards", .mode = SCENE_MODE_BILLBOARD, ALL);
    CHECK_LIST("ground raster_begin billboards* raster_end", .mode = SCENE_MODE_BILLBOARD, ALL, .compute = true);
    CHECK_LIST("ground blades", .mode = SCENE_MODE_BLADE, ALL);
    CHECK_LIST("ground raster_begin blades* raster_end", .mode = SCENE_MODE_BLADE, ALL, .compute = true);
    /* Hybrid on a mesh: the whole field near, billboards far. */
    CHECK_LIST("ground blades billboards", .mode = SCENE_MODE_HYBRID, .ground = GRASS_GROUND_MESH, ALL);
    /* A world: streamed tiles in blade and hybrid modes, the billboard ring in the hybrid and billboard mode. */
    CHECK_LIST("ground tiles billboards", .mode = SCENE_MODE_HYBRID, .ground = GRASS_GROUND_WORLD, ALL);
    CHECK_LIST("ground tiles", .mode = SCENE_MODE_BLADE, .ground = GRASS_GROUND_WORLD, ALL);
    CHECK_LIST("ground billboards", .mode = SCENE_MODE_BILLBOARD, .ground = GRASS_GROUND_WORLD, ALL);
}

static void check_reference_and_fallbacks(void)
{
    /* The reference: every blade of the field in any mode, no billboards. */
    CHECK_LIST("ground blades", .mode = SCENE_MODE_HYBRID, .reference = true, ALL);
    CHECK_LIST("ground blades", .mode = SCENE_MODE_BILLBOARD, .reference = true, ALL);
    CHECK_LIST("ground raster_begin blades* raster_end", .mode = SCENE_MODE_HYBRID, .reference = true, ALL,
               .compute = true);
    /* A world has no whole field: its reference is tiles (GRASS_REFERENCE_REACH). */
    CHECK_LIST("ground tiles", .mode = SCENE_MODE_BLADE, .ground = GRASS_GROUND_WORLD, .reference = true, ALL);
    CHECK_LIST("ground tiles", .mode = SCENE_MODE_HYBRID, .ground = GRASS_GROUND_WORLD, .reference = true, ALL);
    /* Tiles wanted but not made: the whole field when the world has it. */
    CHECK_LIST("ground blades billboards", .mode = SCENE_MODE_HYBRID, .have_blades = true, .have_billboards = true);
    CHECK_LIST("ground billboards", .mode = SCENE_MODE_HYBRID, .have_billboards = true);
    /* Billboards wanted but not made. */
    CHECK_LIST("ground", .mode = SCENE_MODE_BILLBOARD, .have_blades = true);
    /* The compute rasterizer brackets the grass even when none is drawn. */
    CHECK_LIST("ground raster_begin raster_end", .mode = SCENE_MODE_BLADE, .compute = true);
}

static void check_rules(void)
{
    const scene_hybrid_billboards_t ring = SCENE_HYBRID_BILLBOARDS_RING, none = SCENE_HYBRID_BILLBOARDS_NONE;
    CHECK(grass_pass_wants_billboards(SCENE_MODE_HYBRID, ring));
    CHECK(grass_pass_wants_billboards(SCENE_MODE_BILLBOARD, ring));
    CHECK(!grass_pass_wants_billboards(SCENE_MODE_BLADE, ring));
    /* grass.billboards none: the hybrid only; billboard mode keeps its own. */
    CHECK(!grass_pass_wants_billboards(SCENE_MODE_HYBRID, none));
    CHECK(grass_pass_wants_billboards(SCENE_MODE_BILLBOARD, none));
    CHECK(!grass_pass_wants_blades(SCENE_MODE_BILLBOARD));
    CHECK(grass_pass_uses_tiles(SCENE_MODE_HYBRID, GRASS_GROUND_HEIGHTFIELD, false));
    CHECK(!grass_pass_uses_tiles(SCENE_MODE_HYBRID, GRASS_GROUND_MESH, false));
    CHECK(!grass_pass_uses_tiles(SCENE_MODE_BLADE, GRASS_GROUND_HEIGHTFIELD, false));
    CHECK(grass_pass_uses_tiles(SCENE_MODE_BLADE, GRASS_GROUND_WORLD, false));
    CHECK(!grass_pass_uses_tiles(SCENE_MODE_HYBRID, GRASS_GROUND_HEIGHTFIELD, true));
    CHECK(grass_pass_uses_tiles(SCENE_MODE_BLADE, GRASS_GROUND_WORLD, true));
    CHECK(grass_pass_uses_tiles(SCENE_MODE_HYBRID, GRASS_GROUND_WORLD, true));
    /* The tiles end at the switch, on a world in blade mode at grass.blade_distance. */
    scene_grass_desc_t g = {.switch_distance = 25.0f};
    CHECK(grass_pass_tiles_distance(&g, SCENE_MODE_HYBRID, GRASS_GROUND_WORLD, false) == 25.0f);
    CHECK(grass_pass_tiles_distance(&g, SCENE_MODE_BLADE, GRASS_GROUND_WORLD, false) == GRASS_BLADE_DISTANCE);
    g.blade_distance = 50.0f;
    CHECK(grass_pass_tiles_distance(&g, SCENE_MODE_BLADE, GRASS_GROUND_WORLD, false) == 50.0f);
    CHECK(grass_pass_tiles_distance(&g, SCENE_MODE_BLADE, GRASS_GROUND_HEIGHTFIELD, false) == 25.0f);
    /* a world's reference: its tiles to GRASS_REFERENCE_REACH in any mode */
    CHECK(grass_pass_tiles_distance(&g, SCENE_MODE_BLADE, GRASS_GROUND_WORLD, true) == GRASS_REFERENCE_REACH);
    CHECK(grass_pass_tiles_distance(&g, SCENE_MODE_HYBRID, GRASS_GROUND_WORLD, true) == GRASS_REFERENCE_REACH);
    for (int k = 0; k < GRASS_PASS_KINDS; k++) CHECK(strcmp(grass_pass_name((grass_pass_kind_t)k), "?") != 0);
    grass_pass_t p[GRASS_PASS_KINDS];
    int n = grass_pass_list(&(grass_pass_desc_t){.mode = SCENE_MODE_HYBRID, ALL, .compute = true}, p);
    CHECK(n == GRASS_PASS_KINDS - 1); /* everything but the whole field: the most a frame holds */
    CHECK(grass_pass_has(p, n, GRASS_PASS_TILES) && !grass_pass_has(p, n, GRASS_PASS_BLADES));
    /* The hybrid without its ring: tiles, no billboards, on a world and on a heightfield. */
    n = grass_pass_list(&(grass_pass_desc_t){.mode = SCENE_MODE_HYBRID, .ground = GRASS_GROUND_WORLD, ALL,
                                             .billboards = SCENE_HYBRID_BILLBOARDS_NONE},
                        p);
    CHECK(grass_pass_has(p, n, GRASS_PASS_TILES) && !grass_pass_has(p, n, GRASS_PASS_BILLBOARDS));
    n = grass_pass_list(&(grass_pass_desc_t){.mode = SCENE_MODE_HYBRID, .ground = GRASS_GROUND_HEIGHTFIELD, ALL,
                                             .billboards = SCENE_HYBRID_BILLBOARDS_NONE},
                        p);
    CHECK(grass_pass_has(p, n, GRASS_PASS_TILES) && !grass_pass_has(p, n, GRASS_PASS_BILLBOARDS));
}

int main(void)
{
    check_modes();
    check_reference_and_fallbacks();
    check_rules();
    TEST_END();
}

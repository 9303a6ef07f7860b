/* test_world_pass: the frame's passes (world_pass_list) for each mode, ground,
 * rasterizer and the reference, written out as the expected sequence of
 * pass names; GL-free. Also the rules alone: billboards never on a world
 * in the hybrid, tiles never for the reference, and the whole field
 * standing in for tiles the world could not make. */
#include "world/world_pass.h"
#include "test.h"

#include <string.h>

/* The list as "name name ...", compute grass passes marked with "*". */
static const char *listed(const world_pass_desc_t *d)
{
    static char out[256];
    world_pass_t p[WORLD_PASS_KINDS];
    int n = world_pass_list(d, p);
    out[0] = '\0';
    for (int i = 0; i < n; i++) {
        strcat(out, i ? " " : "");
        strcat(out, world_pass_name(p[i].kind));
        if (p[i].compute) strcat(out, "*");
    }
    return out;
}

/* Fails, naming the caller's line, when the list of d is not want. */
static void expect(world_pass_desc_t d, const char *want, int line)
{
    const char *got = listed(&d);
    if (strcmp(got, want) == 0) return;
    fprintf(stderr, "line %d: got \"%s\", want \"%s\"\n", line, got, want);
    test_failures++;
}
#define CHECK_LIST(want, ...) expect((world_pass_desc_t){__VA_ARGS__}, want, __LINE__)

#define ALL .have_tiles = true, .have_blades = true, .have_billboards = true

static void check_modes(void)
{
    /* Nothing made: the terrain alone. */
    CHECK_LIST("terrain", 0);
    CHECK_LIST("terrain tiles billboards", .mode = SCENE_MODE_HYBRID, ALL);
    CHECK_LIST("terrain characters tiles billboards", .mode = SCENE_MODE_HYBRID, ALL, .have_characters = true);
    CHECK_LIST("terrain raster_begin tiles* billboards* raster_end", .mode = SCENE_MODE_HYBRID, ALL, .compute = true);
    CHECK_LIST("terrain billboards", .mode = SCENE_MODE_BILLBOARD, ALL);
    CHECK_LIST("terrain raster_begin billboards* raster_end", .mode = SCENE_MODE_BILLBOARD, ALL, .compute = true);
    CHECK_LIST("terrain blades", .mode = SCENE_MODE_BLADE, ALL);
    CHECK_LIST("terrain raster_begin blades* raster_end", .mode = SCENE_MODE_BLADE, ALL, .compute = true);
    /* Hybrid on a mesh: the whole field near, billboards far. */
    CHECK_LIST("terrain blades billboards", .mode = SCENE_MODE_HYBRID, .ground = WORLD_GROUND_MESH, ALL);
    /* A world: streamed tiles in blade and hybrid modes, the billboard ring in the hybrid and billboard mode. */
    CHECK_LIST("terrain tiles billboards", .mode = SCENE_MODE_HYBRID, .ground = WORLD_GROUND_WORLD, ALL);
    CHECK_LIST("terrain tiles", .mode = SCENE_MODE_BLADE, .ground = WORLD_GROUND_WORLD, ALL);
    CHECK_LIST("terrain billboards", .mode = SCENE_MODE_BILLBOARD, .ground = WORLD_GROUND_WORLD, ALL);
}

static void check_reference_and_fallbacks(void)
{
    /* The reference: every blade of the field in any mode, no billboards. */
    CHECK_LIST("terrain blades", .mode = SCENE_MODE_HYBRID, .reference = true, ALL);
    CHECK_LIST("terrain blades", .mode = SCENE_MODE_BILLBOARD, .reference = true, ALL);
    CHECK_LIST("terrain raster_begin blades* raster_end", .mode = SCENE_MODE_HYBRID, .reference = true, ALL,
               .compute = true);
    /* Tiles wanted but not made: the whole field when the world has it. */
    CHECK_LIST("terrain blades billboards", .mode = SCENE_MODE_HYBRID, .have_blades = true, .have_billboards = true);
    CHECK_LIST("terrain billboards", .mode = SCENE_MODE_HYBRID, .have_billboards = true);
    /* Billboards wanted but not made. */
    CHECK_LIST("terrain", .mode = SCENE_MODE_BILLBOARD, .have_blades = true);
    /* The compute rasterizer brackets the grass even when none is drawn. */
    CHECK_LIST("terrain raster_begin raster_end", .mode = SCENE_MODE_BLADE, .compute = true);
}

static void check_rules(void)
{
    const scene_hybrid_billboards_t ring = SCENE_HYBRID_BILLBOARDS_RING, none = SCENE_HYBRID_BILLBOARDS_NONE;
    CHECK(world_pass_wants_billboards(SCENE_MODE_HYBRID, ring));
    CHECK(world_pass_wants_billboards(SCENE_MODE_BILLBOARD, ring));
    CHECK(!world_pass_wants_billboards(SCENE_MODE_BLADE, ring));
    /* grass.billboards none: the hybrid only; billboard mode keeps its own. */
    CHECK(!world_pass_wants_billboards(SCENE_MODE_HYBRID, none));
    CHECK(world_pass_wants_billboards(SCENE_MODE_BILLBOARD, none));
    CHECK(!world_pass_wants_blades(SCENE_MODE_BILLBOARD));
    CHECK(world_pass_uses_tiles(SCENE_MODE_HYBRID, WORLD_GROUND_HEIGHTFIELD, false));
    CHECK(!world_pass_uses_tiles(SCENE_MODE_HYBRID, WORLD_GROUND_MESH, false));
    CHECK(!world_pass_uses_tiles(SCENE_MODE_BLADE, WORLD_GROUND_HEIGHTFIELD, false));
    CHECK(world_pass_uses_tiles(SCENE_MODE_BLADE, WORLD_GROUND_WORLD, false));
    CHECK(!world_pass_uses_tiles(SCENE_MODE_HYBRID, WORLD_GROUND_WORLD, true));
    for (int k = 0; k < WORLD_PASS_KINDS; k++) CHECK(strcmp(world_pass_name((world_pass_kind_t)k), "?") != 0);
    world_pass_t p[WORLD_PASS_KINDS];
    int n = world_pass_list(&(world_pass_desc_t){.mode = SCENE_MODE_HYBRID, ALL, .have_characters = true, .compute = true},
                          p);
    CHECK(n == WORLD_PASS_KINDS - 1); /* everything but the whole field: the most a frame holds */
    CHECK(world_pass_has(p, n, WORLD_PASS_TILES) && !world_pass_has(p, n, WORLD_PASS_BLADES));
    /* The hybrid without its ring: tiles, no billboards, on a world and on a heightfield. */
    n = world_pass_list(&(world_pass_desc_t){.mode = SCENE_MODE_HYBRID, .ground = WORLD_GROUND_WORLD, ALL,
                                             .billboards = SCENE_HYBRID_BILLBOARDS_NONE},
                        p);
    CHECK(world_pass_has(p, n, WORLD_PASS_TILES) && !world_pass_has(p, n, WORLD_PASS_BILLBOARDS));
    n = world_pass_list(&(world_pass_desc_t){.mode = SCENE_MODE_HYBRID, .ground = WORLD_GROUND_HEIGHTFIELD, ALL,
                                             .billboards = SCENE_HYBRID_BILLBOARDS_NONE},
                        p);
    CHECK(world_pass_has(p, n, WORLD_PASS_TILES) && !world_pass_has(p, n, WORLD_PASS_BILLBOARDS));
}

int main(void)
{
    check_modes();
    check_reference_and_fallbacks();
    check_rules();
    TEST_END();
}

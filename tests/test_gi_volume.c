/* test_gi_volume: the ambient-occlusion and irradiance volumes of
 * gi_volume.h against analytic cases: open ground sees the whole sky (AO 1,
 * a constant sky L gives irradiance pi L facing up, half of it facing
 * sideways, the ground's bounce facing down); a V valley, a wall and the
 * grass layer each lower the AO and the up-facing ambient, the wall turns
 * the irradiance away from itself; the trilinear sample reads cell values
 * at cell centres; start-up cost on a meadow_large-sized field. */
#include "gi/gi_volume.h"
#include "test.h"

#include <math.h>
#include <string.h>

static float valley(const void *user, float x, float z)
{
    (void)z;
    return *(const float *)user * fabsf(x);
}

static float hills(const void *user, float x, float z)
{
    (void)user;
    return 3.0f * sinf(x * 0.06f) * cosf(z * 0.05f);
}

static float half_cover(const void *user, float x, float z)
{
    (void)user;
    (void)z;
    return x < 0.0f ? 1.0f : 0.0f;
}

/* A volume over [-20, 20]^2, y in [0, 8]: 16 x 16 x 16 cells. */
static gi_volume_desc_t small_desc(void)
{
    return (gi_volume_desc_t){.res = {16, 16, 16}, .lo = {-20.0f, 0.0f, -20.0f}, .hi = {20.0f, 8.0f, 20.0f}};
}

static void test_open_ground(void)
{
    gi_volume_desc_t d = small_desc();
    const float sky[3] = {0.3f, 0.5f, 0.9f};
    memcpy(d.sky_zenith, sky, sizeof sky);
    memcpy(d.sky_horizon, sky, sizeof sky);
    gi_volume_t v;
    CHECK(gi_volume_make(&v, &d, &(gi_scene_t){0}));
    const float top[3] = {1.0f, 7.75f, -3.0f}, low[3] = {1.0f, 0.1f, -3.0f};
    const float up[3] = {0, 1, 0}, down[3] = {0, -1, 0}, side[3] = {1, 0, 0};
    float ao, irr[GI_IRR_FLOATS], a[3];
    gi_volume_sample(&v, top, &ao, irr);
    CHECK_NEAR(ao, 1.0, 1e-5);
    gi_volume_sample(&v, low, &ao, irr);
    CHECK_NEAR(ao, 1.0, 1e-5);
    for (int c = 0; c < 3; c++) CHECK_NEAR(irr[c] + irr[6 + c], sky[c], 1e-5); /* irradiance / pi facing up */
    gi_volume_ambient(&v, top, up, a);
    for (int c = 0; c < 3; c++) CHECK_NEAR(a[c], sky[c], 1e-5);
    gi_volume_ambient(&v, top, down, a);
    for (int c = 0; c < 3; c++) CHECK_NEAR(a[c], v.bounce[c], 1e-5);
    gi_volume_ambient(&v, top, side, a);
    for (int c = 0; c < 3; c++) CHECK_NEAR(a[c], 0.5f * (sky[c] + v.bounce[c]), 1e-5);
    gi_volume_free(&v);
}

/* The default sky: open ground facing up has GI_AMBIENT_UP's luminance. */
static void test_default_sky(void)
{
    gi_volume_desc_t d = small_desc();
    gi_volume_t v;
    CHECK(gi_volume_make(&v, &d, &(gi_scene_t){0}));
    const float p[3] = {0.0f, 4.0f, 0.0f}, up[3] = {0, 1, 0}, want[3] = GI_AMBIENT_UP;
    float a[3];
    gi_volume_ambient(&v, p, up, a);
    float lum = 0.2126f * a[0] + 0.7152f * a[1] + 0.0722f * a[2];
    CHECK_NEAR(lum, 0.2126f * want[0] + 0.7152f * want[1] + 0.0722f * want[2], 1e-4);
    CHECK(a[2] > a[0]); /* the sky's blue */
    gi_volume_free(&v);
}

static void test_valley(void)
{
    gi_volume_desc_t d = small_desc();
    float slope = 0.8f;
    gi_volume_t v;
    CHECK(gi_volume_make(&v, &d, &(gi_scene_t){.height = valley, .user = &slope}));
    const float bottom[3] = {0.0f, 0.05f, 0.0f}, flank[3] = {6.0f, 4.85f, 0.0f}, up[3] = {0, 1, 0};
    float ao_bottom, ao_flank, irr[GI_IRR_FLOATS], a_bottom[3], a_open[3];
    gi_volume_sample(&v, bottom, &ao_bottom, irr);
    gi_volume_sample(&v, flank, &ao_flank, irr);
    printf("valley (slope %.1f): AO at the bottom %.3f, on the flank %.3f\n", slope, ao_bottom, ao_flank);
    /* Walls rising at alpha = atan(0.8) = 38.7 deg on both sides of a long
     * valley: the bottom's sky view factor is cos(alpha) = 0.78 (the walls
     * seen 24 m far at most and from the cells' centres 1.25 m off the
     * axis: a little more). */
    CHECK(ao_bottom > 0.72f && ao_bottom < 0.9f);
    CHECK(ao_flank > ao_bottom + 0.03f);
    gi_volume_ambient(&v, bottom, up, a_bottom);
    gi_volume_t open;
    CHECK(gi_volume_make(&open, &d, &(gi_scene_t){0}));
    gi_volume_ambient(&open, bottom, up, a_open);
    for (int c = 0; c < 3; c++) CHECK(a_bottom[c] < a_open[c]);
    gi_volume_free(&open);
    gi_volume_free(&v);
}

static void test_wall(void)
{
    gi_volume_desc_t d = small_desc();
    gi_object_t wall = {.lo = {2.5f, 0.0f, -20.0f}, .hi = {4.0f, 8.0f, 20.0f}};
    gi_volume_t v;
    CHECK(gi_volume_make(&v, &d, &(gi_scene_t){.objects = &wall, .object_count = 1}));
    const float p[3] = {1.25f, 0.75f, 1.25f}, far[3] = {-16.25f, 0.75f, 1.25f};
    float ao, ao_far, irr[GI_IRR_FLOATS], irr_far[GI_IRR_FLOATS];
    gi_volume_sample(&v, p, &ao, irr);
    gi_volume_sample(&v, far, &ao_far, irr_far);
    printf("wall: AO beside it %.3f, 17 m away %.3f; Bx %.3f\n", ao, ao_far, irr[3]);
    CHECK(ao < 0.75f && ao > 0.3f);
    CHECK(ao_far > 0.97f);
    for (int c = 0; c < 3; c++) CHECK(irr[3 + c] < -0.01f); /* light comes from -x, away from the wall */
    gi_volume_free(&v);
}

static void test_grass(void)
{
    gi_volume_desc_t d = small_desc();
    gi_scene_t s = {.cover = half_cover, .grass_height = 1.0f, .grass_extinction = 3.0f, .grass_near = 0.1f};
    gi_volume_t v;
    CHECK(gi_volume_make(&v, &d, &s));
    const float in[3] = {-11.25f, 0.25f, 0.0f}, out[3] = {11.25f, 0.25f, 0.0f}, above[3] = {-11.25f, 3.25f, 0.0f};
    float ao_in, ao_out, ao_above, irr[GI_IRR_FLOATS];
    gi_volume_sample(&v, in, &ao_in, irr);
    gi_volume_sample(&v, out, &ao_out, irr);
    gi_volume_sample(&v, above, &ao_above, irr);
    printf("grass layer: AO inside %.3f, in the clearing %.3f, above %.3f\n", ao_in, ao_out, ao_above);
    CHECK(ao_in < 0.5f * ao_out);
    CHECK_NEAR(ao_out, 1.0, 1e-5);
    CHECK_NEAR(ao_above, 1.0, 1e-5);
    gi_volume_free(&v);
}

/* Cell centres read the cell, midpoints the mean, outside clamps. */
static void test_sample(void)
{
    gi_volume_desc_t d = small_desc();
    float slope = 0.5f;
    gi_volume_t v;
    CHECK(gi_volume_make(&v, &d, &(gi_scene_t){.height = valley, .user = &slope}));
    int nx = v.res[0], ny = v.res[1];
    size_t c0 = ((size_t)3 * (size_t)ny + 2) * (size_t)nx + 7, c1 = c0 + 1;
    const float centre[3] = {-20.0f + 7.5f * 2.5f, 2.5f * 0.5f, -20.0f + 3.5f * 2.5f};
    const float mid[3] = {centre[0] + 1.25f, centre[1], centre[2]};
    float ao, irr[GI_IRR_FLOATS];
    gi_volume_sample(&v, centre, &ao, irr);
    CHECK_NEAR(ao, v.ao[c0], 1e-6);
    CHECK_NEAR(irr[4], v.irr[c0 * GI_IRR_FLOATS + 4], 1e-6);
    gi_volume_sample(&v, mid, &ao, irr);
    CHECK_NEAR(ao, 0.5f * (v.ao[c0] + v.ao[c1]), 1e-6);
    const float below[3] = {0.0f, -5.0f, 0.0f}, edge[3] = {0.0f, 0.25f, 0.0f};
    float ao_below;
    gi_volume_sample(&v, below, &ao_below, irr);
    gi_volume_sample(&v, edge, &ao, irr);
    CHECK_NEAR(ao_below, ao, 1e-6);
    gi_volume_free(&v);
}

static void test_bad_desc(void)
{
    gi_volume_t v;
    CHECK(!gi_volume_make(&v, &(gi_volume_desc_t){.hi = {1, 1, 1}, .lo = {1, 0, 0}}, &(gi_scene_t){0}));
    CHECK(v.ao == NULL);
}

/* The default resolution over meadow_large's field (200 m, hills of 3 m,
 * grass 0.7 m): start-up cost, printed; bounded generously for the CI
 * machine. */
static void test_cost(void)
{
    gi_volume_desc_t d = {.lo = {-100.0f, -3.0f, -100.0f}, .hi = {100.0f, 5.7f, 100.0f}};
    gi_volume_t v;
    CHECK(gi_volume_make(&v, &d, &(gi_scene_t){.height = hills, .grass_height = 0.7f, .grass_extinction = 4.4f}));
    printf("64x16x64 volume over 200 m: %.1f ms\n", v.build_ms);
    CHECK(v.build_ms < 2000.0);
    gi_volume_free(&v);
}

int main(void)
{
    test_open_ground();
    test_default_sky();
    test_valley();
    test_wall();
    test_grass();
    test_sample();
    test_bad_desc();
    test_cost();
    TEST_END();
}

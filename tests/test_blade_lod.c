/* test_blade_lod: the coverage-preserving thinning of blade_lod.h on a
 * seeded strip of blades. Across a dolly the kept blades' drawn width
 * (weight x scale x width) sums to the full field's within 5 % wherever
 * the widening is not capped; every blade that a step of the dolly culls
 * was narrowed first (frame to frame, the shrink window), and without the
 * window the same check fails; the ground's share is 1 - coverage and 0
 * where nothing is thinned; the levels rules keep eq. 20's blades. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "blade/blade_lod.h"
#include "core/core.h"
#include "test.h"

#define N 200000
#define STRIP 400.0f /* m along the dolly's axis */

static float pos[N], width[N];

static void seed(void)
{
    core_rng_t rng;
    core_rng_seed(&rng, 7, 0);
    for (int i = 0; i < N; i++) {
        /* Morton-like order along the strip: sorted positions, so index
         * low bits spread over the ground as in a patch */
        pos[i] = STRIP * ((float)i + core_rng_float(&rng)) / (float)N;
        width[i] = 0.02f + 0.02f * core_rng_float(&rng);
    }
}

/* Sum of drawn width over the blades between d0 and d1 from a camera at
 * distance `cam` before the strip's start, relative to the full field's. */
static double coverage_ratio(const blade_lod_t *l, float cam, float d0, float d1, float focal, float cull)
{
    double drawn = 0.0, full = 0.0;
    for (int i = 0; i < N; i++) {
        float d = cam + pos[i];
        if (d < d0 || d >= d1) continue;
        blade_lod_draw_t b = blade_lod_blade(l, (uint32_t)i, d, width[i], focal, cull);
        drawn += (double)(b.weight * b.scale * width[i]);
        full += (double)width[i];
    }
    return drawn / full;
}

/* Blades of the strip's first 40 m that go from drawn to culled between
 * two camera distances while drawn at a weight above `tol`: pops. */
static int pops(const blade_lod_t *l, float cam0, float cam1, float focal, float cull, float tol)
{
    int n = 0;
    for (int i = 0; i < N / 10; i++) {
        blade_lod_draw_t a = blade_lod_blade(l, (uint32_t)i, cam0 + pos[i], width[i], focal, cull);
        blade_lod_draw_t b = blade_lod_blade(l, (uint32_t)i, cam1 + pos[i], width[i], focal, cull);
        if (a.weight > tol && b.weight == 0.0f) n++;
    }
    return n;
}

int main(void)
{
    seed();
    const float focal = 1080.0f / (2.0f * tanf(0.5f * 60.0f * 3.14159265f / 180.0f));
    const float cull = 1e6f;
    blade_lod_t l = blade_lod_defaults(&(blade_lod_t){.no_fade = true});

    /* coverage constant across a dolly: the band 40-60 m ahead, camera
     * moving 0..50 m back; the widening caps where u < 1/8 (beyond
     * max(start, w f / w_px) * 8, at least 80 m), so this band is in range */
    for (float back = 0.0f; back <= 50.0f; back += 5.0f) {
        double r = coverage_ratio(&l, back - 40.0f, 40.0f, 60.0f, focal, cull);
        CHECK_MSG(fabs(r - 1.0) <= 0.05, "coverage %.4f at camera %.0f m back (kept x width not constant)", r, back);
    }
    /* and thinning really happens there: fewer blades kept than exist */
    {
        int kept = 0, all = 0;
        for (int i = 0; i < N; i++) {
            float d = pos[i];
            if (d < 40.0f || d >= 60.0f) continue;
            all++;
            kept += blade_lod_blade(&l, (uint32_t)i, d, width[i], focal, cull).weight > 0.0f;
        }
        CHECK_MSG(kept < all / 2, "kept %d of %d at 40-60 m: no thinning", kept, all);
    }
    /* without compensation the same band covers less: the metric moves */
    {
        blade_lod_t off = blade_lod_defaults(&(blade_lod_t){.no_fade = true, .no_compensation = true});
        double r = coverage_ratio(&off, 0.0f, 40.0f, 60.0f, focal, cull);
        CHECK_MSG(r < 0.6, "uncompensated coverage %.3f should fall", r);
        float g = blade_lod_ground(&off, 50.0f, 0.03f, focal, cull);
        CHECK_MSG(g > 0.4f && g < 1.0f, "ground share %.3f where thinning removed blades", g);
    }
    /* the ground stays as it is where nothing is thinned */
    CHECK(blade_lod_ground(&l, 5.0f, 0.03f, focal, cull) == 0.0f);
    CHECK(fabsf(blade_lod_ground(&l, 50.0f, 0.03f, focal, cull)) < 1e-4f);

    /* no pops frame to frame: the camera backs away in 0.2 m steps over 120 m */
    {
        int with = 0, without = 0;
        blade_lod_t hard = blade_lod_defaults(&(blade_lod_t){.no_fade = true, .no_shrink = true});
        for (float c = 0.0f; c < 120.0f; c += 0.2f) {
            with += pops(&l, c, c + 0.2f, focal, cull, 0.15f);
            if (c < 30.0f) without += pops(&hard, c, c + 0.2f, focal, cull, 0.15f);
        }
        CHECK_MSG(with == 0, "%d blades culled while drawn at > 15 %% weight", with);
        CHECK_MSG(without > 100, "dropping the shrink window gives only %d pops: the check cannot fail", without);
    }
    /* the end fade: blades shrink over the last metres before the cull */
    {
        blade_lod_t f = blade_lod_defaults(&(blade_lod_t){0});
        CHECK(blade_lod_blade(&f, 0, 58.0f, 0.03f, focal, 60.0f).weight <= 0.5f + 1e-5f);
        CHECK(blade_lod_blade(&f, 0, 61.0f, 0.03f, focal, 60.0f).weight == 0.0f);
        for (float c = 50.0f; c < 70.0f; c += 0.2f) CHECK(pops(&f, c, c + 0.2f, focal, 100.0f, 0.15f) == 0);
    }
    /* eq. 19-20: levels keep (index mod n) <= level, widened by n / kept;
     * the printed inequality keeps 1 in n near the camera */
    {
        blade_lod_t lv = blade_lod_defaults(&(blade_lod_t){.rule = BLADE_LOD_LEVELS, .no_fade = true});
        blade_lod_t pr = blade_lod_defaults(&(blade_lod_t){.rule = BLADE_LOD_PRINTED, .no_fade = true});
        int near_lv = 0, near_pr = 0;
        for (uint32_t i = 0; i < 800; i++) {
            near_lv += blade_lod_blade(&lv, i, 3.0f, 0.03f, focal, 60.0f).weight > 0.0f;
            near_pr += blade_lod_blade(&pr, i, 3.0f, 0.03f, focal, 60.0f).weight > 0.0f;
        }
        CHECK_MSG(near_lv == 800, "levels kept %d of 800 at 3 m", near_lv);
        CHECK_MSG(near_pr == 100, "printed kept %d of 800 at 3 m (1 in 8 expected)", near_pr);
        blade_lod_draw_t far = blade_lod_blade(&lv, 8, 59.0f, 0.03f, focal, 60.0f);
        CHECK(far.weight > 0.0f && fabsf(far.scale - 8.0f) < 1e-4f);
        CHECK(blade_lod_blade(&lv, 9, 59.0f, 0.03f, focal, 60.0f).weight == 0.0f);
    }
    /* A(u, s) against a numeric integral of the weight */
    for (float u = 0.01f; u <= 1.0f; u += 0.07f) {
        double sum = 0.0;
        for (int k = 0; k < 100000; k++) {
            float r = ((float)k + 0.5f) / 100000.0f;
            sum += fminf(fmaxf((u * 1.1f - r) / 0.1f, 0.0f), 1.0f);
        }
        CHECK_MSG(fabs(sum / 100000.0 - blade_lod_area(u, 0.1f)) < 1e-4, "A(%.2f) %.5f vs %.5f", u,
                  blade_lod_area(u, 0.1f), sum / 100000.0);
    }
    /* the focal length from a view-projection */
    {
        float vp[16] = {0};
        float f = 1.0f / tanf(0.5f * 60.0f * 3.14159265f / 180.0f);
        vp[0] = f / 1.5f, vp[5] = f, vp[10] = -1.0f, vp[11] = -1.0f, vp[14] = -0.1f;
        CHECK(fabsf(blade_lod_focal(vp, 1080) - focal) < 1e-2f);
    }
    if (test_failures) return 1;
    printf("test_blade_lod: ok\n");
    return 0;
}

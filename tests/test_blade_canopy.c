/* test_blade_canopy: the ground canopy's table (blade_canopy.h) against an
 * independent estimate. Blades placed uniformly at random form a Boolean
 * model: the gap a ray along dir meets is exp(-rho E[A_dir] / sin e), A_dir
 * a blade's area projected along dir (over sin e: the ground area of roots
 * whose blade the ray crosses), e the elevation, here integrated over blade_ref_surface
 * of blades seeded and settled apart from the table's (own generator, own
 * integration, no ray casting), and the same below the cut heights (the
 * blades' area below the cut). Also: values in range and finite, cover
 * falling as the view rises, cover growing with density, cover below a cut
 * growing with the cut to the whole column's, the same seed giving the same
 * table, the blades' segments, the lookups, the thinning rule, the
 * overhang rule and the wind poses (rest pose, weights, the undersides of
 * blades bent towards the viewer darker). */
#include "blade/blade_canopy.h"
#include "blade/blade_ref.h"
#include "core/core.h"
#include "scene/scene_fields.h"
#include "test.h"

#include <string.h>

/* Mean area of a settled default blade projected along dir (unit), over
 * n blades, by the midpoint rule on 32 x 4 surface cells: of the cells
 * whose centre lies below `below` (m). */
static double projected_area(const float dir[3], int n, float below)
{
    core_rng_t rng;
    core_rng_seed(&rng, 7u, 3u);
    blade_env_t env = blade_env_defaults(&(blade_env_t){.dt = SCENE_DEFAULT_DT, .gravity = 1.0f});
    enum { NV = 32, NU = 4 };
    double sum = 0.0;
    for (int k = 0; k < n; k++) {
        float h = core_rng_range(&rng, BLADE_DEFAULT_HEIGHT_MIN, BLADE_DEFAULT_HEIGHT_MAX);
        float w = core_rng_range(&rng, BLADE_DEFAULT_WIDTH_MIN, BLADE_DEFAULT_WIDTH_MAX);
        float s = core_rng_range(&rng, BLADE_DEFAULT_STIFFNESS_MIN, BLADE_DEFAULT_STIFFNESS_MAX);
        float a = core_rng_range(&rng, 0.0f, 6.2831853f);
        blade_t b = {.v0 = {0, 0, 0, a}, .v1 = {0, h, 0, h}, .v2 = {0, h, 0, w}, .up = {0, 1, 0, s}};
        float eta = 0.0f;
        for (int i = 0; i < 90; i++) blade_ref_step_one(&b, &eta, &env, NULL);
        for (int i = 0; i < NV; i++)
            for (int j = 0; j < NU; j++) {
                float p[4][3], nrm[3];
                float u0 = (float)j / NU, u1 = (float)(j + 1) / NU, v0 = (float)i / NV, v1 = (float)(i + 1) / NV;
                blade_ref_surface(&b, 0, u0, v0, p[0], nrm);
                blade_ref_surface(&b, 0, u1, v0, p[1], nrm);
                blade_ref_surface(&b, 0, u0, v1, p[2], nrm);
                blade_ref_surface(&b, 0, u1, v1, p[3], nrm);
                /* the cell as a parallelogram of its two diagonals */
                float d1[3], d2[3], c[3];
                for (int q = 0; q < 3; q++) d1[q] = p[3][q] - p[0][q], d2[q] = p[2][q] - p[1][q];
                c[0] = d1[1] * d2[2] - d1[2] * d2[1];
                c[1] = d1[2] * d2[0] - d1[0] * d2[2];
                c[2] = d1[0] * d2[1] - d1[1] * d2[0];
                if (p[0][1] + p[1][1] + p[2][1] + p[3][1] < 4.0f * below)
                    sum += 0.5 * fabs(c[0] * dir[0] + c[1] * dir[1] + c[2] * dir[2]);
            }
    }
    return sum / n;
}

int main(void)
{
    core_log_set_quiet(true);
    blade_canopy_t c, again, dense;
    CHECK(blade_canopy_make(&c, &(blade_canopy_desc_t){.seed = 3, .sun = {0.45f, 0.8f, 0.35f}}));
    printf("table of %d blades\n", c.blades);
    CHECK(c.rows == 16 && c.blades == 800);
    bool finite = true, in_range = true;
    for (int r = 0; r < c.rows; r++) {
        const blade_canopy_row_t *w = &c.row[r];
        enum { NF = sizeof *w / sizeof(float) };
        float f[NF];
        memcpy(f, w, sizeof f);
        for (int k = 0; k < NF; k++) finite = finite && isfinite(f[k]);
        /* ao in [0.45, 1], v in [0, 1], the normal's parts in [-1, 1]: each
         * moment within its ao's */
        in_range = in_range && w->cover >= 0 && w->cover <= 1 && w->ao[0] >= 0.45f - 1e-6f &&
                   w->ao[0] <= 1.0f + 1e-6f && w->v_ao[0] >= 0 && w->v_ao[0] <= w->ao[0] + 1e-6f;
        for (int m = 1; m < 4; m++)
            in_range = in_range && fabsf(w->ao[m]) <= w->ao[0] + 1e-6f && fabsf(w->v_ao[m]) <= w->v_ao[0] + 1e-6f;
        for (int k = 0; k < BLADE_CANOPY_SUNS; k++)
            for (int j = 0; j < BLADE_CANOPY_AZIMUTHS; j++)
                in_range = in_range && w->sun[k][j][0] >= 0 && w->sun[k][j][0] <= 1.0f + 1e-6f &&
                           w->sun[k][j][1] >= 0 && w->sun[k][j][1] <= w->sun[k][j][0] + 1e-6f;
    }
    CHECK(finite && in_range);
    CHECK(c.row[0].cover > 0.99f);                   /* along the ground: all grass */
    CHECK(c.row[c.rows - 1].cover < c.row[4].cover); /* from above: ground between the blades */
    /* grazing rays meet the blades' upper parts (mean v = E[v ao] / E[ao]) */
    CHECK(c.row[1].v_ao[0] / c.row[1].ao[0] > c.row[8].v_ao[0] / c.row[8].ao[0]);
    /* the desc's sun is one of the table's elevations; the sun overhead is one
     * whatever the azimuth */
    int ks = (int)lroundf((asinf(0.8f / sqrtf(0.45f * 0.45f + 0.8f * 0.8f + 0.35f * 0.35f)) - c.sun0) /
                          BLADE_CANOPY_SUN_STEP);
    CHECK(c.sun0 <= -1.5707963f && c.sun0 + (BLADE_CANOPY_SUNS - 1) * BLADE_CANOPY_SUN_STEP >= 1.5707963f);
    CHECK_NEAR(c.sun0 + (float)ks * BLADE_CANOPY_SUN_STEP, asinf(0.8f / sqrtf(0.9650f)), 1e-6);
    /* the faces a viewer sees are lit with the sun behind the viewer (azimuth
     * 0), backlit with the sun ahead */
    CHECK(c.row[2].sun[ks][0][0] > 2.0f * c.row[2].sun[ks][BLADE_CANOPY_AZIMUTHS - 1][0]);
    /* seen from straight above the faces met look up: a sun below the ground
     * (the first elevation, at or past the nadir) barely lights them */
    const blade_canopy_row_t *top = &c.row[c.rows - 1];
    CHECK(top->sun[0][0][0] < 0.25f * top->sun[ks][0][0]);
    /* the normals' mean leans towards the viewer and up */
    CHECK(c.row[4].ao[1] > 0.0f && top->ao[2] > 0.0f);

    /* the Boolean model, at the rows whose gap is measurable */
    int compared = 0;
    double worst = 0.0;
    for (int r = 1; r < c.rows; r++) {
        float e = c.elevation[r], dir[3] = {cosf(e), -sinf(e), 0.0f};
        double want = 1.0 - exp(-200.0 * projected_area(dir, 400, INFINITY) / sin(e));
        if (want > 0.97) continue;
        double err = fabs(c.row[r].cover - want);
        printf("elevation %5.1f deg: cover %.3f, Boolean model %.3f, mean v %.2f, sun behind / ahead %.2f / %.2f\n",
               e * 57.29578f, c.row[r].cover, want, c.row[r].v_ao[0] / c.row[r].ao[0], c.row[r].sun[ks][0][0],
               c.row[r].sun[ks][BLADE_CANOPY_AZIMUTHS - 1][0]);
        worst = fmax(worst, err);
        compared++;
    }
    printf("%d rows compared, worst |cover - model| %.3f\n", compared, worst);
    CHECK(compared >= 5);
    CHECK(worst < 0.04);

    /* The cuts: a ray entering at the cut height meets the blades' parts
     * below it, a Boolean model of their area below the cut. The cover
     * below a cut grows with it to the whole column's, and the points met
     * lie lower on the blades (mean v) than the whole column's. */
    printf("top of the blades %.3f m\n", c.top);
    CHECK(c.top > 0.3f && c.top <= 0.7f);
    bool monotone = true, lower = true;
    double worst_cut = 0.0;
    int cuts_compared = 0;
    for (int r = 1; r < c.rows; r++) {
        for (int k = 0; k < BLADE_CANOPY_CUTS; k++) {
            float next = k + 1 < BLADE_CANOPY_CUTS ? c.below[r][k + 1].cover : c.row[r].cover;
            monotone = monotone && c.below[r][k].cover <= next;
        }
        const blade_canopy_row_t *low = &c.below[r][0];
        lower = lower && low->v_ao[0] / low->ao[0] < c.row[r].v_ao[0] / c.row[r].ao[0];
        if (r % 3 != 0) continue; /* the model's integral is slow under the sanitizers */
        float e = c.elevation[r], dir[3] = {cosf(e), -sinf(e), 0.0f};
        for (int k = 2; k < BLADE_CANOPY_CUTS; k += 2) { /* the model's cells are 1-2 cm: above them */
            float h = ldexpf(c.top, k - BLADE_CANOPY_CUTS);
            double want = 1.0 - exp(-200.0 * projected_area(dir, 100, h) / sin(e));
            if (want > 0.97) continue;
            printf("elevation %5.1f deg, cut %.2f m: cover %.3f, Boolean model %.3f\n", e * 57.29578f, h,
                   c.below[r][k].cover, want);
            worst_cut = fmax(worst_cut, fabs(c.below[r][k].cover - want));
            cuts_compared++;
        }
    }
    printf("%d cuts compared, worst |cover - model| %.3f\n", cuts_compared, worst_cut);
    CHECK(monotone && lower);
    CHECK(cuts_compared >= 6);
    CHECK(worst_cut < 0.05);
    float e7 = 0.13f; /* 7.5 degrees, the seam scenes' */
    blade_canopy_row_t whole = blade_canopy_at(&c, e7);
    CHECK(blade_canopy_at_cut(&c, 0, e7, c.top).cover == whole.cover);
    CHECK(blade_canopy_at_cut(&c, 0, e7, 5.0f).cover == whole.cover);
    CHECK(blade_canopy_at_cut(&c, 0, e7, 1e-6f).cover < 1e-4f);
    float step = ldexpf(c.top, -BLADE_CANOPY_CUTS), prev = 0.0f; /* the lowest cut */
    bool grows = true;
    for (int i = 1; i <= 40; i++) {
        float cover = blade_canopy_at_cut(&c, 0, e7, (float)i / 40.0f * c.top).cover;
        grows = grows && cover >= prev;
        prev = cover;
    }
    CHECK(grows);
    printf("7.5 degrees: cover %.3f, below the cuts", whole.cover);
    for (int k = 0; k < BLADE_CANOPY_CUTS; k++) printf(" %.3f", blade_canopy_at_cut(&c, 0, e7, ldexpf(step, k)).cover);
    printf("\n");
    CHECK(blade_canopy_at_cut(&c, 0, e7, step).cover < whole.cover - 0.2f);
    /* half way between levels: linear below the lowest cut, log2 above */
    blade_canopy_row_t a = blade_canopy_at_cut(&c, 0, e7, step), b = blade_canopy_at_cut(&c, 0, e7, 2.0f * step);
    CHECK_NEAR(blade_canopy_at_cut(&c, 0, e7, 0.5f * step).cover, 0.5f * a.cover, 1e-5);
    CHECK_NEAR(blade_canopy_at_cut(&c, 0, e7, sqrtf(2.0f) * step).cover, 0.5f * (a.cover + b.cover), 1e-5);
    CHECK_NEAR(blade_canopy_at_cut(&c, 0, e7, sqrtf(2.0f) * step).ao[0], 0.5f * (a.ao[0] + b.ao[0]), 1e-5);

    CHECK(blade_canopy_make(&again, &(blade_canopy_desc_t){.seed = 3, .sun = {0.45f, 0.8f, 0.35f}}));
    CHECK(memcmp(&c, &again, sizeof c) == 0);
    CHECK(blade_canopy_make(&dense,
                            &(blade_canopy_desc_t){.seed = 3, .population = {.density = 400.0f}, .sun = {0, 1, 0}}));
    CHECK(dense.row[c.rows - 1].cover > c.row[c.rows - 1].cover + 0.05f);

    /* Flat ground lit by the desc's sun: the colour the table gave before it
     * was in the ground's frame (one sun elevation, the ambient's moments in
     * world up), printed by that table's blade_canopy_color for this seed
     * and its one patch: the same within float rounding. */
    blade_canopy_t one;
    CHECK(blade_canopy_make(&one, &(blade_canopy_desc_t){.seed = 3, .sun = {0.45f, 0.8f, 0.35f}, .patches = 1}));
    static const struct {
        float e, phi, rgbc[4];
    } before[] = {
        {0.05f, 0.2f, {0.2050041f, 0.3179236f, 0.09432796f, 1.0f}},
        {0.05f, 1.3f, {0.1485427f, 0.2356416f, 0.07277186f, 1.0f}},
        {0.05f, 2.9f, {0.08196926f, 0.1386697f, 0.04735731f, 1.0f}},
        {0.30f, 0.2f, {0.1644544f, 0.2675467f, 0.07525511f, 0.9948999f}},
        {0.30f, 1.3f, {0.1102004f, 0.1840228f, 0.05433178f, 0.9948999f}},
        {0.30f, 2.9f, {0.05842819f, 0.1043919f, 0.03436898f, 0.9948999f}},
        {0.80f, 0.2f, {0.133748f, 0.2290114f, 0.06138906f, 0.8550678f}},
        {0.80f, 1.3f, {0.08761715f, 0.1536674f, 0.04339475f, 0.8550678f}},
        {0.80f, 2.9f, {0.04548073f, 0.08505315f, 0.02696826f, 0.8550678f}},
        {1.50f, 0.2f, {0.126133f, 0.2160765f, 0.06054408f, 0.1735907f}},
        {1.50f, 1.3f, {0.1067757f, 0.1817749f, 0.05286689f, 0.1735907f}},
        {1.50f, 2.9f, {0.08281945f, 0.1417334f, 0.04347918f, 0.1735907f}},
    };
    static const float root[3] = {0.10f, 0.25f, 0.05f}, tip[3] = {0.45f, 0.65f, 0.20f};
    double flat_worst = 0.0;
    for (size_t i = 0; i < sizeof before / sizeof before[0]; i++) {
        float rgbc[4];
        blade_canopy_view_t v = {.elevation = before[i].e, .sun_elevation = asinf(0.8f / sqrtf(0.9650f)),
                                 .azimuth = before[i].phi, .up = {0.0f, 1.0f, 0.0f}};
        blade_canopy_color(&one, &v, root, tip, rgbc, &rgbc[3]);
        for (int k = 0; k < 4; k++) flat_worst = fmax(flat_worst, fabs(rgbc[k] - before[i].rgbc[k]));
    }
    printf("flat ground: worst |colour - the flat table's| %.2g\n", flat_worst);
    CHECK(flat_worst < 2e-6);

    blade_canopy_row_t mid = blade_canopy_at(&c, 0.5f * (c.elevation[3] + c.elevation[4]));
    CHECK_NEAR(mid.cover, 0.5f * (c.row[3].cover + c.row[4].cover), 1e-5);
    CHECK_NEAR(blade_canopy_at(&c, 2.0f).cover, c.row[c.rows - 1].cover, 1e-6);
    CHECK_NEAR(blade_canopy_thinned(0.75f, 0.5f), 0.5f, 1e-6);
    CHECK_NEAR(blade_canopy_thinned(0.75f, 1.0f), 0.75f, 1e-6);
    CHECK(blade_canopy_thinned(0.75f, 0.0f) == 0.0f);
    CHECK(blade_canopy_thinned(1.0f, 0.0f) == 0.0f); /* full cover in a clearing: no grass, not NaN */
    /* The overhang: every blade drawn leaves the cut column; a cut at the
     * ground (cover 0) the whole column thinned as blade_canopy_under thins
     * it; no blade drawn the whole column. */
    const float full[4] = {0.2f, 0.3f, 0.1f, 0.9f}, cut[4] = {0.1f, 0.15f, 0.05f, 0.4f}, none[4] = {0.1f, 0.1f,
                                                                                                    0.1f, 0.0f};
    float o[4];
    blade_canopy_overhang(full, cut, 1.0f, o);
    for (int k = 0; k < 4; k++) CHECK_NEAR(o[k], cut[k], 1e-6);
    blade_canopy_overhang(full, cut, 0.0f, o);
    for (int k = 0; k < 4; k++) CHECK_NEAR(o[k], full[k], 1e-6);
    blade_canopy_overhang(full, none, 0.3f, o);
    for (int k = 0; k < 3; k++) CHECK_NEAR(o[k], full[k], 1e-6);
    CHECK_NEAR(o[3], blade_canopy_under(full[3], 1.0f, 0.3f), 1e-5);
    blade_canopy_overhang(full, cut, 0.5f, o);
    CHECK(o[3] > cut[3] && o[3] < full[3]);
    blade_canopy_overhang(cut, cut, 0.5f, o); /* a cut at the top: nothing above it */
    for (int k = 0; k < 4; k++) CHECK_NEAR(o[k], cut[k], 1e-6);
    /* the blades cut as the tiles draw them where the canopy takes over */
    CHECK(blade_canopy_make(&again, &(blade_canopy_desc_t){.seed = 3, .sun = {0.45f, 0.8f, 0.35f}, .segments = 2}));
    CHECK(again.row[2].ao[0] != c.row[2].ao[0]);
    CHECK(!blade_canopy_make(&again,
                             &(blade_canopy_desc_t){.segments = BLADE_CANOPY_MAX_SEGMENTS + 1, .sun = {0, 1, 0}}));
    CHECK(!blade_canopy_make(&again, &(blade_canopy_desc_t){.rows = 1, .sun = {0, 1, 0}}));
    CHECK(!blade_canopy_make(&again, &(blade_canopy_desc_t){.seed = 3})); /* no sun */

    /* Wind poses: the rest pose is the calm table's; the weights pick the
     * poses at their nodes and sum to 1 between them; blades bent towards
     * the viewer show their undersides, darker than bent away. 1,024 rays
     * and 8 rows keep the nine poses cheap. */
    static blade_canopy_t calm, windy;
    blade_canopy_desc_t wd = {.seed = 3, .sun = {0.45f, 0.8f, 0.35f}, .segments = 2, .rays = 1024, .rows = 8};
    CHECK(blade_canopy_make(&calm, &wd));
    wd.wind = 1.0f;
    CHECK(blade_canopy_make(&windy, &wd));
    CHECK(calm.poses == 1 && calm.windy == NULL && windy.poses == BLADE_CANOPY_POSES && windy.windy);
    CHECK(memcmp(calm.row, windy.row, sizeof calm.row) == 0 && memcmp(calm.below, windy.below, sizeof calm.below) == 0);
    float wt[BLADE_CANOPY_POSES];
    blade_canopy_wind_weights(&windy, 0.0f, 1.0f, wt);
    CHECK(wt[0] == 1.0f);
    blade_canopy_wind_weights(&calm, 0.7f, 1.0f, wt); /* no poses: at rest */
    CHECK(wt[0] == 1.0f);
    double node_err = 0.0, sum_err = 0.0;
    for (int m = 0; m < BLADE_CANOPY_WIND_STEPS; m++)
        for (int k = 0; k < BLADE_CANOPY_WIND_AZIMUTHS; k++) {
            blade_canopy_wind_weights(&windy, (float)(m + 1) / BLADE_CANOPY_WIND_STEPS, 1.5707963f * (float)k, wt);
            for (int p = 0; p < BLADE_CANOPY_POSES; p++)
                node_err = fmax(node_err, fabs(wt[p] - (p == 1 + m * BLADE_CANOPY_WIND_AZIMUTHS + k ? 1.0f : 0.0f)));
        }
    for (int i = 0; i < 50; i++) {
        blade_canopy_wind_weights(&windy, 0.03f * (float)i, 0.37f * (float)i - 3.0f, wt);
        double sum = 0.0;
        for (int p = 0; p < BLADE_CANOPY_POSES; p++) sum += wt[p];
        sum_err = fmax(sum_err, fabs(sum - 1.0));
    }
    printf("wind weights: worst at the nodes %.2g, worst |sum - 1| %.2g\n", node_err, sum_err);
    CHECK(node_err < 1e-5 && sum_err < 1e-5);
    float lum[3];
    for (int d = 0; d < 3; d++) {
        float rgbc[4];
        blade_canopy_view_t v = {.elevation = 0.13f, .sun_elevation = asinf(0.8f / sqrtf(0.9650f)), .azimuth = 0.5f,
                                 .up = {0.0f, 1.0f, 0.0f}, .wind = d ? 0.5f : 0.0f,
                                 .wind_azimuth = d == 2 ? 3.1415927f : 0.0f};
        blade_canopy_color(&windy, &v, root, tip, rgbc, &rgbc[3]);
        lum[d] = 0.2126f * rgbc[0] + 0.7152f * rgbc[1] + 0.0722f * rgbc[2];
    }
    printf("luminance at 7.5 degrees: at rest %.4f, wind 0.5 towards the viewer %.4f, away %.4f\n", lum[0], lum[1],
           lum[2]);
    CHECK(lum[1] < 0.9f * lum[0] && lum[2] > 1.05f * lum[0]);
    blade_canopy_free(&windy);
    CHECK(windy.windy == NULL);
    TEST_END();
}

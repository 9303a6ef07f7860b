/* test_bb_layout: procedural billboard content (Orthmann et al. 2009,
 * sec. 3). Layout textures must be deterministic by seed, tile, and look
 * like what they claim (clearings, mostly-up directions); clump textures
 * must have 10-60 % opaque coverage in many thin blades, not a rectangle;
 * the generation rule must follow the extent map and its documented hash
 * formula, on the candidate grid and on mesh triangles (by true area, a
 * vertical face as dense as level ground). The clumps are the blade model's (blade_clump_desc_t): every texel
 * holds an albedo on the line from the root's to the tip's (the desc's, not
 * a fixed green), darker below; blades stand at their height in metres, or
 * the layer shrinks so the tallest fits; nothing is cut at the sides or the
 * top; more blades or a wider shape cover more; bb_clump_blades is the
 * documented (pi / 2) density ratio. The extent's clearings follow
 * bb_extent_desc_t: none, a bare fraction, a blob size, an image. The view
 * bakes (bb_view.h) differ as the sun, the wind and the elevation make them
 * differ (test_views). Writes the PNGs to $MEADOW_TEST_OUT for inspection. */
#include "billboard/bb_layout.h"
#include "blade/blade_ref.h"
#include "test.h"

#include <string.h>
#include <unistd.h>

static bool images_equal(const core_image_t *a, const core_image_t *b)
{
    return a->w == b->w && a->h == b->h && a->channels == b->channels &&
           !memcmp(a->px, b->px, (size_t)a->w * a->h * a->channels);
}

static void test_determinism(void)
{
    bb_layout_t a, b, c;
    bb_layout_desc_t d = {.seed = 1, .size = 128, .clump_size = 64};
    CHECK(bb_layout_generate(&a, &d));
    CHECK(bb_layout_generate(&b, &d));
    d.seed = 2;
    CHECK(bb_layout_generate(&c, &d));
    CHECK(images_equal(&a.extent, &b.extent) && images_equal(&a.direction, &b.direction) &&
          images_equal(&a.messiness, &b.messiness));
    for (int k = 0; k < a.clump_layers; k++) CHECK(images_equal(&a.clumps[k], &b.clumps[k]));
    CHECK(!images_equal(&a.extent, &c.extent) && !images_equal(&a.direction, &c.direction) &&
          !images_equal(&a.messiness, &c.messiness) && !images_equal(&a.clumps[0], &c.clumps[0]));
    CHECK(a.extent.w == 128 && a.clumps[0].w == 64 && a.clump_layers == 4);
    bb_layout_free(&a);
    bb_layout_free(&b);
    bb_layout_free(&c);
}

static void test_maps(const bb_layout_t *l)
{
    int n = l->extent.w, clear = 0, dense = 0;
    double mean = 0.0, wrap = 0.0, inner = 0.0;
    for (int y = 0; y < n; y++) {
        for (int x = 0; x < n; x++) {
            int e = l->extent.px[y * n + x];
            mean += e;
            clear += e < 20;
            dense += e > 200;
            int right = l->extent.px[y * n + (x + 1) % n];
            if (x == n - 1) wrap += abs(e - right);
            else if (x == n / 2) inner += abs(e - right);
        }
    }
    mean /= (double)n * n * 255.0;
    printf("extent: mean %.2f, clearings %.1f%%, dense %.1f%%, wrap seam %.2f vs interior %.2f per texel\n", mean,
           100.0 * clear / (n * n), 100.0 * dense / (n * n), wrap / n, inner / n);
    CHECK(mean > 0.3 && mean < 0.9);
    CHECK(clear > n * n / 20 && dense > n * n / 5);
    CHECK(wrap / n < 3.0 * inner / n + 1.0); /* tiles: the seam looks like any other column */
    double minx = 1, maxx = -1, miny = 1;
    for (int i = 0; i < n * n; i++) {
        float d[3], len = 0;
        for (int k = 0; k < 3; k++) {
            d[k] = l->direction.px[i * 3 + k] / 255.0f * 2.0f - 1.0f;
            len += d[k] * d[k];
        }
        CHECK_NEAR(sqrt(len), 1.0, 0.02);
        minx = fmin(minx, d[0]);
        maxx = fmax(maxx, d[0]);
        miny = fmin(miny, d[1]);
    }
    printf("direction: x in [%.2f, %.2f], min y %.2f\n", minx, maxx, miny);
    CHECK(miny > 0.85 && maxx - minx > 0.1);
    int mlo = 255, mhi = 0;
    for (int i = 0; i < n * n; i++) {
        mlo = l->messiness.px[i] < mlo ? l->messiness.px[i] : mlo;
        mhi = l->messiness.px[i] > mhi ? l->messiness.px[i] : mhi;
    }
    CHECK(mlo < 60 && mhi > 190);
}

static void test_clumps(const bb_layout_t *l)
{
    for (int k = 0; k < l->clump_layers; k++) {
        const core_image_t *im = &l->clumps[k];
        int w = im->w, h = im->h, opaque = 0, x0 = w, x1 = -1, y0 = h, y1 = -1;
        double top = 0, bottom = 0, r = 0, g = 0, b = 0, lum_base = 0, lum_mid = 0;
        int n_base = 0, n_mid = 0, partial = 0;
        for (int y = 0; y < h; y++) {
            for (int x = 0; x < w; x++) {
                const uint8_t *p = im->px + ((size_t)y * w + x) * 4;
                if (y < h / 3) top += p[3];
                if (y >= 2 * h / 3) bottom += p[3];
                partial += p[3] > 0 && p[3] < 255;
                if (p[3] <= 127) continue;
                opaque++;
                x0 = x < x0 ? x : x0;
                x1 = x > x1 ? x : x1;
                y0 = y < y0 ? y : y0;
                y1 = y > y1 ? y : y1;
                r += p[0];
                g += p[1];
                b += p[2];
                double lum = 0.3 * p[0] + 0.6 * p[1] + 0.1 * p[2];
                if (y >= h - h / 10) lum_base += lum, n_base++;
                else if (y > h / 3 && y < 2 * h / 3) lum_mid += lum, n_mid++;
            }
        }
        /* Blades crossing the row at 60 % height: count transparent->opaque edges. */
        int row = h - 1 - (int)(0.6 * h), edges = 0;
        for (int x = 1; x < w; x++)
            edges += im->px[((size_t)row * w + x) * 4 + 3] > 127 && im->px[((size_t)row * w + x - 1) * 4 + 3] <= 127;
        double cover = (double)opaque / (w * h);
        double fill = (double)opaque / ((x1 - x0 + 1) * (y1 - y0 + 1));
        printf("clump %d: %.1f%% opaque, bbox fill %.2f, %d blade edges at 60%% height, %d AA pixels, "
               "rgb %.0f %.0f %.0f, base/mid luminance %.0f/%.0f\n", k, 100 * cover, fill, edges, partial,
               r / opaque, g / opaque, b / opaque, lum_base / n_base, lum_mid / n_mid);
        CHECK(cover > 0.10 && cover < 0.80);
        CHECK(fill < 0.85);             /* not a rectangle */
        CHECK(edges >= 8);              /* many thin blades */
        CHECK(bottom > 2.0 * top);      /* a clump: dense base, sparse tips */
        CHECK(partial > opaque / 10);   /* antialiased edges */
        CHECK(g > r && g > 1.5 * b);    /* green */
        CHECK(lum_base < 0.85 * lum_mid); /* darker at the base */
        if (k > 0) CHECK(!images_equal(im, &l->clumps[0]));
        /* The coverage calibration: more blades than the field's density
         * gives (their overlaps made the layer let more ground through),
         * stopping at the blade that reaches the target. */
        const blade_clump_stats_t *st = &l->clump_stats[k];
        printf("clump %d: %d blades (52 for the density), mean alpha %.3f, target %.3f\n", k, st->blades, st->alpha,
               st->target);
        CHECK(st->blades > 52 && st->alpha >= st->target && st->alpha < st->target + 0.02);
    }
}

static void test_sample(const bb_layout_t *l)
{
    bb_gen_desc_t d = {.seed = 77};
    int n = l->extent.w, accepted = 0, zero_acc = 0, full_rej = 0, layer_count[4] = {0};
    double expect = 0.0;
    for (int iz = -n / 2; iz < n / 2; iz++) {
        for (int ix = -n / 2; ix < n / 2; ix++) {
            int tx = ((ix % n) + n) % n, tz = ((iz % n) + n) % n;
            int e = l->extent.px[tz * n + tx];
            expect += e / 255.0;
            bb_point_t p, q;
            bool ok = bb_layout_sample(l, &d, ix, iz, &p);
            CHECK(ok == bb_layout_sample(l, &d, ix, iz, &q));
            if (e == 0) zero_acc += ok;
            if (e == 255) full_rej += !ok;
            if (!ok) continue;
            accepted++;
            CHECK(!memcmp(&p, &q, sizeof p));
            /* The documented hash formula, recomputed here. */
            uint32_t h = core_hash_u32((uint32_t)ix * 0x8da6b343u ^ core_hash_u32((uint32_t)iz ^ core_hash_u32(77u)));
            CHECK(p.seed == h);
            CHECK(p.position[0] >= ix * 0.25f && p.position[0] <= (ix + 1) * 0.25f);
            CHECK(p.position[2] >= iz * 0.25f && p.position[2] <= (iz + 1) * 0.25f);
            CHECK(p.layer < 4);
            if (p.layer < 4) layer_count[p.layer]++;
            CHECK(p.size[0] >= 0.4f - 1e-6f && p.size[0] <= 0.6f + 1e-6f);
            CHECK(p.size[1] > 0.0f && p.size[1] <= 0.56f + 1e-6f);
            CHECK(p.angle >= 0.0f && p.angle < 6.2832f);
            CHECK_NEAR(sqrt(p.growth[0] * p.growth[0] + p.growth[1] * p.growth[1] + p.growth[2] * p.growth[2]),
                       1.0, 1e-5);
            CHECK(p.state == BB_STATE_IDLE && p.recover_time == 0.0f);
        }
    }
    double rate = (double)accepted / (n * n), want = expect / (n * n);
    printf("sample: accepted %.3f of candidates (extent mean %.3f), layers %d %d %d %d\n", rate, want,
           layer_count[0], layer_count[1], layer_count[2], layer_count[3]);
    CHECK(fabs(rate - want) < 0.02);
    CHECK(zero_acc == 0 && full_rej == 0);
    for (int k = 0; k < 4; k++) CHECK(fabs(layer_count[k] / (double)accepted - 0.25) < 0.02);
    /* cells_per_texel = 2: cells (2t, 2t+1) share texel t. */
    bb_gen_desc_t d2 = {.seed = 77, .cells_per_texel = 2, .spacing = 0.5f, .origin = {10.0f, -3.0f}};
    bb_point_t p;
    int agree = 0, tried = 0;
    for (int iz = 0; iz < 64; iz++) {
        for (int ix = 0; ix < 64; ix++) {
            if (!bb_layout_sample(l, &d2, ix, iz, &p)) continue;
            tried++;
            agree += p.messiness == l->messiness.px[iz / 2 * n + ix / 2] / 255.0f;
            CHECK(p.position[0] >= 10.0f + ix * 0.5f && p.position[0] <= 10.0f + (ix + 1) * 0.5f);
            CHECK(p.position[2] >= -3.0f + iz * 0.5f && p.position[2] <= -3.0f + (iz + 1) * 0.5f);
        }
    }
    CHECK_MSG(tried > 0 && agree == tried, "%d of %d agree", agree, tried);
}

/* The triangle rule (bb_layout_sample_tri): frames, faces looking down or
 * of no area refused; with the extent map full, a vertical and a level
 * triangle of the same area get area / spacing^2 roots (to 3 %), every
 * root on its triangle, the documented hash, and a vertical face reads the
 * layout texel of its (z, y) position. */
static void test_sample_tri(const bb_layout_t *l)
{
    bb_gen_tri_t t;
    const float o[3] = {0, 0, 0}, x[3] = {1, 0, 0}, z[3] = {0, 0, 1}, y[3] = {0, 1, 0};
    CHECK(!bb_gen_tri_make(o, x, o, 0.25f, &t) && t.cells[0] == 0);
    CHECK(!bb_gen_tri_make(o, x, z, 0.25f, &t));  /* (1,0,0) x (0,0,1) = -y: looks down */
    CHECK(bb_gen_tri_make(o, z, x, 0.25f, &t));   /* looks up */
    CHECK(t.plane == 1 && fabsf(t.length - sqrtf(2.0f)) < 1e-6f && t.cells[0] == 6 && t.cells[1] == 3);
    CHECK(bb_gen_tri_make(o, y, z, 0.25f, &t) && t.plane == 0); /* looks along -x: vertical */

    bb_layout_t full = *l;
    core_image_t ext;
    CHECK(core_image_alloc(&ext, l->extent.w, l->extent.h, 1));
    memset(ext.px, 255, (size_t)ext.w * ext.h);
    full.extent = ext;
    bb_gen_desc_t d = {.seed = 5, .spacing = 0.25f, .origin = {-3.0f, 2.0f}};
    /* 12 x 9 m right triangles, 54 m^2: level, and vertical facing +x. */
    const float tris[2][3][3] = {{{-6, 0.5f, 0}, {-6, 0.5f, 9}, {6, 0.5f, 0}}, {{0, -4, -6}, {0, 8, -6}, {0, -4, 3}}};
    for (int k = 0; k < 2; k++) {
        CHECK(bb_gen_tri_make(tris[k][0], tris[k][1], tris[k][2], d.spacing, &t));
        CHECK(t.plane == (k ? 0 : 1));
        int n = 0, off = 0, texel = 0;
        for (int j = 0; j < t.cells[1]; j++) {
            for (int i = 0; i < t.cells[0]; i++) {
                bb_point_t p;
                if (!bb_layout_sample_tri(&full, &d, &t, 7u + (uint32_t)k, i, j, &p)) continue;
                n++;
                uint32_t name = 7u + (uint32_t)k;
                uint32_t h = core_hash_u32((uint32_t)i * 0x8da6b343u ^
                                           core_hash_u32((uint32_t)j ^ core_hash_u32(name ^ core_hash_u32(5u))));
                CHECK(p.seed == h);
                /* On the triangle: in its plane, inside its xz (level) or zy (vertical) bounds. */
                float a = k ? p.position[2] : p.position[0], b = k ? p.position[1] : p.position[2];
                float flat = k ? p.position[0] : p.position[1] - 0.5f;
                float a0 = -6.0f, b0 = k ? -4.0f : 0.0f, al = k ? 9.0f : 12.0f, bl = k ? 12.0f : 9.0f;
                off += !(fabsf(flat) < 1e-6f && a >= a0 - 1e-5f && b >= b0 - 1e-5f &&
                         (a - a0) / al + (b - b0) / bl <= 1.0f + 1e-5f);
                if (k == 1) {
                    int tx = ((int)floorf((p.position[2] - 2.0f) / 0.25f) % l->extent.w + l->extent.w) % l->extent.w;
                    int ty = ((int)floorf(p.position[1] / 0.25f) % l->extent.h + l->extent.h) % l->extent.h;
                    texel += p.messiness == l->messiness.px[ty * l->extent.w + tx] / 255.0f;
                }
            }
        }
        printf("sample_tri %s: %d roots, %.3f of area / spacing^2, %d off the triangle, texel agrees %d\n",
               k ? "vertical" : "level", n, n / (54.0 / 0.0625), off, texel);
        CHECK(fabs(n / (54.0 / 0.0625) - 1.0) < 0.03);
        CHECK(off == 0);
        CHECK(k == 0 || texel == n);
    }
    core_image_free(&ext);
}

/* Where the texel colours of one layer lie against the line root -> tip:
 * the largest distance from it (0..1 per channel) and the mean parameter
 * t (0 root, 1 tip) of the texels with alpha >= 1/2 in the bottom and the
 * top quarter of the covered rows. */
static void albedo_line(const core_image_t *im, const float root[3], const float tip[3], double *off, double *t_low,
                        double *t_high)
{
    double d[3], dd = 0.0;
    for (int k = 0; k < 3; k++) {
        d[k] = tip[k] - root[k];
        dd += d[k] * d[k];
    }
    int top = im->h, bottom = -1;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++)
            if (im->px[((size_t)y * im->w + x) * 4 + 3] >= 128) {
                top = y < top ? y : top;
                bottom = y > bottom ? y : bottom;
            }
    double lo = 0, hi = 0, nlo = 0, nhi = 0;
    *off = 0.0;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) {
            const uint8_t *p = im->px + ((size_t)y * im->w + x) * 4;
            if (p[3] == 0) continue;
            double t = 0.0, e2 = 0.0;
            for (int k = 0; k < 3; k++) t += (p[k] / 255.0 - root[k]) * d[k] / dd;
            for (int k = 0; k < 3; k++) {
                double r = p[k] / 255.0 - (root[k] + t * d[k]);
                e2 += r * r;
            }
            *off = fmax(*off, sqrt(e2));
            if (p[3] < 128) continue;
            if (y >= bottom - (bottom - top) / 4) lo += t, nlo++;
            if (y <= top + (bottom - top) / 4) hi += t, nhi++;
        }
    *t_low = lo / fmax(nlo, 1.0);
    *t_high = hi / fmax(nhi, 1.0);
}

/* Rows [first, last] holding any coverage, and whether the outermost
 * columns are clear. */
static void covered_rows(const core_image_t *im, int *first, int *last, bool *sides_clear)
{
    *first = im->h;
    *last = -1;
    *sides_clear = true;
    for (int y = 0; y < im->h; y++)
        for (int x = 0; x < im->w; x++) {
            if (im->px[((size_t)y * im->w + x) * 4 + 3] == 0) continue;
            *first = y < *first ? y : *first;
            *last = y > *last ? y : *last;
            *sides_clear = *sides_clear && x > 0 && x < im->w - 1;
        }
}

static double mean_alpha(const bb_layout_t *l)
{
    double a = 0.0;
    size_t n = (size_t)l->clumps[0].w * l->clumps[0].h;
    for (int k = 0; k < l->clump_layers; k++)
        for (size_t i = 0; i < n; i++) a += l->clumps[k].px[i * 4 + 3] / 255.0;
    return a / (double)(n * (size_t)l->clump_layers);
}

static void test_blade_clumps(void)
{
    CHECK(bb_clump_blades(200.0f, 6.0f) == 52 && bb_clump_blades(160.0f, 6.0f) == 42);
    CHECK(bb_clump_blades(20.0f, 2.0f) == 16 && bb_clump_blades(0.01f, 6.0f) == 1);
    bb_layout_desc_t dd = bb_layout_desc_defaults(NULL);
    CHECK(dd.blades == 52 && dd.clump.size[0] == 1.0f && dd.clump.size[1] == 0.6f &&
          dd.clump.population.gravity == 1.0f);
    CHECK(dd.clump.population.height[0] == 0.35f && dd.clump.population.height[1] == 0.7f &&
          dd.clump.population.width[1] == 0.05f);
    CHECK(dd.clump.population.albedo_root[1] == 0.25f && dd.clump.population.albedo_tip[1] == 0.65f);

    /* The default blades: albedo on the root -> tip line, roots darker. */
    bb_layout_t l;
    CHECK(bb_layout_generate(&l, &(bb_layout_desc_t){.seed = 3, .size = 16}));
    for (int k = 0; k < l.clump_layers; k++) {
        double off, lo, hi;
        albedo_line(&l.clumps[k], dd.clump.population.albedo_root, dd.clump.population.albedo_tip, &off, &lo, &hi);
        int first, last;
        bool sides;
        covered_rows(&l.clumps[k], &first, &last, &sides);
        printf("clump %d (default blades): off the root-tip line %.4f, t bottom %.2f top %.2f, rows %d..%d, "
               "sides clear %d\n",
               k, off, lo, hi, first, last, sides);
        CHECK(off < 3.0 / 255.0);
        CHECK(lo < 0.3 && hi > 0.6);
        /* Tallest settled blade ~0.7 m > 0.98 x 0.6 m: scaled to fit just under the top. */
        CHECK(first >= 1 && first <= 6 && last == l.clumps[k].h - 1 && sides);
    }
    double a52 = mean_alpha(&l);
    bb_layout_free(&l);

    /* Another albedo is taken as it is. */
    bb_layout_desc_t d = {.seed = 3,
                          .size = 16,
                          .clump.population = {.albedo_root = {0.8f, 0.1f, 0.1f}, .albedo_tip = {0.1f, 0.1f, 0.9f}}};
    CHECK(bb_layout_generate(&l, &d));
    double off, lo, hi;
    albedo_line(&l.clumps[0], d.clump.population.albedo_root, d.clump.population.albedo_tip, &off, &lo, &hi);
    printf("red-to-blue blades: off the line %.4f, t bottom %.2f top %.2f\n", off, lo, hi);
    CHECK(off < 3.0 / 255.0 && lo < 0.3 && hi > 0.6);
    bb_layout_free(&l);

    /* Short blades stand at their height in metres: 0.3 m of 0.6 m. */
    d = (bb_layout_desc_t){.seed = 3, .size = 16, .clump.population.height = {0.29f, 0.3f}};
    CHECK(bb_layout_generate(&l, &d));
    int first, last;
    bool sides;
    covered_rows(&l.clumps[0], &first, &last, &sides);
    printf("0.3 m blades in a 0.6 m layer: rows %d..%d of %d\n", first, last, l.clumps[0].h);
    CHECK(abs(first - l.clumps[0].h / 2) <= 3 && last == l.clumps[0].h - 1 && sides);
    bb_layout_free(&l);

    /* More blades, or a wider shape, cover more. */
    CHECK(bb_layout_generate(&l, &(bb_layout_desc_t){.seed = 3, .size = 16, .blades = 20}));
    double a20 = mean_alpha(&l);
    bb_layout_free(&l);
    CHECK(
        bb_layout_generate(&l, &(bb_layout_desc_t){.seed = 3, .size = 16, .clump.population.shape = BLADE_SHAPE_QUAD}));
    double aquad = mean_alpha(&l);
    bb_layout_free(&l);
    CHECK(bb_layout_generate(
        &l, &(bb_layout_desc_t){.seed = 3, .size = 16, .clump.population.shape = BLADE_SHAPE_TRIANGLE}));
    double atri = mean_alpha(&l);
    bb_layout_free(&l);
    printf("mean alpha: 20 blades %.3f, 52 blades %.3f; 52 quad blades %.3f, 52 triangle blades %.3f\n", a20, a52,
           aquad, atri);
    CHECK(a20 < 0.7 * a52 && aquad > 1.2 * atri);

    /* One blade per layer hardly overlaps itself: the calibration adds
     * (almost) nothing. */
    CHECK(bb_layout_generate(&l, &(bb_layout_desc_t){.seed = 3, .size = 16, .blades = 1}));
    for (int k = 0; k < l.clump_layers; k++) {
        printf("1 blade: layer %d takes %d, alpha %.4f, target %.4f\n", k, l.clump_stats[k].blades,
               l.clump_stats[k].alpha, l.clump_stats[k].target);
        CHECK(l.clump_stats[k].blades <= 2);
    }
    bb_layout_free(&l);
}

/* Share of texels below `below`. */
static double share_below(const core_image_t *e, int below)
{
    size_t n = (size_t)e->w * e->h, k = 0;
    for (size_t i = 0; i < n; i++) k += e->px[i] < below;
    return (double)k / (double)n;
}

/* The first lag (texels, along x, wrapping) at which the extent's
 * autocorrelation falls below one half: the blobs' scale. */
static int correlation_length(const core_image_t *e)
{
    int n = e->w;
    double mean = 0.0, var = 0.0;
    for (int i = 0; i < n * n; i++) mean += e->px[i];
    mean /= (double)n * n;
    for (int i = 0; i < n * n; i++) var += (e->px[i] - mean) * (e->px[i] - mean);
    for (int lag = 1; lag < n / 2; lag++) {
        double c = 0.0;
        for (int y = 0; y < n; y++)
            for (int x = 0; x < n; x++) c += (e->px[y * n + x] - mean) * (e->px[y * n + (x + lag) % n] - mean);
        if (c < 0.5 * var) return lag;
    }
    return n / 2;
}

/* bb_extent_desc_t: none is all grass; the default desc is the zero desc;
 * fraction sets the bare share (mask below one half: extent below 102 for
 * sure, below 128 at most) whatever the seed's own share; feature sets the
 * blob scale; an image maps over image_texels, bilinear, clamped. */
static void test_extent_keys(void)
{
    bb_layout_desc_t base = {.seed = 5, .size = 256, .clump_layers = 1, .clump_size = 8, .blades = 1};
    bb_layout_t def, l;
    CHECK(bb_layout_generate(&def, &base));

    bb_layout_desc_t d = base;
    d.extent.clearings = BB_CLEARINGS_NONE;
    CHECK(bb_layout_generate(&l, &d));
    CHECK(share_below(&l.extent, 255) == 0.0);
    CHECK(images_equal(&l.direction, &def.direction) && images_equal(&l.messiness, &def.messiness));
    bb_layout_free(&l);

    d = base;
    d.extent.feature = 64.0f; /* size / 4: the default's base period */
    CHECK(bb_layout_generate(&l, &d));
    CHECK(images_equal(&l.extent, &def.extent));
    bb_layout_free(&l);

    double own = share_below(&def.extent, 128);
    static const float fractions[] = {0.05f, 0.2f, 0.5f, 0.8f};
    for (int k = 0; k < 4; k++) {
        d = base;
        d.extent.fraction = fractions[k];
        CHECK(bb_layout_generate(&l, &d));
        double sure = share_below(&l.extent, 102), most = share_below(&l.extent, 128);
        printf("extent fraction %.2f: bare (extent < 102) %.3f, (< 128) %.3f; the seed's own %.3f\n",
               (double)fractions[k], sure, most, own);
        CHECK(sure <= fractions[k] + 0.005 && most >= fractions[k] - 0.005);
        CHECK_NEAR(most, fractions[k], 0.04);
        bb_layout_free(&l);
    }

    int lengths[3];
    static const float features[3] = {8.0f, 32.0f, 128.0f};
    for (int k = 0; k < 3; k++) {
        d = base;
        d.extent.feature = features[k];
        d.extent.fraction = 0.3f;
        CHECK(bb_layout_generate(&l, &d));
        lengths[k] = correlation_length(&l.extent);
        CHECK_NEAR(share_below(&l.extent, 128), 0.3, 0.04);
        bb_layout_free(&l);
    }
    printf("extent feature 8 / 32 / 128 texels: correlation length %d / %d / %d texels\n", lengths[0], lengths[1],
           lengths[2]);
    CHECK(lengths[1] >= 2 * lengths[0] && lengths[2] >= 2 * lengths[1]);

    core_image_t im;
    CHECK(core_image_alloc(&im, 2, 1, 3));
    memset(im.px, 0, 6);
    memset(im.px + 3, 255, 3); /* black left, white right */
    d = base;
    d.extent.clearings = BB_CLEARINGS_IMAGE;
    d.extent.image = &im;
    d.extent.image_texels[0] = 128.0f;
    d.extent.image_texels[1] = 64.0f;
    CHECK(bb_layout_generate(&l, &d));
    const uint8_t *row = l.extent.px + 200 * 256;
    printf("extent image: texels 0, 31, 64, 96, 127, 200: %d %d %d %d %d %d\n", row[0], row[31], row[64], row[96],
           row[127], row[200]);
    CHECK(row[0] == 0 && row[31] == 0 && row[127] == 255 && row[200] == 255);
    CHECK(row[64] > 120 && row[64] < 136 && row[96] == 255);
    bb_layout_free(&l);
    core_image_free(&im);
    bb_layout_free(&def);
}

/* View v of layer k: its mean alpha, the mean luminance of its covered
 * texels' lit colour (the light image) and the alpha-weighted mean row (0
 * top). */
static void view_look(const bb_layout_t *l, int v, int k, double *alpha, double *lum, double *row)
{
    static const double y709[3] = {0.2126, 0.7152, 0.0722};
    const core_image_t *im = &l->clumps[v * l->clump_layers + k], *li = &l->clump_light[v * l->clump_layers + k];
    double a = 0.0, y = 0.0, r = 0.0;
    for (int i = 0; i < im->w * im->h; i++) {
        double t = im->px[4 * i + 3] / 255.0;
        a += t;
        r += t * (i / im->w);
        for (int c = 0; c < 3; c++) y += t * y709[c] * li->px[4 * i + c] / 255.0;
    }
    *alpha = a / (im->w * im->h);
    *lum = y / a;
    *row = r / a;
}

/* The view bakes (bb_view.h), meadow_large's blades and wind (1, 0.3):
 * - looking with the wind is looking towards the program's sun (0.45, 0.8,
 *   0.35), so the blades show their shaded faces: darker than looking
 *   against it;
 * - the wind's own part: against the same bakes without wind, the view
 *   looking with it and the one looking against it change in opposite
 *   ways (a bake that dropped the wind's azimuth would change both alike);
 * - seen from 60 degrees the slab behind the card rises into view: the
 *   covered rows move up. */
static void test_views(void)
{
    bb_view_desc_t vd = bb_view_desc_defaults(NULL);
    CHECK(!vd.on && vd.elevations == 1 && vd.azimuths == 1);
    vd = bb_view_desc_defaults(&(bb_view_desc_t){.on = true});
    CHECK(vd.elevations == 1 && vd.azimuths == 4 && fabsf(vd.elevation_max - 1.0471976f) < 1e-6f);
    float e, a;
    bb_view_angles(&(bb_view_desc_t){.elevations = 3, .azimuths = 4, .elevation_max = 1.0471976f}, 9, &e, &a);
    CHECK(fabsf(e - 1.0471976f) < 1e-6f && fabsf(a - 1.5707963f) < 1e-6f);
    double lum[2][12], row[2][12];
    for (int wind = 0; wind < 2; wind++) {
        bb_layout_t l;
        CHECK(bb_layout_generate(&l, &(bb_layout_desc_t){.seed = 7, .size = 16, .clump_size = 64,
                                                         .blades = bb_clump_blades(250.0f, 20.0f),
                                                         .clump = {.wind = 1.0f * (float)wind,
                                                                   .wind_dir = {1.0f, 0.3f}},
                                                         .views = {.on = true, .elevations = 3}}));
        CHECK(l.views.elevations * l.views.azimuths == 12);
        for (int v = 0; v < 12; v++) {
            double al = 0;
            lum[wind][v] = row[wind][v] = 0;
            for (int k = 0; k < l.clump_layers; k++) {
                double ak, yk, rk;
                view_look(&l, v, k, &ak, &yk, &rk);
                al += ak / l.clump_layers;
                lum[wind][v] += yk / l.clump_layers;
                row[wind][v] += rk / l.clump_layers;
            }
            printf("wind %d view %2d (elevation %d, azimuth %d): alpha %.3f, lit luminance %.4f, mean row %.1f\n",
                   wind, v, v / 4, v % 4, al, lum[wind][v], row[wind][v]);
        }
        bb_layout_free(&l);
    }
    double with = lum[1][0] - lum[0][0], against = lum[1][2] - lum[0][2];
    printf("wind's change of lit luminance: looking with it %+.4f, against it %+.4f\n", with, against);
    CHECK(lum[1][2] > 2.0 * lum[1][0]);
    CHECK(with - against > 0.008 && with > 0.0 && against < 0.0);
    for (int az = 0; az < 4; az++) CHECK(row[1][8 + az] < row[1][az] - 2.0);
}

int main(void)
{
    core_log_set_quiet(true);
    test_determinism();
    test_extent_keys();
    bb_layout_t l;
    CHECK(bb_layout_generate(&l, &(bb_layout_desc_t){.seed = 2009}));
    CHECK(l.extent.w == 256 && l.clumps[0].w == 128);
    test_maps(&l);
    test_clumps(&l);
    test_sample(&l);
    test_sample_tri(&l);
    test_blade_clumps();
    test_views();
    const char *out = getenv("MEADOW_TEST_OUT");
    char dir[1024];
    snprintf(dir, sizeof dir, "%s", out ? out : "/tmp/meadow-test-bb-layout");
    CHECK(bb_layout_write_pngs(&l, dir));
    char path[1100];
    snprintf(path, sizeof path, "%s/clump_3.png", dir);
    CHECK(access(path, R_OK) == 0);
    printf("layout PNGs in %s\n", dir);
    bb_layout_free(&l);
    TEST_END();
}

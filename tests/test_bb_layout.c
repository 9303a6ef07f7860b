/* test_bb_layout: procedural billboard content (Orthmann et al. 2009,
 * sec. 3). Layout textures must be deterministic by seed, tile, and look
 * like what they claim (clearings, mostly-up directions); clump textures
 * must have 10-60 % opaque coverage in many thin blades, not a rectangle;
 * the generation rule must follow the extent map and its documented hash
 * formula. Writes the PNGs to $MEADOW_TEST_OUT for inspection. */
#include "billboard/bb_layout.h"
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
        /* Blades crossing the row at 40 % height: count transparent->opaque edges. */
        int row = h - 1 - (int)(0.4 * h), edges = 0;
        for (int x = 1; x < w; x++)
            edges += im->px[((size_t)row * w + x) * 4 + 3] > 127 && im->px[((size_t)row * w + x - 1) * 4 + 3] <= 127;
        double cover = (double)opaque / (w * h);
        double fill = (double)opaque / ((x1 - x0 + 1) * (y1 - y0 + 1));
        printf("clump %d: %.1f%% opaque, bbox fill %.2f, %d blade edges at 40%% height, %d AA pixels, "
               "rgb %.0f %.0f %.0f, base/mid luminance %.0f/%.0f\n", k, 100 * cover, fill, edges, partial,
               r / opaque, g / opaque, b / opaque, lum_base / n_base, lum_mid / n_mid);
        CHECK(cover > 0.10 && cover < 0.60);
        CHECK(fill < 0.7);              /* not a rectangle */
        CHECK(edges >= 8);              /* many thin blades */
        CHECK(bottom > 2.0 * top);      /* a clump: dense base, sparse tips */
        CHECK(partial > opaque / 10);   /* antialiased edges */
        CHECK(g > r && g > 1.5 * b);    /* green */
        CHECK(lum_base < 0.85 * lum_mid); /* darker at the base */
        if (k > 0) CHECK(!images_equal(im, &l->clumps[0]));
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

int main(void)
{
    core_log_set_quiet(true);
    test_determinism();
    bb_layout_t l;
    CHECK(bb_layout_generate(&l, &(bb_layout_desc_t){.seed = 2009}));
    CHECK(l.extent.w == 256 && l.clumps[0].w == 128);
    test_maps(&l);
    test_clumps(&l);
    test_sample(&l);
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

/* test_raster: the compute rasterizer against its CPU reference
 * (raster_ref) on the same triangles, in every variant this GL has: the
 * two-pass 32-bit buffer always, the one-pass 64-bit atomic buffer where
 * GL_NV_shader_atomic_int64 exists (the GPU machine; llvmpipe lacks it and
 * the test says so). Triangles: many small ones at random depths, large
 * ones (the work-group queue), ones crossing the near plane (clipping) and
 * ones wholly behind it; small thresholds, so all three work lists are
 * used; large triangles both ways (a row per invocation, and shared out
 * pixel by pixel with RASTER_GROUP_SCAN). Checks per sample: coverage and colour equal,
 * depth equal to 1e-5 (window depth; fused multiply-adds on GPUs), except for a small budget of samples on edges
 * (float rounding); the queue was used; the composite writes the mean
 * colour of a pixel's samples and coverage over the background, and the
 * colour-only compute composite the same colour into 1- and 4-sample
 * targets, leaving their depth. */
#include "common/bindings_tests.glsl"
#include "raster/raster.h"
#include "raster/raster_ref.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <string.h>

#define W 96
#define H 150
#define NTRI 400

static float frand(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return (float)(*s >> 8) / 16777216.0f;
}

/* Triangle i: 4 vec4, the last holding the colour word in x. */
static void make_triangles(float *t)
{
    uint32_t s = 12345u;
    for (int i = 0; i < NTRI; i++) {
        float *v = t + 16 * i;
        float cx = frand(&s) * 2.4f - 1.2f, cy = frand(&s) * 2.4f - 1.2f;
        float size = i % 50 == 0 ? 1.2f : 0.02f + 0.15f * frand(&s);
        float w = 0.5f + 3.0f * frand(&s), z = (frand(&s) * 1.8f - 0.9f) * w;
        for (int k = 0; k < 3; k++) {
            v[4 * k + 0] = (cx + size * (frand(&s) - 0.5f)) * w;
            v[4 * k + 1] = (cy + size * (frand(&s) - 0.5f)) * w;
            v[4 * k + 2] = z + 0.1f * (frand(&s) - 0.5f) * w;
            v[4 * k + 3] = w;
        }
        if (i % 37 == 1) {
            /* crosses the near plane: one vertex behind the camera */
            v[2] = -3.0f;
            v[3] = -1.0f;
        } else if (i % 97 == 2) {
            /* wholly behind */
            for (int k = 0; k < 3; k++) v[4 * k + 3] = -1.0f, v[4 * k + 2] = 0.5f;
        }
        uint32_t rgba = 0xff000000u | (uint32_t)(i * 2654435761u >> 8);
        memcpy(&v[12], &rgba, 4);
        v[13] = v[14] = v[15] = 0.0f;
    }
}

typedef struct bind_t {
    gfx_buffer_t tris;
} bind_t;

static void bind(gfx_program_t p, void *user)
{
    const bind_t *b = user;
    glUniform1ui(gfx_uniform(p, "u_count"), NTRI);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN, b->tris.id);
}

/* raster_end_color into a new target of `samples` per pixel, cleared as
 * run_variant's: the colour raster_end gave (want) to 1 level per channel
 * (each blend rounds once), the depth still the clear's 0.9. */
static void check_color_composite(raster_t *r, const core_image_t *want, int samples)
{
    gfx_target_t t = gfx_target_make(&(gfx_target_desc_t){.w = W, .h = H, .samples = samples, .label = "t2"});
    gfx_target_bind(&t);
    glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
    glClearDepth(0.9);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glClearDepth(1.0);
    raster_end_color(r, &t);
    gfx_target_resolve(&t);
    core_image_t img = {0};
    float *depth = malloc(sizeof(float) * W * H);
    CHECK(depth && gfx_target_read(&t, &img) && gfx_target_read_depth(&t, depth));
    int worst = 0, depth_moved = 0;
    for (size_t i = 0; i < (size_t)W * H * 4; i++) {
        int d = abs((int)img.px[i] - (int)want->px[i]);
        worst = d > worst ? d : worst;
    }
    for (size_t i = 0; i < (size_t)W * H; i++) depth_moved += fabsf(depth[i] - 0.9f) > 1e-6f;
    printf("colour-only composite, %d sample%s: largest difference from raster_end %d levels, %d depths moved\n",
           samples, samples > 1 ? "s" : "", worst, depth_moved);
    CHECK(worst <= 1);
    CHECK(depth_moved == 0);
    free(depth);
    core_image_free(&img);
    gfx_target_destroy(&t);
}

static void run_variant(bool no_atomic64, bool group_scan, const float *tris, const raster_ref_t *ref)
{
    raster_t r;
    int ns = ref->samples;
    CHECK(raster_make(&r, &(raster_desc_t){.w = W, .h = H, .samples = ns, .no_atomic64 = no_atomic64,
                                            .small_samples = 16, .medium_samples = 256}));
    printf("variant: %s, %d sample%s per pixel, large triangles %s\n",
           r.atomic64 ? "64-bit atomic, one pass" : "32-bit, two passes", ns, ns > 1 ? "s" : "",
           group_scan ? "in row bands, shared out pixel by pixel (RASTER_GROUP_SCAN)" : "one row per invocation");
    gfx_target_t target = gfx_target_make(&(gfx_target_desc_t){.w = W, .h = H, .samples = 1, .label = "t"});
    gfx_target_bind(&target);
    glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
    glClearDepth(0.9);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glClearDepth(1.0);
    gfx_buffer_t buf = gfx_buffer_make(&(gfx_buffer_desc_t){.size = NTRI * 64, .data = tris, .label = "tris"});
    /* The shared scan with large triangles in bands (RASTER_BANDS) of 16
     * rows from 1024 samples: up to 10 bands here. */
    const char *defines = group_scan ? "#define RASTER_GROUP_SCAN 1\n#define RASTER_BANDS 1\n#define RASTER_BAND_ROWS 16\n"
                                       "#define RASTER_BAND_SPLIT_SAMPLES 1024\n"
                                     : NULL;
    raster_program_t prog = raster_program_make(&r, "tests/raster_tris.comp", defines, "raster_tris");
    CHECK(prog.prim.id && prog.big.id);
    raster_begin(&r, &target);
    bind_t b = {buf};
    raster_draw(&r, &prog, &(raster_items_t){.count = NTRI}, bind, &b);
    raster_stats_t st;
    raster_read_stats(&r, &st);
    printf("queued: %u medium triangles, %u bands of large or clipped ones (overflow %u)\n", st.medium, st.large,
           st.overflow);
    CHECK(st.medium >= 8 && st.large >= 8 && st.overflow == 0);

    size_t n = (size_t)W * H * (size_t)ns;
    uint32_t *words = malloc(n * 8);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_buffer_read(r.vis, 0, n * 8, words);
    size_t covered = 0, mismatch = 0, depth_bad = 0;
    double depth_max = 0.0;
    for (size_t s = 0; s < n; s++) {
        uint32_t gc = words[2 * s], gd = words[2 * s + 1];
        if (ref->colour[s]) covered++;
        if (gc != ref->colour[s]) {
            mismatch++;
            continue;
        }
        float a, c;
        memcpy(&a, &gd, 4);
        memcpy(&c, &ref->depth[s], 4);
        depth_max = fmax(depth_max, fabs((double)a - c));
        if (fabsf(a - c) > 1e-5f) depth_bad++;
    }
    printf("samples %zu, covered %zu, colour mismatches %zu (%.3f%%), depth mismatches %zu (largest difference %.2g)\n",
           n, covered, mismatch, 100.0 * (double)mismatch / (double)covered, depth_bad, depth_max);
    CHECK(covered > n / 8);
    CHECK((double)mismatch < 0.005 * (double)covered);
    CHECK(depth_bad == 0);

    /* Composite: mean of the covered samples over the blue background. */
    raster_end(&r, &target);
    core_image_t img = {0};
    CHECK(gfx_target_read(&target, &img));
    int bad_px = 0;
    for (int py = 0; py < H; py++)
        for (int px = 0; px < W; px++) {
            double want[3] = {0, 0, 0};
            for (int k = 0; k < ns; k++) {
                uint32_t c = ref->colour[(py * W + px) * ns + k];
                double rgb[3] = {(c & 255) / 255.0, (c >> 8 & 255) / 255.0, (c >> 16 & 255) / 255.0};
                if (!c) rgb[0] = rgb[1] = 0.0, rgb[2] = 1.0;
                for (int i = 0; i < 3; i++) want[i] += rgb[i] / ns;
            }
            const uint8_t *got = img.px + ((size_t)(H - 1 - py) * W + (size_t)px) * 4;
            for (int i = 0; i < 3; i++)
                if (fabs(got[i] / 255.0 - want[i]) > 0.02) {
                    bad_px++;
                    break;
                }
        }
    printf("composite: %d of %d pixels differ by more than 0.02\n", bad_px, W * H);
    CHECK(bad_px < W * H / 100);
    check_color_composite(&r, &img, 1);
    check_color_composite(&r, &img, 4);
    core_image_free(&img);
    free(words);
    raster_program_destroy(&prog);
    gfx_buffer_destroy(&buf);
    gfx_target_destroy(&target);
    raster_destroy(&r);
}

int main(void)
{
    test_gl_init();
    static float tris[NTRI * 16];
    make_triangles(tris);
    /* 4 samples (the default) with both large-triangle scans, then one
     * sample per pixel (the widest words of raster_init and the composite
     * differ by sample count). */
    for (int ns = 4; ns >= 1; ns -= 3) {
        raster_ref_t ref;
        CHECK(raster_ref_init(&ref, W, H, ns, 0.9f));
        for (int i = 0; i < NTRI; i++)
            raster_ref_triangle(&ref, tris + 16 * i, tris + 16 * i + 4, tris + 16 * i + 8,
                                0xff000000u | (uint32_t)(i * 2654435761u >> 8));
        for (int g = 0; g < (ns == 4 ? 2 : 1); g++) {
            run_variant(true, g == 1, tris, &ref);
            if (raster_has_atomic64()) run_variant(false, g == 1, tris, &ref);
        }
        raster_ref_free(&ref);
    }
    if (!raster_has_atomic64())
        printf("GL_NV_shader_atomic_int64 missing: the one-pass variant is checked on the GPU machine only\n");
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

/* test_core: RNG determinism, hash bits, atomic file writes, growable
 * buffers, PNG round trip, box distance. */
#include "core/core.h"
#include "test.h"

#include <math.h>
#include <string.h>
#include <unistd.h>

int main(void)
{
    core_rng_t a, b;
    core_rng_seed(&a, 42, 1);
    core_rng_seed(&b, 42, 1);
    for (int i = 0; i < 1000; i++) CHECK(core_rng_u32(&a) == core_rng_u32(&b));
    core_rng_seed(&b, 43, 1);
    int same = 0;
    for (int i = 0; i < 1000; i++) same += core_rng_u32(&a) == core_rng_u32(&b);
    CHECK(same < 5);
    /* Known PCG32 reference: seed 42, stream 54 -> 0xa15c02b7 (pcg32-demo). */
    core_rng_seed(&a, 42, 54);
    CHECK(core_rng_u32(&a) == 0xa15c02b7u);
    double mean = 0;
    for (int i = 0; i < 10000; i++) {
        float f = core_rng_float(&a);
        CHECK(f >= 0.0f && f < 1.0f);
        mean += f;
    }
    CHECK_NEAR(mean / 10000, 0.5, 0.02);
    CHECK(core_hash_u32(0) == 0u);
    CHECK(core_hash_u32(1) != core_hash_u32(2));
    CHECK(core_hash_float(123) >= 0.0f && core_hash_float(123) < 1.0f);

    char dir[256];
    snprintf(dir, sizeof dir, "/tmp/meadow-test-core-%ld/a/b", (long)getpid());
    char err[256];
    CHECK(core_fs_check_writable_dir(dir, err, sizeof err));
    char path[300];
    snprintf(path, sizeof path, "%s/x.txt", dir);
    CHECK(core_fs_write_atomic(path, "hello", 5));
    size_t n = 0;
    char *txt = core_fs_read(path, &n, err, sizeof err);
    CHECK(txt && n == 5 && strcmp(txt, "hello") == 0);
    free(txt);
    CHECK(core_fs_read("/nonexistent/file", NULL, err, sizeof err) == NULL);
    CHECK(strstr(err, "No such file") != NULL);
    CHECK(!core_fs_check_writable_dir("/proc/meadow-cannot", err, sizeof err));

    /* Growable buffer: text and bytes, past the first 4096-byte block. */
    core_buf_t buf = {0};
    CHECK(strcmp(core_buf_str(&buf), "") == 0);
    core_buf_printf(&buf, "a,%d\n", 1);
    core_buf_printf(&buf, "%s", "b,2\n");
    CHECK(buf.len == 8 && strcmp(buf.data, "a,1\nb,2\n") == 0);
    static const char zeros[3] = {0};
    core_buf_put(&buf, zeros, sizeof zeros);
    CHECK(buf.len == 11 && buf.data[11] == 0);
    for (int i = 0; i < 1000; i++) core_buf_printf(&buf, "%08d", i);
    CHECK(buf.len == 8011 && buf.cap > 8011 && strcmp(buf.data + 8003, "00000999") == 0);
    snprintf(path, sizeof path, "%s/buf.txt", dir);
    CHECK(core_buf_write(&buf, path));
    txt = core_fs_read(path, &n, err, sizeof err);
    CHECK(txt && n == buf.len && memcmp(txt, buf.data, n) == 0);
    free(txt);
    core_buf_free(&buf);
    CHECK(buf.data == NULL && buf.len == 0 && buf.cap == 0);

    core_image_t img, back;
    CHECK(core_image_alloc(&img, 7, 5, 4));
    for (int i = 0; i < 7 * 5 * 4; i++) img.px[i] = (uint8_t)(i * 13);
    snprintf(path, sizeof path, "%s/img.png", dir);
    CHECK(core_image_write_png(&img, path));
    CHECK(core_image_load(&back, path, 4));
    CHECK(back.w == 7 && back.h == 5 && memcmp(img.px, back.px, 7 * 5 * 4) == 0);
    core_image_free(&img);
    core_image_free(&back);
    /* JPEG for docs: 200x100, left half dark, right half bright, written at
     * most 64 wide -> a factor of 4, 50x25, the halves kept. */
    CHECK(core_image_alloc(&img, 200, 100, 4));
    for (int i = 0; i < 200 * 100; i++) memset(img.px + i * 4, i % 200 < 100 ? 40 : 220, 4);
    snprintf(path, sizeof path, "%s/img.jpg", dir);
    CHECK(core_image_write_jpg(&img, path, 64, 0));
    CHECK(core_image_load(&back, path, 3));
    CHECK(back.w == 50 && back.h == 25);
    CHECK(abs(back.px[(12 * 50 + 5) * 3] - 40) < 6 && abs(back.px[(12 * 50 + 45) * 3] - 220) < 6);
    core_image_free(&img);
    core_image_free(&back);
    /* Drawing: text lands inside its box, blit copies, fill clips. */
    core_image_t canvas, tile;
    CHECK(core_image_alloc(&canvas, 64, 32, 4) && core_image_alloc(&tile, 4, 4, 1));
    memset(tile.px, 200, 16);
    core_image_blit(&canvas, &tile, 62, 30);
    CHECK(canvas.px[(31 * 64 + 63) * 4] == 200 && canvas.px[(31 * 64 + 63) * 4 + 3] == 255);
    CHECK(canvas.px[(29 * 64 + 63) * 4] == 0);
    static const uint8_t white[4] = {255, 255, 255, 255};
    core_image_fill(&canvas, -5, -5, 10, 10, white);
    CHECK(canvas.px[(4 * 64 + 4) * 4] == 255 && canvas.px[(5 * 64 + 5) * 4] == 0);
    core_image_t label;
    CHECK(core_image_alloc(&label, 64, 16, 4));
    core_image_text(&label, 2, 2, 1, "HI", white);
    int lit = 0, outside = 0;
    for (int j = 0; j < 16; j++)
        for (int i = 0; i < 64; i++) {
            bool on = label.px[(j * 64 + i) * 4] == 255;
            lit += on;
            outside += on && (i >= 20 || j >= 12);
        }
    CHECK(lit > 10 && outside == 0);
    core_image_free(&label);
    core_image_free(&canvas);
    core_image_free(&tile);
    char probe[300];
    CHECK(core_fs_resolve("CMakeLists.txt", probe, sizeof probe));
    /* box distance */
    {
        const float lo[3] = {0, 0, 0}, hi[3] = {2, 1, 2};
        CHECK(core_box_dist2((float[3]){1, 0.5f, 1}, lo, hi) == 0.0f);
        CHECK(fabsf(core_box_dist2((float[3]){5, 3, -1}, lo, hi) - (9 + 4 + 1)) < 1e-5f);
    }
    TEST_END();
}

/* core_image: 8-bit images loaded with stb_image and written as PNG or JPEG
 * with stb_image_write (implementations in core_stb.c) (atomically, through core_fs_write_atomic). */
#include "core.h"

#include <stdint.h>
#include <stdio.h>
#include <sys/stat.h>

#include <stdlib.h>
#include <string.h>

#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_ONLY_TGA
#define STBI_FAILURE_USERMSG
#include <stb_image.h>
#include <stb_image_write.h>

bool core_image_alloc(core_image_t *img, int w, int h, int channels)
{
    memset(img, 0, sizeof *img);
    if (w <= 0 || h <= 0 || channels < 1 || channels > 4) return false;
    img->px = calloc((size_t)w * (size_t)h, (size_t)channels);
    if (!img->px) return false;
    img->w = w;
    img->h = h;
    img->channels = channels;
    return true;
}

void core_image_free(core_image_t *img)
{
    free(img->px);
    memset(img, 0, sizeof *img);
}

/* Moves stb's pixels into img (malloc'd, so core_image_free owns them). */
static bool image_take(core_image_t *img, uint8_t *px, int w, int h, int channels)
{
    size_t bytes = (size_t)w * (size_t)h * (size_t)channels;
    img->px = malloc(bytes);
    if (img->px) memcpy(img->px, px, bytes);
    stbi_image_free(px);
    if (!img->px) return false;
    img->w = w;
    img->h = h;
    img->channels = channels;
    return true;
}

bool core_image_load(core_image_t *img, const char *path, int channels)
{
    memset(img, 0, sizeof *img);
    int w, h, n;
    struct stat st;
    if (stat(path, &st) == 0 && (!S_ISREG(st.st_mode) || (uint64_t)st.st_size > CORE_FS_READ_MAX)) {
        core_log_error("%s: cannot load image: %s", path,
                       S_ISREG(st.st_mode) ? "larger than the 64 MiB this program reads" : "not a regular file");
        return false;
    }
    if (stbi_info(path, &w, &h, &n) && (double)w * h > CORE_IMAGE_MAX_PIXELS) {
        core_log_error("%s: cannot load image: %d x %d pixels, more than the %.0f this program decodes", path, w, h,
                       (double)CORE_IMAGE_MAX_PIXELS);
        return false;
    }
    uint8_t *px = stbi_load(path, &w, &h, &n, channels);
    if (!px) {
        core_log_error("%s: cannot load image: %s", path, stbi_failure_reason());
        return false;
    }
    return image_take(img, px, w, h, channels ? channels : n);
}

bool core_image_decode(core_image_t *img, const void *data, size_t size, int channels, char *err, size_t err_size)
{
    memset(img, 0, sizeof *img);
    int w, h, n;
    uint8_t *px = size <= INT32_MAX ? stbi_load_from_memory(data, (int)size, &w, &h, &n, channels) : NULL;
    if (!px) {
        snprintf(err, err_size, "%s", size <= INT32_MAX ? stbi_failure_reason() : "image file too large");
        return false;
    }
    if (image_take(img, px, w, h, channels ? channels : n)) return true;
    snprintf(err, err_size, "out of memory");
    return false;
}

typedef struct png_buf_t {
    uint8_t *data;
    size_t size, cap;
    bool failed;
} png_buf_t;

static void png_append(void *ctx, void *data, int size)
{
    png_buf_t *b = ctx;
    if (b->failed) return;
    if (b->size + (size_t)size > b->cap) {
        size_t cap = b->cap ? b->cap * 2 : 65536;
        while (cap < b->size + (size_t)size) cap *= 2;
        uint8_t *grown = realloc(b->data, cap);
        if (!grown) {
            b->failed = true;
            return;
        }
        b->data = grown;
        b->cap = cap;
    }
    memcpy(b->data + b->size, data, (size_t)size);
    b->size += (size_t)size;
}

bool core_image_write_png(const core_image_t *img, const char *path)
{
    png_buf_t b = {0};
    int ok = stbi_write_png_to_func(png_append, &b, img->w, img->h, img->channels, img->px,
                                    img->w * img->channels);
    bool done = ok && !b.failed && core_fs_write_atomic(path, b.data, b.size);
    if (!ok || b.failed) core_log_error("%s: PNG encoding failed", path);
    free(b.data);
    return done;
}

bool core_image_write_jpg(const core_image_t *img, const char *path, int max_width, int quality)
{
    int f = max_width > 0 && img->w > max_width ? (img->w + max_width - 1) / max_width : 1;
    core_image_t s = {0};
    if (!core_image_alloc(&s, img->w / f, img->h / f, 3)) return false;
    for (int y = 0; y < s.h; ++y)
        for (int x = 0; x < s.w; ++x)
            for (int c = 0; c < 3; ++c) {
                int sum = 0;
                for (int j = 0; j < f; ++j)
                    for (int i = 0; i < f; ++i) {
                        const uint8_t *q = img->px + ((size_t)(y * f + j) * img->w + (x * f + i)) * img->channels;
                        sum += q[img->channels >= 3 ? c : 0];
                    }
                s.px[((size_t)y * s.w + x) * 3 + c] = (uint8_t)((sum + f * f / 2) / (f * f));
            }
    png_buf_t b = {0};
    int ok = stbi_write_jpg_to_func(png_append, &b, s.w, s.h, 3, s.px, quality > 0 ? quality : 85);
    bool done = ok && !b.failed && core_fs_write_atomic(path, b.data, b.size);
    if (!ok || b.failed) core_log_error("%s: JPEG encoding failed", path);
    free(b.data);
    core_image_free(&s);
    return done;
}

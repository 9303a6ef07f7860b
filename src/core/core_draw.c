/* core_draw: CPU drawing on RGBA images for montages and reports: blits,
 * rectangles, and text from stb_easy_font's glyph quads. */
#include "core.h"

#include <string.h>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-braces"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

void core_image_blit(core_image_t *dst, const core_image_t *src, int x, int y)
{
    for (int j = 0; j < src->h; j++) {
        int dy = y + j;
        if (dy < 0 || dy >= dst->h) continue;
        for (int i = 0; i < src->w; i++) {
            int dx = x + i;
            if (dx < 0 || dx >= dst->w) continue;
            const uint8_t *s = src->px + ((size_t)j * (size_t)src->w + (size_t)i) * (size_t)src->channels;
            uint8_t *d = dst->px + ((size_t)dy * (size_t)dst->w + (size_t)dx) * 4;
            if (src->channels >= 3) {
                d[0] = s[0], d[1] = s[1], d[2] = s[2];
            } else {
                d[0] = d[1] = d[2] = s[0];
            }
            d[3] = src->channels == 4 ? s[3] : (src->channels == 2 ? s[1] : 255);
        }
    }
}

void core_image_fill(core_image_t *img, int x, int y, int w, int h, const uint8_t rgba[4])
{
    for (int j = y < 0 ? 0 : y; j < y + h && j < img->h; j++)
        for (int i = x < 0 ? 0 : x; i < x + w && i < img->w; i++)
            memcpy(img->px + ((size_t)j * (size_t)img->w + (size_t)i) * 4, rgba, 4);
}

void core_image_text(core_image_t *img, int x, int y, int scale, const char *text, const uint8_t rgba[4])
{
    static char quads[64 * 1024];
    int nq = stb_easy_font_print(0, 0, (char *)text, NULL, quads, sizeof quads);
    for (int q = 0; q < nq; q++) {
        const float *v0 = (const float *)(quads + (size_t)q * 64);
        const float *v2 = (const float *)(quads + (size_t)q * 64 + 32);
        int x0 = x + (int)(v0[0] * (float)scale), y0 = y + (int)(v0[1] * (float)scale);
        int x1 = x + (int)(v2[0] * (float)scale), y1 = y + (int)(v2[1] * (float)scale);
        core_image_fill(img, x0, y0, x1 - x0, y1 - y0, rgba);
    }
}

/* eval_image: block statistics image error at several block sizes (see
 * eval_image.h and docs/METRICS.md "Image error"). */
#include "eval/eval_image.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BINS 8
#define PI 3.14159265358979323846
/* Gradient energy (L* per pixel) added to the structure distance's
 * denominator, so flat blocks (sky, fog) compare as equal instead of
 * amplifying rounding noise. */
#define STRUCTURE_FLOOR 1.0
/* Default finest block: the image height / BLOCKS_PER_HEIGHT. */
#define BLOCKS_PER_HEIGHT 8
/* The scores' units, shared by eval_image_error and eval_image_seam: the
 * Delta E (CIE76 JND) and the grass-fraction step that score 1. */
#define COLOUR_SCALE 2.3
#define COVERAGE_SCALE 0.05

eval_image_desc_t eval_image_desc_defaults(const eval_image_desc_t *d)
{
    eval_image_desc_t r = d ? *d : (eval_image_desc_t){0};
    if (r.levels <= 0) r.levels = 2;
    if (r.grass_threshold <= 0) r.grass_threshold = 8;
    if (r.colour_scale <= 0) r.colour_scale = COLOUR_SCALE;
    if (r.coverage_scale <= 0) r.coverage_scale = COVERAGE_SCALE;
    if (r.structure_scale <= 0) r.structure_scale = 0.2;
    return r;
}

/* Sums over the pixels of a block (additive, so coarser levels merge
 * 2 x 2 blocks). */
typedef struct block_t {
    double rgb[3];       /* linear light */
    double grass;        /* grass pixels */
    double hist[BINS];   /* gradient magnitude of L* per orientation */
    double n;            /* pixels */
} block_t;

double eval_srgb_to_linear(int v)
{
    double c = v / 255.0;
    return c <= 0.04045 ? c / 12.92 : pow((c + 0.055) / 1.055, 2.4);
}

static double lab_f(double t)
{
    const double e = 216.0 / 24389.0, k = 24389.0 / 27.0;
    return t > e ? cbrt(t) : (k * t + 16.0) / 116.0;
}

void eval_linear_to_lab(const double rgb[3], double lab[3])
{
    double x = 0.4124564 * rgb[0] + 0.3575761 * rgb[1] + 0.1804375 * rgb[2];
    double y = 0.2126729 * rgb[0] + 0.7151522 * rgb[1] + 0.0721750 * rgb[2];
    double z = 0.0193339 * rgb[0] + 0.1191920 * rgb[1] + 0.9503041 * rgb[2];
    double fx = lab_f(x / 0.95047), fy = lab_f(y), fz = lab_f(z / 1.08883);
    lab[0] = 116.0 * fy - 16.0;
    lab[1] = 500.0 * (fx - fy);
    lab[2] = 200.0 * (fy - fz);
}

/* Finest-level block sums of one image (bx x by blocks of side s). */
static bool image_blocks(const core_image_t *img, const core_image_t *bg, int threshold, int s, int bx, int by,
                         const double *lut, block_t *blocks)
{
    int w = img->w, h = img->h, c = img->channels;
    float *lstar = malloc(sizeof(float) * (size_t)w * (size_t)h);
    if (!lstar) return false;
    memset(blocks, 0, sizeof(block_t) * (size_t)bx * (size_t)by);
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            const uint8_t *p = img->px + i * (size_t)c;
            block_t *b = &blocks[(y / s) * bx + x / s];
            double lin[3] = {lut[p[0]], lut[p[1]], lut[p[2]]};
            bool grass = false;
            for (int k = 0; k < 3 && bg && !grass; k++)
                grass = abs((int)p[k] - (int)bg->px[i * (size_t)bg->channels + (size_t)k]) > threshold;
            for (int k = 0; k < 3; k++) b->rgb[k] += lin[k];
            b->grass += grass ? 1.0 : 0.0;
            b->n += 1.0;
            lstar[i] = (float)(116.0 * lab_f(0.2126729 * lin[0] + 0.7151522 * lin[1] + 0.0721750 * lin[2]) - 16.0);
        }
    /* Central differences inside the image; the orientation's magnitude is
     * split linearly between its two nearest of BINS unsigned bins. */
    for (int y = 1; y + 1 < h; y++)
        for (int x = 1; x + 1 < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            double gx = 0.5 * ((double)lstar[i + 1] - lstar[i - 1]);
            double gy = 0.5 * ((double)lstar[i + (size_t)w] - lstar[i - (size_t)w]);
            double mag = sqrt(gx * gx + gy * gy);
            if (mag <= 0.0) continue;
            double a = atan2(gy, gx);
            if (a < 0.0) a += PI;
            double f = a / PI * BINS - 0.5;
            if (f < 0.0) f += BINS;
            int b0 = (int)f % BINS, b1 = (b0 + 1) % BINS;
            double t = f - floor(f);
            block_t *b = &blocks[(y / s) * bx + x / s];
            b->hist[b0] += mag * (1.0 - t);
            b->hist[b1] += mag * t;
        }
    free(lstar);
    return true;
}

/* Merges 2 x 2 blocks into the next level (in place; returns its size). */
static void merge_level(block_t *blocks, int *bx, int *by)
{
    int nx = (*bx + 1) / 2, ny = (*by + 1) / 2;
    for (int y = 0; y < ny; y++)
        for (int x = 0; x < nx; x++) {
            block_t m = {0};
            for (int dy = 0; dy < 2; dy++)
                for (int dx = 0; dx < 2; dx++) {
                    int sx = 2 * x + dx, sy = 2 * y + dy;
                    if (sx >= *bx || sy >= *by) continue;
                    const block_t *b = &blocks[sy * *bx + sx];
                    for (int k = 0; k < 3; k++) m.rgb[k] += b->rgb[k];
                    for (int k = 0; k < BINS; k++) m.hist[k] += b->hist[k];
                    m.grass += b->grass;
                    m.n += b->n;
                }
            blocks[y * nx + x] = m; /* index y * nx + x <= the sources' smallest index */
        }
    *bx = nx;
    *by = ny;
}

/* The three terms at one level: colour (grass-weighted mean Delta E),
 * coverage and structure (pixel-weighted means). */
static void level_terms(const block_t *ba, const block_t *bb, int nb, double t[3])
{
    double colour = 0.0, coverage = 0.0, structure = 0.0, pixels = 0.0;
    for (int i = 0; i < nb; i++) {
        const block_t *a = &ba[i], *b = &bb[i];
        double ma[3], mb[3], la[3], lb[3];
        for (int k = 0; k < 3; k++) ma[k] = a->rgb[k] / a->n, mb[k] = b->rgb[k] / b->n;
        eval_linear_to_lab(ma, la);
        eval_linear_to_lab(mb, lb);
        colour += a->n * sqrt((la[0] - lb[0]) * (la[0] - lb[0]) + (la[1] - lb[1]) * (la[1] - lb[1]) +
                              (la[2] - lb[2]) * (la[2] - lb[2]));
        coverage += fabs(a->grass - b->grass);
        double diff = 0.0, sum = 0.0;
        for (int k = 0; k < BINS; k++) {
            diff += fabs(a->hist[k] - b->hist[k]);
            sum += a->hist[k] + b->hist[k];
        }
        structure += a->n * diff / (sum + STRUCTURE_FLOOR * a->n);
        pixels += a->n;
    }
    t[0] = colour / pixels;
    t[1] = coverage / pixels;
    t[2] = structure / pixels;
}

bool eval_image_error(const core_image_t *img, const core_image_t *ref, const eval_image_desc_t *desc,
                      eval_image_error_t *out)
{
    memset(out, 0, sizeof *out);
    eval_image_desc_t d = eval_image_desc_defaults(desc);
    const core_image_t *bg = d.background;
    if (img->w != ref->w || img->h != ref->h || img->channels < 3 || ref->channels < 3 || img->w < 1 || img->h < 1)
        return false;
    if (bg && (bg->w != img->w || bg->h != img->h || bg->channels < 3)) return false;
    double lut[256];
    for (int v = 0; v < 256; v++) lut[v] = eval_srgb_to_linear(v);
    int s = d.block > 0 ? d.block : (img->h + BLOCKS_PER_HEIGHT / 2) / BLOCKS_PER_HEIGHT;
    s = s < 1 ? 1 : s;
    int bx = (img->w + s - 1) / s, by = (img->h + s - 1) / s;
    size_t nb = (size_t)bx * (size_t)by;
    block_t *ba = malloc(sizeof(block_t) * nb), *bb = malloc(sizeof(block_t) * nb);
    bool ok = ba && bb && image_blocks(img, bg, d.grass_threshold, s, bx, by, lut, ba) &&
              image_blocks(ref, bg, d.grass_threshold, s, bx, by, lut, bb);
    for (int l = 0; ok && l < d.levels; l++) {
        if (l > 0) {
            int ax = bx, ay = by;
            merge_level(ba, &ax, &ay);
            merge_level(bb, &bx, &by);
        }
        double t[3];
        level_terms(ba, bb, bx * by, t);
        out->colour += t[0] / d.levels;
        out->coverage += t[1] / d.levels;
        out->structure += t[2] / d.levels;
    }
    free(ba);
    free(bb);
    if (!ok) return false;
    out->score = fmax(fmax(out->colour / d.colour_scale, out->structure / d.structure_scale),
                      out->coverage / d.coverage_scale);
    return true;
}

/* ---- hybrid seam (eval_image.h) ------------------------------------------------ */

eval_seam_desc_t eval_seam_desc_defaults(const eval_seam_desc_t *d)
{
    eval_seam_desc_t r = d ? *d : (eval_seam_desc_t){0};
    if (r.fade <= 0.0f) r.fade = 1.0f;
    if (r.window <= 0.0f) r.window = 3.0f;
    if (r.colour_scale <= 0) r.colour_scale = COLOUR_SCALE;
    if (r.coverage_scale <= 0) r.coverage_scale = COVERAGE_SCALE;
    return r;
}

/* Window statistics of one frame (near, far): CIELAB of the mean colour of
 * the grass pixels and of all counted pixels, grass fraction, counted
 * pixels. */
static bool seam_windows(const eval_seam_frame_t *f, const eval_seam_desc_t *d, const double *lut, double lab[2][3],
                         double lab_all[2][3], double grass[2], long pixels[2])
{
    double s = d->switch_distance, rgb[2][3] = {{0}}, all[2][3] = {{0}}, g[2] = {0}, n[2] = {0};
    size_t count = (size_t)f->img->w * (size_t)f->img->h;
    for (size_t i = 0; i < count; i++) {
        double x = f->dist[i];
        if (f->cls[i] == EVAL_SEAM_SKIP || !(fabs(x - s) > d->fade && fabs(x - s) <= d->fade + d->window)) continue;
        int side = x > s;
        n[side] += 1.0;
        const uint8_t *p = f->img->px + i * (size_t)f->img->channels;
        for (int c = 0; c < 3; c++) all[side][c] += lut[p[c]];
        if (f->cls[i] != EVAL_SEAM_GRASS) continue;
        for (int c = 0; c < 3; c++) rgb[side][c] += lut[p[c]];
        g[side] += 1.0;
    }
    for (int side = 0; side < 2; side++) {
        if (g[side] <= 0.0) return false;
        for (int c = 0; c < 3; c++) {
            rgb[side][c] /= g[side];
            all[side][c] /= n[side];
        }
        eval_linear_to_lab(rgb[side], lab[side]);
        eval_linear_to_lab(all[side], lab_all[side]);
        grass[side] = g[side] / n[side];
        pixels[side] = (long)n[side];
    }
    return true;
}

bool eval_image_seam(const eval_seam_frame_t *frame, const eval_seam_frame_t *ref, const eval_seam_desc_t *desc,
                     eval_seam_t *out)
{
    memset(out, 0, sizeof *out);
    eval_seam_desc_t d = eval_seam_desc_defaults(desc);
    const core_image_t *a = frame->img, *b = ref ? ref->img : NULL;
    if (d.switch_distance <= 0.0f || a->channels < 3 || (b && (b->w != a->w || b->h != a->h || b->channels < 3)))
        return false;
    double lut[256];
    for (int v = 0; v < 256; v++) lut[v] = eval_srgb_to_linear(v);
    bool ok = seam_windows(frame, &d, lut, out->lab[0], out->lab_all[0], out->grass[0], out->pixels[0]);
    if (ok && ref) {
        ok = seam_windows(ref, &d, lut, out->lab[1], out->lab_all[1], out->grass[1], out->pixels[1]);
    } else if (ok) {
        /* No reference: one that does not change across the band. */
        for (int side = 0; side < 2; side++) {
            memcpy(out->lab[1][side], out->lab[0][0], sizeof out->lab[1][side]);
            memcpy(out->lab_all[1][side], out->lab_all[0][0], sizeof out->lab_all[1][side]);
            out->grass[1][side] = out->grass[0][0];
        }
    }
    if (!ok) {
        memset(out, 0, sizeof *out);
        return false;
    }
    double e2 = 0.0, a2 = 0.0;
    for (int c = 0; c < 3; c++) {
        double v = (out->lab[0][1][c] - out->lab[0][0][c]) - (out->lab[1][1][c] - out->lab[1][0][c]);
        double va = (out->lab_all[0][1][c] - out->lab_all[0][0][c]) - (out->lab_all[1][1][c] - out->lab_all[1][0][c]);
        e2 += v * v;
        a2 += va * va;
        if (c == 0) {
            out->delta_l = v;
            out->delta_l_all = va;
        }
    }
    out->delta_e = sqrt(e2);
    out->delta_e_all = sqrt(a2);
    out->coverage = fabs((out->grass[0][1] - out->grass[0][0]) - (out->grass[1][1] - out->grass[1][0]));
    out->score = fmax(out->delta_e / d.colour_scale, out->coverage / d.coverage_scale);
    return true;
}

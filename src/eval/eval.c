/* eval: image metrics, heatmaps, Pareto fronts and report files. */
#include "eval/eval.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static double luma(const core_image_t *img, int x, int y)
{
    const uint8_t *p = img->px + ((size_t)y * (size_t)img->w + (size_t)x) * (size_t)img->channels;
    if (img->channels < 3) return p[0];
    return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

double eval_image_mad(const core_image_t *a, const core_image_t *b)
{
    if (a->w != b->w || a->h != b->h) return 1.0;
    double sum = 0;
    int ca = a->channels < 3 ? 1 : 3;
    for (int y = 0; y < a->h; y++)
        for (int x = 0; x < a->w; x++)
            for (int c = 0; c < ca; c++) {
                size_t i = ((size_t)y * (size_t)a->w + (size_t)x);
                sum += fabs((double)a->px[i * (size_t)a->channels + (size_t)c] -
                            (double)b->px[i * (size_t)b->channels + (size_t)c]);
            }
    return sum / ((double)a->w * a->h * ca * 255.0);
}

double eval_image_ssim(const core_image_t *a, const core_image_t *b)
{
    if (a->w != b->w || a->h != b->h || a->w < 8 || a->h < 8) return -1.0;
    const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    double total = 0;
    int windows = 0;
    for (int y0 = 0; y0 + 8 <= a->h; y0 += 4)
        for (int x0 = 0; x0 + 8 <= a->w; x0 += 4) {
            double ma = 0, mb = 0, va = 0, vb = 0, cov = 0;
            for (int y = y0; y < y0 + 8; y++)
                for (int x = x0; x < x0 + 8; x++) {
                    ma += luma(a, x, y);
                    mb += luma(b, x, y);
                }
            ma /= 64, mb /= 64;
            for (int y = y0; y < y0 + 8; y++)
                for (int x = x0; x < x0 + 8; x++) {
                    double da = luma(a, x, y) - ma, db = luma(b, x, y) - mb;
                    va += da * da, vb += db * db, cov += da * db;
                }
            va /= 63, vb /= 63, cov /= 63;
            total += ((2 * ma * mb + c1) * (2 * cov + c2)) / ((ma * ma + mb * mb + c1) * (va + vb + c2));
            windows++;
        }
    return total / windows;
}

bool eval_image_heatmap(const core_image_t *a, const core_image_t *b, int full_scale, core_image_t *out)
{
    if (a->w != b->w || a->h != b->h || !core_image_alloc(out, a->w, a->h, 4)) return false;
    for (int y = 0; y < a->h; y++)
        for (int x = 0; x < a->w; x++) {
            double t = fabs(luma(a, x, y) - luma(b, x, y)) / (full_scale > 0 ? full_scale : 64);
            t = t > 1 ? 1 : t;
            uint8_t *p = out->px + ((size_t)y * (size_t)a->w + (size_t)x) * 4;
            p[0] = (uint8_t)(255 * fmin(1, t * 3));
            p[1] = (uint8_t)(255 * fmin(1, fmax(0, t * 3 - 1)));
            p[2] = (uint8_t)(255 * fmin(1, fmax(0, t * 3 - 2)));
            p[3] = 255;
        }
    return true;
}

void eval_pareto(const double *x, const double *y, int n, bool *on_front)
{
    for (int i = 0; i < n; i++) {
        on_front[i] = true;
        for (int j = 0; j < n && on_front[i]; j++)
            if (j != i && x[j] <= x[i] && y[j] <= y[i] && (x[j] < x[i] || y[j] < y[i])) on_front[i] = false;
    }
}

void eval_pareto_noise(const double *x, const double *y, const double *ex, const double *ey, int n, bool *on_front)
{
    for (int i = 0; i < n; i++) {
        on_front[i] = true;
        for (int j = 0; j < n && on_front[i]; j++) {
            if (j == i) continue;
            double tx = ex ? fmax(ex[i], ex[j]) : 0.0, ty = ey ? fmax(ey[i], ey[j]) : 0.0;
            bool no_worse = x[j] <= x[i] + tx && y[j] <= y[i] + ty;
            bool better = x[j] < x[i] - tx || y[j] < y[i] - ty;
            if (no_worse && better) on_front[i] = false;
        }
    }
}

double eval_linear_fit(const double *x, const double *y, int n, double *slope, double *intercept)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0, syy = 0;
    for (int i = 0; i < n; i++) {
        sx += x[i];
        sy += y[i];
        sxx += x[i] * x[i];
        sxy += x[i] * y[i];
        syy += y[i] * y[i];
    }
    double vx = n * sxx - sx * sx, vy = n * syy - sy * sy, cxy = n * sxy - sx * sy;
    *slope = vx > 0 ? cxy / vx : 0.0;
    *intercept = n > 0 ? (sy - *slope * sx) / n : 0.0;
    return vx > 0 && vy > 0 ? cxy * cxy / (vx * vy) : 0.0;
}

bool eval_gnuplot(const char *script_path)
{
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>&1", script_path);
    FILE *p = popen(cmd, "r");
    if (!p) {
        core_log_warn("gnuplot: cannot run: charts skipped");
        return false;
    }
    char line[512];
    while (fgets(line, sizeof line, p)) {
        line[strcspn(line, "\n")] = 0;
        if (line[0]) core_log_info("gnuplot: %s", line);
    }
    int rc = pclose(p);
    if (rc != 0) core_log_warn("gnuplot %s failed (exit %d): charts missing", script_path, rc);
    return rc == 0;
}

bool eval_gnuplot_chart(const char *dir, const char *name, const char *body)
{
    char path[1200];
    core_buf_t g = {0};
    core_buf_printf(&g, "set terminal pngcairo size 800,500 noenhanced\nset output '%s/%s.png'\n%s\n", dir, name,
                    body);
    core_buf_printf(&g, "set terminal svg size 800,500 noenhanced\nset output '%s/%s.svg'\n%s\n", dir, name, body);
    snprintf(path, sizeof path, "%s/%s.gp", dir, name);
    bool ok = core_buf_write(&g, path) && eval_gnuplot(path);
    core_buf_free(&g);
    return ok;
}

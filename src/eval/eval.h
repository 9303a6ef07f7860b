/* eval: GL-free evaluation helpers for `meadow bench` and `meadow compare`:
 * image error (mean absolute difference, SSIM), diff heatmaps, Pareto fronts,
 * least squares lines and gnuplot charts. */
#ifndef MEADOW_EVAL_H
#define MEADOW_EVAL_H

#include <stdbool.h>
#include <stddef.h>

#include "core/core.h"

/* Mean absolute difference of the RGB channels, in [0, 1]. */
double eval_image_mad(const core_image_t *a, const core_image_t *b);
/* Mean SSIM of the luminance (Wang et al. 2004: 8x8 windows with stride 4,
 * C1 = (0.01*255)^2, C2 = (0.03*255)^2), in [-1, 1]; 1 = identical. */
double eval_image_ssim(const core_image_t *a, const core_image_t *b);
/* Heatmap of the per-pixel luminance difference (black -> red -> yellow ->
 * white over 0 .. `full_scale` levels). */
bool eval_image_heatmap(const core_image_t *a, const core_image_t *b, int full_scale, core_image_t *out);

/* Marks the Pareto-optimal points (minimise both x and y). */
void eval_pareto(const double *x, const double *y, int n, bool *on_front);
/* The same with each point's measured spread ex[i], ey[i] (>= 0; NULL: 0):
 * j dominates i only beyond the spread, tx = max(ex[i], ex[j]) and ty
 * likewise: x[j] <= x[i] + tx, y[j] <= y[i] + ty, and x[j] < x[i] - tx or
 * y[j] < y[i] - ty (no worse within the noise, better beyond it in one).
 * A point better than another by less than the spread in one measure and
 * worse beyond it in the other leaves the front; two points apart by less
 * than the spread in both stay on it. With zero spreads: eval_pareto. */
void eval_pareto_noise(const double *x, const double *y, const double *ex, const double *ey, int n, bool *on_front);
/* Least squares line y = intercept + slope x over n points; returns R^2
 * (0 when x or y does not vary, slope then 0). */
double eval_linear_fit(const double *x, const double *y, int n, double *slope, double *intercept);

/* Runs gnuplot on a script file (PNG + SVG terminals are the script's
 * business). Returns false, with a warning, when gnuplot is missing or fails. */
bool eval_gnuplot(const char *script_path);
/* A chart as dir/name.png and dir/name.svg (800 x 500): writes dir/name.gp
 * with `body` (settings and the plot command) under each terminal, then
 * runs it through eval_gnuplot. */
bool eval_gnuplot_chart(const char *dir, const char *name, const char *body);

#endif

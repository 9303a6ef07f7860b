/* stability: the stability suite of `meadow bench --stability` and
 * --report (stability.c): for each case a parameter swept until a method
 * breaks, measured with the accuracy metrics (measure_metrics.h) over
 * offscreen sessions. docs/METRICS.md "Stability variants and failure
 * measures" defines the measures; docs/RESULTS.md holds the table. */
#ifndef MEADOW_STABILITY_H
#define MEADOW_STABILITY_H

#include "core/core.h"
#include "world/world.h"

/* Stability suite: writes stability.csv, stability.md and
 * stability_<case>.png into out; with report (a folder) the screenshots
 * also go to report/images and md (when non-NULL) gets the table with links
 * relative to report.
 * Needs a current GL context (gfx_init done). Returns 0 or 1 (1 also for
 * an unknown case name). */
typedef struct stability_desc_t {
    const world_options_t *world; /* the program's options as the world takes them
                                     (app_world_options): every session starts from them */
    const char *only_case;        /* --case NAME: that case alone; NULL: every case */
    bool quick;                   /* two values per case */
} stability_desc_t;
int stability_run(const stability_desc_t *o, const char *out, core_buf_t *md, const char *report);

#endif

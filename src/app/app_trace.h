/* app_trace: the per-frame log of `meadow --frame-log` (OUT/frames.csv;
 * app_trace.c says what each column is). */
#ifndef MEADOW_APP_TRACE_H
#define MEADOW_APP_TRACE_H
#include <stdbool.h>

typedef struct world_t world_t;
typedef struct app_trace_t app_trace_t;

typedef struct app_trace_frame_t {
    int frame;                           /* 1-based */
    double wall_ms, submit_ms, thread_ms; /* as summary.txt's frame times */
    bool screenshot;                     /* the frame wrote one */
    const double *marks;                 /* world_frame_desc_t.marks of the frame, or NULL */
} app_trace_frame_t;

/* A log for frames.csv in folder `out`; NULL (logged) without memory. */
app_trace_t *app_trace_open(const char *out);
/* A row for the frame just done (no-op on NULL). */
void app_trace_row(app_trace_t *tr, world_t *w, const app_trace_frame_t *fr);
/* Writes frames.csv and frees the log; false (logged) when it could not
 * be written. NULL: true. */
bool app_trace_close(app_trace_t *tr);
#endif

/* app_hud: the HUD's list of pass timings as text, GL-free so a test can
 * feed it passes: a pass that has not run for APP_HUD_STALE_FRAMES frames
 * (a mode switched away at runtime, a start-up pass) is left out instead
 * of showing its last time for ever. */
#include "app/app.h"

#include <stdio.h>

int app_hud_timings(const app_hud_pass_t *passes, int count, char *buf, size_t size)
{
    int n = 0;
    if (size) buf[0] = 0;
    for (int i = 0; i < count && n < (int)size - 64; i++) {
        if (passes[i].frames_since > APP_HUD_STALE_FRAMES) continue;
        n += snprintf(buf + n, size - (size_t)n, "%-12s %7.3f ms\n", passes[i].name, passes[i].ms);
    }
    return n;
}

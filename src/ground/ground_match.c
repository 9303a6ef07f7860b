/* ground_match: the canopy match's step and window (ground_match.h). */
#include "ground/ground_match.h"

#include <math.h>
#include <string.h>

void ground_match_step(ground_match_state_t *s)
{
    if (s->frame[3] >= GROUND_MATCH_MIN_PIXELS && s->ref[3] >= GROUND_MATCH_MIN_PIXELS)
        for (int c = 0; c < 3; c++) {
            float f = (float)s->frame[c] / (float)s->frame[3], r = (float)s->ref[c] / (float)s->ref[3];
            float g = s->gain[c] * powf((f + 1.0f) / (r + 1.0f), GROUND_MATCH_RATE);
            s->gain[c] = fminf(fmaxf(g, GROUND_MATCH_GAIN_MIN), GROUND_MATCH_GAIN_MAX);
        }
    memset(s->frame, 0, sizeof s->frame);
    memset(s->ref, 0, sizeof s->ref);
}

void ground_match_window(float switch_distance, float fade, float out[2])
{
    out[1] = switch_distance - fade;
    out[0] = out[1] - GROUND_MATCH_WINDOW;
}

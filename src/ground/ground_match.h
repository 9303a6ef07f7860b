/* ground_match: the canopy match's rule (GL-free; the GLSL twin of the step
 * is shaders/ground/canopy_match_update.comp, ground.c runs it). Where the
 * hybrid's blades end in the ground canopy, the canopy's colour is scaled
 * per channel in linear light by a gain measured on the frame itself: over
 * the pixels whose ground lies in the seam measure's near window before the
 * switch band, the mean colour of the drawn grass against that of the
 * canopy drawn from the camera (canopy_match.comp). Each frame the gain
 * moves by the ratio's GROUND_MATCH_RATE power, so that the two means meet.
 * The table (blade_canopy.h) predicts the blades' mean colour to a few per
 * cent; what it leaves (the rasterizers' sampling of sub-pixel blades, the
 * spread of pixel values that a mean in linear light sees, the slopes'
 * gravity, the wind's crests) the match takes up where the two meet
 * (docs/HYBRID.md "Canopy match"). */
#ifndef MEADOW_GROUND_MATCH_H
#define MEADOW_GROUND_MATCH_H

#include <stdint.h>

/* The step's power of the ratio of the linear-light means: the gain is a
 * factor on the frame's stored colour, about the ratio's 1 / 2.4 power */
#define GROUND_MATCH_RATE 0.4f
#define GROUND_MATCH_MIN_PIXELS 32u  /* grass pixels each side needs for a step */
#define GROUND_MATCH_GAIN_MIN 0.5f
#define GROUND_MATCH_GAIN_MAX 2.0f
#define GROUND_MATCH_ROWS 270        /* a target of more rows samples every (rows / 270)-th pixel */
#define GROUND_MATCH_WINDOW 3.0f     /* m: the windows' width, eval_seam's */

/* The match's state as the GPU keeps it (canopy_match.comp's buffer): the
 * gain (rgb, w unused), then one frame's sums per side (the frame's, the
 * canopy's): linear-light rgb in fixed point (GROUND_MATCH_FIXED per unit)
 * and the pixels counted. */
typedef struct ground_match_state_t {
    float gain[4];
    uint32_t frame[4], ref[4];
} ground_match_state_t;

/* The step: the gain times ((frame + 1) / (ref + 1))^GROUND_MATCH_RATE of
 * the means in fixed point, clamped to [GROUND_MATCH_GAIN_MIN,
 * GROUND_MATCH_GAIN_MAX]; unchanged when a side counted fewer than
 * GROUND_MATCH_MIN_PIXELS; then the sums are zeroed. */
void ground_match_step(ground_match_state_t *s);

/* The near window [out[0], out[1]) of ground eye distance (m) before a
 * switch at `switch_distance` with a fade band of +-fade: the seam
 * measure's (eval_seam_desc_t's). */
void ground_match_window(float switch_distance, float fade, float out[2]);

#endif

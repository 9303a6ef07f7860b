/* bb_view: the views of the view-dependent clump cards (beyond Orthmann et
 * al. 2009, whose clump textures have one appearance). bb_layout bakes each
 * clump layer from the blade model once per view: `elevations` view
 * elevations from 0 to `elevation_max` (the card seen from above) times
 * `azimuths` directions of the wind relative to the view, spread over the
 * full circle (with the blades bent by the scene's mean wind). At draw time
 * a card blends the four bakes around its view direction (bilinear in
 * elevation and azimuth), dithered: each pixel shows the one bake that its
 * draw picks with the bake's weight as probability; bb_view_weights and
 * bb_view_pick are the rule, twins of shaders/billboard/bb_view.glsl.
 *
 * Frame of a view (the bake's "slab" frame): y up, z horizontal towards the
 * camera, x = y cross z (the viewer's right). The bake looks along -z from
 * elevation theta; azimuth phi is the angle of the wind in that frame,
 * wind = (sin phi, 0, -cos phi): phi 0 blows away from the viewer (looking
 * with the wind), pi towards it (against), pi/2 to the viewer's right. */
#ifndef MEADOW_BB_VIEW_H
#define MEADOW_BB_VIEW_H

#include <stdbool.h>

#define BB_VIEW_MAX 64 /* elevations x azimuths at most */

/* Zero means default. The defaults below are the views' when `on`. */
typedef struct bb_view_desc_t {
    int elevations;      /* view elevations baked, default 3 (0, 30, 60 degrees) */
    int azimuths;        /* wind azimuths baked over the circle, default 4 (with, right of,
                            against, left of the view) */
    float elevation_max; /* elevation of the last bake, radians, default pi/3 (60 degrees) */
    bool on;             /* true: the view-dependent cards (the bakes above, cards showing
                            their lit colour); default false: Orthmann's cards, one clump
                            image per layer drawn from the front without wind and lit by
                            the card's quad normal and the image row (elevations and
                            azimuths forced to 1) */
} bb_view_desc_t;
bb_view_desc_t bb_view_desc_defaults(const bb_view_desc_t *desc);

/* View v (0 <= v < elevations x azimuths; v = e azimuths + a): its elevation
 * e elevation_max / (elevations - 1) (0 when there is one) and azimuth
 * 2 pi a / azimuths. desc resolved. */
void bb_view_angles(const bb_view_desc_t *desc, int v, float *elevation, float *azimuth);

/* The blend of a card seen along to_eye (card point to camera, any length)
 * under the horizontal wind direction wind (x, z; (0, 0): none, azimuth 0):
 * views view[4] with weights w[4] (sum 1; elevation clamped to
 * [0, elevation_max], linear between neighbours; azimuth linear between
 * neighbours, wrapping). Looking straight down, the view's z is world +z. */
void bb_view_weights(const bb_view_desc_t *desc, const float to_eye[3], const float wind[2], int view[4], float w[4]);

/* The view of the four that a pixel with draw xi in [0, 1) shows (the
 * cards dither the blend: each pixel one bake): the first whose running
 * sum of weights exceeds xi, else the last. */
int bb_view_pick(const int view[4], const float w[4], float xi);

#endif

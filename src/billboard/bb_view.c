/* bb_view: the view set of the view-dependent clump cards and the blend
 * rule a card applies at draw time (twin: shaders/billboard/bb_view.glsl);
 * see bb_view.h. */
#include "billboard/bb_view.h"

#include <assert.h>
#include <math.h>

bb_view_desc_t bb_view_desc_defaults(const bb_view_desc_t *desc)
{
    bb_view_desc_t d = desc ? *desc : (bb_view_desc_t){0};
    if (d.elevations <= 0) d.elevations = 1;
    if (d.azimuths <= 0) d.azimuths = 4;
    if (d.elevation_max <= 0.0f) d.elevation_max = 1.0471976f;
    if (!d.on) d.elevations = d.azimuths = 1;
    assert(d.elevations * d.azimuths <= BB_VIEW_MAX && d.elevation_max < 1.5707964f);
    return d;
}

void bb_view_angles(const bb_view_desc_t *desc, int v, float *elevation, float *azimuth)
{
    assert(v >= 0 && v < desc->elevations * desc->azimuths);
    int e = v / desc->azimuths, a = v % desc->azimuths;
    *elevation = desc->elevations > 1 ? desc->elevation_max * (float)e / (float)(desc->elevations - 1) : 0.0f;
    *azimuth = 6.2831853f * (float)a / (float)desc->azimuths;
}

void bb_view_weights(const bb_view_desc_t *desc, const float to_eye[3], const float wind[2], int view[4], float w[4])
{
    float x[3], z[3];
    float len = sqrtf(to_eye[0] * to_eye[0] + to_eye[1] * to_eye[1] + to_eye[2] * to_eye[2]);
    float hl = sqrtf(to_eye[0] * to_eye[0] + to_eye[2] * to_eye[2]);
    z[0] = hl > 1e-6f ? to_eye[0] / hl : 0.0f;
    z[1] = 0.0f;
    z[2] = hl > 1e-6f ? to_eye[2] / hl : 1.0f;
    x[0] = z[2];
    x[1] = 0.0f;
    x[2] = -z[0];
    float elev = asinf(fminf(fmaxf(to_eye[1] / fmaxf(len, 1e-12f), 0.0f), 1.0f));
    int ne = desc->elevations, na = desc->azimuths;
    float t = ne > 1 ? fminf(elev / desc->elevation_max, 1.0f) * (float)(ne - 1) : 0.0f;
    int e0 = ne > 1 ? (int)fminf(floorf(t), (float)(ne - 2)) : 0, e1 = ne > 1 ? e0 + 1 : 0;
    float fe = ne > 1 ? t - (float)e0 : 0.0f;
    float wx = wind[0] * x[0] + wind[1] * x[2], wz = wind[0] * z[0] + wind[1] * z[2];
    float phi = atan2f(wx, -wz);
    phi = phi < 0.0f ? phi + 6.2831853f : phi;
    float s = phi / 6.2831853f * (float)na;
    float fs = floorf(s);
    int a0 = (int)fs % na, a1 = (a0 + 1) % na;
    float fa = s - fs;
    view[0] = e0 * na + a0;
    view[1] = e0 * na + a1;
    view[2] = e1 * na + a0;
    view[3] = e1 * na + a1;
    w[0] = (1.0f - fe) * (1.0f - fa);
    w[1] = (1.0f - fe) * fa;
    w[2] = fe * (1.0f - fa);
    w[3] = fe * fa;
}

int bb_view_pick(const int view[4], const float w[4], float xi)
{
    float sum = 0.0f;
    for (int i = 0; i < 3; i++) {
        sum += w[i];
        if (xi < sum) return view[i];
    }
    return view[3];
}

/* hybrid_slope: GL-free reference of the blade <-> billboard deformation
 * hand-over (see hybrid_slope.h; twin: shaders/common/slope.glsl). */
#include "hybrid/hybrid_slope.h"

#include <math.h>

hybrid_slope_grid_t hybrid_slope_grid(float min_x, float min_z, float tile_size, int tiles_x, int tiles_z,
                                      int cells_per_tile)
{
    hybrid_slope_grid_t g = {.origin = {min_x, min_z},
                             .cell = tile_size / (float)cells_per_tile,
                             .nx = tiles_x * cells_per_tile,
                             .nz = tiles_z * cells_per_tile};
    return g;
}

int hybrid_slope_cell_at(const hybrid_slope_grid_t *g, float x, float z)
{
    int i = (int)floorf((x - g->origin[0]) / g->cell), j = (int)floorf((z - g->origin[1]) / g->cell);
    if (i < 0 || j < 0 || i >= g->nx || j >= g->nz) return -1;
    return j * g->nx + i;
}

void hybrid_slope_offset(const float dir[3], const float pose_dir[3], float out[2])
{
    out[0] = dir[0] - pose_dir[0];
    out[1] = dir[2] - pose_dir[2];
}

static int32_t fixed(float v) { return (int32_t)lroundf(v * HYBRID_SLOPE_FIXED); }

void hybrid_slope_add(hybrid_slope_sum_t *s, const float o[2], float eta)
{
    s->t[0] += fixed(o[0]);
    s->t[1] += fixed(o[1]);
    s->m += fixed(sqrtf(o[0] * o[0] + o[1] * o[1]));
    s->eta += fixed(eta);
    s->count++;
}

hybrid_slope_cell_t hybrid_slope_resolve(const hybrid_slope_sum_t *s, float tau)
{
    hybrid_slope_cell_t c = {.tau = tau};
    if (s->count == 0) return c;
    float k = 1.0f / ((float)s->count * HYBRID_SLOPE_FIXED);
    c.t[0] = (float)s->t[0] * k;
    c.t[1] = (float)s->t[1] * k;
    c.m = (float)s->m * k;
    c.eta = (float)s->eta * k;
    c.count = (float)s->count;
    return c;
}

float hybrid_slope_weight(float age, float recover)
{
    float u = 1.0f - fminf(fmaxf(age / recover, 0.0f), 1.0f);
    return u * u * u;
}

void hybrid_slope_apply(const float pose_dir[3], const float fallback[2], const hybrid_slope_cell_t *c, float w,
                        float out_dir[3])
{
    float tl = sqrtf(c->t[0] * c->t[0] + c->t[1] * c->t[1]);
    float rest = fmaxf(c->m - tl, 0.0f);
    float q[2] = {pose_dir[0] + w * (c->t[0] + fallback[0] * rest), pose_dir[2] + w * (c->t[1] + fallback[1] * rest)};
    float ql = sqrtf(q[0] * q[0] + q[1] * q[1]);
    if (ql > HYBRID_SLOPE_MAX_TILT) {
        q[0] *= HYBRID_SLOPE_MAX_TILT / ql;
        q[1] *= HYBRID_SLOPE_MAX_TILT / ql;
        ql = HYBRID_SLOPE_MAX_TILT;
    }
    out_dir[0] = q[0];
    out_dir[1] = sqrtf(1.0f - ql * ql);
    out_dir[2] = q[1];
}

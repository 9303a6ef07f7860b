/* blade_lod: coverage-preserving thinning (blade_lod.h), the CPU twin of
 * shaders/common/lod.glsl: same functions, same order of operations. */
#include "blade/blade_lod.h"

#include <math.h>

#include "core/core.h"

static float clampf(float x, float lo, float hi) { return fminf(fmaxf(x, lo), hi); }

blade_lod_t blade_lod_defaults(const blade_lod_t *lod)
{
    blade_lod_t l = lod ? *lod : (blade_lod_t){0};
    if (l.start <= 0.0f) l.start = BLADE_LOD_START_DEFAULT;
    if (l.width_px <= 0.0f) l.width_px = BLADE_LOD_WIDTH_PX_DEFAULT;
    if (l.levels <= 0) l.levels = 8;
    if (l.max_scale < 1.0f) l.max_scale = 8.0f;
    l.shrink = l.no_shrink ? 0.0f : (l.shrink > 0.0f ? l.shrink : 0.1f);
    l.fade = l.no_fade ? 0.0f : (l.fade > 0.0f ? l.fade : 4.0f);
    return l;
}

float blade_lod_focal(const float viewproj[16], int height_px)
{
    /* row 1 of P V is P[1][1] times the view's unit up row */
    float y = sqrtf(viewproj[1] * viewproj[1] + viewproj[5] * viewproj[5] + viewproj[9] * viewproj[9]);
    return 0.5f * (float)height_px * y;
}

float blade_lod_rank(uint32_t index)
{
    uint32_t k = index & 255u, rev = 0;
    for (int b = 0; b < 8; b++) rev |= ((k >> b) & 1u) << (7 - b);
    return ((float)rev + core_hash_float(index * 0x9e3779b9u ^ 0x68e31da4u)) * (1.0f / 256.0f);
}

static int level_of(const blade_lod_t *l, float d, float cull)
{
    float end = l->level_distance > 0.0f ? l->level_distance : cull;
    float level = floorf((float)l->levels * (1.0f - d / end));
    return (int)clampf(level, 0.0f, (float)(l->levels - 1));
}

float blade_lod_kept(const blade_lod_t *l, float d, float width, float focal_px, float cull)
{
    float n = (float)l->levels;
    switch (l->rule) {
    case BLADE_LOD_WIDTH: {
        float far = fmaxf(l->start, width * focal_px / l->width_px);
        return d <= far ? 1.0f : far / d;
    }
    case BLADE_LOD_LEVELS:
        return ((float)level_of(l, d, cull) + 1.0f) / n;
    case BLADE_LOD_PRINTED:
        return (n - (float)level_of(l, d, cull)) / n;
    case BLADE_LOD_OFF:
        break;
    }
    return 1.0f;
}

float blade_lod_area(float u, float s)
{
    if (s <= 0.0f) return u;
    float a = u * (1.0f + s);
    float r0 = clampf(a - s, 0.0f, 1.0f), r1 = clampf(a, 0.0f, 1.0f);
    return r0 + ((a - r0) * (a - r0) - (a - r1) * (a - r1)) / (2.0f * s);
}

static float end_fade(const blade_lod_t *l, float d, float cull)
{
    return l->fade > 0.0f ? clampf((cull - d) / l->fade, 0.0f, 1.0f) : (d <= cull ? 1.0f : 0.0f);
}

static float widening(const blade_lod_t *l, float area)
{
    if (l->no_compensation || l->rule == BLADE_LOD_PRINTED) return 1.0f;
    return fminf(1.0f / fmaxf(area, 1e-6f), l->max_scale);
}

blade_lod_draw_t blade_lod_blade(const blade_lod_t *l, uint32_t index, float d, float width, float focal_px,
                                 float cull)
{
    float u = blade_lod_kept(l, d, width, focal_px, cull);
    float e = end_fade(l, d, cull);
    if (l->rule == BLADE_LOD_LEVELS || l->rule == BLADE_LOD_PRINTED) {
        int n = l->levels, level = level_of(l, d, cull);
        int m = (int)(index % (uint32_t)n);
        bool kept = l->rule == BLADE_LOD_LEVELS ? m <= level : m >= level;
        return (blade_lod_draw_t){.weight = kept ? e : 0.0f, .scale = widening(l, u)};
    }
    float s = l->shrink, r = blade_lod_rank(index);
    float w = s > 0.0f ? clampf((u * (1.0f + s) - r) / s, 0.0f, 1.0f) : (r < u ? 1.0f : 0.0f);
    return (blade_lod_draw_t){.weight = w * e, .scale = widening(l, blade_lod_area(u, s))};
}

float blade_lod_coverage(const blade_lod_t *l, float d, float width, float focal_px, float cull)
{
    float u = blade_lod_kept(l, d, width, focal_px, cull);
    float area = l->rule == BLADE_LOD_WIDTH ? blade_lod_area(u, l->shrink) : u;
    return clampf(area * widening(l, area), 0.0f, 1.0f) * end_fade(l, d, cull);
}

float blade_lod_ground(const blade_lod_t *l, float d, float width, float focal_px, float cull)
{
    return l->no_ground ? 0.0f : 1.0f - blade_lod_coverage(l, d, width, focal_px, cull);
}

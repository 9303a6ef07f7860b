/* bb_lod: coverage-preserving thinning of the billboard cards (bb_lod.h),
 * the CPU twin of shaders/billboard/bb_lod.glsl. */
#include "billboard/bb_lod.h"

#include <math.h>

blade_lod_t bb_lod_rule(const blade_lod_t *lod)
{
    blade_lod_t l = lod ? *lod : (blade_lod_t){.rule = BLADE_LOD_OFF};
    l.no_fade = true;
    return blade_lod_defaults(&l);
}

blade_lod_draw_t bb_lod_card(const blade_lod_t *rule, const bb_point_t *p, const float eye[3], float focal_px)
{
    if (rule->rule == BLADE_LOD_OFF) return (blade_lod_draw_t){.weight = 1.0f, .scale = 1.0f};
    float dx = p->position[0] - eye[0], dy = p->position[1] - eye[1], dz = p->position[2] - eye[2];
    float d = sqrtf(dx * dx + dy * dy + dz * dz);
    return blade_lod_blade(rule, p->seed, d, p->size[0], focal_px, BB_LOD_CULL);
}

float bb_lod_reach(const blade_lod_t *rule, float card_width)
{
    if (rule->rule == BLADE_LOD_OFF || rule->no_compensation || rule->max_scale <= 1.0f) return 0.0f;
    return 0.6f * card_width * (rule->max_scale - 1.0f);
}

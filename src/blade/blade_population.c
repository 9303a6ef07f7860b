/* blade_population: the defaults of a blade population (see
 * blade_population.h). */
#include "blade/blade_population.h"

#include <string.h>

/* A [min, max] range left at [0, 0] takes [lo, hi]. */
static void default_range(float r[2], float lo, float hi)
{
    if (r[0] != 0.0f || r[1] != 0.0f) return;
    r[0] = lo;
    r[1] = hi;
}

static void default_rgb(float c[3], const float def[3])
{
    if (c[0] == 0.0f && c[1] == 0.0f && c[2] == 0.0f) memcpy(c, def, 3 * sizeof *c);
}

blade_population_t blade_population_defaults(const blade_population_t *p)
{
    blade_population_t d = p ? *p : (blade_population_t){0};
    static const float root[3] = BLADE_DEFAULT_ALBEDO_ROOT, tip[3] = BLADE_DEFAULT_ALBEDO_TIP;
    if (d.density == 0.0f) d.density = BLADE_DEFAULT_DENSITY;
    default_range(d.height, BLADE_DEFAULT_HEIGHT_MIN, BLADE_DEFAULT_HEIGHT_MAX);
    default_range(d.width, BLADE_DEFAULT_WIDTH_MIN, BLADE_DEFAULT_WIDTH_MAX);
    default_range(d.stiffness, BLADE_DEFAULT_STIFFNESS_MIN, BLADE_DEFAULT_STIFFNESS_MAX);
    default_rgb(d.albedo_root, root);
    default_rgb(d.albedo_tip, tip);
    if (d.gravity <= 0.0f) d.gravity = BLADE_DEFAULT_GRAVITY;
    return d;
}

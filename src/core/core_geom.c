/* core_geom: small geometry helpers shared by the GL-free modules (the
 * octree broad phase, the hybrid tiles, the blades' draw order). */
#include "core.h"

float core_box_dist2(const float p[3], const float lo[3], const float hi[3])
{
    float d2 = 0.0f;
    for (int a = 0; a < 3; a++) {
        float q = p[a] < lo[a] ? lo[a] - p[a] : (p[a] > hi[a] ? p[a] - hi[a] : 0.0f);
        d2 += q * q;
    }
    return d2;
}

/* switch.glsl: the hybrid's one switch distance. Every decision of the
 * blade / billboard / canopy switch reads it: the tiles' representation
 * (hybrid.c, to the tile's box), the tiles' thinning (tiles_cull.comp,
 * blade_ref_cull_distance with eye_distance), the blades' fade (at the
 * root), the billboards' fades and the canopy's (per fragment), and the
 * seam measure (app_seam.c, per pixel): the eye distance |p - camera|. */
#ifndef SWITCH_GLSL
#define SWITCH_GLSL

float grass_distance(vec3 p, vec3 camera)
{
    return distance(p, camera);
}

#endif

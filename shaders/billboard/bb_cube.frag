#version 450
/* bb_cube.frag: one depth cube map texel (Orthmann et al. 2009, eq. 1-3
 * read it): distance from the face plane along `inward` and the object's
 * unit outward normal (cube space). The depth test keeps the nearest hit. */
in float v_dist;
in vec3 v_normal;

out vec4 texel;

void main()
{
    texel = vec4(v_dist, normalize(v_normal));
}

#version 450
/* bb_occlude.vert: an octree leaf's box for its occlusion query
 * (bb_occlude.c, Orthmann et al. 2009 sec. 6): 36 vertices, 12 triangles
 * over the 8 corners of [u_lo, u_hi] (corner bit 0: x, 1: y, 2: z). */
uniform mat4 u_viewproj;
uniform vec3 u_lo;
uniform vec3 u_hi;

void main()
{
    const int corners[36] = int[](0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                                  2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3);
    int c = corners[gl_VertexID];
    vec3 t = vec3(float(c & 1), float((c >> 1) & 1), float((c >> 2) & 1));
    gl_Position = u_viewproj * vec4(mix(u_lo, u_hi, t), 1.0);
}

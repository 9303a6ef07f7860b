/* heightfield.glsl: a heightfield terrain's vertex texels (normal xyz,
 * height w; RGBA32F, (res + 1)^2, texel (i, j) the vertex j (res + 1) + i,
 * the field centred on the origin, half_size its half side), interpolated
 * at a ground point over the mesh's triangles, split along their (i, j) -
 * (i + 1, j + 1) diagonal: the tiles' ground (tiles_common.glsl; C twin
 * blade_tiles_root) and the canopy match's (ground/canopy_match.comp). The
 * normal comes back unnormalized. */
#ifndef HEIGHTFIELD_GLSL
#define HEIGHTFIELD_GLSL

vec4 heightfield_at(sampler2D grid, int res, float half_size, vec2 xz)
{
    float cell = (2.0 * half_size) / float(res);
    float fx = (clamp(xz.x, -half_size, half_size) + half_size) / cell;
    float fz = (clamp(xz.y, -half_size, half_size) + half_size) / cell;
    int i = clamp(int(floor(fx)), 0, res - 1);
    int j = clamp(int(floor(fz)), 0, res - 1);
    float u = fx - float(i), v = fz - float(j);
    vec4 p00 = texelFetch(grid, ivec2(i, j), 0), p10 = texelFetch(grid, ivec2(i + 1, j), 0);
    vec4 p01 = texelFetch(grid, ivec2(i, j + 1), 0), p11 = texelFetch(grid, ivec2(i + 1, j + 1), 0);
    return v >= u ? p00 + u * (p11 - p01) + v * (p01 - p00) : p00 + u * (p10 - p00) + v * (p11 - p10);
}

#endif

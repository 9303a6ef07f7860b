/* extent.glsl: the texel of the shared extent map (bb_layout.h: where grass
 * grows) under ground point p, read by the tiles' cull and the ground
 * canopy: its candidate cell floor((p - origin) / spacing), wrapped as the
 * billboards' layout wraps it. */
#ifndef EXTENT_GLSL
#define EXTENT_GLSL

ivec2 extent_texel(sampler2D extent, vec2 p, vec2 origin, float spacing)
{
    /* the wrap in float: integer % took 0.08 of meadow_large's 0.95 ms
     * terrain pass (H200, compute path) */
    vec2 size = vec2(textureSize(extent, 0));
    vec2 cell = floor((p - origin) / spacing);
    return clamp(ivec2(cell - size * floor(cell / size)), ivec2(0), ivec2(size) - 1);
}

#endif

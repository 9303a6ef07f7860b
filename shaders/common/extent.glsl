/* extent.glsl: the texel of the shared extent map (bb_layout.h: where grass
 * grows) under ground point p, read by the tiles' cull and the ground
 * canopy: its candidate cell floor((p - origin) / spacing), wrapped as the
 * billboards' layout wraps it. */
#ifndef EXTENT_GLSL
#define EXTENT_GLSL

ivec2 extent_texel(sampler2D extent, vec2 p, vec2 origin, float spacing)
{
    ivec2 size = textureSize(extent, 0);
    ivec2 cell = ivec2(floor((p - origin) / spacing));
    return ((cell % size) + size) % size;
}

#endif

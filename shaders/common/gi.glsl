/* gi.glsl: the global illumination of Orthmann et al. 2009 sec. 6.1 (GLSL
 * twin of gi_volume_ambient, src/gi/gi_volume.h): the ambient light at a
 * point from the ambient-occlusion volume A and the irradiance volume
 * (irradiance / pi = a + B n of the sky seen through the terrain, the
 * objects and the grass), plus the ground's bounce light where the sky is
 * hidden:
 *   ambient(p, n) = a + B n + bounce (1 - A (1 + n.y) / 2).
 * The volumes span the box u_gi_lo + [0, 1] / u_gi_inv_size, on fixed
 * texture units (common/bindings_gi.glsl). u_gi_on 0 (the default of a program no one
 * sets it on): the hemispheric ambient of common/lighting.glsl instead.
 * Billboards take it per vertex (Orthmann's interpolation), blades and the
 * ground per fragment. docs/BILLBOARDS.md "Global illumination". */
#ifndef GI_GLSL
#define GI_GLSL

#include "common/bindings_gi.glsl"
#include "common/lighting.glsl"

#ifdef GRASS_GI_OFF
const int u_gi_on = 0; /* compiled out (blade_raster_list without GI) */
#else
uniform int u_gi_on;
#endif
uniform vec3 u_gi_lo;
uniform vec3 u_gi_inv_size;
uniform vec3 u_gi_bounce;
layout(binding = GI_TEX_AO) uniform sampler3D u_gi_ao;
layout(binding = GI_TEX_IRR0) uniform sampler3D u_gi_irr0;
layout(binding = GI_TEX_IRR1) uniform sampler3D u_gi_irr1;
layout(binding = GI_TEX_IRR2) uniform sampler3D u_gi_irr2;

/* The volumes' ambient at pos for the unit normal n. */
vec3 gi_ambient(vec3 pos, vec3 n)
{
    vec3 uvw = (pos - u_gi_lo) * u_gi_inv_size;
    float ao = texture(u_gi_ao, uvw).r;
    vec4 t0 = texture(u_gi_irr0, uvw), t1 = texture(u_gi_irr1, uvw), t2 = texture(u_gi_irr2, uvw);
    vec3 e = t0.rgb + n.x * vec3(t0.a, t1.rg) + n.y * vec3(t1.ba, t2.r) + n.z * t2.gba;
    return max(e + u_gi_bounce * (1.0 - ao * (1.0 + n.y) * 0.5), vec3(0.0));
}

/* The ambient light of a grass or ground point: the volumes' when on. */
vec3 grass_ambient(vec3 pos, vec3 n)
{
    return u_gi_on != 0 ? gi_ambient(pos, n) : hemisphere_ambient(n);
}

#endif

/* gi_volume: the global illumination of Orthmann et al. 2009 sec. 6.1, GL-free
 * (the reference the shaders follow, common/gi.glsl): an ambient-occlusion
 * volume and an irradiance volume of the field, both computed at start-up
 * from one set of rays per cell through the terrain (horizon angles of its
 * height profile), the static objects (boxes) and the grass (a density
 * layer of the grass's height over the ground, thinned by its cover).
 *   AO volume: A = (1/pi) int_up T(w) cos dw, the cosine-weighted share of
 *     the upper hemisphere the cell sees unoccluded (1 on open ground).
 *   Irradiance volume: the environment map's sky radiance seen through the
 *     same transmittance T, projected to first-order spherical harmonics and
 *     stored as irradiance / pi = a + B n (Ramamoorthi and Hanrahan 2001).
 * The ambient light a surface of unit normal n at p takes is then
 *   ambient(p, n) = a + B n + bounce (1 - A (1 + n.y) / 2),
 * the sky it sees plus the ground's bounce light from every direction the
 * sky is hidden in (below the horizon, and A's occluded share above it,
 * spread as a hemisphere): on open ground with no occluder it is the sky's
 * irradiance above and the ground's below, the hemispheric ambient of
 * common/lighting.glsl. docs/BILLBOARDS.md "Global illumination". */
#ifndef MEADOW_GI_VOLUME_H
#define MEADOW_GI_VOLUME_H

#include <stdbool.h>

/* Twins of common/lighting.glsl: sky_color's zenith and horizon, and the
 * hemispheric ambient's up and down colours. */
#define GI_SKY_ZENITH {0.36f, 0.55f, 0.85f}
#define GI_SKY_HORIZON {0.78f, 0.85f, 0.92f}
#define GI_AMBIENT_UP {0.35f, 0.42f, 0.55f}
#define GI_AMBIENT_DOWN {0.18f, 0.17f, 0.14f}

/* Floats per cell of the irradiance volume: a.rgb, then B's x, y, z columns
 * (each rgb), so irradiance / pi = a + n.x Bx + n.y By + n.z Bz. */
#define GI_IRR_FLOATS 12

/* Zero means default. */
typedef struct gi_volume_desc_t {
    int res[3];            /* cells along x, y, z; default 64, 16, 64 */
    float lo[3], hi[3];    /* the box the volume spans, required (hi > lo) */
    int azimuths;          /* ray azimuths per cell; default 8 */
    int elevations;        /* ray elevations per azimuth (equal solid angle); default 4 */
    float reach;           /* m, how far rays see the terrain and objects; default 24 */
    int steps;             /* terrain height samples per ray; default 12 */
    float soft;            /* radians: a ray within soft / 2 of the terrain's horizon is
                              partly visible; default 0.1 */
    float sky_zenith[3];   /* sky radiance at the zenith and the horizon (the sky's colour */
    float sky_horizon[3];  /* mixes as sky_color); default: GI_SKY_* scaled so that open
                              ground's up-facing ambient has GI_AMBIENT_UP's luminance */
    float bounce[3];       /* radiance of the ground and occluders; default GI_AMBIENT_DOWN */
} gi_volume_desc_t;

/* A static object's bounding box. */
typedef struct gi_object_t {
    float lo[3], hi[3];
} gi_object_t;

/* The occluders. All optional: no height function is flat ground at the
 * volume's floor, no cover function is cover 1. */
typedef struct gi_scene_t {
    float (*height)(const void *user, float x, float z); /* ground height (non-finite: none) */
    float (*cover)(const void *user, float x, float z);  /* grass cover in [0, 1] */
    const void *user;
    float grass_height;     /* m; 0: no grass layer */
    float grass_extinction; /* 1/m inside the layer at cover 1 (blade area per volume / 2) */
    float grass_near;       /* m: grass nearer than this along a ray is left to the blades'
                               own occlusion (grass_shade.glsl's ao); default: one cell (x) */
    const gi_object_t *objects;
    int object_count;
} gi_scene_t;

typedef struct gi_volume_t {
    int res[3];
    float lo[3], hi[3];
    float bounce[3];
    float *ao;  /* res[0] res[1] res[2] cells, x fastest, then y, then z (a GL 3-D texture) */
    float *irr; /* GI_IRR_FLOATS per cell, same order */
    double build_ms; /* wall time of gi_volume_make */
} gi_volume_t;

/* Returns d with the zero fields resolved. */
gi_volume_desc_t gi_volume_desc_defaults(const gi_volume_desc_t *d);

/* Computes both volumes; false (logged) on a bad desc or out of memory.
 * A cell below the ground is evaluated on the ground above it, so that
 * interpolation next to the ground never reads buried cells. */
bool gi_volume_make(gi_volume_t *v, const gi_volume_desc_t *desc, const gi_scene_t *scene);
void gi_volume_free(gi_volume_t *v);

/* Trilinear sample at pos as GL samples the 3-D textures (texel centres,
 * clamped to the edge): ao and irr[GI_IRR_FLOATS]. */
void gi_volume_sample(const gi_volume_t *v, const float pos[3], float *ao, float irr[GI_IRR_FLOATS]);

/* ambient(pos, n) of the banner (n unit), clamped at 0: gi_ambient of
 * common/gi.glsl. */
void gi_volume_ambient(const gi_volume_t *v, const float pos[3], const float n[3], float out[3]);

#endif

/* ground: the terrain as drawn and the sky behind it (ground.c). A terrain
 * mesh is uploaded and lit as soil and grass (ground/terrain.vert,
 * ground/terrain.frag); a world terrain (no vertices) is drawn as a clipmap
 * (terrain/terrain_clipmap.h): one grid of integer coordinates, five index
 * ranges, a draw per level of ground/terrain_world.vert displaced by the
 * world's height, the same fragment shader. Beyond the billboards the
 * ground is shaded as the ground canopy (blade_canopy.h,
 * shaders/common/canopy.glsl), thinned by an extent map; the sky gradient
 * fills what the ground leaves empty. The world (src/world) owns one. */
#ifndef MEADOW_GROUND_H
#define MEADOW_GROUND_H

#include <stdbool.h>

#include "grass_view/grass_view.h"
#include "blade/blade_canopy.h"
#include "blade/blade_lod.h"
#include "blade/blade_ref.h"
#include "core/core.h"
#include "gfx/gfx.h"
#include "gi/gi.h"
#include "ground/ground_match.h"
#include "terrain/terrain.h"

typedef struct ground_t ground_t;

/* The mesh's (or the world's clipmap's) buffers and programs; NULL when
 * they cannot be made (a GL object or a program failed, logged). The mesh
 * is read during the call only. */
ground_t *ground_make(const terrain_mesh_t *mesh);
/* Releases every object and g itself (NULL: nothing). */
void ground_destroy(ground_t *g);
/* The canopy's table (uploaded here, blade_canopy_pack's texture) and the
 * extent map that thins it (an R8 texture the caller owns, 0: none;
 * common/extent.glsl says which texel). */
void ground_set_canopy(ground_t *g, const blade_canopy_t *c, GLuint extent, const float origin[2], float spacing);
/* The winds (blade_env_t's, at most BLADE_MAX_WINDS; copied) whose force
 * at a ground point mixes the canopy table's wind poses; none: the rest
 * pose. */
void ground_set_winds(ground_t *g, const blade_wind_t *winds, int count);
/* A canopy table was set (more than one row). */
bool ground_has_canopy(const ground_t *g);
/* This frame's canopy band: none nearer than start, fully shaded beyond
 * end (m from the camera); end 0: no canopy drawn. overhang: the band is
 * the tiles' switch and the canopy continues their blades, standing for
 * the part of the blade column below the overhang of the last drawn ones
 * (common/canopy.glsl's cut; else the whole column, faded in). */
void ground_set_canopy_fade(ground_t *g, float start, float end, bool overhang);
/* Grass-shaded ground under thinned blades (blade_canopy_under with the
 * coverage blade_lod_coverage keeps): from this frame on, nearer than far
 * (m; beyond, only the canopy band of ground_set_canopy_fade), blades of
 * mean width `width` thinned by lod (NULL or lod->no_ground: off) with the
 * frame's focal length and cull distance. Needs a canopy table. */
void ground_set_lod(ground_t *g, const blade_lod_t *lod, float width, float focal_px, float cull, float far);
/* Global illumination of the ground and its canopy; zero: off. */
void ground_set_gi(ground_t *g, gi_bind_t gi);
/* The canopy match (ground_match.h), after the grass: measures the frame
 * in target against the canopy from the camera over the near window
 * before a switch at switch_distance (fade: the half width of its band),
 * where the opaque depth the grass was drawn over (a single-sample texture
 * of the target's size) shows the terrain, and steps the gain that the
 * canopy is drawn with from the next draw on. Nothing without a canopy
 * band, a colour texture in target or opaque_depth, or terrain normals to
 * shade the canopy by (a world's function, or ground_set_grid's). */
void ground_match(ground_t *g, const grass_view_t *view, const gfx_target_t *target, GLuint opaque_depth,
                  float switch_distance, float fade);
/* A heightfield's vertex normals and heights for the match (a texture the
 * caller owns, common/heightfield.glsl's layout: the tiles' ground), its
 * cells a side and the field's half side (m); 0: none, no match on a
 * heightfield. */
void ground_set_grid(ground_t *g, GLuint grid, int res, float half);
/* Starts compiling the match's programs (gfx_programs_prefetch), for a
 * field that will run it. */
void ground_match_prefetch(const ground_t *g);
/* The gain back to 1 and the sums to 0 (the match off, or a new view). */
void ground_match_reset(ground_t *g);
/* The gains and the sums the next step reads (a read-back: measures and
 * tests only). */
void ground_match_state(const ground_t *g, ground_match_state_t *out);
/* Draws the ground, then the sky where it left the far plane (inv_viewproj:
 * the inverse of view->viewproj, column-major). */
void ground_draw(const ground_t *g, const grass_view_t *view, const float inv_viewproj[16]);
#endif

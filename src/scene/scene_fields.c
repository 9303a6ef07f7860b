/* scene_fields: the table of scene keys (see scene_fields.h) and its
 * markdown rendering, docs/SCENES.md. */
#include "scene/scene_fields.h"

#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"

static const char *const mode_names[] = {"hybrid", "billboard", "blade", NULL};
static const char *const raster_names[] = {"auto", "hw", "compute", NULL};
static const char *const shape_names[] = {"quadratic", "quad", "triangle", "triangle_tip", "dandelion", NULL};
static const char *const blade_render_names[] = {"pull", "tess", NULL};
static const char *const hybrid_billboards_names[] = {"ring", "none", NULL};
static const char *const canopy_match_names[] = {"off", "on", NULL};
static const char *const terrain_names[] = {"heightfield", "mesh", "world", NULL};
static const char *const wind_names[] = {"directional", "point", NULL};
static const char *const collider_names[] = {"sphere", "capsule", "box", NULL};
static const char *const clearings_names[] = {"noise", "none", "image", NULL};
static const char *const lod_rule_names[] = {"width", "levels", "printed", "off", NULL};
static const char *const axis_names[] = {"auto", "+x", "-x", "+y", "-y", "+z", "-z", NULL};

/* Entry-type bits of scene_field_t.variants. */
#define DIRECTIONAL (1u << SCENE_WIND_DIRECTIONAL)
#define POINT (1u << SCENE_WIND_POINT)
#define SPHERE (1u << SCENE_COLLIDER_SPHERE)
#define CAPSULE (1u << SCENE_COLLIDER_CAPSULE)
#define BOX (1u << SCENE_COLLIDER_BOX)
#define NOISE (1u << SCENE_CLEARINGS_NOISE)
#define IMAGE (1u << SCENE_CLEARINGS_IMAGE)
#define HEIGHTFIELD (1u << TERRAIN_HEIGHTFIELD)
#define MESH (1u << TERRAIN_MESH)
#define WORLD (1u << TERRAIN_WORLD)

#define AT(T, m) .offset = offsetof(T, m), .size = sizeof(((T *)0)->m)
#define ROOT(m) .section = SCENE_SEC_ROOT, AT(scene_desc_t, m)
#define TERRAIN(m) .section = SCENE_SEC_TERRAIN, AT(terrain_desc_t, m)
#define GRASS(m) .section = SCENE_SEC_GRASS, AT(scene_grass_desc_t, m)
#define CLEARINGS(m) .section = SCENE_SEC_CLEARINGS, AT(scene_clearings_desc_t, m)
#define LOD(m) .section = SCENE_SEC_LOD, AT(blade_lod_t, m)
#define CAMERA(m) .section = SCENE_SEC_CAMERA, AT(scene_camera_desc_t, m)
#define CAMERA_KEY(m) .section = SCENE_SEC_CAMERA_KEY, AT(cam_path_key_t, m)
#define WIND(m) .section = SCENE_SEC_WIND, AT(scene_wind_t, m)
#define COLLIDER(m) .section = SCENE_SEC_COLLIDER, AT(scene_collider_t, m)
#define COLLIDER_KEY(m) .section = SCENE_SEC_COLLIDER_KEY, AT(scene_path_key_t, m)
#define CHARACTER(m) .section = SCENE_SEC_CHARACTER, AT(scene_character_t, m)

/* Rows in the order of the unknown-key lists and of parsing. */
const scene_field_t scene_fields[] = {
    /* ---- top level ---- */
    {ROOT(seed), .key = "seed", .type = SCENE_FIELD_U32, .hi = 4294967295.0, .flags = SCENE_FIELD_NO_DEFAULT,
      .doc = "random seed of everything generated (0 is a valid seed)", .def_doc = "0"},
    {ROOT(frames), .key = "frames", .type = SCENE_FIELD_INT, .lo = 1, .hi = 1e7, .def = {SCENE_DEFAULT_FRAMES},
      .flags = SCENE_FIELD_ZERO_OK,
      .doc = "frames of a headless run"},
    {ROOT(dt), .key = "dt", .type = SCENE_FIELD_FLOAT, .hi = 1, .def = {SCENE_DEFAULT_DT},
      .doc = "fixed timestep (s)", .def_doc = "1/60"},
    {ROOT(size), .key = "size", .type = SCENE_FIELD_INTS, .n = 2, .lo = 16, .hi = 16384,
      .def = {SCENE_DEFAULT_WIDTH, SCENE_DEFAULT_HEIGHT}, .flags = SCENE_FIELD_ZERO_OK,
      .doc = "framebuffer [w, h] (px); --size overrides it"},
    {ROOT(msaa), .key = "msaa", .type = SCENE_FIELD_INT, .hi = 16, .def = {SCENE_DEFAULT_MSAA},
      .flags = SCENE_FIELD_POW2, .doc = "samples per pixel of the hardware path (1 = off); the compute rasterizer draws the opaque "
             "scene single-sampled and the grass with its own samples"},
    {ROOT(mode), .key = "mode", .type = SCENE_FIELD_ENUM, .names = mode_names,
      .doc = "grass model: blades near and billboards far (hybrid), or one method alone"},
    {ROOT(raster), .key = "raster", .type = SCENE_FIELD_ENUM, .names = raster_names,
      .doc = "how grass is rasterized: the faster of the two measured at start-up (summary.txt says which "
             "and what the measure cost), the hardware pipeline, or compute shaders (docs/RASTER.md)"},
    {ROOT(raster_samples), .key = "raster_samples", .type = SCENE_FIELD_INT, .lo = 1, .hi = 4,
      .def = {SCENE_DEFAULT_RASTER_SAMPLES}, .flags = SCENE_FIELD_ENDS,
      .doc = "compute rasterizer samples per pixel: 4 (the 4x MSAA pattern) or 1 (the pixel centre); "
             "--raster-samples overrides it"},
    {ROOT(terrain), .key = "terrain", .type = SCENE_FIELD_OBJECT, .doc = "the ground (keys `terrain.*`)"},
    {ROOT(grass), .key = "grass", .type = SCENE_FIELD_OBJECT, .doc = "grass of both models (keys `grass.*`)"},
    {ROOT(camera), .key = "camera", .type = SCENE_FIELD_OBJECT, .doc = "the view (keys `camera.*`)"},
    {ROOT(wind), .key = "wind", .type = SCENE_FIELD_ARRAY, .hi = SCENE_MAX_WIND, .limit = "SCENE_MAX_WIND",
      .doc = "wind fields (keys `wind[].*`)", .def_doc = "none"},
    {ROOT(colliders), .key = "colliders", .type = SCENE_FIELD_ARRAY, .hi = SCENE_MAX_COLLIDERS,
      .limit = "SCENE_MAX_COLLIDERS", .doc = "analytic colliders (keys `colliders[].*`)", .def_doc = "none"},
    {ROOT(characters), .key = "characters", .type = SCENE_FIELD_ARRAY, .hi = SCENE_MAX_CHARACTERS,
      .limit = "SCENE_MAX_CHARACTERS", .doc = "walking characters (keys `characters[].*`)", .def_doc = "none"},

    /* ---- terrain ---- */
    {TERRAIN(type), .key = "type", .type = SCENE_FIELD_ENUM, .names = terrain_names,
      .doc = "procedural heightfield, an imported mesh, or the open world's height function (docs/WORLD.md)"},
    {TERRAIN(size), .key = "size", .variants = HEIGHTFIELD | WORLD, .type = SCENE_FIELD_FLOAT, .hi = 10000, .def = {TERRAIN_DEFAULT_SIZE},
      .doc = "heightfield or world side (m), square; a world's at most 8192 (TERRAIN_WORLD_SIZE_MAX)"},
    {TERRAIN(resolution), .key = "resolution", .variants = HEIGHTFIELD, .type = SCENE_FIELD_INT, .hi = TERRAIN_RESOLUTION_MAX,
      .def = {TERRAIN_DEFAULT_RESOLUTION}, .doc = "heightfield grid cells per side"},
    {TERRAIN(height), .key = "height", .variants = HEIGHTFIELD | WORLD, .type = SCENE_FIELD_FLOAT, .hi = 1000,
      .def = {TERRAIN_DEFAULT_HEIGHT}, .doc = "heightfield or world amplitude: heights in [-height, height] (m)"},
    {TERRAIN(mesh), .key = "mesh", .variants = MESH, .type = SCENE_FIELD_STRING, .flags = SCENE_FIELD_NO_DEFAULT,
      .doc = "mesh file, repository-relative; required when type is \"mesh\""},
    {TERRAIN(scale), .key = "scale", .variants = MESH, .type = SCENE_FIELD_FLOAT, .hi = 1e6, .def = {TERRAIN_DEFAULT_SCALE},
      .doc = "uniform scale of the mesh"},

    /* ---- grass ---- */
    {GRASS(population.density), .key = "density", .type = SCENE_FIELD_FLOAT, .hi = 10000,
      .def = {BLADE_DEFAULT_DENSITY}, .doc = "blades per m^2"},
    {GRASS(population.height), .key = "height", .type = SCENE_FIELD_RANGE, .hi = 10,
      .def = {BLADE_DEFAULT_HEIGHT_MIN, BLADE_DEFAULT_HEIGHT_MAX}, .doc = "blade height (m)"},
    {GRASS(population.width), .key = "width", .type = SCENE_FIELD_RANGE, .hi = 1,
      .def = {BLADE_DEFAULT_WIDTH_MIN, BLADE_DEFAULT_WIDTH_MAX}, .doc = "blade width (m)"},
    {GRASS(population.stiffness), .key = "stiffness", .type = SCENE_FIELD_RANGE, .hi = 100,
      .def = {BLADE_DEFAULT_STIFFNESS_MIN, BLADE_DEFAULT_STIFFNESS_MAX}, .flags = SCENE_FIELD_ABOVE_LO,
      .doc = "blade stiffness (1/s: recovery speed per metre of deflection, eq. 3); 0 is refused: such a blade "
             "never stands up"},
    {GRASS(billboard_density), .key = "billboard_density", .type = SCENE_FIELD_FLOAT, .hi = 1000,
      .def = {BB_DEFAULT_DENSITY}, .doc = "billboards per m^2"},
    {GRASS(billboard_size), .key = "billboard_size", .type = SCENE_FIELD_FLOATS, .n = 2, .hi = 20,
      .def = {BB_DEFAULT_WIDTH, BB_DEFAULT_HEIGHT}, .doc = "billboard [w, h] (m)"},
    {GRASS(switch_distance), .key = "switch_distance", .type = SCENE_FIELD_FLOAT, .hi = 1000,
      .def = {HYBRID_DEFAULT_SWITCH_DISTANCE}, .doc = "hybrid: blades nearer than this (m), billboards beyond"},
    {GRASS(canopy_distance), .key = "canopy_distance", .type = SCENE_FIELD_FLOAT, .hi = 100000,
      .def = {SCENE_DEFAULT_CANOPY_DISTANCE},
      .doc = "hybrid: billboards nearer than this (m), the ground shaded as grass canopy beyond (docs/HYBRID.md); "
             "with billboards (grass.billboards ring) at least switch_distance + 5 (the two fade bands apart)"},
    {GRASS(tile_size), .key = "tile_size", .type = SCENE_FIELD_FLOAT, .hi = 1000,
      .def = {HYBRID_DEFAULT_TILE_SIZE}, .doc = "side of the square grass tiles of the hybrid field (m)"},
    {GRASS(population.shape), .key = "shape", .type = SCENE_FIELD_ENUM, .names = shape_names,
      .doc = "blade shape function (Jahrmann & Wimmer 2017, section 5)"},
    {GRASS(blade_render), .key = "blade_render", .type = SCENE_FIELD_ENUM, .names = blade_render_names,
      .doc = "how the hardware path draws blades, in blade mode and the hybrid's tiles: instanced triangle strips "
             "by vertex pulling, or one patch per blade through the tessellation shaders (docs/BLADES.md); "
             "--blade-render overrides it"},
    {GRASS(displacement), .key = "displacement", .type = SCENE_FIELD_FLOAT, .hi = 4,
      .doc = "blades' 3-D shape, Jahrmann & Wimmer 2017 eq. 23 as printed, scaled by this (1: the paper): the midrib "
             "folds out of the blade by width/4 at the root (docs/BLADES.md); blade mode and the hybrid's tiles; 0: "
             "flat blades",
      .def_doc = "0 (off)"},
    {GRASS(width_correction), .key = "width_correction", .type = SCENE_FIELD_FLOAT, .hi = 1,
      .doc = "blades seen edge-on widened by 1 / max(|n.view|, this), at most 4x: the eq. 24 step as this project "
             "reads it (docs/BLADES.md); blade mode and the hybrid's tiles; 0: off",
      .def_doc = "0 (off)"},
    {GRASS(width_printed), .key = "width_printed", .type = SCENE_FIELD_FLOATS, .n = 2, .hi = 100,
      .doc = "[w_min, w_span] px: Jahrmann & Wimmer 2017 eq. 24 as printed, the variant of width_correction: a "
             "blade thinner on screen than w_min pixels is drawn as a quad, its shape back over w_span more "
             "(docs/BLADES.md); blade mode and the hybrid's tiles; w_span 0: off",
      .def_doc = "[0, 0] (off)"},
    {GRASS(subdiv), .key = "subdiv", .type = SCENE_FIELD_INTS, .n = 2, .lo = BB_SUBDIV_MIN,
      .hi = BB_SUBDIV_MAX, .def = {BB_DEFAULT_SUBDIV, BB_DEFAULT_SUBDIV}, .flags = SCENE_FIELD_ZERO_OK,
      .doc = "deformable billboard mesh [N columns, M rows]"},
    {GRASS(spring_iterations), .key = "spring_iterations", .type = SCENE_FIELD_INT, .hi = 64,
      .def = {BB_DEFAULT_SPRING_ITERATIONS}, .doc = "billboard spring relaxation sweeps per step (eq. 6-7)"},
    {GRASS(deformed_pool), .key = "deformed_pool", .type = SCENE_FIELD_INT, .hi = 262144,
      .def = {BB_DEFAULT_DEFORMED_POOL},
      .doc = "billboards deformed at once (the deformed-mesh pool's slots, N x M vec4 each); a full pool is "
             "reported"},
    {GRASS(tile_pool), .key = "tile_pool", .type = SCENE_FIELD_INT, .hi = 1024, .def = {HYBRID_DEFAULT_POOL_SLOTS},
      .doc = "hybrid: tiles simulated at once (state slots of one template of blades each); a full pool is "
             "reported"},
    {GRASS(cube_resolution), .key = "cube_resolution", .type = SCENE_FIELD_INT, .hi = 4096,
      .def = {BB_DEFAULT_CUBE_RESOLUTION}, .doc = "side of the collision depth cube maps (texels)"},
    {GRASS(cube_texel), .key = "cube_texel", .type = SCENE_FIELD_FLOAT, .hi = 10,
      .doc = "largest cube-map texel (m): the resolution rises above cube_resolution until the largest collider's "
             "texel (2 r / resolution) is at most this (capped by the GL's texture size, with a warning); 0: off",
      .def_doc = "0 (off)"},
    {GRASS(recover_time), .key = "recover_time", .type = SCENE_FIELD_FLOAT, .hi = 3600,
      .def = {SCENE_DEFAULT_RECOVER_TIME},
      .doc = "seconds grass takes to stand up after a push (billboards eq. 8, blade trails, hand-over)"},
    {GRASS(lod_table), .key = "lod_table", .type = SCENE_FIELD_STRING,
      .doc = "hybrid: a lod.json of `meadow bench --chart hybrid_canopy_distance`: on the GL renderer it was "
             "measured on, its switch and canopy distances (and with raster auto its path) replace the scene's "
             "(docs/HYBRID.md)",
      .def_doc = "\"\" (none)"},
    {GRASS(blade_distance), .key = "blade_distance", .type = SCENE_FIELD_FLOAT, .hi = SCENE_COORD_MAX,
      .doc = "blade mode: blades are drawn up to this distance (m) from the camera; 0: as far as grass is visible, "
             "the field's farthest corner or camera.far, whichever is nearer (the hybrid uses switch_distance)",
      .def_doc = "0 (the field)"},
    {GRASS(gi), .key = "gi", .type = SCENE_FIELD_BOOL,
      .doc = "global illumination (Orthmann et al. 2009 sec. 6.1): an ambient-occlusion and an irradiance volume of "
             "the terrain, static colliders and grass, computed at start-up, light billboards per vertex, blades, "
             "the ground and its canopy alike (docs/BILLBOARDS.md)"},
    {GRASS(bb_occlusion), .key = "bb_occlusion", .type = SCENE_FIELD_BOOL,
      .doc = "occlusion culling of billboard batches (Orthmann et al. 2009 sec. 6): an occlusion query per octree "
             "leaf's box; a leaf whose box was hidden last frame is not drawn (hardware path, docs/BILLBOARDS.md)"},
    {GRASS(bb_lod), .key = "bb_lod", .type = SCENE_FIELD_BOOL,
      .doc = "billboard cards thin with distance by the `grass.lod.*` rule, the card's width in place of the "
             "blade's: fewer cards, each narrowing to nothing before it is culled, the kept ones widened so the "
             "covered area stays (both rasterizer paths; no end fade; docs/BILLBOARDS.md)"},
    {GRASS(bb_lod_width_px), .key = "bb_lod_width_px", .type = SCENE_FIELD_FLOAT, .hi = 1000,
      .doc = "with bb_lod, the width rule: cards thin where they are this narrow on screen (px); a 1 m card at "
             "1.5 px (grass.lod.width_px's default) is over 400 m away at 720 rows, at 24 px 26 m",
      .def_doc = "0: grass.lod.width_px"},
    {GRASS(billboards), .key = "billboards", .type = SCENE_FIELD_ENUM, .names = hybrid_billboards_names,
      .doc = "hybrid: `ring` draws billboards between the blades and the ground canopy (a world streams them "
             "around the camera); `none` shades the ground as canopy from the switch distance, where the thinned "
             "blades end (docs/HYBRID.md)"},
    {GRASS(canopy_match), .key = "canopy_match", .type = SCENE_FIELD_ENUM, .names = canopy_match_names,
      .doc = "hybrid, where the blades end in the ground canopy (`billboards` none): `on` matches the canopy's colour to the "
             "blades' by a gain per channel measured on each frame, their mean colours in the seam measure's near "
             "window (docs/HYBRID.md \"Canopy match\"); `off` draws the table's colour as it is (the default: against blades "
             "drawn across the band the match made meadow_large's worst frames worse)"},
    {GRASS(lod), .key = "lod", .type = SCENE_FIELD_OBJECT,
      .doc = "how blades thin with distance (keys `grass.lod.*`)", .def_doc = "width"},
    {GRASS(clearings), .key = "clearings", .type = SCENE_FIELD_OBJECT,
      .doc = "bare ground of both models, the extent map (keys `grass.clearings.*`)", .def_doc = "noise"},

    /* ---- grass.clearings ---- */
    {CLEARINGS(type), .key = "type", .type = SCENE_FIELD_ENUM, .names = clearings_names,
      .doc = "bare blobs where a noise field dips, none (full coverage: a lawn, scenes/lawn.json), or a grey image"},
    {CLEARINGS(fraction), .key = "fraction", .variants = NOISE, .type = SCENE_FIELD_FLOAT, .hi = 1,
      .doc = "share of the ground left bare", .def_doc = "0 (the noise's fixed threshold: the share varies with the seed)"},
    {CLEARINGS(size), .key = "size", .variants = NOISE, .type = SCENE_FIELD_FLOAT, .hi = 10000,
      .doc = "blob scale (m): the cell of the noise's coarsest octave, rounded so the map tiles",
      .def_doc = "0 (about a quarter of the field's side)"},
    {CLEARINGS(image), .key = "image", .variants = IMAGE, .type = SCENE_FIELD_STRING,
      .flags = SCENE_FIELD_REQUIRED | SCENE_FIELD_NO_DEFAULT,
      .doc = "grey image file (PNG), repository-relative, stretched over the terrain seen from above (row 0 at "
             "-z, column 0 at -x): white grass, black bare"},

    /* ---- grass.lod ---- */
    {LOD(rule), .key = "rule", .type = SCENE_FIELD_ENUM, .names = lod_rule_names,
      .doc = "how blades thin with distance (blade mode and the hybrid's tiles; src/blade/blade_lod.h): by projected "
             "width, kept blades widened so the coverage stays; eq. 19-20 levels as the paper's text states them; "
             "eq. 20 as printed; or not at all"},
    {LOD(start), .key = "start", .type = SCENE_FIELD_FLOAT, .hi = 1e5, .def = {BLADE_LOD_START_DEFAULT},
      .doc = "width rule: nothing thinned nearer than this (m)"},
    {LOD(width_px), .key = "width_px", .type = SCENE_FIELD_FLOAT, .hi = 100, .def = {BLADE_LOD_WIDTH_PX_DEFAULT},
      .doc = "width rule: thinning starts where a blade is this narrow on screen (px); beyond, one blade is kept "
             "per this much drawn width"},
    {LOD(levels), .key = "levels", .type = SCENE_FIELD_INT, .hi = 256, .def = {8},
      .doc = "levels and printed rules: n of eq. 19-20"},
    {LOD(level_distance), .key = "level_distance", .type = SCENE_FIELD_FLOAT, .hi = 1e6,
      .doc = "levels and printed rules: where one blade in n remains (m)", .def_doc = "0: the cull distance"},
    {LOD(max_scale), .key = "max_scale", .type = SCENE_FIELD_FLOAT, .lo = 1, .hi = 64, .def = {8}, .flags = SCENE_FIELD_ZERO_OK,
      .doc = "the widest a kept blade is drawn (times its width); farther, the grass-shaded ground makes up the rest"},
    {LOD(shrink), .key = "shrink", .type = SCENE_FIELD_FLOAT, .hi = 1, .def = {0.1f},
      .doc = "width rule: rank window over which a blade narrows to nothing before it is culled (no pops)"},
    {LOD(fade), .key = "fade", .type = SCENE_FIELD_FLOAT, .hi = 1000, .def = {4},
      .doc = "blades narrow to nothing over this many metres before the cull distance (m)"},
    {LOD(no_shrink), .key = "no_shrink", .type = SCENE_FIELD_BOOL, .doc = "drop the shrink window: thinned blades pop"},
    {LOD(no_fade), .key = "no_fade", .type = SCENE_FIELD_BOOL, .doc = "drop the end fade: the grass ends in a hard cut"},
    {LOD(no_compensation), .key = "no_compensation", .type = SCENE_FIELD_BOOL,
      .doc = "kept blades keep their width (the field thins out; the ground shows through, grass-shaded)"},
    {LOD(no_ground), .key = "no_ground", .type = SCENE_FIELD_BOOL,
      .doc = "the ground under thinned blades keeps its soil colour instead of making up the coverage thinning "
             "removed as grass canopy"},

    /* ---- camera ---- */
    {CAMERA(position), .key = "position", .type = SCENE_FIELD_FLOATS, .n = 3, .lo = -SCENE_COORD_MAX, .hi = SCENE_COORD_MAX,
      .flags = SCENE_FIELD_NO_DEFAULT, .doc = "eye (m)", .def_doc = "[0, 8, 24] when target is also zero"},
    {CAMERA(target), .key = "target", .type = SCENE_FIELD_FLOATS, .n = 3, .lo = -SCENE_COORD_MAX, .hi = SCENE_COORD_MAX,
      .flags = SCENE_FIELD_NO_DEFAULT, .doc = "point looked at (m); must differ from position", .def_doc = "[0, 0, 0]"},
    {CAMERA(fov), .key = "fov", .type = SCENE_FIELD_FLOAT, .hi = 179, .def = {SCENE_DEFAULT_FOV},
      .doc = "vertical field of view (degrees)"},
    {CAMERA(near), .key = "near", .type = SCENE_FIELD_FLOAT, .hi = 1e4, .def = {SCENE_DEFAULT_NEAR},
      .doc = "near plane (m)"},
    {CAMERA(far), .key = "far", .type = SCENE_FIELD_FLOAT, .hi = 1e6, .def = {SCENE_DEFAULT_FAR},
      .doc = "far plane (m); must exceed near"},
    {CAMERA(path), .key = "path", .type = SCENE_FIELD_ARRAY, .hi = SCENE_MAX_PATH_KEYS,
      .limit = "SCENE_MAX_PATH_KEYS", .doc = "camera keys over time (keys `camera.path[].*`)", .def_doc = "none"},
    {CAMERA_KEY(t), .key = "t", .type = SCENE_FIELD_FLOAT, .lo = -SCENE_COORD_MAX, .hi = SCENE_COORD_MAX,
      .flags = SCENE_FIELD_REQUIRED | SCENE_FIELD_NO_DEFAULT, .doc = "time (s), strictly increasing"},
    {CAMERA_KEY(position), .key = "position", .type = SCENE_FIELD_FLOATS, .n = 3, .lo = -SCENE_COORD_MAX, .hi = SCENE_COORD_MAX,
      .flags = SCENE_FIELD_REQUIRED | SCENE_FIELD_NO_DEFAULT, .doc = "eye (m)"},
    {CAMERA_KEY(target), .key = "target", .type = SCENE_FIELD_FLOATS, .n = 3, .lo = -SCENE_COORD_MAX, .hi = SCENE_COORD_MAX,
      .flags = SCENE_FIELD_REQUIRED | SCENE_FIELD_NO_DEFAULT, .doc = "point looked at (m); must differ from position"},

    /* ---- wind ---- */
    {WIND(type), .key = "type", .type = SCENE_FIELD_ENUM, .names = wind_names,
      .doc = "travelling gusts along a direction, or a radial source"},
    {WIND(direction), .key = "direction", .variants = DIRECTIONAL, .type = SCENE_FIELD_FLOATS, .n = 2,
      .lo = -SCENE_COORD_MAX, .hi = SCENE_COORD_MAX, .flags = SCENE_FIELD_NO_DEFAULT, .doc = "(x, z), normalised on load", .def_doc = "[1, 0]"},
    {WIND(position), .key = "position", .variants = POINT, .type = SCENE_FIELD_FLOATS, .n = 3, .lo = -SCENE_COORD_MAX,
      .hi = SCENE_COORD_MAX, .flags = SCENE_FIELD_NO_DEFAULT, .doc = "centre (m)", .def_doc = "[0, 0, 0]"},
    {WIND(strength), .key = "strength", .type = SCENE_FIELD_FLOAT, .hi = 100, .def = {SCENE_DEFAULT_WIND_STRENGTH},
      .doc = "strength"},
    {WIND(wavelength), .key = "wavelength", .variants = DIRECTIONAL, .type = SCENE_FIELD_FLOAT, .hi = 1e4,
      .def = {SCENE_DEFAULT_WIND_WAVELENGTH}, .doc = "gust wavelength (m)"},
    {WIND(speed), .key = "speed", .variants = DIRECTIONAL, .type = SCENE_FIELD_FLOAT, .hi = 1000,
      .def = {SCENE_DEFAULT_WIND_SPEED}, .doc = "gust speed (m/s)"},
    {WIND(radius), .key = "radius", .variants = POINT, .type = SCENE_FIELD_FLOAT, .hi = 1e4,
      .def = {SCENE_DEFAULT_WIND_RADIUS}, .doc = "falloff radius (m)"},

    /* ---- colliders ---- */
    {COLLIDER(type), .key = "type", .type = SCENE_FIELD_ENUM, .names = collider_names,
      .doc = "shape (capsule: vertical axis; box: axis aligned)"},
    {COLLIDER(path), .key = "position", .type = SCENE_FIELD_CUSTOM, .n = 3, .lo = -SCENE_COORD_MAX, .hi = SCENE_COORD_MAX,
      .flags = SCENE_FIELD_NO_DEFAULT,
      .doc = "a static centre (m), not with path; on heightfields y is the height above the ground", .type_doc = "[3 numbers]", .def_doc = "[0, 0, 0]"},
    {COLLIDER(path), .key = "path", .type = SCENE_FIELD_ARRAY, .hi = SCENE_MAX_PATH_KEYS,
      .limit = "SCENE_MAX_PATH_KEYS", .doc = "a moving centre, not with position (keys `colliders[].path[].*`)", .def_doc = "none"},
    {COLLIDER(loop), .key = "loop", .type = SCENE_FIELD_BOOL, .doc = "repeat the path"},
    {COLLIDER(radius), .key = "radius", .variants = SPHERE | CAPSULE, .type = SCENE_FIELD_FLOAT, .hi = 100,
      .def = {SCENE_DEFAULT_SPHERE_RADIUS}, .doc = "radius (m)", .def_doc = "0.5 (sphere), 0.3 (capsule)"},
    {COLLIDER(length), .key = "length", .variants = CAPSULE, .type = SCENE_FIELD_FLOAT, .hi = 100,
      .def = {SCENE_DEFAULT_CAPSULE_LENGTH}, .doc = "segment length (m)"},
    {COLLIDER(half_extents), .key = "half_extents", .variants = BOX, .type = SCENE_FIELD_FLOATS, .n = 3,
      .hi = 100, .def = {SCENE_DEFAULT_HALF_EXTENT, SCENE_DEFAULT_HALF_EXTENT, SCENE_DEFAULT_HALF_EXTENT},
      .doc = "half size along x, y, z (m)"},
    {COLLIDER_KEY(t), .key = "t", .type = SCENE_FIELD_FLOAT, .lo = -SCENE_COORD_MAX, .hi = SCENE_COORD_MAX,
      .flags = SCENE_FIELD_REQUIRED | SCENE_FIELD_NO_DEFAULT, .doc = "time (s), strictly increasing"},
    {COLLIDER_KEY(position), .key = "position", .type = SCENE_FIELD_FLOATS, .n = 3, .lo = -SCENE_COORD_MAX, .hi = SCENE_COORD_MAX,
      .flags = SCENE_FIELD_REQUIRED | SCENE_FIELD_NO_DEFAULT, .doc = "centre (m)"},

    /* ---- characters ---- */
    {CHARACTER(model), .key = "model", .type = SCENE_FIELD_STRING,
      .flags = SCENE_FIELD_REQUIRED | SCENE_FIELD_NO_DEFAULT,
      .doc = "model file, repository-relative (e.g. models/humanoid.gltf); not empty"},
    {CHARACTER(clip_index), .key = "clip", .type = SCENE_FIELD_CUSTOM, .hi = 1000, .flags = SCENE_FIELD_NO_DEFAULT,
      .doc = "walk clip by name (a name of `clips` first, then the file's clips), or by index in [0, 1000]; "
             "`--clip` overrides it (the same names, or START:END)",
      .type_doc = "string or integer", .def_doc = "0 (the first clip)"},
    {CHARACTER(clip_ranges), .key = "clips", .type = SCENE_FIELD_CUSTOM, .hi = 1e7, .flags = SCENE_FIELD_NO_DEFAULT,
      .limit = "SCENE_MAX_CLIP_RANGES",
      .doc = "named ranges of one long clip, e.g. {\"walk\": [1, 14]}: frames (ticks of the model's first clip, "
             "as `meadow --list-clips` prints them; glTF: 1000 per second) start < end, at most 8 names "
             "(SCENE_MAX_CLIP_RANGES), none empty, an index or START:END; an end past the model's timeline is "
             "refused when it loads",
      .type_doc = "object of [start, end]", .def_doc = "none"},
    {CHARACTER(speed), .key = "speed", .type = SCENE_FIELD_FLOAT, .hi = 100, .def = {SCENE_DEFAULT_WALK_SPEED},
      .doc = "walking speed (m/s)"},
    {CHARACTER(scale), .key = "scale", .type = SCENE_FIELD_FLOAT, .hi = 1000,
      .def = {SCENE_DEFAULT_CHARACTER_SCALE}, .doc = "uniform scale on top of the import's fit (height and summary.txt include it)"},
    {CHARACTER(height), .key = "height", .type = SCENE_FIELD_FLOAT, .lo = 0.01, .hi = 1000, .flags = SCENE_FIELD_ZERO_OK,
      .doc = "fit the bind pose to this height (m); `--character-height` overrides it (the same range)",
      .def_doc = "0 (automatic: the file's unit, else metres when 0.25-3 units tall, else fitted to 1.75 m with a warning; docs/CHARACTERS.md)"},
    {CHARACTER(up), .key = "up", .type = SCENE_FIELD_ENUM, .names = axis_names,
      .doc = "the file's up axis", .def_doc = "auto (the file's metadata, else its format's convention, else +y)"},
    {CHARACTER(forward), .key = "forward", .type = SCENE_FIELD_ENUM, .names = axis_names,
      .doc = "the file's forward axis (where the model faces); not along `up`",
      .def_doc = "auto (the file's metadata, else its format's convention, else +z)"},
    {CHARACTER(rotation), .key = "rotation", .type = SCENE_FIELD_FLOAT, .lo = -360, .hi = 360,
      .flags = SCENE_FIELD_NO_DEFAULT,
      .doc = "turn about the vertical after import (degrees, counter-clockwise seen from above: 90 turns +z to +x)",
      .def_doc = "0"},
    {CHARACTER(waypoints), .key = "path", .type = SCENE_FIELD_ARRAY, .hi = SCENE_MAX_PATH_KEYS,
      .limit = "SCENE_MAX_PATH_KEYS", .doc = "waypoints [[x, z], ...], each component in [-1e6, 1e6]",
     .type_doc = "array of [x, z]", .def_doc = "stands at the origin"},
    {CHARACTER(loop), .key = "loop", .type = SCENE_FIELD_BOOL, .doc = "closed walk"},
};

const int scene_field_count = (int)(sizeof scene_fields / sizeof scene_fields[0]);

/* ---- lookups ------------------------------------------------------------- */

static const char *const section_names[SCENE_SEC_COUNT] = {
    "", "terrain", "grass", "grass.clearings", "grass.lod", "camera", "camera.path[]", "wind[]", "colliders[]", "colliders[].path[]", "characters[]",
};

const char *scene_section_name(scene_section_t section) { return section_names[section]; }

const scene_field_t *scene_field_find(scene_section_t section, const char *key)
{
    for (int i = 0; i < scene_field_count; i++)
        if (scene_fields[i].section == section && strcmp(scene_fields[i].key, key) == 0) return &scene_fields[i];
    return NULL;
}

bool scene_field_accepts(const scene_field_t *f, double x, char *why, size_t why_size)
{
    if ((f->flags & SCENE_FIELD_ZERO_OK) && x == 0) return true;
    if (f->flags & SCENE_FIELD_ENDS) {
        if (x == f->lo || x == f->hi) return true;
        snprintf(why, why_size, "%g is not %g or %g", x, f->lo, f->hi);
        return false;
    }
    bool above = f->flags & SCENE_FIELD_ABOVE_LO;
    if (x < f->lo || x > f->hi || (above && x == f->lo)) {
        snprintf(why, why_size, "%g is out of range %c%g, %g]%s", x, above ? '(' : '[', f->lo, f->hi,
                 f->flags & SCENE_FIELD_ZERO_OK ? " (or 0 for the default)" : "");
        return false;
    }
    if ((f->flags & SCENE_FIELD_POW2) && ((long)x & ((long)x - 1))) {
        int used = snprintf(why, why_size, "%ld is not one of 0", (long)x);
        for (long p = 1; p <= (long)f->hi && used > 0 && (size_t)used < why_size; p *= 2)
            used += snprintf(why + used, why_size - (size_t)used, ", %ld", p);
        return false;
    }
    return true;
}

/* ---- markdown ------------------------------------------------------------ */

typedef struct md_t {
    char *buf;
    size_t len, cap;
    bool failed;
} md_t;

__attribute__((format(printf, 2, 3))) static void md_printf(md_t *m, const char *fmt, ...)
{
    if (m->failed) return;
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int n = vsnprintf(m->buf + m->len, m->cap - m->len, fmt, ap);
        va_end(ap);
        if (n < 0) {
            m->failed = true;
            return;
        }
        if ((size_t)n < m->cap - m->len) {
            m->len += (size_t)n;
            return;
        }
        size_t cap = (m->cap + (size_t)n + 1) * 2;
        char *b = realloc(m->buf, cap);
        if (!b) {
            m->failed = true;
            return;
        }
        m->buf = b;
        m->cap = cap;
    }
}

static void md_names(md_t *m, const char *const *names)
{
    for (int i = 0; names[i]; i++) md_printf(m, "%s\"%s\"", i ? ", " : "", names[i]);
}

static void md_type(md_t *m, const scene_field_t *f)
{
    static const char *const plain[] = {
        [SCENE_FIELD_INT] = "integer", [SCENE_FIELD_U32] = "integer", [SCENE_FIELD_FLOAT] = "number",
        [SCENE_FIELD_RANGE] = "[min, max]", [SCENE_FIELD_ENUM] = "string", [SCENE_FIELD_BOOL] = "bool",
        [SCENE_FIELD_STRING] = "string", [SCENE_FIELD_OBJECT] = "object", [SCENE_FIELD_ARRAY] = "array",
        [SCENE_FIELD_CUSTOM] = "-"};
    if (f->type_doc) md_printf(m, "%s", f->type_doc);
    else if (f->type == SCENE_FIELD_INTS) md_printf(m, "[%d integers]", f->n);
    else if (f->type == SCENE_FIELD_FLOATS) md_printf(m, "[%d numbers]", f->n);
    else md_printf(m, "%s", plain[f->type]);
}

static void md_accepted(md_t *m, const scene_field_t *f)
{
    switch (f->type) {
    case SCENE_FIELD_ENUM: md_names(m, f->names); break;
    case SCENE_FIELD_BOOL: md_printf(m, "true, false"); break;
    case SCENE_FIELD_STRING: md_printf(m, "at most %zu bytes", f->size - 1); break;
    case SCENE_FIELD_OBJECT: md_printf(m, "-"); break;
    case SCENE_FIELD_ARRAY: md_printf(m, "at most %.10g entries (%s)", f->hi, f->limit); break;
    default:
        if (f->flags & SCENE_FIELD_POW2) {
            md_printf(m, "0");
            for (int v = 1; v <= (int)f->hi; v *= 2) md_printf(m, ", %d", v);
            break;
        }
        if (f->type == SCENE_FIELD_INTS || f->type == SCENE_FIELD_FLOATS || f->type == SCENE_FIELD_RANGE)
            md_printf(m, "each ");
        if (f->flags & SCENE_FIELD_ZERO_OK) md_printf(m, "0 or ");
        if (f->flags & SCENE_FIELD_ENDS) md_printf(m, "%.10g or %.10g", f->lo, f->hi);
        else md_printf(m, "%c%.10g, %.10g]", f->flags & SCENE_FIELD_ABOVE_LO ? '(' : '[', f->lo, f->hi);
        if (f->type == SCENE_FIELD_RANGE) md_printf(m, ", min <= max");
        break;
    }
}

static void md_default(md_t *m, const scene_field_t *f)
{
    if (f->def_doc) {
        md_printf(m, "%s", f->def_doc);
        return;
    }
    switch (f->type) {
    case SCENE_FIELD_ENUM: md_printf(m, "\"%s\"", f->names[0]); break;
    case SCENE_FIELD_BOOL: md_printf(m, "false"); break;
    case SCENE_FIELD_RANGE: md_printf(m, "[%g, %g]", (double)f->def[0], (double)f->def[1]); break;
    case SCENE_FIELD_INTS:
    case SCENE_FIELD_FLOATS:
        md_printf(m, "[");
        for (int k = 0; k < f->n; k++) md_printf(m, "%s%g", k ? ", " : "", (double)f->def[k]);
        md_printf(m, "]");
        break;
    case SCENE_FIELD_INT:
    case SCENE_FIELD_U32:
    case SCENE_FIELD_FLOAT: md_printf(m, "%g", (double)f->def[0]); break;
    default: md_printf(m, "-"); break;
    }
}

/* "*directional*: " for keys of some entry types only. */
static void md_variants(md_t *m, const scene_field_t *f)
{
    if (!f->variants) return;
    const scene_field_t *type = scene_field_find(f->section, "type");
    bool first = true;
    for (int i = 0; type && type->names[i]; i++) {
        if (!(f->variants & (1u << i))) continue;
        md_printf(m, "%s*%s*", first ? "" : ", ", type->names[i]);
        first = false;
    }
    md_printf(m, " only: ");
}

char *scene_keys_markdown(void)
{
    md_t m = {.buf = malloc(4096), .cap = 4096};
    if (!m.buf) return NULL;
    md_printf(&m, "# Scene keys\n\n"
                  "<!-- Generated by `meadow --scene-keys` from the table in src/scene/scene_fields.c;\n"
                  "     test_scene_json fails when this file differs from its output. -->\n\n"
                  "Scene files (`scenes/*.json`) are strict JSON: unknown keys, wrong types, values out\n"
                  "of range and too many entries are errors naming the file, line and field. Every\n"
                  "key is optional unless marked *required*; absent selects the default. An explicit\n"
                  "0 selects the default too where the *accepted* column allows 0, except where the\n"
                  "default column gives 0 a meaning of its own (a seed, a coordinate, \"0 (off)\");\n"
                  "where the column does not allow 0 (`raster_samples`, `grass.stiffness`) 0 is\n"
                  "refused. Command-line options that set a key (`--frames`, `--seed`, `--size`,\n"
                  "`--raster-samples`) accept what the key accepts, 0 for the default excepted.\n"
                  "`[]` in a key is an array entry. The defaults are the constants of\n"
                  "src/scene/scene_fields.h, which the modules' descs default to as well.\n");
    for (int s = 0; s < SCENE_SEC_COUNT; s++) {
        md_printf(&m, "\n## %s\n\n", s == SCENE_SEC_ROOT ? "Top level" : section_names[s]);
        md_printf(&m, "| key | type | accepted | default | meaning |\n| --- | --- | --- | --- | --- |\n");
        for (int i = 0; i < scene_field_count; i++) {
            const scene_field_t *f = &scene_fields[i];
            if ((int)f->section != s) continue;
            md_printf(&m, "| `%s%s%s` | ", section_names[s], s == SCENE_SEC_ROOT ? "" : ".", f->key);
            md_type(&m, f);
            md_printf(&m, " | ");
            md_accepted(&m, f);
            md_printf(&m, " | ");
            if (f->flags & SCENE_FIELD_REQUIRED) md_printf(&m, "*required*");
            else md_default(&m, f);
            md_printf(&m, " | ");
            md_variants(&m, f);
            md_printf(&m, "%s |\n", f->doc);
        }
    }
    if (m.failed) {
        free(m.buf);
        return NULL;
    }
    return m.buf;
}

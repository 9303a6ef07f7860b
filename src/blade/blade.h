/* blade: the GPU half of Jahrmann & Wimmer 2017, "Responsive Real-Time Grass
 * Rendering for General 3D Scenes". Uploads a seeded field (blade_seed.h),
 * simulates it in a compute shader (eq. 3-16 plus the collision exit of
 * blade_ref.h), culls it per patch and per blade in compute shaders
 * (eq. 17-20, the thinning with distance of blade_lod.h in place of the
 * distance levels) into an indirect draw command, and draws the
 * survivors, each as wide as the thinning says, either through tessellation (GL_PATCHES; the control shader
 * picks the level by distance, the evaluation shader builds the blade by
 * De Casteljau, eq. 21, with the shape functions of sec. 6.3 and the
 * optional displacement and width correction, eq. 23-24) or by vertex
 * pulling (instanced triangle strips reading the blade SSBO and the
 * survivor list: same geometry function, same levels), two-sided lighting
 * from shaders/common/lighting.glsl.
 *
 * Beyond both papers: the cube proxies of the collide set add depth
 * cube-map colliders (the billboard model's, Orthmann et al. 2009 eq. 1-5)
 * to the physics. The patch test (on the GPU: the patch boxes against the
 * frustum, the visible patches listed nearest first in distance buckets,
 * the blade cull dispatched indirectly over them) keeps the survivors
 * blade_ref_cull keeps; the blades of a culled patch are counted in
 * blade_gpu_stats_t.patch_culled only. Both, and every departure with its
 * measurement: docs/BLADES.md.
 *
 * Timer passes: "blade.physics", "blade.cull", "blade.draw". */
#ifndef MEADOW_BLADE_H
#define MEADOW_BLADE_H

#include <stdbool.h>
#include <stdint.h>

#include "grass_view/grass_view.h"
#include "blade/blade_ref.h"
#include "blade/blade_seed.h"
#include "blade/blade_seed_plan.h"
#include "gfx/gfx.h"
#include "gi/gi.h"
#include "raster/raster.h"
#include "terrain/terrain.h"

typedef enum blade_render_path_t {
    BLADE_PATH_TESSELLATION = 0, /* the desc's zero; the program passes grass.blade_render (pull by default) */
    BLADE_PATH_PULLING = 1,      /* instanced strips, vertex pulling */
} blade_render_path_t;

/* A field the GPU seeds (blade_seed_plan.h; blade_seed.comp and
 * blade_seed_boxes.comp, twins of blade_seed_plan_field): the plan and its
 * mesh (borrowed for the make only) and the extent map that thins it, an
 * R8 texture with blade_seed_extent_t's origin, spacing and key (texture 0:
 * no thinning). */
typedef struct blade_gpu_seed_t {
    const blade_seed_plan_t *plan;
    const blade_mesh_t *mesh;
    GLuint extent_texture;
    float extent_origin[2], extent_spacing;
    uint32_t extent_key;
} blade_gpu_seed_t;

/* Zero means default:
 *   field, seed    exactly one: field (seeded on the CPU, blade_seed.h) is
 *                  copied to the GPU (the caller may free it); seed is
 *                  seeded on the GPU, no blade crosses the bus
 *   shape          BLADE_SHAPE_QUADRATIC (the enum's 0)
 *   max_tess_level 8 segments along the blade at the nearest LOD (1..64)
 *   lod_distance   30 m: the level falls linearly from max_tess_level at
 *                  the camera to max(max_tess_level / 4, 1) at lod_distance
 *   cull           per-blade culling defaults for blade_gpu_cull calls with
 *                  desc NULL (blade_cull_desc_defaults)
 *   path           BLADE_PATH_TESSELLATION
 *   displacement   0: flat blades; k > 0: eq. 23 as printed, scaled by k
 *                  (1 the paper): p += k (width / 2) n (0.5 - |u - 0.5|
 *                  (1 - v)) (scene, grass.displacement); the tessellation
 *                  and the pulled strips then build 2 columns across the
 *                  width, the compute rasterizer keeps 1 (docs/BLADES.md)
 *   width_correction 0: off; > 0: the eq. 24 step, this project's reading
 *                  (docs/BLADES.md): a blade seen edge-on is widened by
 *                  1 / max(|n.view|, width_correction), at most 4x (scene,
 *                  grass.width_correction)
 *   width_printed  {w_min, w_span} px; w_span 0: off; > 0: eq. 24 as
 *                  printed, its variant (blade_ref_surface_desc_t): a blade
 *                  thinner on screen than w_min pixels is drawn as a quad,
 *                  its shape back over w_span more (the focal length from
 *                  blade_draw_desc_t.focal_px)
 *   no_patch_cull  false: the patch test on (blade_gpu_cull)
 *   label          "blade" (prefix of every GL object label) */
typedef struct blade_gpu_desc_t {
    const blade_field_t *field;
    const blade_gpu_seed_t *seed;
    blade_shape_t shape;
    int max_tess_level;
    float lod_distance;
    blade_cull_desc_t cull;
    blade_render_path_t path;
    float displacement;
    float width_correction;
    float width_printed[2];
    bool no_patch_cull;
    const char *label;
} blade_gpu_desc_t;

/* Latest culling statistics. */
typedef struct blade_gpu_stats_t {
    uint32_t total;        /* real blades (padding excluded) */
    uint32_t survivors;    /* blades in the draw command */
    uint32_t culled[4];    /* orientation, frustum, distance, occlusion (per blade) */
    uint32_t patch_culled; /* real blades of the patches the patch test culled */
    uint32_t patches_drawn; /* patches listed by the patch test (all without it) */
    bool valid;            /* false until a cull result has been read */
    long triangles_max;    /* survivors x 2 x max_tess_level: an upper bound of the
                              drawn triangles (level of detail lowers it with distance) */
} blade_gpu_stats_t;

/* The blade field on the GPU (opaque; blade_local.h). */
typedef struct blade_gpu_t blade_gpu_t;

/* What a made field holds (blade_gpu_info). */
typedef struct blade_gpu_info_t {
    blade_gpu_desc_t desc;  /* resolved; desc.field and desc.seed are NULL */
    uint32_t blade_count;   /* real blades */
    uint32_t thinned;       /* real blades a GPU seeding's extent map thinned to height 0 */
    uint32_t padded_count;  /* blades in the GPU arrays (padding has height 0): the length of
                               blade_gpu_read_blades' arrays */
    uint32_t patch_count, patch_size;
} blade_gpu_info_t;

/* Per-frame drawing parameters. Zero means default:
 *   view.viewproj, view.camera required; view.sun (0,0,0) ->
 *   normalize(0.4, 0.8, 0.3);
 *   fade_start = fade_end = 0: no fade; otherwise blades are fully drawn
 *   nearer than fade_start (distance from the camera to the root), absent
 *   beyond fade_end, and cross-faded in between by a dithered alpha that
 *   the fragment shader turns into its sample mask (blade_fade_mask; enable
 *   MSAA on the target for a smooth fade).
 *   albedo_root / albedo_tip (0,0,0) -> (0.10, 0.25, 0.05) / (0.45, 0.65, 0.20)
 *   (BLADE_DEFAULT_ALBEDO_ROOT / _TIP of blade/blade_population.h).
 *   focal_px: the frame's blade_lod_focal (eq. 24 as printed); 0: 1000. */
typedef struct blade_draw_desc_t {
    grass_view_t view; /* the frame's view (sun, planes and time not read) */
    float focal_px;
    float fade_start, fade_end;
    float albedo_root[3], albedo_tip[3];
    gi_bind_t gi; /* global illumination (common/gi.glsl); zero: off */
} blade_draw_desc_t;

blade_gpu_desc_t blade_gpu_desc_defaults(const blade_gpu_desc_t *desc);

/* Uploads the field and builds the programs. Returns NULL (logged, every
 * object released) on failure. */
blade_gpu_t *blade_gpu_make(const blade_gpu_desc_t *desc);
/* Releases every object and g itself (NULL: nothing). */
void blade_gpu_destroy(blade_gpu_t *g);
blade_gpu_info_t blade_gpu_info(const blade_gpu_t *g);

/* One physics step of every blade (timer "blade.physics") against the
 * spheres and cube proxies of `colliders` (NULL: none; any number of
 * spheres up to BLADE_MAX_SPHERES: the sphere buffer grows to hold them,
 * from 512, doubling; its cube_texture
 * holds cubes[k]'s faces in layers 6k .. 6k+5 as collide_cube.h describes,
 * e.g. bb_field_t's cube array or blade_gpu_upload_cubes'; its cube_maps
 * are not read). env is resolved with blade_env_defaults. */
void blade_gpu_update(blade_gpu_t *g, const blade_env_t *env, const collide_set_t *colliders);

/* Uploads CPU cube maps (all of one res) into a texture that g owns
 * (remade when the count or res changes; freed by blade_gpu_destroy), object
 * k in layers 6k .. 6k+5. Returns its name for a collide set's
 * cube_texture, 0 on failure (logged). count in 1..BLADE_MAX_CUBES. */
GLuint blade_gpu_upload_cubes(blade_gpu_t *g, const collide_cubemap_t *cubes, int count);

/* Culls for one frame (timer "blade.cull"): the patch test
 * (blade_patch_cull.comp, blade_patch_list.comp: boxes outside a clip
 * plane grown by the frustum tolerance dropped, blade_ref_box_outside; the
 * rest listed by distance bucket, blade_ref_patch_bucket over
 * max_distance) and blade_cull.comp dispatched indirectly over the listed
 * patches' blades; no work per patch or blade on the CPU, no wait. desc
 * NULL uses the make-time cull desc; desc->depth is ignored: depth_texture
 * is a GL_TEXTURE_2D of window depth (single sample, e.g. the resolved
 * depth of the previous frame's opaque pass), 0 for no occlusion test. */
void blade_gpu_cull(blade_gpu_t *g, const blade_cull_desc_t *desc, GLuint depth_texture);
/* Sets the u_lod_* uniforms of common/lod.glsl, the GLSL twin of
 * blade_lod.h, on the bound program p: lod resolved here
 * (blade_lod_defaults), the frame's focal length, the cull distance (m).
 * The blade and tile culls and the grass-shaded ground (ground.c) take it. */
void blade_lod_uniforms(gfx_program_t p, const blade_lod_t *lod, float focal_px, float cull);

/* Draws the survivors of the latest cull into the bound framebuffer (timer
 * "blade.draw"). Depth test on, no face culling (two-sided). Without a fade
 * band the program is opaque and depth tested before shading; with one
 * (desc->fade_end > fade_start) every blade takes the fade program
 * (discard, sample mask). */
void blade_gpu_draw(blade_gpu_t *g, const blade_draw_desc_t *desc);

/* Projected blade length in pixels per segment of the compute
 * rasterizer's level of detail (segments = ceil(projected length / this),
 * 1 to max_tess_level). */
#define BLADE_RASTER_SEGMENT_PIXELS 4.0f

/* Draws the survivors of the latest cull with the compute rasterizer
 * (timer "blade.raster"); the same surface and shading as blade_gpu_draw,
 * coverage from r's samples. Between raster_begin and raster_end. False
 * when the raster program cannot be made (logged). */
bool blade_gpu_raster(blade_gpu_t *g, raster_t *r, const blade_draw_desc_t *desc);
/* Starts compiling the raster program that blade_gpu_raster and
 * blade_tiles_raster make for a raster_t from rd, drawing with GI (gi) or
 * without (raster_program_prefetch): it builds while the caller goes on. */
void blade_raster_prefetch(const raster_desc_t *rd, bool gi);
/* Latest culling statistics without stalling (a result is read once its
 * GPU copy has completed, typically a frame or two late); with wait, the
 * latest cull is waited for and read (tests). */
blade_gpu_stats_t blade_gpu_stats(blade_gpu_t *g, bool wait);

/* Blocking reads for tests: blades (padded_count), eta, and the survivor
 * list of the latest cull: ids and their width factors (the thinning's
 * weight * scale; factors NULL: not read), each padded_count long; returns
 * the count. */
void blade_gpu_read_blades(const blade_gpu_t *g, blade_t *out, float *eta_out);
uint32_t blade_gpu_read_survivors(const blade_gpu_t *g, uint32_t *ids, float *factors);
/* Blocking read of the patch boxes (patch_count x 8 floats: min xyz, real
 * blades as uint bits, max xyz, 0), as the patch test reads them. */
void blade_gpu_read_patch_boxes(const blade_gpu_t *g, float (*out)[8]);
/* Blocking read of the patch list of the latest cull as the GPU wrote it
 * (in nondecreasing blade_ref_patch_bucket, any order within a bucket; out
 * holds patch_count); returns its length, 0 without the patch test
 * (no_patch_cull) or before the first cull. */
uint32_t blade_gpu_read_patches(const blade_gpu_t *g, uint32_t *out);
/* Blocking read of the sphere proxies the latest update's physics read
 * (its buffer, as the GPU holds it): writes at most max and returns their
 * count. */
int blade_gpu_read_spheres(const blade_gpu_t *g, blade_sphere_t *out, int max);
/* Blocking read of the indirect command {count, instanceCount, first, base}. */
void blade_gpu_read_command(const blade_gpu_t *g, uint32_t out[4]);
/* Replaces the blade state (tests): padded_count blades and eta (NULL: 0). */
void blade_gpu_write_blades(blade_gpu_t *g, const blade_t *blades, const float *eta);

#endif

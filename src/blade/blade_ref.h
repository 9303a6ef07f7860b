/* blade_ref: GL-free CPU reference of the per-blade simulation and culling of
 * Jahrmann & Wimmer 2017, "Responsive Real-Time Grass Rendering for General
 * 3D Scenes". Each blade is a quadratic Bézier curve v0 (root), v1 (control
 * point), v2 (simulated tip). The functions here are the exact twins of
 * shaders/common/blade.glsl, shaders/blade/blade_physics.comp,
 * shaders/blade/blade_cull.comp and shaders/blade/blade_geom.glsl, one
 * function per step so tests can check each: recovery (eq. 3), gravity
 * (eq. 4-6), wind (eq. 7-8), state validation (eq. 9-13), collision
 * (eq. 14-16), culling (eq. 17-20), the blade surface (eq. 21, 23, 24).
 *
 * blade_ref_step_one, in this order:
 *   1. height <= 0 (a padding blade): nothing happens;
 *   2. r, g, w are evaluated on the state at the start of the step;
 *   3. v2 += (r + g + w) k, k of blade_ref_step_gain (the paper's k is dt);
 *   4. validation (eq. 9-13): v1 placed, the tip rescaled about v0 by r;
 *   5. collision: v2 += d from v2 and the validated midpoint m, spheres
 *      first, then the depth cube maps of Orthmann et al. 2009 (eq. 1-5);
 *   6. after a contact only: the total translation validated once
 *      (blade_ref_revalidate), Coulomb friction, the collision exit;
 *   7. eta += k d.d (BLADE_ETA_DT / dt), then eta = clamp(eta - a dt, 0, 1).
 * Why each step departs from the paper, with the measurements:
 * docs/BLADES.md ("One simulation step", "Departures from the paper"). */
#ifndef MEADOW_BLADE_REF_H
#define MEADOW_BLADE_REF_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "grass_view/grass_view.h"
#include "blade/blade_lod.h"
#include "blade/blade_population.h"
#include "collide/collide_set.h"
#include "core/core.h"

/* One blade, 64 bytes (4 vec4), std430; mirrors `struct Blade` in
 * shaders/common/blade.glsl. */
typedef struct blade_t {
    float v0[4]; /* xyz root position, w: direction angle (radians) */
    float v1[4]; /* xyz Bézier control point, w: height */
    float v2[4]; /* xyz tip (the simulated point), w: width */
    float up[4]; /* xyz unit up vector at the root, w: stiffness */
} blade_t;

/* A wind field, 32 bytes (2 vec4), std430; mirrors `struct BladeWind` in
 * shaders/common/blade.glsl. Build with blade_wind_wave / blade_wind_point.
 *   kind BLADE_WIND_WAVE:  a = (dir.x, dir.z, wavelength, speed),
 *                          b = (strength, kind, 0, 0)
 *     w_i(p, t) = D * strength * (0.5 + 0.5 sin(2 pi (D.p - speed t) / wavelength))
 *     where D = normalize(dir.x, 0, dir.z): waves of gusts travelling along D.
 *   kind BLADE_WIND_POINT: a = (position.xyz, radius), b = (strength, kind, 0, 0)
 *     w_i(p, t) = normalize(p - position) * strength * max(1 - |p - position| / radius, 0)
 *     (radial blast, linear falloff; zero at the source point itself).
 * p is the blade root v0; the blade's wind is w = (sum_i w_i) * theta. */
typedef struct blade_wind_t {
    float a[4];
    float b[4];
} blade_wind_t;

#define BLADE_WIND_WAVE 0.0f
#define BLADE_WIND_POINT 1.0f

/* A sphere collider: the collide set's sphere proxy (centre, radius and
 * the step's sweep, std430), mirrored by `struct BladeSphere` in
 * shaders/common/blade.glsl. */
typedef collide_sphere_t blade_sphere_t;

#define BLADE_MAX_WINDS 8
#define BLADE_LENGTH_QUADRATURE 0 /* default: docs/BLADES.md */
#define BLADE_LENGTH_PAPER 1      /* eq. 12 with n = 2 */
#define BLADE_MAX_SPHERES COLLIDE_MAX_SPHERES
#define BLADE_ETA_DT (1.0f / 60.0f) /* step at which k d.d is the paper's eta gain */
#define BLADE_STIFFNESS_MIN 1e-3f   /* the tile pose's 1/s takes at least this s */

#define BLADE_MAX_CUBES COLLIDE_MAX_CUBES
#define BLADE_CUBE_MARGIN 1e-3f  /* exit target beyond the surface, in units of half */
#define BLADE_CUBE_DIRECTIONS 33 /* straight-blade candidates of the cube exit */

/* Per-frame environment. Zero means default:
 *   gravity_dir        (0,0,0) -> (0,-1,0); normalized when resolved
 *   gravity            0 -> 9.81 m/s^2 (forced to 0 when gravity_off)
 *   gravity_centre_mix t in [0,1]: 0 (default) pure direction gravity,
 *                      1 pure centre gravity towards gravity_centre
 *   collision_decay    a, 0 -> 1.0 per second (eta loses a*dt per step)
 *   collision_gain     k, 0 -> 1 (the paper): eta += k d.d (BLADE_ETA_DT / dt),
 *                      the paper's k d.d at 60 Hz. d is in metres,
 *                      so with k = 1 a push of a few cm leaves eta ~1e-3 and
 *                      the blade stands up at full speed; k ~ 1/(0.1 h)^2
 *                      makes a push of a tenth of the height count fully,
 *                      which keeps a trodden trail down while eta decays
 *   length_mode        BLADE_LENGTH_QUADRATURE (0) or BLADE_LENGTH_PAPER
 *   paper              false (default): this project's step; true: the
 *                      paper's step as printed, for the stability suite's
 *                      paper variant: explicit Euler (v2 += (r + g + w) dt),
 *                      eta += k d.d per step whatever dt, no friction and no
 *                      collision exit (the validation after a contact stays:
 *                      the paper validates its total translation once)
 * dt and time are used as given (seconds). */
/* The step the CPU bakes settle blades with (the clump layers, the ground
 * canopy): the scene's default dt (SCENE_DEFAULT_DT; test_scene_defaults). */
#define BLADE_SETTLE_DT (1.0f / 60.0f)
typedef struct blade_env_t {
    float dt;
    float time;
    float gravity_dir[3];
    float gravity;
    bool gravity_off;
    float gravity_centre[3];
    float gravity_centre_mix;
    float collision_decay;
    float collision_gain;
    int length_mode;
    bool paper;
    blade_wind_t winds[BLADE_MAX_WINDS];
    int wind_count;
} blade_env_t;

blade_env_t blade_env_defaults(const blade_env_t *env);

blade_wind_t blade_wind_wave(float dir_x, float dir_z, float strength, float wavelength,
                             float speed);
blade_wind_t blade_wind_point(const float position[3], float strength, float radius);

/* Width direction (unit, perpendicular to up; from the direction angle a:
 * (cos a, 0, sin a) projected onto the plane orthogonal to up, falling back
 * to (-sin a, 0, cos a) when up is nearly parallel to the first) and front
 * direction f = normalize(cross(up, width)). */
void blade_ref_frame(const blade_t *b, float width_dir[3], float front[3]);

/* Eq. 3: r = (I_v2 - v2) s max(1 - eta, 0.1), I_v2 = v0 + up h. */
void blade_ref_recovery(const blade_t *b, float eta, float out[3]);

/* Eq. 4-6: g_E = gravity ((1-t) D + t normalize(C - v0)), g_F = 1/4 |g_E| f,
 * g = g_E + g_F. env must be resolved (blade_env_defaults). */
void blade_ref_gravity(const blade_t *b, const blade_env_t *env, float out[3]);

/* w_i(p, time) of one field (see blade_wind_t). */
void blade_ref_wind_field(const blade_wind_t *w, const float p[3], float time, float out[3]);

/* Eq. 7-8: w = (sum_i w_i(v0, time)) theta, theta = f_d f_r,
 * f_d = 1 - |normalize(w_sum) . normalize(v2 - v0)|, f_r = (v2 - v0).up / h. */
void blade_ref_wind(const blade_t *b, const blade_env_t *env, float out[3]);

/* Sec. 5.2 collision (eq. 14-16), spheres in order (residual: docs/BLADES.md). Per sphere: v2 is pushed out of the
 * sphere along (v2 - c); then m = 1/4 v0 + 1/2 v1 + 1/4 v2 is recomputed and
 * v2 moves by 4 times m's push-out (a move of v2 moves m by a quarter),
 * scaled by p / (p + q) when a copy revalidated as the step will
 * (blade_ref_revalidate with rescale, the r returned by the validation
 * before the collision; length_mode) would leave m q > 0 outside (p: m's
 * penetration before the push).
 * Applies the displacement to b->v2 and writes the total into d.
 * Swept collision (beyond the paper): a sphere with a sweep is the capsule
 * between its previous and current centre; every test of a point p (the
 * push of v2, of m, the exit rotations of v2 and m, the straight exit, at
 * m, and friction's test of the start pose) takes the sphere of that
 * capsule closest to p (blade_ref_sphere_at), so a sphere moving more than
 * its diameter per step still bends every blade along its path instead of
 * tunnelling past them. A point behind the previous centre (on the side
 * the sphere moved away from) takes the current sphere: the sphere left
 * that region as the step began (departure from the plain capsule; it held
 * blades one whole step longer behind a sphere at low rates). */
void blade_ref_sphere_at(const blade_sphere_t *s, const float p[3], blade_sphere_t *out);
void blade_ref_collide(blade_t *b, const blade_sphere_t *spheres, int count, int length_mode, float rescale,
                       float d[3]);

/* Departure from the paper (collision exit, docs/BLADES.md); no-op for a
 * padding blade. Rounds: BLADE_EXIT_ROUNDS passes over the spheres in
 * order, each moving first v2 then m onto the distance r * BLADE_EXIT_MARGIN
 * from the centre by a rigid rotation of v1 and v2 about v0 in the plane of
 * (c - v0) and (p - v0); a rotation that would put v2 under the ground plane
 * is replaced by the rotation about up that brings the point onto the exit
 * distance of the sphere's cross-section at its height (the blade turns
 * along the ground; skipped when no turn clears it). Then, per sphere
 * still holding v2 or m, the blade is made the straight segment
 * v0 + u [0, h] (length exactly h) along the direction nearest the tip that
 * clears both points, on the ground plane when needed.
 * Spheres that contain the root are skipped. eta is not changed (d stays
 * the paper's push). */
#define BLADE_EXIT_ROUNDS 3
#define BLADE_EXIT_MARGIN 1.0001f
void blade_ref_exit(blade_t *b, const blade_sphere_t *spheres, int count);

/* Coulomb friction after a contact (departure, docs/BLADES.md), applied
 * after the revalidation and before the exit. Skipped when a sphere or cube
 * proxy of colliders holds start's v2 or m (wherever the root is).
 * Else, with mv = b.v2 - start.v2: |mv| <= BLADE_FRICTION |d|: b takes
 * start's v1 and v2; otherwise v1, v2 = start + (1 - BLADE_FRICTION |d| /
 * |mv|) (b - start), rescaled about v0 so length_estimate is h (left as b
 * when that length is under 1e-3 h). start: the blade at the start of the
 * step; d: the step's total push. No-op for a padding blade. mu = 0.5,
 * measured under a resting ball (no wind, 60 Hz, bench resting_blade,
 * worst tip change per frame at 7.5-8 s, stiffness 20/10/5/2, seeds 2, 3,
 * 5, 7, 8): 0.3 leaves 0.25/0.74/2.7/3.6 mm, 0.5 0.40/0.33/0.27/2.1 mm,
 * 1.0 0.007/0.007/0.007/2.4 mm (at stiffness 2 a blade leaning on the
 * ball creeps down its side at any mu). */
#define BLADE_FRICTION 0.5f
void blade_ref_friction(blade_t *b, const blade_t *start, const float d[3], const collide_set_t *colliders,
                        int length_mode);

/* Cube-map collision of one blade (docs/BLADES.md): every object's push of
 * v2 and then of m, applied to b->v2; the total goes into d. */
void blade_ref_collide_cubes(blade_t *b, const collide_cube_proxy_t *objects, const collide_cubemap_t *cubes,
                             int count, float d[3]);
/* The cube-map collision exit (docs/BLADES.md); no-op for a padding blade. */
void blade_ref_exit_cubes(blade_t *b, const collide_cube_proxy_t *objects, const collide_cubemap_t *cubes, int count);
/* Whether world point p is inside object k's shape per its cube map
 * (collide_test_inside after the broad phase). */
bool blade_ref_inside_cube(const collide_cube_proxy_t *object, const collide_cubemap_t *cube, const float p[3]);

/* Curve length as used by the validation: BLADE_LENGTH_PAPER is eq. 12
 * with n = 2, BLADE_LENGTH_QUADRATURE the split Gauss-Legendre arc length. */
float blade_ref_length_estimate(const blade_t *b, int length_mode);

/* Eq. 9-13: tip above the ground plane of the root, v1 placed from the
 * projected length, then v1 and v2 rescaled about v0 by r so the curve
 * length (blade_ref_length_estimate) equals the height. Returns r. No-op
 * for height <= 0 (returns 1). */
float blade_ref_validate(blade_t *b, int length_mode);

/* The validation after a contact (step 6, departure): v2 = v0 + (v2 - v0) /
 * rescale (undoing the rescale r that blade_ref_validate returned before the
 * collision), then blade_ref_validate. No-op for height <= 0. */
void blade_ref_revalidate(blade_t *b, int length_mode, float rescale);

/* Step 3's gain k = (1 - exp(-s' dt)) / s', s' = stiffness max(1 - eta, 0.1);
 * dt (1 - s' dt / 2) below s' dt = 1e-3. 0 < k <= dt, and k s' < 1 for
 * every s' and dt. */
float blade_ref_step_gain(float stiffness, float eta, float dt);

/* One step of one blade (order in the banner) against the spheres and the
 * cube proxies of `colliders` (its cube_maps, required when cube_count > 0;
 * NULL: no colliders). env must be resolved. */
void blade_ref_step_one(blade_t *b, float *eta, const blade_env_t *env, const collide_set_t *colliders);

/* Applies blade_ref_step_one to n blades; resolves env first. Pure function
 * of its inputs, deterministic. */
void blade_ref_step(blade_t *b, float *eta, size_t n, const blade_env_t *env, const collide_set_t *colliders);

/* Arc length of the blade's Bézier curve by summing `samples` chords. */
float blade_ref_curve_length(const blade_t *b, int samples);

/* Curve midpoint m = 1/4 v0 + 1/2 v1 + 1/4 v2. */
void blade_ref_midpoint(const blade_t *b, float m[3]);

/* ---- geometry (sec. 6.3, eq. 21; twin of shaders/blade/blade_geom.glsl) ----
 * Shapes: BLADE_SHAPE_* (blade_population.h), the values of the GLSL's
 * SHAPE_* (0 quadratic, 1 quad, 2 triangle, 3 triangle_tip, 4 dandelion).
 * The width profile f(v) of blade_profile. */
float blade_ref_profile(int shape, float v);

/* The surface point of blade_build at u (0..1 across the width) and v
 * (0 root, 1 tip) and its normal normalize(cross(b - a, width_dir)) (the
 * front direction where that degenerates), without eq. 23 and eq. 24
 * (u_displacement and u_width_correction 0: the program's default). */
void blade_ref_surface(const blade_t *b, int shape, float u, float v, float pos[3], float normal[3]);

/* The blade_geom.glsl uniforms of blade_ref_surface_at. Zero means off:
 *   shape            BLADE_SHAPE_* (0 quadratic)
 *   displacement     0: off; k > 0: eq. 23 as printed, scaled by k:
 *                    p += k (w / 2) n (0.5 - |u - 0.5| (1 - v)), w / 2 the
 *                    paper's w (eq. 21 spans c -+ w t1); k = 1 the paper
 *   width_correction 0: off; > 0: the eq. 24 step (this project's reading,
 *                    docs/BLADES.md): w / max(|n . view|, width_correction),
 *                    at most 4 w, view towards camera from the curve point
 *   width_printed    {w_min, w_span} px; w_span 0: off; > 0: eq. 24 as
 *                    printed (the form, after width_correction):
 *                    w_p = w focal_px / |camera - c| the blade's width in
 *                    pixels at the curve point, Phi = 1 - clamp((w_p -
 *                    w_min) / w_span, 0, 1), t = t (1 - Phi) + u Phi^2 (t
 *                    the shape's, u across the width): a blade thinner
 *                    than w_min pixels is drawn as a quad
 *   focal_px         pixels per unit tangent (blade_lod_focal; width_printed)
 *   camera           world position (width_correction, width_printed) */
typedef struct blade_ref_surface_desc_t {
    int shape;
    float displacement;
    float width_correction;
    float width_printed[2];
    float focal_px;
    float camera[3];
} blade_ref_surface_desc_t;

/* blade_ref_surface with eq. 23 and eq. 24 as desc sets them: the twin of
 * blade_build with the same uniforms (test_blade_surface). */
void blade_ref_surface_at(const blade_t *b, const blade_ref_surface_desc_t *desc, float u, float v, float pos[3],
                          float normal[3]);

/* ---- culling (sec. 6, eq. 17-20) ----------------------------------------
 * First the thinning (blade_lod.h) of a blade within max_distance, unless
 * the distance test is disabled: (weight, scale) = blade_lod_blade(lod,
 * index, d, width, focal_px, max_distance), d the distance of test 2,
 * width the blade's (v2.w); a survivor is drawn weight * scale times as
 * wide (its width factor; 1 without the distance test).
 * Tests, in this order (the first that fails culls the blade and only that
 * test's counter counts it; same order as the paper, cheapest first):
 *   0 orientation: dir_c = (v0 - cam) projected onto the blade's ground
 *     plane (orthogonal to up) and normalized, dir_b = width direction;
 *     culled when |dir_c . dir_b| > blade_ref_lod_orientation(
 *     orientation_threshold, width factor) (seen edge-on; a widened blade
 *     keeps the drawn width the plain threshold keeps).
 *     Skipped when the projection is shorter than 1e-6 (camera above).
 *   1 frustum: v0, m, v2 to clip space p = VP (x, 1); a point is inside when
 *     |p.x|, |p.y|, |p.z| <= p.w + frustum_tolerance; culled when none of the
 *     three is inside.
 *   2 distance: d = blade_ref_cull_distance (eq. 19's ground distance
 *     d_proj = |(v0 - cam) - up ((v0 - cam).up)|, or with eye_distance the
 *     hybrid's switch distance |v0 - cam|); culled when d > max_distance or
 *     the thinning's weight is 0 (eq. 19-20 are its rules LEVELS and
 *     PRINTED; the default WIDTH keeps a share by projected width,
 *     blade_lod.h, docs/BLADES.md).
 *   3 occlusion (only when depth != NULL): a point with p.w > 0 and NDC x,y
 *     inside [-1,1] maps to pixel (floor((x*0.5+0.5) W), floor((y*0.5+0.5) H))
 *     clamped to the image, row 0 at the bottom (glReadPixels order); it is
 *     occluded when ndc.z > depth[py*W+px] + depth_bias. Culled when v0, m
 *     and v2 are all occluded. depth holds NDC depth in [-1,1] (the shader
 *     reads window depth d and uses 2d-1).
 * Padding blades (height <= 0) are dropped before the tests and counted by
 * no counter. Zero means default:
 *   max_distance BLADE_CULL_MAX_DISTANCE_DEFAULT (60 m), orientation_threshold
 *   0.9, frustum_tolerance 0.1 (clip units), depth_bias 1e-3, lod
 *   blade_lod_defaults, focal_px 1000.
 * disable: bitmask of BLADE_CULL_* tests to skip (0: all enabled). */
enum {
    BLADE_CULL_VISIBLE = 0,
    BLADE_CULL_ORIENTATION = 1,
    BLADE_CULL_FRUSTUM = 2,
    BLADE_CULL_DISTANCE = 4,
    BLADE_CULL_OCCLUSION = 8,
    BLADE_CULL_PADDING = 16
};

#define BLADE_CULL_MAX_DISTANCE_DEFAULT 60.0f

typedef struct blade_cull_desc_t {
    grass_view_t view; /* the frame's view: camera and viewproj are read */
    float max_distance;
    float orientation_threshold;
    float frustum_tolerance;
    const float *depth; /* NULL: no occlusion test */
    int depth_w, depth_h;
    float depth_bias;
    uint32_t disable;
    bool eye_distance; /* distance test on |v0 - cam| instead of eq. 19's d_proj: the
                          hybrid's tiles, whose representation, thinning and fades
                          share one distance (docs/HYBRID.md); default false */
    blade_lod_t lod;   /* thinning with distance (blade_lod.h; resolved by the defaults) */
    float focal_px;    /* the frame's blade_lod_focal: pixels per unit tangent (BLADE_LOD_WIDTH);
                          0: 1000 */
} blade_cull_desc_t;

/* ---- the patch test of blade mode (beyond the paper; twins of
 * blade_patch_outside and blade_patch_bucket in shaders/common/blade.glsl,
 * run by blade_patch_cull.comp) ----------------------------------------------
 * blade_ref_box_outside: conservative box-vs-frustum, true when all 8
 * corners of [lo, hi] are outside one clip plane of viewproj grown by tol
 * (w +- x + tol < 0 for x, y, z). A patch box outside holds only blades
 * whose three sample points fail the frustum test (1) with the same
 * tolerance, so culling it removes no survivor. The tiles test their
 * boxes with it too. */
bool blade_ref_box_outside(const float lo[3], const float hi[3], const float viewproj[16], float tol);

/* Distance buckets the visible patches are listed in, nearest first. */
#define BLADE_PATCH_BUCKETS 256

/* The bucket of a patch box: floor(n sqrt(d / range)) clamped to [0, n - 1],
 * d = sqrt(core_box_dist2(camera, lo, hi)): square-root spacing, finer near
 * the camera where the order hides more (range 100 m, n 256: 1.5 mm wide
 * at the camera, 0.78 m at 100 m). range > 0. */
uint32_t blade_ref_patch_bucket(const float camera[3], const float lo[3], const float hi[3], float range, uint32_t n);

/* Culled counts per test, indexed 0 orientation, 1 frustum, 2 distance,
 * 3 occlusion (the order of the GPU counter buffer), and the survivors. */
typedef struct blade_cull_stats_t {
    uint32_t culled[4];
    uint32_t visible;
} blade_cull_stats_t;

blade_cull_desc_t blade_cull_desc_defaults(const blade_cull_desc_t *desc);

/* Which test culls blade `index` (a BLADE_CULL_* value, BLADE_CULL_VISIBLE
 * when it survives); a survivor's width factor (weight * scale of the
 * thinning) into *width_factor (NULL: not wanted). desc must be resolved. */
int blade_ref_cull_one(const blade_t *b, uint32_t index, const blade_cull_desc_t *desc, float *width_factor);

/* The distance the distance test (2) reads for blade b: eq. 19's d_proj, or
 * |v0 - cam| with desc->eye_distance. */
float blade_ref_cull_distance(const blade_t *b, const blade_cull_desc_t *desc);

/* Culls n blades; survivors (capacity n) receives the surviving indices in
 * increasing order (the GPU writes them in any order: compare as sets),
 * factors (capacity n, or NULL) their width factors in the same order.
 * Returns the number of survivors; stats may be NULL. Resolves desc. */
size_t blade_ref_cull(const blade_t *b, size_t n, const blade_cull_desc_t *desc, uint32_t *survivors,
                      float *factors, blade_cull_stats_t *stats);

/* Orientation threshold for a blade drawn width_scale times as wide (the
 * thinning's width factor; at most 1 changes nothing): the culling drops a
 * blade whose drawn width seen from the camera, width_scale sqrt(1 - c^2) for c =
 * |dir_c . dir_b|, is below what an unwidened blade keeps at the
 * threshold t, sqrt(1 - t^2): culled when c > sqrt(1 - (1 - t^2) /
 * width_scale^2). width_scale 1 gives t. Culling a blade widened 8 times
 * at t = 0.9 would drop a surface 8 times as wide as the test meant to
 * (on meadow_large the blades before the switch then showed 2 % more ground
 * than the billboards behind it). */
float blade_ref_lod_orientation(float threshold, float width_scale);

#endif

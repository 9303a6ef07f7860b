/* bench_stability: `meadow bench --stability`: for each case, sweeps one
 * parameter over small scenes built here (6 m heightfield, a few thousand
 * blades or a few hundred billboards; the wall cases write a small mesh
 * terrain and its scene file into the output folder for the run and remove
 * them afterwards), applies the case's failure
 * criterion and reports the first value where the method breaks, with a
 * screenshot of that run (or of the last value when none broke). The
 * measures come from bench_metrics.c (docs/METRICS.md): penetration against
 * the exact collider shapes, blade length error, recovery time after a
 * collider leaves (offset from an undisturbed twin world for blades, from
 * the wind pose of eq. 8 for billboards), jitter of a resting collider,
 * trail coverage of a fast collider (tunnelling), texture distortion of
 * deformed billboard meshes (worst frame; its rendering is the screenshot)
 * and root density on a mesh face relative to the floor. */
#include "bench/bench_local.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "platform/plat.h"

#define STAB_VALUES 6
#define RECOVERY_EPS 0.01 /* m: back within 1 cm of the undisturbed pose */
#define JITTER_TIME 8.0f  /* s a ball rests; the jitter is measured over the last 0.5 s */
#define PASS_FROM -2.5f
#define PASS_TO 2.5f

typedef enum stab_measure_t {
    MEASURE_STATIC = 0, /* metrics of the last frame */
    MEASURE_PASS,       /* a ball passes once and leaves: recovery, coverage */
    MEASURE_JITTER,     /* a ball rests: frame-to-frame offset change */
    MEASURE_DISTORTION, /* billboard texture distortion, worst frame of the run */
} stab_measure_t;

typedef struct stab_result_t {
    bench_metrics_t m;
    bench_metrics_ext_t x;
    double recovery;  /* s after the collider left; INFINITY: not recovered */
    double coverage;  /* trail coverage: blades ever deflected during the pass */
    double jitter;    /* m per frame over the last 0.5 s */
    bench_bb_distortion_t distortion; /* worst stretch and fold count over the frames */
    double measure;   /* the case's measure */
    bool fails;
} stab_result_t;

typedef struct stab_case_t {
    const char *name;
    scene_mode_t mode;
    const char *param;
    float values[STAB_VALUES];
    stab_measure_t measure;
    const char *measure_name;
    const char *criterion;
    const char *note;
    void (*setup)(scene_desc_t *s, float v);
    /* Fills r->measure and r->fails; first is the run of values[0]. */
    void (*judge)(stab_result_t *r, const stab_result_t *first, float v, float dt);
} stab_case_t;

/* ---- scenes ----------------------------------------------------------------- */

static void base_scene(scene_desc_t *s)
{
    s->terrain = (terrain_desc_t){.type = TERRAIN_HEIGHTFIELD, .size = 6, .resolution = 16, .height = 0.05f};
    terrain_desc_t td = terrain_desc_defaults(&s->terrain);
    s->terrain = td;
    s->grass.density = 60;
    s->grass.height[0] = 0.35f;
    s->grass.height[1] = 0.5f;
    s->grass.billboard_density = 6;
    s->grass.billboard_size[0] = 0.6f;
    s->grass.billboard_size[1] = 0.4f;
    s->grass.subdiv[0] = s->grass.subdiv[1] = 4;
    s->grass.cube_resolution = 16;
    s->grass.spring_iterations = 2;
    s->grass.recover_time = 1.0f;
    s->dt = 1.0f / 60.0f;
    s->size[0] = 240;
    s->size[1] = 160;
    s->msaa = 1;
    s->wind_count = 1;
    s->wind[0] = (scene_wind_t){.type = SCENE_WIND_DIRECTIONAL, .direction = {1, 0}, .strength = 0.5f,
                                .wavelength = 4, .speed = 1};
    s->camera.path.count = 0;
    glm_vec3_copy((vec3){0.0f, 1.8f, 3.0f}, s->camera.position);
    glm_vec3_copy((vec3){0.0f, 0.1f, 0.0f}, s->camera.target);
    s->collider_count = 0;
    s->character_count = 0;
}

static scene_collider_t *add_sphere(scene_desc_t *s, float r, float x, float y, float z)
{
    scene_collider_t *c = &s->colliders[s->collider_count++];
    *c = (scene_collider_t){.type = SCENE_COLLIDER_SPHERE, .radius = r};
    c->path.count = 1;
    glm_vec3_copy((vec3){x, y, z}, c->path.keys[0].position);
    return c;
}

/* A ball crossing the field along x at z = 0 from t = 0 to t_pass, then
 * lifted 30 m within a millisecond (it leaves). */
static void add_pass(scene_desc_t *s, float r, float t_pass)
{
    scene_collider_t *c = add_sphere(s, r, PASS_FROM, r, 0);
    c->path.count = 3;
    c->path.keys[1] = (scene_path_key_t){.t = t_pass, .position = {PASS_TO, r, 0}};
    c->path.keys[2] = (scene_path_key_t){.t = t_pass + 0.001f, .position = {PASS_TO, 30.0f, 0}};
}

#define PASS_SPEED 5.0f
#define PASS_TIME ((PASS_TO - PASS_FROM) / PASS_SPEED)

/* The ball waits one step at the end of the path before it leaves, so the
 * last sampled position is the path's end whatever the speed (a lift within
 * the step after a sampled position short of the end would cut the corner
 * at speeds where a step is a large part of the path). */
static void setup_tunnel(scene_desc_t *s, float v)
{
    float t_pass = (PASS_TO - PASS_FROM) / v;
    add_pass(s, 0.3f, t_pass);
    scene_collider_t *c = &s->colliders[s->collider_count - 1];
    c->path.count = 4;
    c->path.keys[3] = c->path.keys[2];
    c->path.keys[3].t = t_pass + s->dt + 0.001f;
    c->path.keys[2] = c->path.keys[1];
    c->path.keys[2].t = t_pass + s->dt;
}
static void setup_rate(scene_desc_t *s, float v)
{
    s->dt = 1.0f / v;
    add_pass(s, 0.3f, PASS_TIME);
}
static void setup_thin(scene_desc_t *s, float v)
{
    scene_collider_t *c = add_sphere(s, 0, 0, 0.3f, 0);
    c->type = SCENE_COLLIDER_BOX;
    glm_vec3_copy((vec3){0.6f, 0.3f, v}, c->half_extents);
}
static void setup_concave(scene_desc_t *s, float v)
{
    add_sphere(s, 0.35f, -0.5f * v, 0.3f, 0);
    add_sphere(s, 0.35f, 0.5f * v, 0.3f, 0);
}
static void setup_large(scene_desc_t *s, float v)
{
    s->grass.cube_texel = 0.02f;
    add_sphere(s, v, 0, v - 0.15f, 0);
    glm_vec3_copy((vec3){0.0f, 1.2f + v, 3.0f + 1.2f * v}, s->camera.position);
}
static void setup_squeeze(scene_desc_t *s, float v)
{
    add_sphere(s, 0.35f, -(0.35f + 0.5f * v), 0.3f, 0);
    add_sphere(s, 0.35f, 0.35f + 0.5f * v, 0.3f, 0);
}
/* No wind: a pressed blade (eta near 1, stiffness x 0.1) sways with the
 * wind ten times as far as its unpressed twin, a legitimate motion the
 * twin's offset does not remove. */
static void setup_resting(scene_desc_t *s, float v)
{
    s->wind_count = 0;
    s->grass.stiffness[0] = s->grass.stiffness[1] = v;
    add_sphere(s, 0.35f, 0, 0.3f, 0);
}
/* A ball resting on the grass; the spike itself comes from spike_dt. */
static void setup_spikes(scene_desc_t *s, float v)
{
    (void)v;
    add_sphere(s, 0.35f, 0, 0.3f, 0);
}
static void setup_steep(scene_desc_t *s, float v)
{
    s->terrain.height = v;
    add_pass(s, 0.3f, 1.5f);
    glm_vec3_copy((vec3){0.0f, 1.5f + 1.5f * v, 3.5f + v}, s->camera.position);
}
static void setup_many(scene_desc_t *s, float v)
{
    int n = (int)v, side = (int)ceilf(sqrtf((float)n));
    s->grass.subdiv[0] = s->grass.subdiv[1] = 6;
    for (int i = 0; i < n; i++)
        add_sphere(s, 0.12f, -2.2f + 4.4f * ((float)(i % side) + 0.5f) / (float)side, 0.08f,
                   -2.2f + 4.4f * ((float)(i / side) + 0.5f) / (float)side);
    glm_vec3_copy((vec3){0.0f, 4.0f, 4.0f}, s->camera.position);
}
/* Sparse billboards at the field border: a ball of radius v (on the
 * ground) rolls along the edge z = +3 of the 6 m field, 0.3 m inside it,
 * through the outermost billboards of a 1.5 billboards/m^2 layout (one
 * candidate per 0.82 m cell), and stops 0.25 s before the end of the run;
 * the camera looks from inside the field across the ball's path to the
 * edge. */
#define BORDER_Z 2.7f
#define BORDER_TIME 2.0f
static void setup_border(scene_desc_t *s, float v)
{
    s->grass.billboard_density = 1.5f;
    s->grass.cube_texel = 0.02f;
    scene_collider_t *c = add_sphere(s, v, -2.6f, v, BORDER_Z);
    c->path.count = 2;
    c->path.keys[1] = (scene_path_key_t){.t = BORDER_TIME, .position = {0.6f, v, BORDER_Z}};
    s->size[0] = 360;
    s->size[1] = 240;
    glm_vec3_copy((vec3){-0.4f, 1.6f, BORDER_Z - 1.7f}, s->camera.position);
    glm_vec3_copy((vec3){-1.3f, 0.1f, BORDER_Z - 0.1f}, s->camera.target);
}

/* A wall: a mesh terrain (written by write_wall) with a floor at y = 0
 * for x < 0, a face rising at v degrees from x = 0 to WALL_H and a
 * plateau beyond, 4 m deep along z. No collider: the question is whether
 * the grass grows on the face at all, and stays valid there. */
#define WALL_H 1.0f
#define WALL_Z 2.0f
static float wall_run(float deg) { return fmaxf(0.0f, WALL_H * cosf(glm_rad(deg)) / sinf(glm_rad(deg))); }
static void setup_wall(scene_desc_t *s, float v)
{
    (void)v;
    glm_vec3_copy((vec3){-2.6f, 1.6f, 2.4f}, s->camera.position);
    glm_vec3_copy((vec3){0.2f, 0.5f, 0.0f}, s->camera.target);
}

/* Writes the wall of v degrees as an OBJ (flat normals, one quad per part)
 * and a scene file naming it, both into dir; scene gets the scene's path. */
static bool write_wall(const char *dir, float v, char *scene, size_t n)
{
    char obj[1100];
    snprintf(obj, sizeof obj, "%s/stability_wall.obj", dir);
    snprintf(scene, n, "%s/stability_wall.json", dir);
    float xf = wall_run(v), sn = sinf(glm_rad(v)), cs = cosf(glm_rad(v));
    float quads[3][4][2] = {{{-3, 0}, {0, 0}, {0, 0}, {-3, 0}},
                            {{0, 0}, {xf, WALL_H}, {xf, WALL_H}, {0, 0}},
                            {{xf, WALL_H}, {3, WALL_H}, {3, WALL_H}, {xf, WALL_H}}};
    float normals[3][3] = {{0, 1, 0}, {-sn, cs, 0}, {0, 1, 0}};
    core_buf_t t = {0};
    for (int q = 0; q < 3; q++) {
        for (int k = 0; k < 4; k++)
            core_buf_printf(&t, "v %.6f %.6f %.6f\n", quads[q][k][0], quads[q][k][1], k < 2 ? WALL_Z : -WALL_Z);
        core_buf_printf(&t, "vn %.6f %.6f %.6f\n", normals[q][0], normals[q][1], normals[q][2]);
        core_buf_printf(&t, "f %d//%d %d//%d %d//%d %d//%d\n", 4 * q + 1, q + 1, 4 * q + 2, q + 1, 4 * q + 3, q + 1,
                        4 * q + 4, q + 1);
    }
    bool ok = core_buf_write(&t, obj);
    core_buf_free(&t);
    core_buf_printf(&t, "{ \"seed\": 7, \"terrain\": { \"type\": \"mesh\", \"mesh\": \"%s\" } }\n", obj);
    ok = ok && core_buf_write(&t, scene);
    core_buf_free(&t);
    return ok;
}

/* ---- failure criteria ------------------------------------------------------------- */

static void judge_tunnel(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = r->coverage;
    r->fails = r->coverage < 0.9;
}
static void judge_rate(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)v;
    r->measure = r->recovery;
    double tol = fmax(0.15 * first->recovery, 2.0 * dt);
    r->fails = r->x.nonfinite > 0 || !isfinite(r->recovery) || fabs(r->recovery - first->recovery) > tol;
}
static void judge_rate_blade(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)v, (void)dt;
    r->measure = r->recovery;
    r->fails = r->x.nonfinite > 0 || !isfinite(r->recovery) || fabs(r->recovery - first->recovery) > 0.05 * first->recovery;
}
static void judge_thin(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)v, (void)dt;
    r->measure = r->m.penetration_fraction;
    r->fails = r->measure > fmax(0.01, 2.0 * first->m.penetration_fraction);
}
/* Depth criteria are relative to the case's easiest value (values[0]):
 * a method fails when the deepest sample exceeds both the absolute limit
 * and twice its depth at the easy value (the baseline of the method, e.g.
 * blades test only v2 and the midpoint). */
static void judge_depth5(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)v, (void)dt;
    r->measure = r->m.penetration_max;
    r->fails = r->x.nonfinite > 0 || r->m.penetration_max > fmax(0.05, 2.0 * first->m.penetration_max);
}
static void judge_depth2(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)v, (void)dt;
    r->measure = r->m.penetration_max;
    r->fails = r->x.nonfinite > 0 || r->m.penetration_max > fmax(0.02, 2.0 * first->m.penetration_max);
}
static void judge_jitter(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = r->jitter;
    r->fails = r->x.nonfinite > 0 || r->jitter > 0.001;
}
static void judge_spikes(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)v, (void)dt;
    r->measure = r->m.penetration_max;
    r->fails = r->x.nonfinite > 0 || r->m.blade_length_error > 0.05 ||
               r->m.penetration_max > fmax(0.05, 2.0 * first->m.penetration_max);
}
static void judge_steep(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = fmax(r->m.blade_length_error, r->x.below_ground);
    r->fails = r->x.nonfinite > 0 || r->measure > 0.05 || r->m.penetration_max > 0.05;
}
static void judge_border(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = r->distortion.max_stretch;
    r->fails = r->distortion.nonfinite > 0 || r->distortion.folded > 0 || !(r->measure <= 0.25);
}
static void judge_wall(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = r->coverage;
    r->fails = r->x.nonfinite > 0 || r->m.blade_length_error > 0.05 || !(r->coverage >= 0.5);
}

static const stab_case_t cases[] = {
    {"tunnelling", SCENE_MODE_BLADE, "ball speed m/s (r 0.3 m, dt 1/60)", {2, 5, 10, 20, 40, 80}, MEASURE_PASS,
     "trail coverage", "coverage < 0.9 (blades within r/2 of the path ever deflected > 0.2 h while the ball passes)",
     "a sphere is the capsule between its previous and current centre (swept collision, blade_ref.h), so blades "
     "between two frames' spheres are bent even when the step exceeds 2 r; without it they were never touched",
     setup_tunnel, judge_tunnel},
    {"tunnelling_bb", SCENE_MODE_BILLBOARD, "ball speed m/s (r 0.3 m, dt 1/60)", {2, 5, 10, 20, 40, 80}, MEASURE_PASS,
     "trail coverage", "coverage < 0.9 (billboards within r/2 of the path ever bent > 0.2 h while the ball passes)",
     "each object's cube map is looked up as if the object stood at the point of its step's path nearest the vertex "
     "(swept collision, bb_collide_desc_t.sweep) and the broad phase boxes the path, so billboards between two "
     "frames' positions are bent at any speed",
     setup_tunnel, judge_tunnel},
    {"framerate_blade", SCENE_MODE_BLADE, "simulation rate Hz (dt = 1/Hz)", {144, 240, 60, 30, 15, 4}, MEASURE_PASS,
     "recovery s", "abs(recovery - recovery at 144 Hz) > 5%, or NaN",
     "the step's forces (eq. 3-8) are integrated exactly (v2 += (r + g + w) (1 - exp(-s' dt)) / s', docs/BLADES.md) and eta gains collision_gain |d|^2 (1/60 s) / dt, so the recovery does not depend on the rate; the ball is swept (a capsule per step, less the half of its start sphere it moves away from), so at 4 Hz it still presses every blade on its path, but its last step presses the last 1.25 m of the path at once, sideways: at 4 Hz the recovery is 4.3 % longer than at 144 Hz (5.4 % while the capsule's trailing half held the blades under the lifted ball for the whole 0.25 s step)", setup_rate, judge_rate_blade},
    {"framerate_bb", SCENE_MODE_BILLBOARD, "simulation rate Hz (dt = 1/Hz)", {144, 60, 30, 15, 8, 4},
     MEASURE_PASS, "recovery s", "abs(recovery - recovery at 144 Hz) > max(15%, 2 dt), or NaN",
     "eq. 8 recovery is a function of the remaining time, not of the step count; the ball is swept, so at 8 and 4 "
     "Hz its last step presses the end of its path at once, a step (0.125, 0.25 s) after the ball was there: "
     "recovery ends up to dt later",
     setup_rate, judge_rate},
    {"thin_bb", SCENE_MODE_BILLBOARD, "box half-thickness m (cube 16, texel ~0.084 m)",
     {0.2f, 0.1f, 0.05f, 0.025f, 0.0125f, 0.006f}, MEASURE_STATIC, "penetration fraction",
     "fraction inside > max(1%, 2 x first value's)",
     "a wall thinner than a cube-map texel falls between texel centres of the side faces", setup_thin,
     judge_thin},
    {"concave_bb", SCENE_MODE_BILLBOARD, "centre separation of two r 0.35 m spheres (notch)",
     {0, 0.2f, 0.35f, 0.5f, 0.6f, 0.65f}, MEASURE_STATIC, "max depth m", "deepest sample > max(0.05 m, 2 x first value's)",
     "each sphere has its own cube map; a push out of one can end inside the other", setup_concave,
     judge_depth5},
    {"concave_blade", SCENE_MODE_BLADE, "centre separation of two r 0.35 m spheres (notch)",
     {0, 0.2f, 0.35f, 0.5f, 0.6f, 0.65f}, MEASURE_STATIC, "max depth m", "deepest sample > max(0.05 m, 2 x first value's)",
     "blade_ref_exit handles several spheres; only v2 and the midpoint are tested", setup_concave, judge_depth5},
    {"large_bb", SCENE_MODE_BILLBOARD, "sphere radius m (cube 16, grass.cube_texel 0.02 m)", {0.25f, 0.5f, 1, 2, 3, 4},
     MEASURE_STATIC, "max depth m", "deepest sample > max(0.05 m, 2 x first value's)",
     "the cube covers the bounding sphere, so at a fixed resolution its texel grows with the collider (2 r / 16: "
     "the case broke from r 1 m, 0.056 m deep, 0.23 m at 4 m); grass.cube_texel raises the resolution until a "
     "texel is at most 2 cm (400 texels per face at 4 m); the 0.062 m then left at r 3 m were vertices the ground "
     "held inside the ball (1 cm texels left the same), which now leave it sideways (bb_collide_desc_t.ground)",
     setup_large, judge_depth5},
    {"squeeze_blade", SCENE_MODE_BLADE, "gap between two r 0.35 m spheres m", {0.4f, 0.2f, 0.1f, 0.05f, 0.02f, 0},
     MEASURE_STATIC, "max depth m", "deepest sample > max(0.02 m, 2 x first value's), or NaN",
     "a blade between two spheres is pushed by both", setup_squeeze, judge_depth2},
    {"squeeze_bb", SCENE_MODE_BILLBOARD, "gap between two r 0.35 m spheres m", {0.4f, 0.2f, 0.1f, 0.05f, 0.02f, 0},
     MEASURE_STATIC, "max depth m", "deepest sample > max(0.02 m, 2 x first value's), or NaN",
     "eq. 5 pushes along one face's normal per object and pass", setup_squeeze, judge_depth2},
    {"resting_blade", SCENE_MODE_BLADE, "blade stiffness (r 0.35 m ball resting, 5 cm sunk)",
     {100, 50, 20, 10, 5, 2}, MEASURE_JITTER, "jitter m/frame",
     "frame-to-frame tip change > 1 mm over the last 0.5 s of 8 s at rest (no wind), or NaN",
     "three departures hold a resting contact still (docs/BLADES.md): the validation after a contact validates the "
     "step's total translation once (validating the validated blade again moved v1 by about h (1 - r) for any "
     "push, however small: period-2 contact / no-contact cycles of 1.6 mm), Coulomb friction mu 0.5 (pressed tips "
     "and blades rooted under the ball slid along it 2-4 mm per frame for seconds) and an exit that turns a blade "
     "lying on the ground along it (it was straightened elsewhere: 10 cm jumps every 1.5 s at stiffness 2). "
     "llvmpipe, mm per frame at 100/50/20/10/5/2: 0/0/0.16/0.12/0.05/0.23; the physics before, same measure: "
     "0/0.008/2.1/2.1/2.1/18.4 (last 0.5 s of 1.5 s, with wind: 0.38/0.82/2.8/2.8/11.0/6.5). The run is 8 s "
     "because the blades pressed as the ball appears swing back smoothly once eta has decayed (3-5 mm per frame "
     "at 1-3 s at stiffness 2, legitimate motion); other seeds at stiffness 2 can still show a blade creeping "
     "down the ball's side under friction at 8 s (seed 7: 2.1 mm, smooth)",
     setup_resting, judge_jitter},
    {"spikes_blade", SCENE_MODE_BLADE, "spike step ms (every 10th step; the others 1/60 s; r 0.35 m ball resting)",
     {16.7f, 33, 66, 100, 250, 500}, MEASURE_STATIC, "max depth m (after a spike)",
     "NaN, length error > 5%, or deepest sample > max(0.05 m, 2 x first value's)",
     "forces are displacement rates times dt (eq. 3-8): one long step moves a tip by (r + g + w) dt at once, "
     "then validation (eq. 9-13) and the collision exit put it back on a valid curve outside the sphere",
     setup_spikes, judge_spikes},
    {"spikes_bb", SCENE_MODE_BILLBOARD, "spike step ms (every 10th step; the others 1/60 s; r 0.35 m ball resting)",
     {16.7f, 33, 66, 100, 250, 500}, MEASURE_STATIC, "max depth m (after a spike)",
     "NaN, or deepest sample > max(0.05 m, 2 x first value's)",
     "collision is positional (push-out, springs): a long step only shortens the recover time left (eq. 8)",
     setup_spikes, judge_spikes},
    {"steep_blade", SCENE_MODE_BLADE, "heightfield amplitude m (6 m terrain)", {0.5f, 1, 2, 4, 8, 16},
     MEASURE_STATIC, "max(length error, tips under ground)", "> 5%, or a sample > 0.05 m deep, or NaN",
     "gravity (eq. 4-6) pulls tips downhill; blades stand along the surface normal", setup_steep, judge_steep},
    {"many_bb", SCENE_MODE_BILLBOARD, "resting r 0.12 m balls (mesh 6 x 6)", {1, 4, 16, 17, 32, 128}, MEASURE_STATIC,
     "max depth m", "deepest sample > max(0.05 m, 2 x first value's)",
     "the field collides with up to BB_MAX_OBJECTS (128) objects: colliding leaves are grouped into collide passes "
     "of at most BB_PASS_OBJECTS (16) objects (a leaf meeting more is split into runs of billboards). The depth "
     "left is the mesh's, not the object count's: with the default 4 x 4 mesh (cells 0.33 x 0.2 m, wider than a "
     "0.24 m ball) balls poke through between vertices, 0.062 m from 16 balls and 0.094 m at 128 (llvmpipe); the "
     "6 x 6 mesh run here holds 0.046 m at 128 (8 x 8 exceeds the geometry shader's output limit)",
     setup_many, judge_depth5},
    {"many_blade", SCENE_MODE_BLADE, "resting r 0.12 m balls", {1, 4, 16, 17, 32, 128}, MEASURE_STATIC,
     "max depth m", "deepest sample > max(0.05 m, 2 x first value's)", "BLADE_MAX_SPHERES (512) sphere proxies per step", setup_many,
     judge_depth5},
    {"bb_border", SCENE_MODE_BILLBOARD,
     "ball radius m (billboards 0.6 x 0.4 m, mesh 4 x 4, 1.5 /m^2 at the border, grass.cube_texel 0.02 m)",
     {0.05f, 0.1f, 0.2f, 0.3f, 0.5f, 0.8f}, MEASURE_DISTORTION, "max stretch abs(l/l0 - 1) (folded cells)",
     "stretch > 25%, any folded cell, or NaN (worst frame of the pass)",
     "the worst billboard is the one the ball stops on at the end of its path, pressed into the wedge between "
     "ball and ground. A ball wider than the billboards are tall presses their upper rows down towards the roots; "
     "the push-out (eq. 4-5) came last, after every spring sweep (eq. 6-7), so vertical springs shortened under "
     "the ball stayed short (llvmpipe, r 0.05-0.8 m: 0.035, 0.13, 0.45, 0.36, 0.29 (1 folded), 0.26 (1 folded)). "
     "A pushed vertex now slides at its row length to the vertex below (bb_ref.c bb_slide), and the case "
     "raises the cube maps to 2 cm texels as large_bb does: at 16 texels a 0.8 m ball's are 10 cm, coarser "
     "than the few-cm wedge the billboard lies in (the slide alone: 0.45 at r 0.2, 0.40 at 0.8; the texels "
     "alone: 0.50 at 0.2, 0.30 at 0.8). That left at r 0.2 (and 0.15) one cell of a column draped under the "
     "resting ball folded by a hair (signed area ratio -0.002, stretch 0.21): the push turned the column up the "
     "ball's back, past 90 degrees. A bend limit now keeps each joint within about 75 degrees by leaning the "
     "segments below into the bend (bb_ref.c bb_ref_bend_limit): no fold, worst stretch 0.035, 0.15, 0.19, 0.19, "
     "0.18, 0.20 (also none at r 0.15, 0.25, 0.4, 0.6, 1.0 m: 0.23, 0.23, 0.21, 0.18, 0.19). Billboards are "
     "simulated one by one, so a pass "
     "through the middle of the field behaves the same; the sparse border (its last candidate row, z 2.71 to "
     "3.53 m, is cut by the terrain edge at 3 m) only leaves the distorted billboards in plain view",
     setup_border, judge_border},
    {"wall_blade", SCENE_MODE_BLADE, "face angle deg (mesh terrain, 1 m high face)", {30, 45, 55, 70, 80, 90},
     MEASURE_STATIC, "face coverage (roots/m^2 on the face / on the floor)",
     "coverage < 0.5, length error > 5%, or NaN",
     "blades are seeded on the mesh triangles by area, up = the interpolated vertex normal (blade_seed), so a "
     "vertical face gets as many roots per m^2 as the floor and its blades grow out of it horizontally",
     setup_wall, judge_wall},
    {"wall_bb", SCENE_MODE_BILLBOARD, "face angle deg (mesh terrain, 1 m high face)", {30, 45, 55, 70, 80, 90},
     MEASURE_STATIC, "face coverage (roots/m^2 on the face / on the floor)", "coverage < 0.5, or NaN",
     "on a mesh terrain billboards are seeded per triangle by true area (bb_layout_sample_tri: a jittered grid of "
     "candidates in the triangle's plane, roots on the triangle), so a vertical face gets as many candidates per m^2 "
     "as the floor; coverage stays below 1 because the face reads other extent texels (its (z, y) projection) than "
     "the floor (with the extent map set to full for a check: 1.085, 0.980, 1.037, 1.019, 0.950, 0.904). Before "
     "(a horizontal candidate grid, 0.41 m, over heights resampled from the mesh) the face's density fell with its "
     "plan area, about cos angle, and a vertical face had none: 0.876, 0.780, 0.585, 0.488, 0.320, 0.065",
     setup_wall, judge_wall},
};
#define CASE_COUNT ((int)(sizeof cases / sizeof cases[0]))

/* ---- one run --------------------------------------------------------------------------- */

typedef struct stab_run_t {
    const stab_case_t *c;
    float v;
    bool twin_wanted, no_colliders;
    const app_options_t *o;
    app_world_t *twin;
    float t_exit, t_end;
    float *prev;
    uint8_t *ever; /* blades deflected so far during the pass (coverage) */
    bool primed, covered;
    double last_over, jitter, coverage;
    double last_off, next_t, next_off; /* offsets around the 1 cm crossing (recovery interpolation) */
    bench_bb_distortion_t distortion;
    bench_bb_distortion_t worst_frame; /* the most distorted frame so far: most folded cells, then stretch */
    bool worst_now;                  /* this frame is it */
    core_image_t worst;              /* its rendering */
} stab_run_t;

static void tweak(scene_desc_t *s, void *user)
{
    const stab_run_t *r = user;
    terrain_desc_t terrain = s->terrain;
    base_scene(s);
    if (r->c->setup == setup_wall) s->terrain = terrain;
    r->c->setup(s, r->v);
    if (r->no_colliders) s->collider_count = 0;
}

static void frame(app_world_t *w, int f, float t, void *user)
{
    stab_run_t *r = user;
    if (f == 0 && r->twin_wanted) {
        stab_run_t tw = *r;
        tw.no_colliders = true;
        r->twin = calloc(1, sizeof *r->twin);
        bench_session_desc_t d = {.opts = r->o, .mode = r->c->mode, .mode_set = true, .tweak = tweak, .user = &tw};
        if (r->twin && bench_session_world(&d, r->twin) != 0) {
            free(r->twin);
            r->twin = NULL;
        }
        r->prev = calloc((size_t)app_world_blades(w)->padded_count * 3, sizeof(float));
        r->ever = calloc(app_world_blades(w)->padded_count, 1);
    }
    if (r->twin) app_world_update(r->twin, t, app_world_scene(w)->dt);
    if (r->c->measure == MEASURE_PASS && t > r->t_exit) {
        double off = r->twin ? bench_metrics_blade_offset(w, r->twin, NULL, NULL, NULL) : bench_metrics_bb_offset(w);
        if (!(off <= RECOVERY_EPS)) {
            r->last_over = t, r->last_off = off, r->next_t = 0;
        } else if (r->next_t == 0) {
            r->next_t = t, r->next_off = off;
        }
    }
    /* Trail coverage: blades ever deflected along the path, checked every
     * frame while the ball passes and on the first frame after it left. */
    if (r->c->judge == judge_tunnel && r->c->mode == SCENE_MODE_BILLBOARD && !r->covered) {
        bb_field_t *bf = app_world_billboards(w);
        if (!r->ever && bf) r->ever = calloc((size_t)bf->billboards, 1);
        long corridor;
        if (r->ever)
            r->coverage = bench_metrics_bb_coverage(w, (float[2]){PASS_FROM + 0.3f, 0}, (float[2]){PASS_TO - 0.3f, 0},
                                                    0.15f, 0.2f, r->ever, &corridor);
        r->covered = t > r->t_exit;
    }
    if (r->c->measure == MEASURE_PASS && r->twin && r->ever && !r->covered) {
        long corridor;
        r->coverage = bench_metrics_blade_coverage(w, r->twin, (float[2]){PASS_FROM + 0.3f, 0},
                                                   (float[2]){PASS_TO - 0.3f, 0}, 0.15f, 0.2f, r->ever, &corridor);
        r->covered = t > r->t_exit;
    }
    if (r->c->measure == MEASURE_DISTORTION) {
        bench_bb_distortion_t d;
        bench_metrics_bb_distortion(w, &d);
        bench_bb_distortion_t *m = &r->distortion;
        const bench_bb_distortion_t *b = &r->worst_frame;
        r->worst_now = f == 0 || d.folded > b->folded || (d.folded == b->folded && d.max_stretch > b->max_stretch);
        if (r->worst_now) r->worst_frame = d;
        m->max_stretch = fmax(m->max_stretch, d.max_stretch);
        if (d.folded > m->folded) m->folded = d.folded;
        if (d.cells > m->cells) m->cells = d.cells;
        if (d.deformed > m->deformed) m->deformed = d.deformed;
        m->nonfinite += d.nonfinite;
    }
    if (r->c->setup == setup_wall && f == 0) {
        /* Root density on the face (its middle 80 % in height, 10 % from
         * the sides) over that on the floor away from the face. */
        float xf = wall_run(r->v), zr = 0.9f * WALL_Z;
        long face = bench_metrics_roots_in(w, (float[3]){-0.02f, 0.1f * WALL_H, -zr},
                                           (float[3]){xf + 0.02f, 0.9f * WALL_H, zr});
        long floor = bench_metrics_roots_in(w, (float[3]){-2.9f, -0.05f, -zr}, (float[3]){-0.2f, 0.05f, zr});
        double face_area = 0.8 * WALL_H / sin(glm_rad(r->v)) * 2.0 * zr, floor_area = 2.7 * 2.0 * zr;
        r->coverage = floor ? ((double)face / face_area) / ((double)floor / floor_area) : 0.0;
    }
    if (r->c->measure == MEASURE_JITTER && r->twin && r->prev && t > r->t_end - 0.5f) {
        double j = 0;
        bench_metrics_blade_offset(w, r->twin, r->prev, &r->primed, &j);
        if (j > r->jitter) r->jitter = j;
    }
}

/* Keeps the rendering of the most distorted frame (MEASURE_DISTORTION). */
static void drawn(const gfx_target_t *target, int f, void *user)
{
    (void)f;
    stab_run_t *r = user;
    if (!r->worst_now) return;
    core_image_free(&r->worst);
    if (!gfx_target_read(target, &r->worst)) core_image_free(&r->worst);
}

/* Frame spikes: every 10th step (the last one included) lasts v ms. */
static float spike_dt(int frame, float dt, void *user)
{
    const stab_run_t *r = user;
    return (frame + 1) % 10 == 0 ? r->v / 1000.0f : dt;
}

static int run_one(const app_options_t *o, const stab_case_t *c, float v, bool quick, const char *out,
                   core_image_t *img, stab_result_t *res)
{
    memset(res, 0, sizeof *res);
    app_options_t wall = *o;
    char scene[1100];
    if (c->setup == setup_wall) {
        if (!write_wall(out, v, scene, sizeof scene)) return 1;
        wall.scene = scene;
        o = &wall;
    }
    stab_run_t r = {.c = c, .v = v, .o = o};
    scene_desc_t probe;
    memset(&probe, 0, sizeof probe);
    base_scene(&probe);
    c->setup(&probe, v);
    float dt = probe.dt;
    float duration = 0.5f;
    if (c->measure == MEASURE_PASS) {
        r.t_exit = probe.colliders[0].path.keys[1].t;
        duration = r.t_exit + (c == &cases[0] ? 0.1f : (quick ? 2.0f : 3.5f));
    } else if (c->measure == MEASURE_JITTER) {
        duration = JITTER_TIME;
    } else if (quick) {
        duration = 0.25f;
    }
    if (c->setup == setup_steep) duration = 1.6f;
    if (c->setup == setup_border) duration = BORDER_TIME + 0.25f;
    r.t_end = duration;
    r.twin_wanted = c->mode == SCENE_MODE_BLADE && c->measure != MEASURE_STATIC;
    int frames = (int)ceilf(duration / dt);
    if (c->setup == setup_spikes) frames = (frames + 9) / 10 * 10; /* the last step is a spike */
    bench_session_desc_t d = {.opts = o, .mode = c->mode, .mode_set = true, .frames = frames, .tweak = tweak,
                              .user = &r};
    bool distortion = c->measure == MEASURE_DISTORTION;
    bench_session_hooks_t h = {.frame = frame, .user = &r, .draw_last_only = !distortion, .ext = &res->x,
                               .step_dt = c->setup == setup_spikes ? spike_dt : NULL,
                               .drawn = distortion ? drawn : NULL};
    int rc = bench_session_run_hooks(&d, &h, img, &res->m);
    if (r.worst.px) {
        core_image_free(img);
        *img = r.worst;
    }
    /* The crossing of RECOVERY_EPS between the last frame above it and the
     * next, log-linear (the offset decays about exponentially), so the
     * recovery time does not step with dt. */
    double cross = r.last_over;
    if (r.last_over > 0 && r.next_t > r.last_over && r.next_off > 0)
        cross += (r.next_t - r.last_over) * log(r.last_off / RECOVERY_EPS) / log(r.last_off / r.next_off);
    res->recovery = r.last_over >= (float)frames * dt - 0.5f * dt ? INFINITY : fmax(cross - r.t_exit, 0.0);
    res->coverage = r.coverage;
    res->jitter = r.jitter;
    res->distortion = r.distortion;
    if (c->setup == setup_wall) {
        char obj[1100];
        snprintf(obj, sizeof obj, "%s/stability_wall.obj", out);
        remove(obj);
        remove(scene);
    }
    if (r.twin) {
        app_world_destroy(r.twin);
        free(r.twin);
    }
    free(r.prev);
    free(r.ever);
    return rc;
}

/* ---- the suite ---------------------------------------------------------------------------- */

/* Every case, or only the one named by --case. */
static bool case_selected(const app_options_t *o, const stab_case_t *c)
{
    return !o->stability_case || strcmp(o->stability_case, c->name) == 0;
}

static void fmt_value(char *buf, size_t n, double v)
{
    if (isinf(v)) snprintf(buf, n, "never");
    else snprintf(buf, n, "%.4g", v);
}

int bench_stability_run(const app_options_t *o, const char *out, bool quick, core_buf_t *md_out, const char *report)
{
    char path[1200], buf[32];
    core_buf_t csv = {0}, md = {0}, mdr = {0};
    core_buf_printf(&csv, "case,method,parameter,value,measure,fails,penetration_fraction,penetration_max,"
                          "blade_length_error,spring_error,recovery_s,jitter_m,coverage,nonfinite,below_ground,"
                          "bb_max_stretch,bb_folded_cells\n");
    static const char *head = "| case | method | parameter | values | measure | measured | failure criterion | "
                              "breaks at | screenshot |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    core_buf_printf(&md, "%s", head);
    core_buf_printf(&mdr, "%s", head);
    int rc = 0, runs = quick ? 2 : STAB_VALUES, done = 0, selected = 0;
    for (int ci = 0; ci < CASE_COUNT; ci++) selected += case_selected(o, &cases[ci]);
    if (selected == 0) {
        core_buf_t names = {0};
        for (int ci = 0; ci < CASE_COUNT; ci++) core_buf_printf(&names, "%s%s", ci ? ", " : "", cases[ci].name);
        core_log_error("--case '%s': no such stability case (%s)", o->stability_case, names.data);
        core_buf_free(&names);
        rc = 1;
    }
    double t0 = plat_time();
    for (int ci = 0; ci < CASE_COUNT && rc == 0; ci++) {
        const stab_case_t *c = &cases[ci];
        if (!case_selected(o, c)) continue;
        stab_result_t res[STAB_VALUES], first = {0};
        core_image_t shot = {0}, img = {0};
        int broke = -1;
        char values[160] = "", measured[320] = "";
        for (int k = 0; k < runs && rc == 0; k++) {
            int vi = quick && k == 1 ? STAB_VALUES - 1 : k;
            float v = c->values[vi];
            rc = run_one(o, c, v, quick, out, &img, &res[k]);
            if (rc) break;
            if (k == 0) first = res[0];
            float dt = 1.0f / 60.0f;
            if (c->setup == setup_rate) dt = 1.0f / v;
            c->judge(&res[k], &first, v, dt);
            if (res[k].fails && broke < 0) broke = vi;
            if ((res[k].fails && broke == vi) || (broke < 0 && k == runs - 1) || !shot.px) {
                core_image_free(&shot);
                shot = img;
                img = (core_image_t){0};
            }
            core_image_free(&img);
            const bench_metrics_t *m = &res[k].m;
            const bench_metrics_ext_t *x = &res[k].x;
            const bench_bb_distortion_t *dd = &res[k].distortion;
            bool distortion = c->measure == MEASURE_DISTORTION;
            core_buf_printf(&csv, "%s,%s,\"%s\",%g,%.6g,%d,%.6f,%.6f,%.6f,%.6f,%.4f,%.6f,%.4f,%ld,%.4f,%.6g,%ld\n",
                            c->name, scene_mode_name(c->mode), c->param, v, res[k].measure, res[k].fails,
                            m->penetration_fraction, m->penetration_max, m->blade_length_error, m->spring_error,
                            res[k].recovery, res[k].jitter, res[k].coverage, x->nonfinite + dd->nonfinite,
                            x->below_ground, distortion ? dd->max_stretch : -1.0, distortion ? dd->folded : -1L);
            size_t lv = strlen(values), lm = strlen(measured);
            fmt_value(buf, sizeof buf, res[k].measure);
            snprintf(values + lv, sizeof values - lv, "%s%g", k ? ", " : "", v);
            char folds[48] = "";
            if (distortion && dd->folded) snprintf(folds, sizeof folds, " (%ld folded)", dd->folded);
            snprintf(measured + lm, sizeof measured - lm, "%s%s%s%s", k ? ", " : "", buf, folds,
                     res[k].fails ? "*" : "");
            done++;
            fprintf(stderr, "\rstability: %d/%d %-16s %-8g %-12s %-5s (%.0f s)   ", done, selected * runs, c->name,
                    v, buf, res[k].fails ? "FAILS" : "ok", plat_time() - t0);
        }
        if (rc) {
            core_image_free(&shot);
            break;
        }
        snprintf(path, sizeof path, "%s/stability_%s.png", out, c->name);
        if (shot.px && !core_image_write_png(&shot, path)) rc = 1;
        snprintf(path, sizeof path, "%s/images/stability_%s.png", report ? report : ".", c->name);
        if (report && shot.px && !core_image_write_png(&shot, path)) rc = 1;
        core_image_free(&shot);
        char brk[64];
        if (broke >= 0) snprintf(brk, sizeof brk, "**%g**", c->values[broke]);
        else snprintf(brk, sizeof brk, "none in range");
        for (int e = 0; e < 2; e++)
            core_buf_printf(e ? &mdr : &md, "| %s | %s | %s | %s | %s | %s | %s | %s | ![](%sstability_%s.png) |\n",
                            c->name, scene_mode_name(c->mode), c->param, values, c->measure_name, measured,
                            c->criterion, brk, e ? "images/" : "", c->name);
    }
    fputc('\n', stderr);
    if (rc == 0) {
        for (int e = 0; e < 2; e++) {
            core_buf_t *t = e ? &mdr : &md;
            core_buf_printf(t, "\n`*` marks a failing value. Notes per case (mechanism):\n\n");
            for (int ci = 0; ci < CASE_COUNT; ci++)
                if (case_selected(o, &cases[ci])) core_buf_printf(t, "- **%s**: %s.\n", cases[ci].name, cases[ci].note);
        }
        if (md_out) core_buf_printf(md_out, "%s", mdr.data);
        snprintf(path, sizeof path, "%s/stability.csv", out);
        if (!core_buf_write(&csv, path)) rc = 1;
        snprintf(path, sizeof path, "%s/stability.md", out);
        if (!core_buf_write(&md, path)) rc = 1;
        if (rc == 0) core_log_info("stability: wrote %s/stability.csv, stability.md and screenshots", out);
    }
    core_buf_free(&csv);
    core_buf_free(&md);
    core_buf_free(&mdr);
    return rc;
}

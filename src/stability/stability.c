/* bench_stability: `meadow bench --stability`: for each case, sweeps one
 * parameter over small scenes built here (6 m heightfield, a few thousand
 * blades or a few hundred billboards; the wall cases write a small mesh
 * terrain and its scene file into the output folder for the run and remove
 * them afterwards), applies the case's failure
 * criterion and reports the first value where the method breaks, with a
 * screenshot of that run (or of the last value when none broke). The
 * measures come from measure_metrics.c (docs/METRICS.md): penetration against
 * the exact collider shapes, blade length error, recovery time after a
 * collider leaves (offset from an undisturbed twin world for blades, from
 * the wind pose of eq. 8 for billboards), jitter of a resting collider,
 * trail coverage of a fast collider (tunnelling), texture distortion of
 * deformed billboard meshes (worst frame; its rendering is the screenshot)
 * and root density on a mesh face relative to the floor. */
#include "stability/stability.h"

#include "measure/measure.h"
#include "measure/measure_session.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "platform/plat.h"

#define STAB_VALUES 8
#define STAB_SEEDS 3      /* placement seeds of the depth cases (1 with --quick) */
#define DEPTH_FRAC 0.1    /* depth limit: a tenth of the grass height */
#define BLADE_H 0.425f    /* mean blade height of base_scene (0.35-0.5 m) */
#define BB_H 0.4f         /* billboard height of base_scene */
#define RATE_FRAC 0.1     /* framerate cases: recovery within 10 % of 144 Hz's */
#define RECOVERY_EPS 0.01 /* m: back within 1 cm of the undisturbed pose */
#define JITTER_TIME 8.0f  /* s a ball rests; the jitter is measured over the last 0.5 s */
#define PASS_FROM -2.5f
#define PASS_TO 2.5f

typedef enum stab_measure_t {
    MEASURE_STATIC = 0, /* metrics of the last frame */
    MEASURE_PASS,       /* a ball passes once and leaves: recovery, coverage */
    MEASURE_JITTER,     /* a ball rests: frame-to-frame offset change */
    MEASURE_DISTORTION, /* billboard texture distortion, worst frame of the run */
    MEASURE_SPIKES,     /* a ball passes with frame spikes: pose jump per step */
} stab_measure_t;

/* The three variants of every case: both papers' methods as printed
 * (grass_tuning_t.paper), this project's defaults, and settings tuned for the
 * case (only where the case names them). */
enum { VAR_PAPER, VAR_DEFAULT, VAR_TUNED, VAR_COUNT };
static const char *const variant_names[VAR_COUNT] = {"paper", "default", "tuned"};

typedef struct stab_result_t {
    measure_metrics_t m;
    measure_metrics_ext_t x;
    double recovery;  /* s after the collider left; INFINITY: not recovered */
    double coverage;  /* trail coverage: blades ever deflected during the pass */
    double jitter;    /* m per frame over the last 0.5 s */
    measure_bb_distortion_t distortion; /* worst stretch and fold count over the frames */
    double depth95;   /* 95th percentile over frames (and seeds) of the frame's deepest sample, m */
    double crossing;  /* billboards across the wall's mid-plane (thin_bb) */
    double jump;      /* largest pose change in one step (offset from the twin or the wind pose), m */
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
    int count;           /* values used (0: 6) */
    const char *limit;   /* the physical limit that bounds the range; NULL: the range runs until
                            the defaults break */
    const char *tuned;   /* the tuned variant's settings; NULL: no tuned variant */
    void (*tune)(scene_desc_t *s, float v);
} stab_case_t;

/* ---- scenes ----------------------------------------------------------------- */

static void base_scene(scene_desc_t *s)
{
    s->terrain = (terrain_desc_t){.type = TERRAIN_HEIGHTFIELD, .size = 6, .resolution = 16, .height = 0.05f};
    terrain_desc_t td = terrain_desc_defaults(&s->terrain);
    s->terrain = td;
    s->grass.population.density = 60;
    s->grass.population.height[0] = 0.35f;
    s->grass.population.height[1] = 0.5f;
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
/* A wall 1.2 m long and 0.6 m high in a field of 24 billboards/m^2 (the
 * crossing counts the few dozen rooted within reach of it). */
static void setup_thin(scene_desc_t *s, float v)
{
    s->grass.billboard_density = 24;
    scene_collider_t *c = add_sphere(s, 0, 0, 0.3f, 0);
    c->type = SCENE_COLLIDER_BOX;
    glm_vec3_copy((vec3){0.6f, 0.3f, v}, c->half_extents);
}
static void setup_concave(scene_desc_t *s, float v)
{
    add_sphere(s, 0.35f, -0.5f * v, 0.3f, 0);
    add_sphere(s, 0.35f, 0.5f * v, 0.3f, 0);
}
/* Tuned: cube maps of at most 2 cm texels (large_bb, bb_border). */
static void tune_texel(scene_desc_t *s, float v)
{
    (void)v;
    s->grass.cube_texel = 0.02f;
}
/* Tuned: the 6 x 6 billboard mesh (many_bb). */
static void tune_mesh6(scene_desc_t *s, float v)
{
    (void)v;
    s->grass.subdiv[0] = s->grass.subdiv[1] = 6;
}
static void setup_large(scene_desc_t *s, float v)
{
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
    s->grass.population.stiffness[0] = s->grass.population.stiffness[1] = v;
    add_sphere(s, 0.35f, 0, 0.3f, 0);
}
/* A ball passing (and leaving: the grass recovers for the rest of the
 * run); the spikes themselves come from spike_dt. */
static void setup_spikes(scene_desc_t *s, float v)
{
    (void)v;
    add_pass(s, 0.35f, PASS_TIME);
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

/* ---- failure criteria -------------------------------------------------------------
 * Absolute and tied to the grass's size (DEPTH_FRAC of the height of the
 * case's grass), never to a method's own first value; the framerate cases
 * compare a method with itself at 144 Hz (rate independence), one rule for
 * both. */

static void judge_tunnel(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = r->coverage;
    r->fails = r->coverage < 0.9;
}
static void judge_rate(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)v, (void)dt;
    r->measure = r->recovery;
    r->fails = r->x.nonfinite > 0 || !isfinite(r->recovery) || !isfinite(first->recovery) ||
               fabs(r->recovery - first->recovery) > RATE_FRAC * first->recovery;
}
static void judge_thin(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = r->crossing;
    r->fails = r->x.nonfinite > 0 || r->crossing > 0.1;
}
static void judge_depth_bb(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = r->depth95;
    r->fails = r->x.nonfinite > 0 || !(r->depth95 <= DEPTH_FRAC * BB_H);
}
static void judge_depth_blade(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = r->depth95;
    r->fails = r->x.nonfinite > 0 || !(r->depth95 <= DEPTH_FRAC * BLADE_H);
}
static void judge_jitter(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = r->jitter;
    r->fails = r->x.nonfinite > 0 || !(r->jitter <= 0.001);
}
/* A pose jump of half the grass height in one step is a visible pop. */
static void judge_spikes(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    double h = r->m.blade_length_error >= 0 ? BLADE_H : BB_H;
    r->measure = r->jump;
    r->fails = r->x.nonfinite > 0 || r->m.blade_length_error > 0.05 || !(r->jump <= 0.5 * h) ||
               !(r->depth95 <= DEPTH_FRAC * h);
}
static void judge_steep(stab_result_t *r, const stab_result_t *first, float v, float dt)
{
    (void)first, (void)v, (void)dt;
    r->measure = fmax(r->m.blade_length_error, r->x.below_ground);
    r->fails = r->x.nonfinite > 0 || r->measure > 0.05 || !(r->depth95 <= DEPTH_FRAC * BLADE_H);
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
    {"tunnelling", SCENE_MODE_BLADE, "ball speed m/s (r 0.3 m, dt 1/60)", {2, 5, 10, 20, 40, 80, 160, 300},
     MEASURE_PASS,
     "trail coverage", "coverage < 0.9 (blades within r/2 of the path ever deflected > 0.2 h while the ball passes)",
     "a sphere is the capsule between its previous and current centre (swept collision, blade_ref.h), so blades "
     "between two frames' spheres are bent even when the step exceeds 2 r; without it (the paper variant) they are "
     "never touched",
     setup_tunnel, judge_tunnel, .count = 8,
     .limit = "300 m/s: a step of 5 m, the whole path in one step"},
    {"tunnelling_bb", SCENE_MODE_BILLBOARD, "ball speed m/s (r 0.3 m, dt 1/60)", {2, 5, 10, 20, 40, 80, 160, 300},
     MEASURE_PASS,
     "trail coverage", "coverage < 0.9 (billboards within r/2 of the path ever bent > 0.2 h while the ball passes)",
     "each object's cube map is looked up as if the object stood at the point of its step's path nearest the vertex "
     "(swept collision, bb_collide_desc_t.sweep) and the broad phase boxes the path, so billboards between two "
     "frames' positions are bent at any speed; the paper looks the cube map up where the object stands",
     setup_tunnel, judge_tunnel, .count = 8,
     .limit = "300 m/s: a step of 5 m, the whole path in one step"},
    {"framerate_blade", SCENE_MODE_BLADE, "simulation rate Hz (dt = 1/Hz)", {144, 240, 60, 30, 15, 8, 4, 2},
     MEASURE_PASS,
     "recovery s", "abs(recovery - recovery at 144 Hz) > 10%, never, or NaN",
     "the tip update is integrated exactly for the step's forces (v2 += (r + g + w) (1 - exp(-s' dt)) / s', docs/BLADES.md) and eta gains collision_gain |d|^2 (1/60 s) / dt, so the recovery does not depend on the rate; the ball is swept (a capsule per step, less the half of its start sphere it moves away from), so at 4 Hz it still presses every blade on its path, but its last step presses the last 1.25 m of the path at once, sideways: at 4 Hz the recovery is 4.3 % longer than at 144 Hz (5.4 % while the capsule's trailing half held the blades under the lifted ball for the whole 0.25 s step). The paper's explicit Euler step overshoots the rest pose for s' dt > 1 and swings forever for s' dt >= 2", setup_rate, judge_rate, .count = 8,
     .limit = "2 Hz: the 1 s pass in two steps"},
    {"framerate_bb", SCENE_MODE_BILLBOARD, "simulation rate Hz (dt = 1/Hz)", {144, 240, 60, 30, 15, 8, 4, 2},
     MEASURE_PASS, "recovery s", "abs(recovery - recovery at 144 Hz) > 10%, never, or NaN",
     "eq. 8 recovery is a function of the remaining time, not of the step count; the ball is swept, so at 8 and 4 "
     "Hz its last step presses the end of its path at once, a step (0.125, 0.25 s) after the ball was there: "
     "recovery ends up to dt later",
     setup_rate, judge_rate, .count = 8, .limit = "2 Hz: the 1 s pass in two steps"},
    {"thin_bb", SCENE_MODE_BILLBOARD, "box half-thickness m (cube 16, texel ~0.084 m)",
     {0.2f, 0.1f, 0.05f, 0.025f, 0.0125f, 0.006f, 0.003f}, MEASURE_STATIC, "wall crossing",
     "more than 10% of the billboards rooted within reach of the wall have a vertex beyond its mid-plane "
     "(24 billboards/m^2)",
     "a wall thinner than a cube-map texel falls between texel centres of the side faces; a vertex that ends "
     "beyond the mid-plane was pushed out of the far face or never seen inside (a billboard rooted within half its "
     "width of the wall spans it at rest: only a push back to its own side, or a fold, keeps it there; llvmpipe: "
     "0.083 at 0.2 m, 0.24 at 0.1, 0.48 at 3 mm, both variants)", setup_thin,
     judge_thin, .count = 7, .limit = "3 mm: a texel 28 times the wall"},
    {"concave_bb", SCENE_MODE_BILLBOARD, "centre separation of two r 0.35 m spheres (notch)",
     {0, 0.2f, 0.35f, 0.5f, 0.6f, 0.65f, 0.7f}, MEASURE_STATIC, "depth p95 m",
     "95th percentile over frames and seeds of the deepest sample > 0.1 x billboard height (0.04 m)",
     "each sphere has its own cube map; a push out of one can end inside the other", setup_concave,
     judge_depth_bb, .count = 7, .limit = "0.7 m: the spheres touch"},
    {"concave_blade", SCENE_MODE_BLADE, "centre separation of two r 0.35 m spheres (notch)",
     {0, 0.2f, 0.35f, 0.5f, 0.6f, 0.65f, 0.7f}, MEASURE_STATIC, "depth p95 m",
     "95th percentile over frames and seeds of the deepest sample > 0.1 x blade height (0.0425 m)",
     "blade_ref_exit handles several spheres; only v2 and the midpoint are tested (the paper: no exit)",
     setup_concave, judge_depth_blade, .count = 7, .limit = "0.7 m: the spheres touch"},
    {"large_bb", SCENE_MODE_BILLBOARD, "sphere radius m (cube 16)", {0.25f, 0.5f, 1, 2, 3, 4, 6},
     MEASURE_STATIC, "depth p95 m",
     "95th percentile over frames and seeds of the deepest sample > 0.1 x billboard height (0.04 m)",
     "the cube covers the bounding sphere, so at a fixed resolution its texel grows with the collider (2 r / 16: "
     "the case broke from r 1 m, 0.056 m deep, 0.23 m at 4 m); grass.cube_texel raises the resolution until a "
     "texel is at most 2 cm (400 texels per face at 4 m); the 0.062 m then left at r 3 m were vertices the ground "
     "held inside the ball (1 cm texels left the same), which now leave it sideways (bb_collide_desc_t.ground)",
     setup_large, judge_depth_bb, .count = 7, .limit = "6 m: the ball covers the 6 m field",
     .tuned = "grass.cube_texel 0.02", .tune = tune_texel},
    {"squeeze_blade", SCENE_MODE_BLADE, "gap between two r 0.35 m spheres m", {0.4f, 0.2f, 0.1f, 0.05f, 0.02f, 0},
     MEASURE_STATIC, "depth p95 m",
     "95th percentile over frames and seeds of the deepest sample > 0.1 x blade height (0.0425 m), or NaN",
     "a blade between two spheres is pushed by both", setup_squeeze, judge_depth_blade,
     .limit = "gap 0: the spheres touch"},
    {"squeeze_bb", SCENE_MODE_BILLBOARD, "gap between two r 0.35 m spheres m", {0.4f, 0.2f, 0.1f, 0.05f, 0.02f, 0},
     MEASURE_STATIC, "depth p95 m",
     "95th percentile over frames and seeds of the deepest sample > 0.1 x billboard height (0.04 m), or NaN",
     "eq. 5 pushes along one face's normal per object and pass", setup_squeeze, judge_depth_bb,
     .limit = "gap 0: the spheres touch"},
    {"resting_blade", SCENE_MODE_BLADE, "blade stiffness (r 0.35 m ball resting, 5 cm sunk)",
     {100, 50, 20, 10, 5, 2, 1}, MEASURE_JITTER, "jitter m/frame",
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
     "down the ball's side under friction at 8 s (seed 7: 2.1 mm, smooth). The paper variant has none of the three "
     "but validates the step's total translation once, as printed (0.49 mm at stiffness 2 on llvmpipe): the 18.4 mm "
     "before came from this project's earlier second validation, not from the paper's step",
     setup_resting, judge_jitter, .count = 7, .limit = "stiffness 1: a pressed blade takes 10 s to rise (eta)"},
    {"spikes_blade", SCENE_MODE_BLADE,
     "spike step ms (every 10th step; the others 1/60 s; r 0.35 m ball passing at 5 m/s, then leaving)",
     {16.7f, 33, 66, 100, 250, 500, 1000}, MEASURE_SPIKES,
     "pose jump m (largest step change of a tip from its twin while the grass recovers)",
     "jump > 0.5 x blade height, depth p95 (while the ball passes) > 0.1 x blade height, length error > 5%, or NaN",
     "forces are displacement rates times dt (eq. 3-8): one long step moves a tip by (r + g + w) dt at once, "
     "then validation (eq. 9-13) and the collision exit put it back on a valid curve outside the sphere; the "
     "exact integration of the tip update never overshoots the rest pose, the paper's explicit Euler does for s' dt > 1",
     setup_spikes, judge_spikes, .count = 7, .limit = "1 s: a step as long as the recovery"},
    {"spikes_bb", SCENE_MODE_BILLBOARD,
     "spike step ms (every 10th step; the others 1/60 s; r 0.35 m ball passing at 5 m/s, then leaving)",
     {16.7f, 33, 66, 100, 250, 500, 1000}, MEASURE_SPIKES,
     "pose jump m (largest step change of a vertex's offset from its wind pose while the grass recovers)",
     "jump > 0.5 x billboard height, depth p95 (while the ball passes) > 0.1 x billboard height, or NaN",
     "collision is positional (push-out, springs): a long step moves the ball far (swept) and shortens the "
     "recover time left (eq. 8) by dt at once, so the pose jumps by what it would move in that time",
     setup_spikes, judge_spikes, .count = 7, .limit = "1 s: a step as long as the recovery"},
    {"steep_blade", SCENE_MODE_BLADE, "heightfield amplitude m (6 m terrain)", {0.5f, 1, 2, 4, 8, 16, 32},
     MEASURE_STATIC, "max(length error, tips under ground)", "> 5%, depth p95 > 0.1 x blade height, or NaN",
     "gravity (eq. 4-6) pulls tips downhill; blades stand along the surface normal", setup_steep, judge_steep,
     .count = 7, .limit = "32 m on a 6 m field with 16 cells: faces of about 85 degrees"},
    {"many_bb", SCENE_MODE_BILLBOARD, "resting r 0.12 m balls", {1, 4, 16, 17, 32, 128}, MEASURE_STATIC,
     "depth p95 m", "95th percentile over frames and seeds of the deepest sample > 0.1 x billboard height (0.04 m)",
     "the field collides with up to BB_MAX_OBJECTS (128) objects: colliding leaves are grouped into collide passes "
     "of at most BB_PASS_OBJECTS (16) objects (a leaf meeting more is split into runs of billboards). The depth "
     "left is the mesh's, not the object count's: with the default 4 x 4 mesh (cells 0.33 x 0.2 m, wider than a "
     "0.24 m ball) balls poke through between vertices, 0.062 m from 16 balls and 0.094 m at 128 (llvmpipe); the "
     "6 x 6 mesh of the tuned variant holds 0.046 m at 128 (8 x 8 exceeds the geometry shader's output limit)",
     setup_many, judge_depth_bb, .limit = "128: BB_MAX_OBJECTS", .tuned = "grass.subdiv [6, 6]",
     .tune = tune_mesh6},
    {"many_blade", SCENE_MODE_BLADE, "resting r 0.12 m balls", {1, 4, 16, 17, 32, 128}, MEASURE_STATIC,
     "depth p95 m", "95th percentile over frames and seeds of the deepest sample > 0.1 x blade height (0.0425 m)",
     "BLADE_MAX_SPHERES (4096) sphere proxies per step, admission-checked", setup_many, judge_depth_blade,
     .limit = "128: the billboards' BB_MAX_OBJECTS, for a like-for-like row"},
    {"bb_border", SCENE_MODE_BILLBOARD,
     "ball radius m (billboards 0.6 x 0.4 m, mesh 4 x 4, 1.5 /m^2 at the border)",
     {0.05f, 0.1f, 0.2f, 0.3f, 0.5f, 0.8f, 1.2f}, MEASURE_DISTORTION, "max stretch abs(l/l0 - 1) (folded cells)",
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
     setup_border, judge_border, .count = 7, .limit = "1.2 m: a ball three times the billboards' height",
     .tuned = "grass.cube_texel 0.02", .tune = tune_texel},
    {"wall_blade", SCENE_MODE_BLADE, "face angle deg (mesh terrain, 1 m high face)", {30, 45, 55, 70, 80, 90},
     MEASURE_STATIC, "face coverage (roots/m^2 on the face / on the floor)",
     "coverage < 0.5, length error > 5%, or NaN",
     "blades are seeded on the mesh triangles by area, up = the interpolated vertex normal (blade_seed), so a "
     "vertical face gets as many roots per m^2 as the floor and its blades grow out of it horizontally",
     setup_wall, judge_wall, .limit = "90 degrees: a vertical face"},
    {"wall_bb", SCENE_MODE_BILLBOARD, "face angle deg (mesh terrain, 1 m high face)", {30, 45, 55, 70, 80, 90},
     MEASURE_STATIC, "face coverage (roots/m^2 on the face / on the floor)", "coverage < 0.5, or NaN",
     "on a mesh terrain billboards are seeded per triangle by true area (bb_layout_sample_tri: a jittered grid of "
     "candidates in the triangle's plane, roots on the triangle), so a vertical face gets as many candidates per m^2 "
     "as the floor; coverage stays below 1 because the face reads other extent texels (its (z, y) projection) than "
     "the floor (with the extent map set to full for a check: 1.085, 0.980, 1.037, 1.019, 0.950, 0.904). Before "
     "(a horizontal candidate grid, 0.41 m, over heights resampled from the mesh) the face's density fell with its "
     "plan area, about cos angle, and a vertical face had none: 0.876, 0.780, 0.585, 0.488, 0.320, 0.065",
     setup_wall, judge_wall, .limit = "90 degrees: a vertical face"},
};
#define CASE_COUNT ((int)(sizeof cases / sizeof cases[0]))

/* ---- one run --------------------------------------------------------------------------- */

#define MAX_DEPTH_FRAMES 4096

typedef struct stab_run_t {
    const stab_case_t *c;
    float v;
    int variant;
    uint32_t seed; /* placement seed (0: the scene's) */
    bool twin_wanted, no_colliders;
    const world_options_t *o;
    world_t *twin;
    float t_exit, t_end, t_prev;
    int frames;
    float *prev;
    uint8_t *ever; /* blades deflected so far during the pass (coverage) */
    bool primed, covered;
    double last_over, jitter, coverage, crossing, jump;
    double last_off, next_t, next_off; /* offsets around the 1 cm crossing (recovery interpolation) */
    double *depths;  /* the deepest sample of every measured frame (shared by a value's seeds) */
    long *ndepth, cap;
    int depth_every; /* frames between depth measures (1; 3 with --quick) */
    measure_bb_distortion_t distortion;
    measure_bb_distortion_t worst_frame; /* the most distorted frame so far: most folded cells, then stretch */
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
    if (r->variant == VAR_TUNED && r->c->tune) r->c->tune(s, r->v);
    if (r->no_colliders) s->collider_count = 0;
}

static measure_session_desc_t session_desc(const stab_run_t *r, int frames)
{
    return (measure_session_desc_t){.world = *r->o,
                                    .mode = r->c->mode, .mode_set = true, .frames = frames,
                                  .tweak = tweak, .user = (void *)r,
                                  .tuning = {.paper = r->variant == VAR_PAPER, .placement_seed = r->seed}};
}

/* The twin (blade cases that compare with an undisturbed world) and its buffers. */
static void make_twin(world_t *w, stab_run_t *r)
{
    stab_run_t tw = *r;
    tw.no_colliders = true;
    measure_session_desc_t d = session_desc(&tw, 0);
    measure_session_world(&d, &r->twin); /* NULL when it cannot be made */
    measure_grass_t mg;
    measure_grass(w, MEASURE_GRASS_SIZES, false, &mg);
    uint32_t padded = mg.blade_padded;
    r->prev = calloc((size_t)padded * 3, sizeof(float));
    r->ever = calloc(padded, 1);
}

/* Recovery bookkeeping and trail coverage of a passing ball. */
static void frame_pass(world_t *w, float t, stab_run_t *r)
{
    if (t > r->t_exit) {
        double off = r->twin ? measure_blade_offset(w, r->twin, NULL, NULL, NULL) : measure_bb_offset(w);
        if (!(off <= RECOVERY_EPS)) {
            r->last_over = t, r->last_off = off, r->next_t = 0;
        } else if (r->next_t == 0) {
            r->next_t = t, r->next_off = off;
        }
    }
    /* Trail coverage: grass ever deflected along the path, checked every
     * frame while the ball passes and on the first frame after it left. */
    if (r->c->judge != judge_tunnel || r->covered) return;
    long corridor;
    const float a[2] = {PASS_FROM + 0.3f, 0}, b[2] = {PASS_TO - 0.3f, 0};
    if (r->c->mode == SCENE_MODE_BILLBOARD) {
        if (!r->ever) {
            measure_grass_t mg;
            measure_grass(w, MEASURE_GRASS_SIZES, false, &mg);
            if (mg.bb_billboards) r->ever = calloc((size_t)mg.bb_billboards, 1);
        }
        if (r->ever) r->coverage = measure_bb_coverage(w, a, b, 0.15f, 0.2f, r->ever, &corridor);
    } else if (r->twin && r->ever) {
        r->coverage = measure_blade_coverage(w, r->twin, a, b, 0.15f, 0.2f, r->ever, &corridor);
    }
    r->covered = t > r->t_exit;
}

static void frame_distortion(int f, stab_run_t *r, world_t *w)
{
    measure_bb_distortion_t d;
    measure_bb_distortion(w, &d);
    measure_bb_distortion_t *m = &r->distortion;
    const measure_bb_distortion_t *b = &r->worst_frame;
    r->worst_now = f == 0 || d.folded > b->folded || (d.folded == b->folded && d.max_stretch > b->max_stretch);
    if (r->worst_now) r->worst_frame = d;
    m->max_stretch = fmax(m->max_stretch, d.max_stretch);
    if (d.folded > m->folded) m->folded = d.folded;
    if (d.cells > m->cells) m->cells = d.cells;
    if (d.deformed > m->deformed) m->deformed = d.deformed;
    m->nonfinite += d.nonfinite;
}

/* Root density on the face (its middle 80 % in height, 10 % from the
 * sides) over that on the floor away from the face. */
static void frame_wall(world_t *w, stab_run_t *r)
{
    float xf = wall_run(r->v), zr = 0.9f * WALL_Z;
    long face = measure_roots_in(w, (float[3]){-0.02f, 0.1f * WALL_H, -zr},
                                       (float[3]){xf + 0.02f, 0.9f * WALL_H, zr});
    long floor = measure_roots_in(w, (float[3]){-2.9f, -0.05f, -zr}, (float[3]){-0.2f, 0.05f, zr});
    double face_area = 0.8 * WALL_H / sin(glm_rad(r->v)) * 2.0 * zr, floor_area = 2.7 * 2.0 * zr;
    r->coverage = floor ? ((double)face / face_area) / ((double)floor / floor_area) : 0.0;
}

/* The pose jump of this step: blades against their twin, billboards
 * against their wind pose. */
static void frame_jump(world_t *w, stab_run_t *r)
{
    double j = 0;
    if (r->twin && r->prev) {
        measure_blade_offset(w, r->twin, r->prev, &r->primed, &j);
    } else if (r->c->mode == SCENE_MODE_BILLBOARD) {
        if (!r->prev) {
            measure_grass_t mg;
            measure_grass(w, MEASURE_GRASS_SIZES, false, &mg);
            if (mg.bb_billboards)
                r->prev = calloc((size_t)mg.bb_billboards * (size_t)mg.bb_mesh_vertices * 3, sizeof(float));
        }
        if (r->prev) j = measure_bb_jump(w, r->prev, &r->primed);
    }
    if (!(j <= r->jump)) r->jump = j;
}

static void frame(world_t *w, int f, float t, void *user)
{
    stab_run_t *r = user;
    if (f == 0 && r->twin_wanted) make_twin(w, r);
    if (r->twin) world_update(r->twin, t, t - r->t_prev > 0.0f ? t - r->t_prev : world_info(w).scene->dt);
    r->t_prev = t;
    if (r->c->measure == MEASURE_PASS) frame_pass(w, t, r);
    if (r->c->measure == MEASURE_DISTORTION) frame_distortion(f, r, w);
    if (r->c->measure == MEASURE_SPIKES && t > r->t_exit) frame_jump(w, r);
    if (r->c->setup == setup_wall && f == 0) frame_wall(w, r);
    if (r->c->measure == MEASURE_JITTER && r->twin && r->prev && t > r->t_end - 0.5f) {
        double j = 0;
        measure_blade_offset(w, r->twin, r->prev, &r->primed, &j);
        if (j > r->jitter) r->jitter = j;
    }
    /* The deepest sample of every frame after the first (depth p95). */
    bool depth = r->c->measure == MEASURE_STATIC || (r->c->measure == MEASURE_SPIKES && t <= r->t_exit);
    if (depth && f > 0 && f % r->depth_every == 0 && world_collider_count(w) > 0 && *r->ndepth < r->cap) {
        measure_metrics_t m;
        measure_metrics(w, &m, NULL);
        r->depths[(*r->ndepth)++] = m.penetration_max;
    }
    if (r->c->judge == judge_thin && f + 1 == r->frames) {
        long near;
        r->crossing = measure_bb_crossing(w, 0, &near);
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

/* The run's length (s) for value v. */
static float run_duration(const stab_case_t *c, const scene_desc_t *probe, bool quick, float *t_exit)
{
    float duration = 0.5f;
    *t_exit = 0.0f;
    if (c->measure == MEASURE_PASS || c->measure == MEASURE_SPIKES) {
        *t_exit = probe->colliders[0].path.keys[1].t;
        duration = *t_exit + (c == &cases[0] ? 0.1f : (quick ? 2.0f : 3.5f));
        if (c->measure == MEASURE_SPIKES) duration = *t_exit + (quick ? 1.0f : 2.0f);
    } else if (c->measure == MEASURE_JITTER) {
        duration = JITTER_TIME;
    } else if (quick) {
        duration = 0.25f;
    }
    if (c->setup == setup_steep) duration = 1.6f;
    if (c->setup == setup_border) duration = BORDER_TIME + 0.25f;
    return duration;
}

static int run_one(const world_options_t *o, stab_run_t *r, bool quick, const char *out, core_image_t *img,
                   stab_result_t *res)
{
    const stab_case_t *c = r->c;
    memset(res, 0, sizeof *res);
    world_options_t wall = *o;
    char scene[1100];
    if (c->setup == setup_wall) {
        if (!write_wall(out, r->v, scene, sizeof scene)) return 1;
        wall.scene = scene;
        o = &wall;
    }
    r->o = o;
    scene_desc_t probe;
    memset(&probe, 0, sizeof probe);
    base_scene(&probe);
    c->setup(&probe, r->v);
    float dt = probe.dt;
    r->t_end = run_duration(c, &probe, quick, &r->t_exit);
    r->twin_wanted = c->mode == SCENE_MODE_BLADE && c->measure != MEASURE_STATIC;
    int frames = (int)ceilf(r->t_end / dt);
    if (c->setup == setup_spikes) frames = (frames + 9) / 10 * 10; /* the last step is a spike */
    r->frames = frames;
    measure_session_desc_t d = session_desc(r, frames);
    bool distortion = c->measure == MEASURE_DISTORTION;
    measure_session_hooks_t h = {.frame = frame, .user = r, .draw_last_only = !distortion, .ext = &res->x,
                               .step_dt = c->setup == setup_spikes ? spike_dt : NULL,
                               .drawn = distortion ? drawn : NULL};
    int rc = measure_session_run_hooks(&d, &h, img, &res->m);
    if (r->worst.px) {
        core_image_free(img);
        *img = r->worst;
        r->worst = (core_image_t){0};
    }
    /* The crossing of RECOVERY_EPS between the last frame above it and the
     * next, log-linear (the offset decays about exponentially), so the
     * recovery time does not step with dt. */
    double cross = r->last_over;
    if (r->last_over > 0 && r->next_t > r->last_over && r->next_off > 0)
        cross += (r->next_t - r->last_over) * log(r->last_off / RECOVERY_EPS) / log(r->last_off / r->next_off);
    res->recovery = r->last_over >= (float)frames * dt - 0.5f * dt ? INFINITY : fmax(cross - r->t_exit, 0.0);
    res->coverage = r->coverage;
    res->jitter = r->jitter;
    res->distortion = r->distortion;
    res->crossing = r->crossing;
    res->jump = r->jump;
    if (c->setup == setup_wall) {
        char obj[1100];
        snprintf(obj, sizeof obj, "%s/stability_wall.obj", out);
        remove(obj);
        remove(scene);
    }
    world_destroy(r->twin);
    free(r->prev);
    free(r->ever);
    return rc;
}

/* Placement seeds of a value's runs: the scene's, then two more. */
static const uint32_t seeds[STAB_SEEDS] = {0, 0x9e3779b9u, 0x85ebca6bu};

/* Whether the case is judged on depth (runs STAB_SEEDS placements). */
static bool depth_case(const stab_case_t *c)
{
    return c->judge == judge_depth_bb || c->judge == judge_depth_blade || c->judge == judge_spikes;
}

/* The 95th percentile of v[0..n) on a copy (v keeps its order). */
static double p95(const double *v, long n)
{
    double *copy = malloc(sizeof *copy * (size_t)(n > 0 ? n : 1));
    if (!copy) return INFINITY;
    memcpy(copy, v, sizeof *copy * (size_t)n);
    double q = measure_percentile(copy, n, 0.95);
    free(copy);
    return q;
}

/* One value of one variant over its seeds: the first seed's result (the
 * first failing seed's when one fails) judged with the depth p95 over
 * every seed's frames. first: the variant's run of values[0] (NULL: this
 * is it). */
static int run_value(const world_options_t *o, const stab_case_t *c, int variant, float v, bool quick, const char *out,
                     const stab_result_t *first, core_image_t *img, stab_result_t *res)
{
    int ns = depth_case(c) && !quick ? STAB_SEEDS : 1, rc = 0;
    long cap = (long)MAX_DEPTH_FRAMES * STAB_SEEDS, nd = 0;
    double *depths = malloc(sizeof *depths * (size_t)cap);
    if (!depths) return 1;
    float dt = c->setup == setup_rate ? 1.0f / v : 1.0f / 60.0f;
    bool failed = false;
    for (int k = 0; k < ns && rc == 0; k++) {
        stab_run_t r = {.c = c, .v = v, .variant = variant, .seed = seeds[k], .depths = depths, .ndepth = &nd,
                        .cap = cap, .depth_every = quick ? 3 : 1};
        long from = nd;
        stab_result_t one;
        core_image_t im = {0};
        rc = run_one(o, &r, quick, out, &im, &one);
        if (rc == 0) {
            one.depth95 = p95(depths + from, nd - from);
            c->judge(&one, first ? first : &one, v, dt);
            if (k == 0 || (one.fails && !failed)) {
                *res = one;
                core_image_free(img);
                *img = im;
                im = (core_image_t){0};
            }
            failed = failed || one.fails;
        }
        core_image_free(&im);
    }
    if (rc == 0) {
        res->depth95 = p95(depths, nd);
        c->judge(res, first ? first : res, v, dt);
    }
    free(depths);
    return rc;
}

/* ---- the suite ---------------------------------------------------------------------------- */

/* Every case, or only the one named by --case. */
static bool case_selected(const stability_desc_t *o, const stab_case_t *c)
{
    return !o->only_case || strcmp(o->only_case, c->name) == 0;
}

static void fmt_value(char *buf, size_t n, double v)
{
    if (isinf(v)) snprintf(buf, n, "never");
    else snprintf(buf, n, "%.4g", v);
}

static int case_values(const stab_case_t *c) { return c->count ? c->count : 6; }

/* stability_<case>[_<variant>].png: the default variant keeps the plain name. */
static void shot_name(char *buf, size_t n, const stab_case_t *c, int variant)
{
    if (variant == VAR_DEFAULT) snprintf(buf, n, "stability_%s.png", c->name);
    else snprintf(buf, n, "stability_%s_%s.png", c->name, variant_names[variant]);
}

static void csv_row(core_buf_t *csv, const stab_case_t *c, int variant, float v, const stab_result_t *r)
{
    const measure_metrics_t *m = &r->m;
    const measure_bb_distortion_t *dd = &r->distortion;
    bool distortion = c->measure == MEASURE_DISTORTION;
    core_buf_printf(csv,
                    "%s,%s,%s,\"%s\",%g,%.6g,%d,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f,%.6f,%.4f,%.4f,%.6f,%ld,%.4f,%.6g,%ld\n",
                    c->name, variant_names[variant], scene_mode_name(c->mode), c->param, v, r->measure, r->fails,
                    m->penetration_fraction, m->penetration_max, r->depth95, m->blade_length_error, m->spring_error,
                    r->recovery, r->jitter, r->coverage, r->crossing, r->jump, r->x.nonfinite + dd->nonfinite,
                    r->x.below_ground, distortion ? dd->max_stretch : -1.0, distortion ? dd->folded : -1L);
}

typedef struct stab_row_t {
    char values[200], measured[400];
    int broke; /* index of the first failing value, -1: none */
    bool constant;
} stab_row_t;

/* One case in one variant over its values: CSV rows, the table row's
 * text, the screenshot (the first failing value's, else the last's). */
static int run_variant(const world_options_t *o, const stab_case_t *c, int variant, bool quick, const char *out,
                       const char *report, core_buf_t *csv, stab_row_t *row, int *done, int total, double t0)
{
    int n = case_values(c), runs = quick ? 2 : n, rc = 0;
    stab_result_t res, first = {0};
    core_image_t shot = {0}, img = {0};
    double measure0 = 0;
    memset(row, 0, sizeof *row);
    row->broke = -1;
    row->constant = true;
    for (int k = 0; k < runs && rc == 0; k++) {
        int vi = quick && k == 1 ? n - 1 : k;
        float v = c->values[vi];
        rc = run_value(o, c, variant, v, quick, out, k ? &first : NULL, &img, &res);
        if (rc) break;
        if (k == 0) first = res, measure0 = res.measure;
        row->constant = row->constant && (res.measure == measure0 || (isnan(res.measure) && isnan(measure0)));
        if (res.fails && row->broke < 0) row->broke = vi;
        if ((res.fails && row->broke == vi) || (row->broke < 0 && k == runs - 1) || !shot.px) {
            core_image_free(&shot);
            shot = img;
            img = (core_image_t){0};
        }
        core_image_free(&img);
        csv_row(csv, c, variant, v, &res);
        char buf[32], folds[48] = "";
        fmt_value(buf, sizeof buf, res.measure);
        size_t lv = strlen(row->values), lm = strlen(row->measured);
        snprintf(row->values + lv, sizeof row->values - lv, "%s%g", k ? ", " : "", v);
        if (c->measure == MEASURE_DISTORTION && res.distortion.folded)
            snprintf(folds, sizeof folds, " (%ld folded)", res.distortion.folded);
        snprintf(row->measured + lm, sizeof row->measured - lm, "%s%s%s%s", k ? ", " : "", buf, folds,
                 res.fails ? "*" : "");
        (*done)++;
        fprintf(stderr, "\rstability: %d/%d %-16s %-7s %-8g %-12s %-5s (%.0f s)   ", *done, total, c->name,
                variant_names[variant], v, buf, res.fails ? "FAILS" : "ok", plat_time() - t0);
    }
    char name[160], path[1400];
    shot_name(name, sizeof name, c, variant);
    snprintf(path, sizeof path, "%s/%s", out, name);
    if (rc == 0 && shot.px && !core_image_write_png(&shot, path)) rc = 1;
    snprintf(path, sizeof path, "%s/images/%s", report ? report : ".", name);
    if (rc == 0 && report && shot.px && !core_image_write_png(&shot, path)) rc = 1;
    core_image_free(&shot);
    return rc;
}

static void md_row(core_buf_t *md, const stab_case_t *c, int variant, const stab_row_t *row, bool images)
{
    char brk[320], name[160];
    if (row->broke >= 0) snprintf(brk, sizeof brk, "**%g**", c->values[row->broke]);
    else if (c->limit) snprintf(brk, sizeof brk, "none in range (limit: %s)", c->limit);
    else snprintf(brk, sizeof brk, "none in range");
    shot_name(name, sizeof name, c, variant);
    core_buf_printf(md, "| %s | %s%s%s | %s | %s | %s | %s | %s%s | %s | %s | ![](%s%s) |\n", c->name,
                    variant_names[variant], variant == VAR_TUNED ? ": " : "", variant == VAR_TUNED ? c->tuned : "",
                    scene_mode_name(c->mode), c->param, row->values, c->measure_name, row->measured,
                    row->constant ? " (constant)" : "", c->criterion, brk, images ? "images/" : "", name);
}

int stability_run(const stability_desc_t *o, const char *out, core_buf_t *md_out, const char *report)
{
    bool quick = o->quick;
    char path[1200];
    core_buf_t csv = {0}, md = {0}, mdr = {0};
    core_buf_printf(&csv, "case,variant,method,parameter,value,measure,fails,penetration_fraction,penetration_max,"
                          "depth_p95,blade_length_error,spring_error,recovery_s,jitter_m,coverage,crossing,jump_m,"
                          "nonfinite,below_ground,bb_max_stretch,bb_folded_cells\n");
    static const char *head = "| case | variant | method | parameter | values | measure | measured | failure criterion | "
                              "breaks at | screenshot |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n";
    core_buf_printf(&md, "%s", head);
    core_buf_printf(&mdr, "%s", head);
    int rc = 0, done = 0, total = 0, selected = 0;
    for (int ci = 0; ci < CASE_COUNT; ci++)
        if (case_selected(o, &cases[ci])) {
            selected++;
            total += (quick ? 2 : case_values(&cases[ci])) * (cases[ci].tuned && !quick ? 3 : 2);
        }
    if (selected == 0) {
        core_buf_t names = {0};
        for (int ci = 0; ci < CASE_COUNT; ci++) core_buf_printf(&names, "%s%s", ci ? ", " : "", cases[ci].name);
        core_log_error("--case '%s': no such stability case (%s)", o->only_case, names.data);
        core_buf_free(&names);
        rc = 1;
    }
    double t0 = plat_time();
    core_buf_t unbroken = {0}, constant = {0};
    for (int ci = 0; ci < CASE_COUNT && rc == 0; ci++) {
        const stab_case_t *c = &cases[ci];
        if (!case_selected(o, c)) continue;
        bool broke = false;
        for (int var = 0; var < VAR_COUNT && rc == 0; var++) {
            if (var == VAR_TUNED && (!c->tuned || quick)) continue;
            stab_row_t row;
            rc = run_variant(o->world, c, var, quick, out, report, &csv, &row, &done, total, t0);
            if (rc) break;
            broke = broke || row.broke >= 0;
            if (row.constant)
                core_buf_printf(&constant, "%s%s/%s", constant.len ? ", " : "", c->name, variant_names[var]);
            md_row(&md, c, var, &row, false);
            md_row(&mdr, c, var, &row, true);
        }
        if (rc == 0 && !broke && !c->limit) core_buf_printf(&unbroken, "%s%s", unbroken.len ? ", " : "", c->name);
    }
    fputc('\n', stderr);
    if (rc == 0) {
        for (int e = 0; e < 2; e++) {
            core_buf_t *t = e ? &mdr : &md;
            core_buf_printf(t, "\n`*` marks a failing value; (constant): the measure did not change over the values "
                               "(the method holds at every value, or the measure does not answer the knob). Variants: paper = both papers' methods as printed "
                               "(grass_tuning_t.paper: explicit Euler, eq. 12's length, the paper's eta, no sweep, no "
                               "friction or collision exit; billboards without slide, ground, bend limit or push "
                               "after the spring sweeps), default = this project's defaults, tuned = the settings "
                               "named in the row. Notes per case (mechanism):\n\n");
            for (int ci = 0; ci < CASE_COUNT; ci++)
                if (case_selected(o, &cases[ci])) core_buf_printf(t, "- **%s**: %s.\n", cases[ci].name, cases[ci].note);
            if (unbroken.len) core_buf_printf(t, "\nNo variant breaks and no limit is stated: %s.\n", unbroken.data);
        }
        if (unbroken.len) core_log_warn("stability: no variant breaks and no limit is stated: %s", unbroken.data);
        if (constant.len) core_log_warn("stability: measure constant over the values: %s", constant.data);
        if (md_out) core_buf_printf(md_out, "%s", mdr.data);
        snprintf(path, sizeof path, "%s/stability.csv", out);
        if (!core_buf_write(&csv, path)) rc = 1;
        snprintf(path, sizeof path, "%s/stability.md", out);
        if (!core_buf_write(&md, path)) rc = 1;
        if (rc == 0) core_log_info("stability: wrote %s/stability.csv, stability.md and screenshots", out);
    }
    core_buf_free(&unbroken);
    core_buf_free(&constant);
    core_buf_free(&csv);
    core_buf_free(&md);
    core_buf_free(&mdr);
    return rc;
}

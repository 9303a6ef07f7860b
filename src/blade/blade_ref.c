/* blade_ref: CPU reference of the blade simulation (Jahrmann & Wimmer 2017
 * eq. 3-16) and culling (eq. 17-20). Every function mirrors, statement by
 * statement, its twin in shaders/common/blade.glsl (same names without the
 * ref_ prefix), so the GPU result can be compared with an epsilon. Beyond
 * both papers: collision against depth cube maps (Orthmann et al. 2009
 * eq. 1-5 through collide_cube) with its own collision exit. */
#include "blade/blade_ref.h"

#include <assert.h>
#include <math.h>
#include <string.h>

#include <cglm/cglm.h>

/* vec3 by value, so the code reads like the GLSL twin. */
typedef struct v3 {
    float x, y, z;
} v3;

static inline v3 v3_make(float x, float y, float z) { return (v3){x, y, z}; }
static inline v3 v3_load(const float *p) { return (v3){p[0], p[1], p[2]}; }
static inline void v3_store(float *p, v3 a) { p[0] = a.x; p[1] = a.y; p[2] = a.z; }
static inline v3 v3_add(v3 a, v3 b) { return (v3){a.x + b.x, a.y + b.y, a.z + b.z}; }
static inline v3 v3_sub(v3 a, v3 b) { return (v3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static inline v3 v3_scale(v3 a, float s) { return (v3){a.x * s, a.y * s, a.z * s}; }
static inline float v3_dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline float v3_len(v3 a) { return sqrtf(v3_dot(a, a)); }
static inline v3 v3_cross(v3 a, v3 b)
{
    return (v3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
/* Normalize with a zero result for (near-)zero vectors; GLSL twin: safe_normalize. */
static inline v3 v3_safe_normalize(v3 a)
{
    float l = v3_len(a);
    return l > 1e-6f ? v3_scale(a, 1.0f / l) : v3_make(0.0f, 0.0f, 0.0f);
}

blade_env_t blade_env_defaults(const blade_env_t *env)
{
    blade_env_t e = *env;
    v3 d = v3_load(e.gravity_dir);
    d = v3_len(d) > 1e-6f ? v3_scale(d, 1.0f / v3_len(d)) : v3_make(0.0f, -1.0f, 0.0f);
    v3_store(e.gravity_dir, d);
    if (e.gravity_off) e.gravity = 0.0f;
    else if (e.gravity == 0.0f) e.gravity = 9.81f;
    if (e.collision_decay == 0.0f) e.collision_decay = 1.0f;
    if (e.collision_gain == 0.0f) e.collision_gain = 1.0f;
    assert(e.wind_count >= 0 && e.wind_count <= BLADE_MAX_WINDS);
    assert(e.length_mode == BLADE_LENGTH_QUADRATURE || e.length_mode == BLADE_LENGTH_PAPER);
    return e;
}

blade_wind_t blade_wind_wave(float dir_x, float dir_z, float strength, float wavelength,
                             float speed)
{
    assert(wavelength > 0.0f);
    return (blade_wind_t){{dir_x, dir_z, wavelength, speed}, {strength, BLADE_WIND_WAVE, 0, 0}};
}

blade_wind_t blade_wind_point(const float position[3], float strength, float radius)
{
    assert(radius > 0.0f);
    return (blade_wind_t){{position[0], position[1], position[2], radius},
                          {strength, BLADE_WIND_POINT, 0, 0}};
}

static void frame(const blade_t *b, v3 *width_dir, v3 *front)
{
    v3 up = v3_load(b->up);
    float a = b->v0[3];
    v3 d = v3_make(cosf(a), 0.0f, sinf(a));
    v3 t = v3_sub(d, v3_scale(up, v3_dot(d, up)));
    if (v3_len(t) < 1e-3f) {
        d = v3_make(-sinf(a), 0.0f, cosf(a));
        t = v3_sub(d, v3_scale(up, v3_dot(d, up)));
    }
    *width_dir = v3_safe_normalize(t);
    *front = v3_safe_normalize(v3_cross(up, *width_dir));
}

void blade_ref_frame(const blade_t *b, float width_dir[3], float front[3])
{
    v3 w, f;
    frame(b, &w, &f);
    v3_store(width_dir, w);
    v3_store(front, f);
}

static v3 recovery(const blade_t *b, float eta)
{
    v3 v0 = v3_load(b->v0);
    v3 up = v3_load(b->up);
    float h = b->v1[3];
    float s = b->up[3];
    v3 iv2 = v3_add(v0, v3_scale(up, h));
    return v3_scale(v3_sub(iv2, v3_load(b->v2)), s * fmaxf(1.0f - eta, 0.1f));
}

void blade_ref_recovery(const blade_t *b, float eta, float out[3])
{
    v3_store(out, recovery(b, eta));
}

static v3 gravity(const blade_t *b, const blade_env_t *env)
{
    v3 v0 = v3_load(b->v0);
    float t = env->gravity_centre_mix;
    v3 to_centre = v3_safe_normalize(v3_sub(v3_load(env->gravity_centre), v0));
    v3 dir = v3_add(v3_scale(v3_load(env->gravity_dir), 1.0f - t), v3_scale(to_centre, t));
    v3 ge = v3_scale(dir, env->gravity);
    v3 width_dir, front;
    frame(b, &width_dir, &front);
    v3 gf = v3_scale(front, 0.25f * v3_len(ge));
    return v3_add(ge, gf);
}

void blade_ref_gravity(const blade_t *b, const blade_env_t *env, float out[3])
{
    v3_store(out, gravity(b, env));
}

static v3 wind_field(const blade_wind_t *w, v3 p, float time)
{
    float strength = w->b[0];
    if (w->b[1] < 0.5f) {
        v3 d = v3_safe_normalize(v3_make(w->a[0], 0.0f, w->a[1]));
        float wavelength = w->a[2];
        float speed = w->a[3];
        float phase = 6.28318531f * (v3_dot(d, p) - speed * time) / wavelength;
        return v3_scale(d, strength * (0.5f + 0.5f * sinf(phase)));
    }
    v3 rel = v3_sub(p, v3_load(w->a));
    float radius = w->a[3];
    float falloff = fmaxf(1.0f - v3_len(rel) / radius, 0.0f);
    return v3_scale(v3_safe_normalize(rel), strength * falloff);
}

void blade_ref_wind_field(const blade_wind_t *w, const float p[3], float time, float out[3])
{
    v3_store(out, wind_field(w, v3_load(p), time));
}

static v3 wind(const blade_t *b, const blade_env_t *env)
{
    v3 v0 = v3_load(b->v0);
    v3 up = v3_load(b->up);
    float h = b->v1[3];
    v3 wi = v3_make(0.0f, 0.0f, 0.0f);
    for (int i = 0; i < env->wind_count; i++) wi = v3_add(wi, wind_field(&env->winds[i], v0, env->time));
    v3 tip = v3_sub(v3_load(b->v2), v0);
    float fd = 1.0f - fabsf(v3_dot(v3_safe_normalize(wi), v3_safe_normalize(tip)));
    float fr = v3_dot(tip, up) / h;
    return v3_scale(wi, fd * fr);
}

void blade_ref_wind(const blade_t *b, const blade_env_t *env, float out[3])
{
    v3_store(out, wind(b, env));
}

static v3 midpoint(const blade_t *b)
{
    return v3_add(v3_add(v3_scale(v3_load(b->v0), 0.25f), v3_scale(v3_load(b->v1), 0.5f)),
                  v3_scale(v3_load(b->v2), 0.25f));
}

void blade_ref_midpoint(const blade_t *b, float m[3])
{
    v3_store(m, midpoint(b));
}

/* Push-out of point p from sphere s: min(|c - p| - r, 0) normalize(c - p). */
static v3 sphere_push(const blade_sphere_t *s, v3 p)
{
    v3 c = v3_load(s->centre_radius);
    v3 to_c = v3_sub(c, p);
    float pen = fminf(v3_len(to_c) - s->centre_radius[3], 0.0f);
    return v3_scale(v3_safe_normalize(to_c), pen);
}

/* The sphere of s's swept capsule closest to p: the centre moves to the
 * closest point of the segment [c, c + sweep] (the sweep's own sphere
 * when it is zero). A point behind the start c + sweep (on the side the
 * sphere moved away from) takes the sphere where it is now: the sphere
 * left that region as the step began, so a blade recovering into it
 * during the step is not held there. Holding it made a low rate hold
 * blades one step longer behind a moving sphere: the ball lifted off the
 * grass in framerate_blade kept the blades under it pressed for the whole
 * 0.25 s step at 4 Hz (6.9 ms at 144 Hz). */
static blade_sphere_t sphere_at(const blade_sphere_t *s, v3 p)
{
    v3 c = v3_load(s->centre_radius);
    v3 d = v3_load(s->sweep);
    float dd = v3_dot(d, d);
    float t = dd > 0.0f ? fmaxf(v3_dot(v3_sub(p, c), d) / dd, 0.0f) : 0.0f;
    if (t > 1.0f) t = 0.0f;
    blade_sphere_t o = *s;
    v3_store(o.centre_radius, v3_add(c, v3_scale(d, t)));
    return o;
}

void blade_ref_sphere_at(const blade_sphere_t *s, const float p[3], blade_sphere_t *out)
{
    *out = sphere_at(s, v3_load(p));
}

static float validate(blade_t *b, int length_mode);
static void revalidate(blade_t *b, int length_mode, float rescale);

/* Departure from the paper: the 4x midpoint push assumes v1 stays put,
 * but the validation that follows places v1 anew from the tip (eq. 10-11),
 * which can carry m well beyond the surface (measured: 8 mm on blades
 * pressed under a resting ball, so contact and no contact alternated every
 * step, with eta, and tips jittered 9 mm per frame). The push dm is tried
 * on a copy validated as the step will (revalidate, with the rescale of the
 * validation before the collision); when that m ends q > 0 outside, dm is
 * scaled by p / (p + q) (p the penetration before the push), the secant
 * root of the distance along the push. An undershoot is left to the exit. */
static v3 midpoint_push(const blade_t *b, const blade_sphere_t *sweep, int length_mode, float rescale)
{
    blade_sphere_t at = sphere_at(sweep, midpoint(b));
    const blade_sphere_t *s = &at;
    v3 pm = sphere_push(s, midpoint(b));
    v3 dm = v3_scale(pm, 4.0f);
    float p = v3_len(pm);
    if (p > 0.0f) {
        blade_t t = *b;
        v3_store(t.v2, v3_add(v3_load(t.v2), dm));
        revalidate(&t, length_mode, rescale);
        float q = v3_len(v3_sub(midpoint(&t), v3_load(s->centre_radius))) - s->centre_radius[3];
        if (q > 0.0f) dm = v3_scale(dm, p / (p + q));
    }
    return dm;
}

static v3 collide(blade_t *b, const blade_sphere_t *spheres, int count, int length_mode, float rescale)
{
    v3 d = v3_make(0.0f, 0.0f, 0.0f);
    for (int i = 0; i < count; i++) {
        blade_sphere_t at = sphere_at(&spheres[i], v3_load(b->v2));
        v3 dv2 = sphere_push(&at, v3_load(b->v2));
        v3_store(b->v2, v3_add(v3_load(b->v2), dv2));
        v3 dm = midpoint_push(b, &spheres[i], length_mode, rescale);
        v3_store(b->v2, v3_add(v3_load(b->v2), dm));
        d = v3_add(d, v3_add(dv2, dm));
    }
    return d;
}

void blade_ref_collide(blade_t *b, const blade_sphere_t *spheres, int count, int length_mode, float rescale,
                       float d[3])
{
    v3_store(d, collide(b, spheres, count, length_mode, rescale));
}

/* Departure from the paper (see blade_ref.h). Sphere s seen from the root:
 * unit direction ch to the centre, distance dist. A point at distance rho
 * from v0 is outside s (at distance rt = r * BLADE_EXIT_MARGIN from the
 * centre, law of cosines) when its angle a to ch has cos a <= cos_exit. */
static float cos_exit(float rho, float dist, float r)
{
    float rt = r * BLADE_EXIT_MARGIN;
    return fminf(fmaxf((rho * rho + dist * dist - rt * rt) / (2.0f * rho * dist), -1.0f), 1.0f);
}

/* Unit vector orthogonal to ch in the plane of ch and pd (or of ch and up
 * when pd is along ch). */
static v3 exit_side(v3 ch, v3 pd, v3 up)
{
    v3 e = v3_sub(pd, v3_scale(ch, v3_dot(pd, ch)));
    if (v3_len(e) < 1e-4f * v3_len(pd)) {
        e = v3_sub(up, v3_scale(ch, v3_dot(up, ch)));
        if (v3_len(e) < 1e-4f) e = v3_cross(ch, v3_make(0.0f, 0.0f, 1.0f));
        if (v3_len(e) < 1e-4f) e = v3_cross(ch, v3_make(1.0f, 0.0f, 0.0f));
    }
    return v3_safe_normalize(e);
}

static bool inside_sphere(const blade_sphere_t *s, v3 p)
{
    v3 pc = v3_sub(p, v3_load(s->centre_radius));
    return v3_dot(pc, pc) < s->centre_radius[3] * s->centre_radius[3];
}

/* Rodrigues rotation of v1 and v2 about the root v0 (axis k, cos cth, sin
 * sth): the length is kept exactly. With ground_test, skipped (false) when
 * it would put v2 under the ground plane. */
static bool rotate_about_root(blade_t *b, v3 v0, v3 up, v3 k, float cth, float sth, bool ground_test)
{
    v3 x1 = v3_sub(v3_load(b->v1), v0), x2 = v3_sub(v3_load(b->v2), v0);
    v3 r1 = v3_add(v3_add(v3_scale(x1, cth), v3_scale(v3_cross(k, x1), sth)),
                   v3_scale(k, v3_dot(k, x1) * (1.0f - cth)));
    v3 r2 = v3_add(v3_add(v3_scale(x2, cth), v3_scale(v3_cross(k, x2), sth)),
                   v3_scale(k, v3_dot(k, x2) * (1.0f - cth)));
    if (ground_test && v3_dot(r2, up) < 0.0f) return false;
    v3_store(b->v1, v3_add(v0, r1));
    v3_store(b->v2, v3_add(v0, r2));
    return true;
}

/* Departure from the paper: exit_rotate's fallback when its rotation would
 * put v2 under the ground plane (a blade lying on the ground against a
 * sphere sunk into it, whose exit direction points into the ground): the
 * rotation about up (the root's normal) that brings p onto the exit
 * distance of the sphere's cross-section at p's height, the same law of
 * cosines in the ground plane. It keeps every height above the ground (so
 * it is not tested: a tip lying on the ground would fail the test on
 * rounding alone), and the blade turns along the ground by the small
 * angle a small penetration needs; before, it was left inside and
 * exit_straight made it a straight blade elsewhere (measured under a
 * resting ball at stiffness 2: jumps of 10 cm, every 1.5 s). Skipped when
 * the root's vertical line is on the cross-section's centre or no turn
 * clears p. Where the cross-section is small the turn is ill-conditioned:
 * one step from the same state, CPU and GPU differ by up to 6e-5 m. */
static void exit_rotate_up(blade_t *b, const blade_sphere_t *s, v3 p, v3 v0, v3 up)
{
    v3 cd = v3_sub(v3_load(s->centre_radius), v0);
    float cu = v3_dot(cd, up);
    v3 ch = v3_sub(cd, v3_scale(up, cu));
    float dist = v3_len(ch);
    v3 pd = v3_sub(p, v0);
    float pu = v3_dot(pd, up);
    v3 ph = v3_sub(pd, v3_scale(up, pu));
    float rho = v3_len(ph);
    float r = s->centre_radius[3];
    float r2 = r * r - (pu - cu) * (pu - cu);
    if (dist < 1e-6f || rho < 1e-6f || r2 <= 0.0f) return;
    float rt = sqrtf(r2) * BLADE_EXIT_MARGIN;
    float ct = (rho * rho + dist * dist - rt * rt) / (2.0f * rho * dist);
    if (ct < -1.0f) return;
    ct = fminf(ct, 1.0f);
    ch = v3_scale(ch, 1.0f / dist);
    v3 e = v3_sub(ph, v3_scale(ch, v3_dot(ph, ch)));
    if (v3_len(e) < 1e-4f * rho) e = v3_cross(up, ch);
    e = v3_safe_normalize(e);
    float ca = fminf(fmaxf(v3_dot(ph, ch) / rho, -1.0f), 1.0f);
    float sa = sqrtf(fmaxf(1.0f - ca * ca, 0.0f));
    float st = sqrtf(fmaxf(1.0f - ct * ct, 0.0f));
    v3 k = v3_dot(v3_cross(ch, e), up) < 0.0f ? v3_scale(up, -1.0f) : up;
    rotate_about_root(b, v0, up, k, ct * ca + st * sa, st * ca - ct * sa, false);
}

/* Rigid rotation of v1 and v2 about v0, in the plane of ch and (p - v0),
 * that brings p (v2 or m) onto the exit distance. The rotation keeps the
 * curve length; it is built from cosines and sines by algebra only (no
 * trig), so the GLSL twin matches up to sqrt rounding. Skipped when p is
 * outside and when the root is inside s; when it would put v2 under the
 * ground plane, the rotation about up of exit_rotate_up replaces it
 * (exit_straight handles the contacts neither clears). */
static void exit_rotate(blade_t *b, const blade_sphere_t *sweep, v3 p)
{
    blade_sphere_t at = sphere_at(sweep, p);
    const blade_sphere_t *s = &at;
    if (!inside_sphere(s, p)) return;
    v3 v0 = v3_load(b->v0);
    v3 up = v3_load(b->up);
    v3 cd = v3_sub(v3_load(s->centre_radius), v0);
    float dist = v3_len(cd);
    v3 pd = v3_sub(p, v0);
    float rho = v3_len(pd);
    if (dist <= s->centre_radius[3] || rho < 1e-6f) return;
    v3 ch = v3_scale(cd, 1.0f / dist);
    v3 e = exit_side(ch, pd, up);
    float ca = v3_dot(pd, ch) / rho;
    float sa = sqrtf(fmaxf(1.0f - ca * ca, 0.0f));
    float ct = cos_exit(rho, dist, s->centre_radius[3]);
    float st = sqrtf(fmaxf(1.0f - ct * ct, 0.0f));
    float cth = ct * ca + st * sa;
    float sth = st * ca - ct * sa;
    v3 k = v3_cross(ch, e);
    if (!rotate_about_root(b, v0, up, k, cth, sth, true)) exit_rotate_up(b, s, p, v0, up);
}

/* Last resort for a sphere that still holds v2 or m (root outside): the
 * blade becomes the straight segment v0 + u [0, h] (v1 at its middle, so
 * the curve length is exactly h and m = v0 + u h/2) with u the direction
 * closest to the tip's that keeps both v2 (rho = h) and m (rho = h/2)
 * outside: u is rotated from ch, in the plane of ch and the tip, to the
 * larger of the two exit angles; when that u points under the ground plane,
 * u is the ground-plane direction on the same cone (dot(u, up) = 0,
 * dot(u, ch) = cos_exit), on the tip's side. */
static void exit_straight(blade_t *b, const blade_sphere_t *sweep)
{
    blade_sphere_t at = sphere_at(sweep, midpoint(b));
    const blade_sphere_t *s = &at;
    float h = b->v1[3];
    v3 v0 = v3_load(b->v0);
    v3 up = v3_load(b->up);
    if (!inside_sphere(s, v3_load(b->v2)) && !inside_sphere(s, midpoint(b))) return;
    v3 cd = v3_sub(v3_load(s->centre_radius), v0);
    float dist = v3_len(cd);
    float r = s->centre_radius[3];
    if (dist <= r) return;
    v3 ch = v3_scale(cd, 1.0f / dist);
    v3 td = v3_sub(v3_load(b->v2), v0);
    float ct = fminf(cos_exit(h, dist, r), cos_exit(0.5f * h, dist, r));
    float st = sqrtf(fmaxf(1.0f - ct * ct, 0.0f));
    v3 u = v3_add(v3_scale(ch, ct), v3_scale(exit_side(ch, td, up), st));
    if (v3_dot(u, up) < 0.0f) {
        v3 gp = v3_sub(ch, v3_scale(up, v3_dot(ch, up)));
        float gl = v3_len(gp);
        v3 g = v3_safe_normalize(gp);
        v3 w = v3_cross(up, g);
        float x = gl > 1e-6f ? fminf(fmaxf(ct / gl, -1.0f), 1.0f) : 0.0f;
        float y = sqrtf(fmaxf(1.0f - x * x, 0.0f));
        u = v3_add(v3_scale(g, x), v3_scale(w, v3_dot(w, td) < 0.0f ? -y : y));
    }
    v3_store(b->v1, v3_add(v0, v3_scale(u, 0.5f * h)));
    v3_store(b->v2, v3_add(v0, v3_scale(u, h)));
}

static void exit_spheres(blade_t *b, const blade_sphere_t *spheres, int count)
{
    for (int round = 0; round < BLADE_EXIT_ROUNDS; round++) {
        for (int i = 0; i < count; i++) {
            exit_rotate(b, &spheres[i], v3_load(b->v2));
            exit_rotate(b, &spheres[i], midpoint(b));
        }
    }
    for (int i = 0; i < count; i++) exit_straight(b, &spheres[i]);
}

void blade_ref_exit(blade_t *b, const blade_sphere_t *spheres, int count)
{
    if (b->v1[3] <= 0.0f) return;
    exit_spheres(b, spheres, count);
}

/* ---- cube-map colliders (beyond both papers; see blade_ref.h) ------------- */

/* Column-major m (x, 1); GLSL twin: (m * vec4(p, 1.0)).xyz. */
static v3 mat4_point(const float *m, v3 p)
{
    return v3_make(m[0] * p.x + m[4] * p.y + m[8] * p.z + m[12], m[1] * p.x + m[5] * p.y + m[9] * p.z + m[13],
                   m[2] * p.x + m[6] * p.y + m[10] * p.z + m[14]);
}

static bool cube_near(const collide_cube_proxy_t *o, v3 p)
{
    v3 pc = v3_sub(p, v3_load(o->sphere));
    return o->sphere[3] > 0.0f && v3_dot(pc, pc) < o->sphere[3] * o->sphere[3];
}

/* collide_push_out's choice for q (cube space): the smallest penetration
 * p_f = d_f - D_f over the faces and that texel's normal; 0 when q is not
 * inside (some p_f <= 0). */
static float cube_pen(const collide_cubemap_t *c, v3 q, v3 *n)
{
    float best = 3.402823e38f;
    *n = v3_make(0.0f, 0.0f, 0.0f);
    vec3 qq = {q.x, q.y, q.z};
    for (int f = 0; f < 6; f++) {
        vec4 tx;
        float pen = collide_lookup_texel(c, f, qq, tx) - tx[0];
        if (!(pen > 0.0f)) return 0.0f;
        if (pen < best) {
            best = pen;
            *n = v3_make(tx[1], tx[2], tx[3]);
        }
    }
    return best;
}

static bool inside_cube(const collide_cube_proxy_t *o, const collide_cubemap_t *c, v3 p)
{
    if (!cube_near(o, p)) return false;
    v3 n;
    return cube_pen(c, mat4_point(o->w2c, p), &n) > 0.0f;
}

bool blade_ref_inside_cube(const collide_cube_proxy_t *object, const collide_cubemap_t *cube, const float p[3])
{
    return inside_cube(object, cube, v3_load(p));
}

/* World displacement moving p out of the object by pen + margin * half
 * along the stored normal (zero when p is outside). */
static v3 cube_push(const collide_cube_proxy_t *o, const collide_cubemap_t *c, v3 p, float margin)
{
    if (!cube_near(o, p)) return v3_make(0.0f, 0.0f, 0.0f);
    v3 q = mat4_point(o->w2c, p);
    v3 n;
    float pen = cube_pen(c, q, &n);
    if (!(pen > 0.0f)) return v3_make(0.0f, 0.0f, 0.0f);
    v3 t = v3_add(q, v3_scale(n, pen + margin * o->cube[3]));
    return v3_sub(mat4_point(o->c2w, t), p);
}

static v3 collide_cubes(blade_t *b, const collide_cube_proxy_t *objects, const collide_cubemap_t *cubes, int count)
{
    v3 d = v3_make(0.0f, 0.0f, 0.0f);
    for (int k = 0; k < count; k++) {
        v3 dv2 = cube_push(&objects[k], &cubes[k], v3_load(b->v2), 0.0f);
        v3_store(b->v2, v3_add(v3_load(b->v2), dv2));
        v3 dm = v3_scale(cube_push(&objects[k], &cubes[k], midpoint(b), 0.0f), 4.0f);
        v3_store(b->v2, v3_add(v3_load(b->v2), dm));
        d = v3_add(d, v3_add(dv2, dm));
    }
    return d;
}

void blade_ref_collide_cubes(blade_t *b, const collide_cube_proxy_t *objects, const collide_cubemap_t *cubes,
                             int count, float d[3])
{
    v3_store(d, collide_cubes(b, objects, cubes, count));
}

/* Rigid rotation of v1, v2 about v0 turning p - v0 towards the push-out
 * target of p (margin BLADE_CUBE_MARGIN); cosine and sine from the dot and
 * cross products (no trig). Skipped when p is outside, when the root is
 * inside, and when v2 would go under the ground plane. */
static void cube_exit_rotate(blade_t *b, const collide_cube_proxy_t *o, const collide_cubemap_t *c, v3 p)
{
    v3 v0 = v3_load(b->v0);
    v3 up = v3_load(b->up);
    v3 push = cube_push(o, c, p, BLADE_CUBE_MARGIN);
    if (v3_dot(push, push) == 0.0f || inside_cube(o, c, v0)) return;
    v3 a = v3_sub(p, v0);
    v3 t = v3_add(a, push);
    float la = v3_len(a), lt = v3_len(t);
    if (la < 1e-6f || lt < 1e-6f) return;
    v3 ax = v3_cross(a, t);
    float s = v3_len(ax);
    if (s < 1e-9f * la * lt) return;
    v3 k = v3_scale(ax, 1.0f / s);
    float cth = v3_dot(a, t) / (la * lt);
    float sth = s / (la * lt);
    rotate_about_root(b, v0, up, k, cth, sth, true);
}

/* Candidate direction i of the straight fallback: 0 = up, then rings of 8
 * azimuths (about the blade frame) at 22.5, 45, 67.5 and 90 degrees. */
static v3 cube_direction(const blade_t *b, int i)
{
    v3 up = v3_load(b->up);
    if (i == 0) return up;
    v3 wd, fr;
    frame(b, &wd, &fr);
    int ring = (i - 1) / 8 + 1, az = (i - 1) % 8;
    float th = 0.39269908f * (float)ring, ph = 0.78539816f * (float)az;
    v3 side = v3_add(v3_scale(wd, cosf(ph)), v3_scale(fr, sinf(ph)));
    return v3_add(v3_scale(up, cosf(th)), v3_scale(side, sinf(th)));
}

static bool cube_holds(const blade_t *b, const collide_cube_proxy_t *objects, const collide_cubemap_t *cubes,
                       int count, v3 v2, v3 m)
{
    for (int k = 0; k < count; k++) {
        if (inside_cube(&objects[k], &cubes[k], v3_load(b->v0))) continue;
        if (inside_cube(&objects[k], &cubes[k], v2) || inside_cube(&objects[k], &cubes[k], m)) return true;
    }
    return false;
}

static void cube_exit_straight(blade_t *b, const collide_cube_proxy_t *objects, const collide_cubemap_t *cubes,
                               int count)
{
    if (!cube_holds(b, objects, cubes, count, v3_load(b->v2), midpoint(b))) return;
    float h = b->v1[3];
    v3 v0 = v3_load(b->v0);
    v3 td = v3_safe_normalize(v3_sub(v3_load(b->v2), v0));
    float best = -2.0f;
    v3 bu = v3_make(0.0f, 0.0f, 0.0f);
    for (int i = 0; i < BLADE_CUBE_DIRECTIONS; i++) {
        v3 u = cube_direction(b, i);
        float c = v3_dot(u, td);
        if (c <= best) continue;
        if (cube_holds(b, objects, cubes, count, v3_add(v0, v3_scale(u, h)), v3_add(v0, v3_scale(u, 0.5f * h))))
            continue;
        best = c;
        bu = u;
    }
    if (best < -1.5f) return;
    v3_store(b->v1, v3_add(v0, v3_scale(bu, 0.5f * h)));
    v3_store(b->v2, v3_add(v0, v3_scale(bu, h)));
}

static void exit_cubes(blade_t *b, const collide_cube_proxy_t *objects, const collide_cubemap_t *cubes, int count)
{
    for (int round = 0; round < BLADE_EXIT_ROUNDS; round++) {
        for (int k = 0; k < count; k++) {
            cube_exit_rotate(b, &objects[k], &cubes[k], v3_load(b->v2));
            cube_exit_rotate(b, &objects[k], &cubes[k], midpoint(b));
        }
    }
    cube_exit_straight(b, objects, cubes, count);
}

void blade_ref_exit_cubes(blade_t *b, const collide_cube_proxy_t *objects, const collide_cubemap_t *cubes, int count)
{
    if (b->v1[3] <= 0.0f) return;
    exit_cubes(b, objects, cubes, count);
}

/* Gauss-Legendre 3-point nodes on [0,1] and weights (summing to 1). */
static const float gl3_t[3] = {0.11270166f, 0.5f, 0.88729833f};
static const float gl3_w[3] = {0.27777778f, 0.44444444f, 0.27777778f};

/* Integral of |B'(t)| over [t0, t1] by 3-point Gauss-Legendre; B'(t) = 2(e0 + t a). */
static float speed_integral(v3 e0, v3 a, float t0, float t1)
{
    float s = 0.0f;
    for (int i = 0; i < 3; i++) {
        float t = t0 + (t1 - t0) * gl3_t[i];
        s += gl3_w[i] * v3_len(v3_add(e0, v3_scale(a, t)));
    }
    return 2.0f * (t1 - t0) * s;
}

static float length_estimate(v3 v0, v3 v1, v3 v2, int mode)
{
    if (mode == BLADE_LENGTH_PAPER) {
        float l0 = v3_len(v3_sub(v2, v0));
        float l1 = v3_len(v3_sub(v1, v0)) + v3_len(v3_sub(v2, v1));
        return (2.0f * l0 + l1) / 3.0f;
    }
    v3 e0 = v3_sub(v1, v0);
    v3 a = v3_add(v3_sub(v0, v3_scale(v1, 2.0f)), v2);
    float aa = v3_dot(a, a);
    float ts = aa > 1e-12f ? fminf(fmaxf(-v3_dot(a, e0) / aa, 0.0f), 1.0f) : 0.0f;
    return speed_integral(e0, a, 0.0f, ts) + speed_integral(e0, a, ts, 1.0f);
}

float blade_ref_length_estimate(const blade_t *b, int mode)
{
    return length_estimate(v3_load(b->v0), v3_load(b->v1), v3_load(b->v2), mode);
}

static float validate(blade_t *b, int length_mode)
{
    float h = b->v1[3];
    if (h <= 0.0f) return 1.0f;
    v3 v0 = v3_load(b->v0);
    v3 up = v3_load(b->up);
    v3 v2 = v3_load(b->v2);
    /* eq. 9: keep the tip above the ground plane through the root */
    v2 = v3_sub(v2, v3_scale(up, fminf(v3_dot(up, v3_sub(v2, v0)), 0.0f)));
    /* eq. 10-11: v1 from the length of the tip's projection on the ground */
    v3 tip = v3_sub(v2, v0);
    float lproj = v3_len(v3_sub(tip, v3_scale(up, v3_dot(tip, up))));
    v3 v1 = v3_add(v0, v3_scale(up, h * fmaxf(1.0f - lproj / h, 0.05f * fmaxf(lproj / h, 1.0f))));
    /* eq. 12-13: rescale v1 and v2 so the curve length is h. The rescale
     * is a uniform scaling about v0, so the length is exact when the
     * estimate is. */
    float r = h / length_estimate(v0, v1, v2, length_mode);
    v3 v1c = v3_add(v0, v3_scale(v3_sub(v1, v0), r));
    v3 v2c = v3_add(v1c, v3_scale(v3_sub(v2, v1), r));
    v3_store(b->v1, v1c);
    v3_store(b->v2, v2c);
    return r;
}

float blade_ref_validate(blade_t *b, int length_mode)
{
    return validate(b, length_mode);
}

/* Departure from the paper: the validation after a contact. Eq. 11 places
 * v1 from the tip's projection before eq. 13 rescales the tip by r, so
 * validating a validated blade moves v1 by about h (1 - r) (2 cm for a
 * 3 % rescale): a push of 0.004 mm, the last of a resting contact, moved
 * the tip 1.6 mm, the next step had no contact and moved it back (period-2
 * jitter under a resting ball). The tip is first mapped back through the
 * rescale r of the validation before the collision (a uniform scaling
 * about v0), so the step validates the tip of the forces plus d / r once,
 * as the paper validates its total translation once, and a push that
 * tends to zero gives the blade of the first validation. */
static void revalidate(blade_t *b, int length_mode, float rescale)
{
    v3 v0 = v3_load(b->v0);
    v3_store(b->v2, v3_add(v0, v3_scale(v3_sub(v3_load(b->v2), v0), 1.0f / rescale)));
    validate(b, length_mode);
}

void blade_ref_revalidate(blade_t *b, int length_mode, float rescale)
{
    if (b->v1[3] <= 0.0f) return;
    revalidate(b, length_mode, rescale);
}

/* Departure from the paper: v2 += (r + g + w) dt (explicit Euler) swings
 * the tip past the rest pose for s' dt > 1 and never settles for
 * s' dt >= 2 (s' = s max(1 - eta, 0.1); the scene accepts s up to 100 and
 * dt up to 1 s). With g and w frozen over the step, r + g + w is linear in
 * v2: v2' = -s' (v2 - T), T = I_v2 + (g + w) / s', solved exactly by
 * v2 + (r + g + w) (1 - exp(-s' dt)) / s'. It never passes T for any
 * s' dt, and a pressed blade stands up at the same speed at any rate.
 * Below s' dt = 1e-3 the series dt (1 - s' dt / 2) replaces the quotient
 * (float cancellation; also the limit at s' = 0). */
static float step_gain(float s, float dt)
{
    float x = s * dt;
    return x > 1e-3f ? (1.0f - expf(-x)) / s : dt * (1.0f - 0.5f * x);
}

float blade_ref_step_gain(float stiffness, float eta, float dt)
{
    return step_gain(stiffness * fmaxf(1.0f - eta, 0.1f), dt);
}

/* Whether a collider of c holds v2 or m of b (spheres: the capsule's
 * sphere nearest each point; colliders holding the root count too). */
static bool pose_held(const blade_t *b, const collide_set_t *c)
{
    v3 p[2] = {v3_load(b->v2), midpoint(b)};
    for (int k = 0; k < 2; k++) {
        for (int i = 0; i < c->sphere_count; i++) {
            blade_sphere_t at = sphere_at(&c->spheres[i], p[k]);
            if (inside_sphere(&at, p[k])) return true;
        }
        for (int i = 0; i < c->cube_count; i++)
            if (inside_cube(&c->cubes[i], &c->cube_maps[i], p[k])) return true;
    }
    return false;
}

/* Departure from the paper: Coulomb friction at contacts (see blade_ref.h).
 * The slipping blend is brought back to length h by eq. 12-13 alone (a
 * uniform scaling about v0, which leaves a blade of length h as it is). */
static void friction(blade_t *b, const blade_t *start, v3 d, const collide_set_t *c, int length_mode)
{
    if (pose_held(start, c)) return;
    v3 mv = v3_sub(v3_load(b->v2), v3_load(start->v2));
    if (v3_dot(mv, mv) <= BLADE_FRICTION * BLADE_FRICTION * v3_dot(d, d)) {
        memcpy(b->v1, start->v1, sizeof b->v1);
        memcpy(b->v2, start->v2, sizeof b->v2);
        return;
    }
    float slip = 1.0f - BLADE_FRICTION * v3_len(d) / v3_len(mv);
    v3 v0 = v3_load(b->v0);
    v3 v1 = v3_load(start->v1), v2 = v3_load(start->v2);
    v1 = v3_add(v1, v3_scale(v3_sub(v3_load(b->v1), v1), slip));
    v2 = v3_add(v2, v3_scale(v3_sub(v3_load(b->v2), v2), slip));
    float h = b->v1[3], len = length_estimate(v0, v1, v2, length_mode);
    if (!(len > 1e-3f * h)) return;
    float r = h / len;
    v3_store(b->v1, v3_add(v0, v3_scale(v3_sub(v1, v0), r)));
    v3_store(b->v2, v3_add(v0, v3_scale(v3_sub(v2, v0), r)));
}

void blade_ref_friction(blade_t *b, const blade_t *start, const float d[3], const collide_set_t *colliders,
                        int length_mode)
{
    static const collide_set_t none;
    if (b->v1[3] <= 0.0f) return;
    friction(b, start, v3_load(d), colliders ? colliders : &none, length_mode);
}

void blade_ref_step_one(blade_t *b, float *eta, const blade_env_t *env, const collide_set_t *colliders)
{
    float h = b->v1[3];
    if (h <= 0.0f) return;
    const blade_t start = *b;
    static const collide_set_t none;
    const collide_set_t *c = colliders ? colliders : &none;
    assert(c->cube_count == 0 || c->cube_maps);
    float dt = env->dt;
    v3 r = recovery(b, *eta);
    v3 g = gravity(b, env);
    v3 w = wind(b, env);
    float k = env->paper ? dt : step_gain(b->up[3] * fmaxf(1.0f - *eta, 0.1f), dt);
    v3_store(b->v2, v3_add(v3_load(b->v2), v3_scale(v3_add(v3_add(r, g), w), k)));
    float rescale = validate(b, env->length_mode);
    v3 d = collide(b, c->spheres, c->sphere_count, env->length_mode, rescale);
    d = v3_add(d, collide_cubes(b, c->cubes, c->cube_maps, c->cube_count));
    if (v3_dot(d, d) > 0.0f) {
        revalidate(b, env->length_mode, rescale);
        if (!env->paper) {
            friction(b, &start, d, c, env->length_mode);
            exit_spheres(b, c->spheres, c->sphere_count);
            exit_cubes(b, c->cubes, c->cube_maps, c->cube_count);
        }
    }
    float rate = dt > 0.0f && !env->paper ? BLADE_ETA_DT / dt : 1.0f;
    float e = *eta + env->collision_gain * v3_dot(d, d) * rate;
    *eta = fminf(fmaxf(e - env->collision_decay * dt, 0.0f), 1.0f);
}

void blade_ref_step(blade_t *b, float *eta, size_t n, const blade_env_t *env, const collide_set_t *colliders)
{
    blade_env_t e = blade_env_defaults(env);
    for (size_t i = 0; i < n; i++) blade_ref_step_one(&b[i], &eta[i], &e, colliders);
}

float blade_ref_curve_length(const blade_t *b, int samples)
{
    assert(samples > 0);
    double len = 0.0;
    double prev[3] = {b->v0[0], b->v0[1], b->v0[2]};
    for (int i = 1; i <= samples; i++) {
        double t = (double)i / samples, u = 1.0 - t;
        double p[3];
        for (int k = 0; k < 3; k++)
            p[k] = u * u * b->v0[k] + 2.0 * u * t * b->v1[k] + t * t * b->v2[k];
        double dx = p[0] - prev[0], dy = p[1] - prev[1], dz = p[2] - prev[2];
        len += sqrt(dx * dx + dy * dy + dz * dz);
        memcpy(prev, p, sizeof prev);
    }
    return (float)len;
}

/* ---- culling --------------------------------------------------------------- */

blade_cull_desc_t blade_cull_desc_defaults(const blade_cull_desc_t *desc)
{
    blade_cull_desc_t d = *desc;
    if (d.max_distance == 0.0f) d.max_distance = BLADE_CULL_MAX_DISTANCE_DEFAULT;
    if (d.orientation_threshold == 0.0f) d.orientation_threshold = 0.9f;
    if (d.frustum_tolerance == 0.0f) d.frustum_tolerance = 0.1f;
    if (d.depth_bias == 0.0f) d.depth_bias = 1e-3f;
    if (d.focal_px <= 0.0f) d.focal_px = 1000.0f;
    d.lod = blade_lod_defaults(&d.lod);
    assert(!d.depth || (d.depth_w > 0 && d.depth_h > 0));
    return d;
}

static void to_clip(const blade_cull_desc_t *desc, v3 p, float clip[4])
{
    vec4 in = {p.x, p.y, p.z, 1.0f};
    mat4 m;
    memcpy(m, desc->view.viewproj, sizeof m);
    glm_mat4_mulv(m, in, clip);
}

static bool in_frustum(const float clip[4], float tolerance)
{
    float h = clip[3] + tolerance;
    return fabsf(clip[0]) <= h && fabsf(clip[1]) <= h && fabsf(clip[2]) <= h;
}

static bool occluded(const blade_cull_desc_t *desc, const float clip[4])
{
    if (clip[3] <= 0.0f) return false;
    float x = clip[0] / clip[3], y = clip[1] / clip[3], z = clip[2] / clip[3];
    if (fabsf(x) > 1.0f || fabsf(y) > 1.0f) return false;
    int px = (int)floorf((x * 0.5f + 0.5f) * (float)desc->depth_w);
    int py = (int)floorf((y * 0.5f + 0.5f) * (float)desc->depth_h);
    px = px < 0 ? 0 : (px > desc->depth_w - 1 ? desc->depth_w - 1 : px);
    py = py < 0 ? 0 : (py > desc->depth_h - 1 ? desc->depth_h - 1 : py);
    return z > desc->depth[(size_t)py * (size_t)desc->depth_w + (size_t)px] + desc->depth_bias;
}

int blade_ref_cull_one(const blade_t *b, uint32_t index, const blade_cull_desc_t *desc, float *width_factor)
{
    float h = b->v1[3];
    if (h <= 0.0f) return BLADE_CULL_PADDING;
    v3 v0 = v3_load(b->v0);
    v3 up = v3_load(b->up);
    v3 view = v3_sub(v0, v3_load(desc->view.camera));
    v3 view_ground = v3_sub(view, v3_scale(up, v3_dot(view, up)));
    /* the thinning first: the orientation test widens its threshold by it */
    float dist = desc->eye_distance ? v3_len(view) : v3_len(view_ground);
    blade_lod_draw_t lod = {1.0f, 1.0f};
    if (!(desc->disable & BLADE_CULL_DISTANCE) && dist <= desc->max_distance)
        lod = blade_lod_blade(&desc->lod, index, dist, b->v2[3], desc->focal_px, desc->max_distance);
    float factor = lod.weight * lod.scale;

    if (!(desc->disable & BLADE_CULL_ORIENTATION)) {
        v3 width_dir, front;
        frame(b, &width_dir, &front);
        v3 dir_c = v3_safe_normalize(view_ground);
        if (fabsf(v3_dot(dir_c, width_dir)) > blade_ref_lod_orientation(desc->orientation_threshold, factor))
            return BLADE_CULL_ORIENTATION;
    }

    float c0[4], cm[4], c2[4];
    to_clip(desc, v0, c0);
    to_clip(desc, midpoint(b), cm);
    to_clip(desc, v3_load(b->v2), c2);
    if (!(desc->disable & BLADE_CULL_FRUSTUM)) {
        float t = desc->frustum_tolerance;
        if (!in_frustum(c0, t) && !in_frustum(cm, t) && !in_frustum(c2, t))
            return BLADE_CULL_FRUSTUM;
    }

    if (!(desc->disable & BLADE_CULL_DISTANCE) && (dist > desc->max_distance || lod.weight <= 0.0f))
        return BLADE_CULL_DISTANCE;

    if (desc->depth && !(desc->disable & BLADE_CULL_OCCLUSION)) {
        if (occluded(desc, c0) && occluded(desc, cm) && occluded(desc, c2))
            return BLADE_CULL_OCCLUSION;
    }
    if (width_factor) *width_factor = factor;
    return BLADE_CULL_VISIBLE;
}

float blade_ref_cull_distance(const blade_t *b, const blade_cull_desc_t *desc)
{
    v3 up = v3_load(b->up);
    v3 view = v3_sub(v3_load(b->v0), v3_load(desc->view.camera));
    return desc->eye_distance ? v3_len(view) : v3_len(v3_sub(view, v3_scale(up, v3_dot(view, up))));
}

float blade_ref_lod_orientation(float threshold, float width_scale)
{
    float k = fmaxf(width_scale, 1.0f);
    return sqrtf(fmaxf(1.0f - (1.0f - threshold * threshold) / (k * k), 0.0f));
}

bool blade_ref_box_outside(const float lo[3], const float hi[3], const float viewproj[16], float tol)
{
    const float *m = viewproj;
    for (int plane = 0; plane < 6; plane++) {
        int axis = plane / 2;
        float sign = (plane & 1) ? -1.0f : 1.0f;
        bool all_out = true;
        for (int c = 0; c < 8 && all_out; c++) {
            float p[3] = {(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]};
            float clip[4];
            for (int r = 0; r < 4; r++) clip[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
            if (clip[3] + sign * clip[axis] + tol >= 0.0f) all_out = false;
        }
        if (all_out) return true;
    }
    return false;
}

uint32_t blade_ref_patch_bucket(const float camera[3], const float lo[3], const float hi[3], float range, uint32_t n)
{
    float d = sqrtf(core_box_dist2(camera, lo, hi));
    float k = floorf((float)n * sqrtf(d / range));
    return (uint32_t)fminf(k, (float)(n - 1));
}

size_t blade_ref_cull(const blade_t *b, size_t n, const blade_cull_desc_t *desc, uint32_t *survivors,
                      float *factors, blade_cull_stats_t *stats)
{
    blade_cull_desc_t d = blade_cull_desc_defaults(desc);
    blade_cull_stats_t s = {{0, 0, 0, 0}, 0};
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        float factor;
        int why = blade_ref_cull_one(&b[i], (uint32_t)i, &d, &factor);
        switch (why) {
        case BLADE_CULL_VISIBLE:
            if (factors) factors[count] = factor;
            survivors[count++] = (uint32_t)i;
            break;
        case BLADE_CULL_ORIENTATION: s.culled[0]++; break;
        case BLADE_CULL_FRUSTUM: s.culled[1]++; break;
        case BLADE_CULL_DISTANCE: s.culled[2]++; break;
        case BLADE_CULL_OCCLUSION: s.culled[3]++; break;
        default: break;
        }
    }
    s.visible = (uint32_t)count;
    if (stats) *stats = s;
    return count;
}

/* ---- geometry (twin of blade_profile / blade_build in blade_geom.glsl) ------- */

float blade_ref_profile(int shape, float v)
{
    switch (shape) {
    case BLADE_SHAPE_QUAD: return 1.0f;
    case BLADE_SHAPE_TRIANGLE: return 1.0f - v;
    case BLADE_SHAPE_TRIANGLE_TIP: return 1.0f - fmaxf(v - 0.5f, 0.0f) / 0.5f;
    case BLADE_SHAPE_DANDELION: {
        float f = 4.0f * v - floorf(4.0f * v);
        return (1.0f - v) * (0.35f + 0.65f * fabsf(2.0f * f - 1.0f));
    }
    default: return 1.0f - v * v;
    }
}

void blade_ref_surface(const blade_t *b, int shape, float u, float v, float pos[3], float normal[3])
{
    blade_ref_surface_at(b, &(blade_ref_surface_desc_t){.shape = shape}, u, v, pos, normal);
}

void blade_ref_surface_at(const blade_t *b, const blade_ref_surface_desc_t *d, float u, float v, float pos[3],
                          float normal[3])
{
    v3 v0 = v3_load(b->v0), v1 = v3_load(b->v1), v2 = v3_load(b->v2);
    float w = b->v2[3];
    v3 t1, front;
    frame(b, &t1, &front);
    v3 a = v3_add(v0, v3_scale(v3_sub(v1, v0), v));
    v3 bb = v3_add(v1, v3_scale(v3_sub(v2, v1), v));
    v3 c = v3_add(a, v3_scale(v3_sub(bb, a), v));
    v3 n = v3_safe_normalize(v3_cross(v3_sub(bb, a), t1));
    if (v3_dot(n, n) == 0.0f) n = front;
    if (d->width_correction > 0.0f) {
        float nv = fabsf(v3_dot(n, v3_safe_normalize(v3_sub(v3_load(d->camera), c))));
        w = w * fminf(1.0f / fmaxf(nv, d->width_correction), 4.0f);
    }
    v3 c0 = v3_sub(c, v3_scale(t1, 0.5f * w));
    v3 c1 = v3_add(c, v3_scale(t1, 0.5f * w));
    float t = 0.5f + (u - 0.5f) * blade_ref_profile(d->shape, v);
    if (d->width_printed[1] > 0.0f) {
        float wp = w * d->focal_px / fmaxf(v3_len(v3_sub(v3_load(d->camera), c)), 1e-6f);
        float phi = 1.0f - fminf(fmaxf((wp - d->width_printed[0]) / d->width_printed[1], 0.0f), 1.0f);
        t = t * (1.0f - phi) + u * phi * phi;
    }
    v3 p = v3_add(v3_scale(c0, 1.0f - t), v3_scale(c1, t));
    if (d->displacement > 0.0f)
        p = v3_add(p, v3_scale(n, d->displacement * (0.5f * w) * (0.5f - fabsf(u - 0.5f) * (1.0f - v))));
    v3_store(pos, p);
    v3_store(normal, n);
}

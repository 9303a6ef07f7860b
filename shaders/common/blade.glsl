/* blade.glsl: GLSL twins of src/blade/blade_ref.c for the Bézier grass
 * blades of Jahrmann & Wimmer 2017: blade frame, recovery (eq. 3), gravity
 * (eq. 4-6), wind (eq. 7-8), sphere collision (sec. 5.2, eq. 14-16), state validation
 * (eq. 9-13) and the culling tests (eq. 17-20). Each function mirrors the C
 * function of the same name (blade_ref_x -> blade_x) statement by
 * statement, in the same order of operations; see blade_ref.h for the
 * step order and the departures from the paper (quadrature length, second
 * validation only after a contact and of the tip mapped back through the
 * first one's rescale, Coulomb friction, collision exit with its turn
 * along the ground, the capsule less its trailing half). Results match the
 * C code to rounding (sin/sqrt precision, fma contraction).
 *
 * Structs are std430 and vec4-packed; C mirrors in blade_ref.h:
 *   Blade       = blade_t        (64 bytes)
 *   BladeWind   = blade_wind_t   (32 bytes)
 *   BladeSphere = blade_sphere_t (32 bytes)
 *   BladeCube   = collide_cube_proxy_t (160 bytes, collide/collide_cube.h)
 *
 * The cube-map collider functions (beyond both papers; docs/BLADES.md)
 * are compiled only when common/bb.glsl is included before this file. */
#ifndef BLADE_GLSL
#define BLADE_GLSL

struct Blade {
    vec4 v0; /* xyz root, w direction angle */
    vec4 v1; /* xyz control point, w height */
    vec4 v2; /* xyz tip, w width */
    vec4 up; /* xyz unit up, w stiffness */
};

/* kind b.y: 0 wave a = (dir.x, dir.z, wavelength, speed);
 *           1 point a = (position.xyz, radius); b.x strength */
struct BladeWind {
    vec4 a;
    vec4 b;
};

struct BladeSphere {
    vec4 centre_radius;
    vec4 sweep; /* xyz previous centre - centre (0: the plain sphere) */
};

struct BladeCube {
    mat4 w2c;
    mat4 c2w;
    vec4 cube;   /* xyz centre (cube space), w half */
    vec4 sphere; /* xyz world centre, w radius (<= 0: skipped) */
};

#define BLADE_LENGTH_QUADRATURE 0
#define BLADE_LENGTH_PAPER 1
#define BLADE_ETA_DT (1.0 / 60.0)
#define BLADE_STIFFNESS_MIN 1e-3

#define BLADE_CULL_VISIBLE 0u
#define BLADE_CULL_ORIENTATION 1u
#define BLADE_CULL_FRUSTUM 2u
#define BLADE_CULL_DISTANCE 4u
#define BLADE_CULL_OCCLUSION 8u
#define BLADE_CULL_PADDING 16u

vec3 blade_safe_normalize(vec3 a)
{
    float l = length(a);
    return l > 1e-6 ? a * (1.0 / l) : vec3(0.0);
}

/* Width direction and front direction f = normalize(cross(up, width)). */
void blade_frame(Blade b, out vec3 width_dir, out vec3 front)
{
    vec3 up = b.up.xyz;
    float a = b.v0.w;
    vec3 d = vec3(cos(a), 0.0, sin(a));
    vec3 t = d - up * dot(d, up);
    if (length(t) < 1e-3) {
        d = vec3(-sin(a), 0.0, cos(a));
        t = d - up * dot(d, up);
    }
    width_dir = blade_safe_normalize(t);
    front = blade_safe_normalize(cross(up, width_dir));
}

/* Eq. 3: r = (I_v2 - v2) s max(1 - eta, 0.1). */
vec3 blade_recovery(Blade b, float eta)
{
    vec3 v0 = b.v0.xyz;
    vec3 up = b.up.xyz;
    float h = b.v1.w;
    float s = b.up.w;
    vec3 iv2 = v0 + up * h;
    return (iv2 - b.v2.xyz) * (s * max(1.0 - eta, 0.1));
}

/* Step gain k = (1 - exp(-s' dt)) / s' of v2 += (r + g + w) k, the exact
 * solution of the paper's tip update v2 += (r + g + w) dt with g, w frozen
 * (departure; blade_ref_step_gain). */
float blade_step_gain(float s, float dt)
{
    float x = s * dt;
    return x > 1e-3 ? (1.0 - exp(-x)) / s : dt * (1.0 - 0.5 * x);
}

/* Eq. 4-6. gravity: xyz unit direction, w magnitude (0 when off);
 * centre: xyz gravity centre, w mix t. */
vec3 blade_gravity(Blade b, vec4 gravity, vec4 centre)
{
    vec3 v0 = b.v0.xyz;
    float t = centre.w;
    vec3 to_centre = blade_safe_normalize(centre.xyz - v0);
    vec3 dir = gravity.xyz * (1.0 - t) + to_centre * t;
    vec3 ge = dir * gravity.w;
    vec3 width_dir, front;
    blade_frame(b, width_dir, front);
    vec3 gf = front * (0.25 * length(ge));
    return ge + gf;
}

/* w_i(p, time) of one field. */
vec3 blade_wind_field(BladeWind w, vec3 p, float time)
{
    float strength = w.b.x;
    if (w.b.y < 0.5) {
        vec3 d = blade_safe_normalize(vec3(w.a.x, 0.0, w.a.y));
        float wavelength = w.a.z;
        float speed = w.a.w;
        float phase = 6.28318531 * (dot(d, p) - speed * time) / wavelength;
        return d * (strength * (0.5 + 0.5 * sin(phase)));
    }
    vec3 rel = p - w.a.xyz;
    float radius = w.a.w;
    float falloff = max(1.0 - length(rel) / radius, 0.0);
    return blade_safe_normalize(rel) * (strength * falloff);
}

/* Eq. 7-8: w = w_sum theta, theta = f_d f_r. w_sum = sum of
 * blade_wind_field(field_i, v0, time), summed by the caller in field order. */
vec3 blade_wind(Blade b, vec3 wi)
{
    vec3 v0 = b.v0.xyz;
    vec3 up = b.up.xyz;
    float h = b.v1.w;
    vec3 tip = b.v2.xyz - v0;
    float fd = 1.0 - abs(dot(blade_safe_normalize(wi), blade_safe_normalize(tip)));
    float fr = dot(tip, up) / h;
    return wi * (fd * fr);
}

vec3 blade_midpoint(Blade b)
{
    return b.v0.xyz * 0.25 + b.v1.xyz * 0.5 + b.v2.xyz * 0.25;
}

/* Swept collision (twin of sphere_at): the sphere of s's swept capsule
 * closest to p; behind the start of the sweep, the sphere where it is now. */
BladeSphere blade_sphere_at(BladeSphere s, vec3 p)
{
    vec3 c = s.centre_radius.xyz;
    vec3 d = s.sweep.xyz;
    float dd = dot(d, d);
    float t = dd > 0.0 ? max(dot(p - c, d) / dd, 0.0) : 0.0;
    if (t > 1.0) t = 0.0;
    BladeSphere o = s;
    o.centre_radius.xyz = c + d * t;
    return o;
}

/* Push-out of p from a sphere: min(|c - p| - r, 0) normalize(c - p). */
vec3 blade_sphere_push(BladeSphere s, vec3 p)
{
    vec3 c = s.centre_radius.xyz;
    vec3 to_c = c - p;
    float pen = min(length(to_c) - s.centre_radius.w, 0.0);
    return blade_safe_normalize(to_c) * pen;
}

float blade_validate(inout Blade b, int length_mode);
void blade_revalidate(inout Blade b, int length_mode, float rescale);

/* 4x the push-out of m, cut back to the secant root when a copy
 * revalidated as the step will would carry m beyond the surface (twin of
 * midpoint_push; rescale: what blade_validate returned before the
 * collision). */
vec3 blade_midpoint_push(Blade b, BladeSphere sweep, int length_mode, float rescale)
{
    BladeSphere s = blade_sphere_at(sweep, blade_midpoint(b));
    vec3 pm = blade_sphere_push(s, blade_midpoint(b));
    vec3 dm = pm * 4.0;
    float p = length(pm);
    if (p > 0.0) {
        Blade t = b;
        t.v2.xyz = t.v2.xyz + dm;
        blade_revalidate(t, length_mode, rescale);
        float q = length(blade_midpoint(t) - s.centre_radius.xyz) - s.centre_radius.w;
        if (q > 0.0) dm = dm * (p / (p + q));
    }
    return dm;
}

/* Sec. 5.2 for one sphere: v2 pushed out, then the push of the recomputed
 * midpoint (blade_midpoint_push). Updates b.v2, returns the displacement.
 * The caller loops over the spheres in order and sums the results. */
vec3 blade_collide_sphere(inout Blade b, BladeSphere s, int length_mode, float rescale)
{
    vec3 dv2 = blade_sphere_push(blade_sphere_at(s, b.v2.xyz), b.v2.xyz);
    b.v2.xyz = b.v2.xyz + dv2;
    vec3 dm = blade_midpoint_push(b, s, length_mode, rescale);
    b.v2.xyz = b.v2.xyz + dm;
    return dv2 + dm;
}

/* ---- collision exit (departure from the paper; blade_ref_exit) ------------ */
#define BLADE_EXIT_ROUNDS 3
#define BLADE_EXIT_MARGIN 1.0001

float blade_cos_exit(float rho, float dist, float r)
{
    float rt = r * BLADE_EXIT_MARGIN;
    return min(max((rho * rho + dist * dist - rt * rt) / (2.0 * rho * dist), -1.0), 1.0);
}

vec3 blade_exit_side(vec3 ch, vec3 pd, vec3 up)
{
    vec3 e = pd - ch * dot(pd, ch);
    if (length(e) < 1e-4 * length(pd)) {
        e = up - ch * dot(up, ch);
        if (length(e) < 1e-4) e = cross(ch, vec3(0.0, 0.0, 1.0));
        if (length(e) < 1e-4) e = cross(ch, vec3(1.0, 0.0, 0.0));
    }
    return blade_safe_normalize(e);
}

bool blade_inside_sphere(BladeSphere s, vec3 p)
{
    vec3 pc = p - s.centre_radius.xyz;
    return dot(pc, pc) < s.centre_radius.w * s.centre_radius.w;
}

/* Twin of rotate_about_root (blade_ref.c): Rodrigues rotation of v1 and v2
 * about the root; with ground_test, skipped (false) when it would put v2
 * under the ground plane. */
bool blade_rotate_about_root(inout Blade b, vec3 v0, vec3 up, vec3 k, float cth, float sth, bool ground_test)
{
    vec3 x1 = b.v1.xyz - v0, x2 = b.v2.xyz - v0;
    vec3 r1 = (x1 * cth + cross(k, x1) * sth) + k * (dot(k, x1) * (1.0 - cth));
    vec3 r2 = (x2 * cth + cross(k, x2) * sth) + k * (dot(k, x2) * (1.0 - cth));
    if (ground_test && dot(r2, up) < 0.0) return false;
    b.v1.xyz = v0 + r1;
    b.v2.xyz = v0 + r2;
    return true;
}

/* Twin of exit_rotate_up: the turn about up that brings p onto the exit
 * distance of the sphere's cross-section at p's height. */
void blade_exit_rotate_up(inout Blade b, BladeSphere s, vec3 p, vec3 v0, vec3 up)
{
    vec3 cd = s.centre_radius.xyz - v0;
    float cu = dot(cd, up);
    vec3 ch = cd - up * cu;
    float dist = length(ch);
    vec3 pd = p - v0;
    float pu = dot(pd, up);
    vec3 ph = pd - up * pu;
    float rho = length(ph);
    float r = s.centre_radius.w;
    float r2 = r * r - (pu - cu) * (pu - cu);
    if (dist < 1e-6 || rho < 1e-6 || r2 <= 0.0) return;
    float rt = sqrt(r2) * BLADE_EXIT_MARGIN;
    float ct = (rho * rho + dist * dist - rt * rt) / (2.0 * rho * dist);
    if (ct < -1.0) return;
    ct = min(ct, 1.0);
    ch = ch * (1.0 / dist);
    vec3 e = ph - ch * dot(ph, ch);
    if (length(e) < 1e-4 * rho) e = cross(up, ch);
    e = blade_safe_normalize(e);
    float ca = min(max(dot(ph, ch) / rho, -1.0), 1.0);
    float sa = sqrt(max(1.0 - ca * ca, 0.0));
    float st = sqrt(max(1.0 - ct * ct, 0.0));
    vec3 k = dot(cross(ch, e), up) < 0.0 ? up * -1.0 : up;
    blade_rotate_about_root(b, v0, up, k, ct * ca + st * sa, st * ca - ct * sa, false);
}

void blade_exit_rotate(inout Blade b, BladeSphere sweep, vec3 p)
{
    BladeSphere s = blade_sphere_at(sweep, p);
    if (!blade_inside_sphere(s, p)) return;
    vec3 v0 = b.v0.xyz;
    vec3 up = b.up.xyz;
    vec3 cd = s.centre_radius.xyz - v0;
    float dist = length(cd);
    vec3 pd = p - v0;
    float rho = length(pd);
    if (dist <= s.centre_radius.w || rho < 1e-6) return;
    vec3 ch = cd * (1.0 / dist);
    vec3 e = blade_exit_side(ch, pd, up);
    float ca = dot(pd, ch) / rho;
    float sa = sqrt(max(1.0 - ca * ca, 0.0));
    float ct = blade_cos_exit(rho, dist, s.centre_radius.w);
    float st = sqrt(max(1.0 - ct * ct, 0.0));
    float cth = ct * ca + st * sa;
    float sth = st * ca - ct * sa;
    vec3 k = cross(ch, e);
    if (!blade_rotate_about_root(b, v0, up, k, cth, sth, true)) blade_exit_rotate_up(b, s, p, v0, up);
}

void blade_exit_straight(inout Blade b, BladeSphere sweep)
{
    BladeSphere s = blade_sphere_at(sweep, blade_midpoint(b));
    float h = b.v1.w;
    vec3 v0 = b.v0.xyz;
    vec3 up = b.up.xyz;
    if (!blade_inside_sphere(s, b.v2.xyz) && !blade_inside_sphere(s, blade_midpoint(b))) return;
    vec3 cd = s.centre_radius.xyz - v0;
    float dist = length(cd);
    float r = s.centre_radius.w;
    if (dist <= r) return;
    vec3 ch = cd * (1.0 / dist);
    vec3 td = b.v2.xyz - v0;
    float ct = min(blade_cos_exit(h, dist, r), blade_cos_exit(0.5 * h, dist, r));
    float st = sqrt(max(1.0 - ct * ct, 0.0));
    vec3 u = ch * ct + blade_exit_side(ch, td, up) * st;
    if (dot(u, up) < 0.0) {
        vec3 gp = ch - up * dot(ch, up);
        float gl = length(gp);
        vec3 g = blade_safe_normalize(gp);
        vec3 w = cross(up, g);
        float x = gl > 1e-6 ? min(max(ct / gl, -1.0), 1.0) : 0.0;
        float y = sqrt(max(1.0 - x * x, 0.0));
        u = g * x + w * (dot(w, td) < 0.0 ? -y : y);
    }
    b.v1.xyz = v0 + u * (0.5 * h);
    b.v2.xyz = v0 + u * h;
}

/* ---- Coulomb friction (departure from the paper; blade_ref_friction) ----- */
#define BLADE_FRICTION 0.5

/* Sphere part of pose_held: does the sphere hold v2 or m (whatever the
 * root)? */
bool blade_sphere_holds(Blade b, BladeSphere sweep)
{
    vec3 m = blade_midpoint(b);
    return blade_inside_sphere(blade_sphere_at(sweep, b.v2.xyz), b.v2.xyz) ||
           blade_inside_sphere(blade_sphere_at(sweep, m), m);
}

float blade_length_estimate(vec3 v0, vec3 v1, vec3 v2, int mode);

/* Twin of friction's second half, for a start pose no collider holds (the
 * caller tests that): stick (start's v1, v2) or the slipping blend brought
 * back to length h by eq. 12-13 alone. */
void blade_friction(inout Blade b, Blade start, vec3 d, int length_mode)
{
    vec3 mv = b.v2.xyz - start.v2.xyz;
    if (dot(mv, mv) <= BLADE_FRICTION * BLADE_FRICTION * dot(d, d)) {
        b.v1.xyz = start.v1.xyz;
        b.v2.xyz = start.v2.xyz;
        return;
    }
    float slip = 1.0 - BLADE_FRICTION * length(d) / length(mv);
    vec3 v0 = b.v0.xyz;
    vec3 v1 = start.v1.xyz, v2 = start.v2.xyz;
    v1 = v1 + (b.v1.xyz - v1) * slip;
    v2 = v2 + (b.v2.xyz - v2) * slip;
    float h = b.v1.w, len = blade_length_estimate(v0, v1, v2, length_mode);
    if (!(len > 1e-3 * h)) return;
    float r = h / len;
    b.v1.xyz = v0 + (v1 - v0) * r;
    b.v2.xyz = v0 + (v2 - v0) * r;
}

/* ---- cube-map colliders (beyond both papers; blade_ref.c cube_*) ---------- */
#ifdef BB_GLSL
#define BLADE_CUBE_MARGIN 1e-3
#define BLADE_CUBE_DIRECTIONS 33

bool blade_cube_near(BladeCube o, vec3 p)
{
    vec3 pc = p - o.sphere.xyz;
    return o.sphere.w > 0.0 && dot(pc, pc) < o.sphere.w * o.sphere.w;
}

float blade_cube_pen(sampler2DArray tex, bb_cube c, vec3 q, out vec3 n)
{
    float best = 3.402823e38;
    n = vec3(0.0);
    for (int f = 0; f < 6; f++) {
        vec4 tx;
        float pen = bb_lookup(tex, c, f, q, tx) - tx.x;
        if (!(pen > 0.0)) return 0.0;
        if (pen < best) {
            best = pen;
            n = tx.yzw;
        }
    }
    return best;
}

bool blade_inside_cube(sampler2DArray tex, BladeCube o, bb_cube c, vec3 p)
{
    if (!blade_cube_near(o, p)) return false;
    vec3 n;
    return blade_cube_pen(tex, c, (o.w2c * vec4(p, 1.0)).xyz, n) > 0.0;
}

vec3 blade_cube_push(sampler2DArray tex, BladeCube o, bb_cube c, vec3 p, float margin)
{
    if (!blade_cube_near(o, p)) return vec3(0.0);
    vec3 q = (o.w2c * vec4(p, 1.0)).xyz;
    vec3 n;
    float pen = blade_cube_pen(tex, c, q, n);
    if (!(pen > 0.0)) return vec3(0.0);
    vec3 t = q + n * (pen + margin * o.cube.w);
    return (o.c2w * vec4(t, 1.0)).xyz - p;
}

vec3 blade_collide_cube(inout Blade b, sampler2DArray tex, BladeCube o, bb_cube c)
{
    vec3 dv2 = blade_cube_push(tex, o, c, b.v2.xyz, 0.0);
    b.v2.xyz = b.v2.xyz + dv2;
    vec3 dm = blade_cube_push(tex, o, c, blade_midpoint(b), 0.0) * 4.0;
    b.v2.xyz = b.v2.xyz + dm;
    return dv2 + dm;
}

void blade_cube_exit_rotate(inout Blade b, sampler2DArray tex, BladeCube o, bb_cube c, vec3 p)
{
    vec3 v0 = b.v0.xyz;
    vec3 up = b.up.xyz;
    vec3 push = blade_cube_push(tex, o, c, p, BLADE_CUBE_MARGIN);
    if (dot(push, push) == 0.0 || blade_inside_cube(tex, o, c, v0)) return;
    vec3 a = p - v0;
    vec3 t = a + push;
    float la = length(a), lt = length(t);
    if (la < 1e-6 || lt < 1e-6) return;
    vec3 ax = cross(a, t);
    float s = length(ax);
    if (s < 1e-9 * la * lt) return;
    vec3 k = ax * (1.0 / s);
    float cth = dot(a, t) / (la * lt);
    float sth = s / (la * lt);
    blade_rotate_about_root(b, v0, up, k, cth, sth, true);
}

vec3 blade_cube_direction(Blade b, int i)
{
    vec3 up = b.up.xyz;
    if (i == 0) return up;
    vec3 wd, fr;
    blade_frame(b, wd, fr);
    int ring = (i - 1) / 8 + 1, az = (i - 1) % 8;
    float th = 0.39269908 * float(ring), ph = 0.78539816 * float(az);
    vec3 side = wd * cos(ph) + fr * sin(ph);
    return up * cos(th) + side * sin(th);
}
#endif

/* Integral of |B'(t)| over [t0, t1], 3-point Gauss-Legendre; B'(t) = 2(e0 + t a). */
float blade_speed_integral(vec3 e0, vec3 a, float t0, float t1)
{
    const float gl3_t[3] = float[3](0.11270166, 0.5, 0.88729833);
    const float gl3_w[3] = float[3](0.27777778, 0.44444444, 0.27777778);
    float s = 0.0;
    for (int i = 0; i < 3; i++) {
        float t = t0 + (t1 - t0) * gl3_t[i];
        s += gl3_w[i] * length(e0 + a * t);
    }
    return 2.0 * (t1 - t0) * s;
}

float blade_length_estimate(vec3 v0, vec3 v1, vec3 v2, int mode)
{
    if (mode == BLADE_LENGTH_PAPER) {
        float l0 = length(v2 - v0);
        float l1 = length(v1 - v0) + length(v2 - v1);
        return (2.0 * l0 + l1) / 3.0;
    }
    vec3 e0 = v1 - v0;
    vec3 a = (v0 - v1 * 2.0) + v2;
    float aa = dot(a, a);
    float ts = aa > 1e-12 ? min(max(-dot(a, e0) / aa, 0.0), 1.0) : 0.0;
    return blade_speed_integral(e0, a, 0.0, ts) + blade_speed_integral(e0, a, ts, 1.0);
}

/* Eq. 9-13; returns the rescale r of eq. 13 (1 for a padding blade). */
float blade_validate(inout Blade b, int length_mode)
{
    float h = b.v1.w;
    if (h <= 0.0) return 1.0;
    vec3 v0 = b.v0.xyz;
    vec3 up = b.up.xyz;
    vec3 v2 = b.v2.xyz;
    v2 = v2 - up * min(dot(up, v2 - v0), 0.0);
    vec3 tip = v2 - v0;
    float lproj = length(tip - up * dot(tip, up));
    vec3 v1 = v0 + up * (h * max(1.0 - lproj / h, 0.05 * max(lproj / h, 1.0)));
    float r = h / blade_length_estimate(v0, v1, v2, length_mode);
    vec3 v1c = v0 + (v1 - v0) * r;
    vec3 v2c = v1c + (v2 - v1) * r;
    b.v1.xyz = v1c;
    b.v2.xyz = v2c;
    return r;
}

/* Twin of revalidate: the validation after a contact, of the tip mapped
 * back through the rescale of the validation before the collision. */
void blade_revalidate(inout Blade b, int length_mode, float rescale)
{
    vec3 v0 = b.v0.xyz;
    b.v2.xyz = v0 + (b.v2.xyz - v0) * (1.0 / rescale);
    blade_validate(b, length_mode);
}

/* ---- culling (blade_ref_cull_one) ---------------------------------------- */

/* Twin of blade_ref_lod_orientation: the orientation threshold of a blade
 * drawn width_scale times as wide (the thinning's width factor,
 * common/lod.glsl). */
float blade_lod_orientation(float threshold, float width_scale)
{
    float k = max(width_scale, 1.0);
    return sqrt(max(1.0 - (1.0 - threshold * threshold) / (k * k), 0.0));
}

/* Twin of blade_ref_box_outside: the box [lo, hi] lies outside one clip
 * plane of vp grown by tol (blade mode's patch test). */
bool blade_patch_outside(vec3 lo, vec3 hi, mat4 vp, float tol)
{
    for (int plane = 0; plane < 6; plane++) {
        int axis = plane / 2;
        float sign = (plane & 1) != 0 ? -1.0 : 1.0;
        bool all_out = true;
        for (int c = 0; c < 8 && all_out; c++) {
            vec3 p = vec3((c & 1) != 0 ? hi.x : lo.x, (c & 2) != 0 ? hi.y : lo.y, (c & 4) != 0 ? hi.z : lo.z);
            vec4 clip = vp * vec4(p, 1.0);
            if (clip.w + sign * clip[axis] + tol >= 0.0) all_out = false;
        }
        if (all_out) return true;
    }
    return false;
}

/* Twin of blade_ref_patch_bucket: floor(n sqrt(d / range)), at most n - 1,
 * d the distance from the camera to the box. */
uint blade_patch_bucket(vec3 camera, vec3 lo, vec3 hi, float range, uint n)
{
    vec3 q = max(max(lo - camera, camera - hi), vec3(0.0));
    float d = sqrt(q.x * q.x + q.y * q.y + q.z * q.z);
    float k = floor(float(n) * sqrt(d / range));
    return uint(min(k, float(n - 1u)));
}

bool blade_in_frustum(vec4 clip, float tolerance)
{
    float h = clip.w + tolerance;
    return abs(clip.x) <= h && abs(clip.y) <= h && abs(clip.z) <= h;
}

/* Occlusion test of one point (sec. 6; twin of blade_ref.c's occluded,
 * used by blade_cull.comp and tiles_cull.comp): a point in front of the
 * camera whose NDC x, y lie in [-1, 1] maps to the depth texel
 * (floor((x 0.5 + 0.5) W), floor((y 0.5 + 0.5) H)), clamped; it is
 * occluded when its NDC z lies beyond the texel's window depth d (NDC
 * 2 d - 1) by more than bias. Points outside the image are never
 * occluded. */
bool blade_occluded(sampler2D depth, vec4 clip, float bias)
{
    if (clip.w <= 0.0) return false;
    float x = clip.x / clip.w, y = clip.y / clip.w, z = clip.z / clip.w;
    if (abs(x) > 1.0 || abs(y) > 1.0) return false;
    ivec2 size = textureSize(depth, 0);
    int px = clamp(int(floor((x * 0.5 + 0.5) * float(size.x))), 0, size.x - 1);
    int py = clamp(int(floor((y * 0.5 + 0.5) * float(size.y))), 0, size.y - 1);
    float ndc = texelFetch(depth, ivec2(px, py), 0).r * 2.0 - 1.0;
    return z > ndc + bias;
}

#endif

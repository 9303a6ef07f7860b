/* collide_cube: depth cube maps (see collide_cube.h): face table, CPU
 * rasterisation of spheres, capsules and boxes by one ray per texel, and
 * the lookup, inside test (Orthmann et al. 2009 eq. 1-3) and push-out
 * (eq. 4-5) that shaders/common/bb.glsl mirrors. */
#include "collide/collide_cube.h"

#include "core/core.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Rows of the face table in collide_cube.h: u, v, inward. */
static const float face_table[6][3][3] = {
    {{0, 0, -1}, {0, 1, 0}, {-1, 0, 0}},
    {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}},
    {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}},
    {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}},
    {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
};

void collide_get_face_basis(int face, vec3 axis_u, vec3 axis_v, vec3 inward)
{
    assert(face >= 0 && face < 6);
    for (int k = 0; k < 3; k++) {
        axis_u[k] = face_table[face][0][k];
        axis_v[k] = face_table[face][1][k];
        inward[k] = face_table[face][2][k];
    }
}

bool collide_init_cubemap(collide_cubemap_t *cube, int res, const vec3 centre, float half)
{
    assert(res > 0 && half > 0.0f);
    memset(cube, 0, sizeof *cube);
    cube->texels = malloc(sizeof(float) * 4u * 6u * (size_t)res * (size_t)res);
    if (!cube->texels) {
        core_log_error("out of memory for a %d^2 cube map", res);
        return false;
    }
    cube->res = res;
    glm_vec3_copy((float *)centre, cube->centre);
    cube->half = half;
    collide_clear_cubemap(cube);
    return true;
}

void collide_free_cubemap(collide_cubemap_t *cube)
{
    free(cube->texels);
    memset(cube, 0, sizeof *cube);
}

void collide_clear_cubemap(collide_cubemap_t *cube)
{
    int res = cube->res;
    for (int f = 0; f < 6; f++) {
        vec3 u, v, in;
        collide_get_face_basis(f, u, v, in);
        for (int t = 0; t < res * res; t++) {
            float *tx = cube->texels + ((size_t)f * res * res + t) * 4;
            tx[0] = 2.0f * cube->half;
            tx[1] = -in[0];
            tx[2] = -in[1];
            tx[3] = -in[2];
        }
    }
}

void collide_get_texel_origin(const collide_cubemap_t *cube, int face, int i, int j, vec3 out)
{
    vec3 u, v, in;
    collide_get_face_basis(face, u, v, in);
    float step = 2.0f * cube->half / (float)cube->res;
    float cu = -cube->half + ((float)i + 0.5f) * step;
    float cv = -cube->half + ((float)j + 0.5f) * step;
    for (int k = 0; k < 3; k++)
        out[k] = cube->centre[k] - in[k] * cube->half + cu * u[k] + cv * v[k];
}

/* ---- ray casts ---------------------------------------------------------------
 * Each returns the entry parameter t0 >= 0 of the ray o + t d (|d| = 1), or
 * -1 for no hit in front of the origin; origin inside the shape returns 0
 * with *inside set. Hits are reported as distances along d. */

static float ray_sphere(const vec3 o, const vec3 d, const vec3 c, float r, bool *inside)
{
    vec3 oc;
    glm_vec3_sub((float *)o, (float *)c, oc);
    float cc = glm_vec3_dot(oc, oc) - r * r;
    if (cc <= 0.0f) {
        *inside = true;
        return 0.0f;
    }
    float b = glm_vec3_dot(oc, (float *)d);
    float disc = b * b - cc;
    if (disc < 0.0f || b > 0.0f) return -1.0f;
    return -b - sqrtf(disc);
}

static void closest_on_segment(const vec3 p, const vec3 a, const vec3 b, vec3 out)
{
    vec3 ab, ap;
    glm_vec3_sub((float *)b, (float *)a, ab);
    glm_vec3_sub((float *)p, (float *)a, ap);
    float den = glm_vec3_dot(ab, ab);
    float t = den > 0.0f ? glm_clamp(glm_vec3_dot(ap, ab) / den, 0.0f, 1.0f) : 0.0f;
    for (int k = 0; k < 3; k++) out[k] = a[k] + t * ab[k];
}

/* Capsule = sphere(a) U sphere(b) U open cylinder side; the first entry into
 * a union of convex pieces is the smallest entry over the pieces. */
static float ray_capsule(const vec3 o, const vec3 d, const vec3 a, const vec3 b, float r,
                            bool *inside)
{
    vec3 cl;
    closest_on_segment(o, a, b, cl);
    if (glm_vec3_distance2((float *)o, cl) <= r * r) {
        *inside = true;
        return 0.0f;
    }
    bool dummy = false;
    float best = -1.0f;
    float ts[2] = {ray_sphere(o, d, a, r, &dummy), ray_sphere(o, d, b, r, &dummy)};
    for (int k = 0; k < 2; k++)
        if (ts[k] >= 0.0f && (best < 0.0f || ts[k] < best)) best = ts[k];
    vec3 ba, oa;
    glm_vec3_sub((float *)b, (float *)a, ba);
    glm_vec3_sub((float *)o, (float *)a, oa);
    float baba = glm_vec3_dot(ba, ba), bard = glm_vec3_dot(ba, (float *)d);
    float baoa = glm_vec3_dot(ba, oa), rdoa = glm_vec3_dot((float *)d, oa);
    float oaoa = glm_vec3_dot(oa, oa);
    float qa = baba - bard * bard;
    float qb = baba * rdoa - baoa * bard;
    float qc = baba * oaoa - baoa * baoa - r * r * baba;
    float disc = qb * qb - qa * qc;
    if (qa > 1e-9f * baba && disc >= 0.0f) {
        float t = (-qb - sqrtf(disc)) / qa;
        float y = baoa + t * bard;
        if (t >= 0.0f && y > 0.0f && y < baba && (best < 0.0f || t < best)) best = t;
    }
    return best;
}

static float ray_box(const vec3 o, const vec3 d, const vec3 c, const vec3 he, bool *inside,
                        int *axis_out)
{
    float t0 = -INFINITY, t1 = INFINITY;
    int axis = -1;
    bool in = true;
    for (int k = 0; k < 3; k++) {
        float lo = c[k] - he[k], hi = c[k] + he[k];
        if (o[k] < lo || o[k] > hi) in = false;
        if (fabsf(d[k]) < 1e-12f) {
            if (o[k] < lo || o[k] > hi) return -1.0f;
            continue;
        }
        float ta = (lo - o[k]) / d[k], tb = (hi - o[k]) / d[k];
        if (ta > tb) {
            float s = ta;
            ta = tb;
            tb = s;
        }
        if (ta > t0) {
            t0 = ta;
            axis = k;
        }
        if (tb < t1) t1 = tb;
    }
    if (in) {
        *inside = true;
        return 0.0f;
    }
    if (t0 > t1 || t0 < 0.0f) return -1.0f;
    *axis_out = axis;
    return t0;
}

enum { RAY_SPHERE, RAY_CAPSULE, RAY_BOX };

typedef struct ray_shape_t {
    int kind;
    vec3 a, b; /* sphere: a = centre; capsule: segment a-b; box: centre a, half extents b */
    float r;
} ray_shape_t;

static void render_rays(collide_cubemap_t *cube, const ray_shape_t *s)
{
    int res = cube->res;
    for (int f = 0; f < 6; f++) {
        vec3 u, v, in;
        collide_get_face_basis(f, u, v, in);
        for (int j = 0; j < res; j++) {
            for (int i = 0; i < res; i++) {
                vec3 o, hit, n;
                collide_get_texel_origin(cube, f, i, j, o);
                bool inside = false;
                int axis = 0;
                float t = -1.0f;
                switch (s->kind) {
                case RAY_SPHERE: t = ray_sphere(o, in, s->a, s->r, &inside); break;
                case RAY_CAPSULE: t = ray_capsule(o, in, s->a, s->b, s->r, &inside); break;
                default: t = ray_box(o, in, s->a, s->b, &inside, &axis); break;
                }
                if (t < 0.0f || t > 2.0f * cube->half) continue;
                float *tx = cube->texels + (((size_t)f * res + j) * res + i) * 4;
                if (t >= tx[0]) continue;
                glm_vec3_scale(in, -1.0f, n);
                if (!inside) {
                    glm_vec3_copy(o, hit);
                    glm_vec3_muladds(in, t, hit);
                    if (s->kind == RAY_SPHERE) {
                        glm_vec3_sub(hit, (float *)s->a, n);
                    } else if (s->kind == RAY_CAPSULE) {
                        vec3 cl;
                        closest_on_segment(hit, s->a, s->b, cl);
                        glm_vec3_sub(hit, cl, n);
                    } else {
                        glm_vec3_zero(n);
                        n[axis] = in[axis] > 0.0f ? -1.0f : 1.0f;
                    }
                    glm_vec3_normalize(n);
                }
                tx[0] = t;
                tx[1] = n[0];
                tx[2] = n[1];
                tx[3] = n[2];
            }
        }
    }
}

void collide_render_sphere(collide_cubemap_t *cube, const vec3 centre, float radius)
{
    ray_shape_t s = {.kind = RAY_SPHERE, .r = radius};
    glm_vec3_copy((float *)centre, s.a);
    render_rays(cube, &s);
}

void collide_render_capsule(collide_cubemap_t *cube, const vec3 a, const vec3 b, float radius)
{
    ray_shape_t s = {.kind = RAY_CAPSULE, .r = radius};
    glm_vec3_copy((float *)a, s.a);
    glm_vec3_copy((float *)b, s.b);
    render_rays(cube, &s);
}

void collide_render_box(collide_cubemap_t *cube, const vec3 centre, const vec3 half_extents)
{
    ray_shape_t s = {.kind = RAY_BOX};
    glm_vec3_copy((float *)centre, s.a);
    glm_vec3_copy((float *)half_extents, s.b);
    render_rays(cube, &s);
}

/* ---- eq. 1-5 ------------------------------------------------------------------ */

float collide_lookup_texel(const collide_cubemap_t *cube, int face, const vec3 q, vec4 texel)
{
    vec3 u, v, in, rel;
    collide_get_face_basis(face, u, v, in);
    glm_vec3_sub((float *)q, (float *)cube->centre, rel);
    float pu = glm_vec3_dot(rel, u);
    float pv = glm_vec3_dot(rel, v);
    float depth = glm_vec3_dot(rel, in) + cube->half;
    float scale = (float)cube->res / (2.0f * cube->half);
    int i = (int)floorf((pu + cube->half) * scale);
    int j = (int)floorf((pv + cube->half) * scale);
    i = i < 0 ? 0 : (i > cube->res - 1 ? cube->res - 1 : i);
    j = j < 0 ? 0 : (j > cube->res - 1 ? cube->res - 1 : j);
    const float *tx = cube->texels + (((size_t)face * cube->res + j) * cube->res + i) * 4;
    glm_vec4_copy((float *)tx, texel);
    return depth;
}

bool collide_test_inside(const collide_cubemap_t *cube, const vec3 q)
{
    for (int f = 0; f < 6; f++) {
        vec4 tx;
        float d = collide_lookup_texel(cube, f, q, tx);
        if (!(d > tx[0])) return false;
    }
    return true;
}

bool collide_push_out(const collide_cubemap_t *cube, const vec3 q, vec3 out)
{
    float best = INFINITY;
    vec3 n = {0, 0, 0};
    for (int f = 0; f < 6; f++) {
        vec4 tx;
        float pen = collide_lookup_texel(cube, f, q, tx) - tx[0];
        if (!(pen > 0.0f)) {
            glm_vec3_copy((float *)q, out);
            return false;
        }
        if (pen < best) {
            best = pen;
            glm_vec3_copy(tx + 1, n);
        }
    }
    for (int k = 0; k < 3; k++) out[k] = q[k] + best * n[k];
    return true;
}

void collide_make_cube_proxy(const float model[16], const float centre[3], float half,
                             collide_cube_proxy_t *out)
{
    mat4 m, inv;
    memcpy(m, model, sizeof m);
    glm_mat4_inv(m, inv);
    memcpy(out->w2c, inv, sizeof out->w2c);
    memcpy(out->c2w, m, sizeof out->c2w);
    glm_vec3_copy((float *)centre, out->cube);
    out->cube[3] = half;
    glm_mat4_mulv3(m, (float *)centre, 1.0f, out->sphere);
    float sc = fmaxf(glm_vec3_norm(m[0]), fmaxf(glm_vec3_norm(m[1]), glm_vec3_norm(m[2])));
    out->sphere[3] = half * sqrtf(3.0f) * sc;
}

/* bb_ref: CPU reference of Orthmann et al. 2009 billboard collisions: depth
 * cube map rasterisation, inside test (eq. 1-3), push-out (eq. 4-5), spring
 * relaxation (eq. 6-7), recovery (eq. 8) and the procedural wind pose.
 * shaders/common/bb.glsl mirrors the lookup-to-wind functions line by line. */
#include "billboard/bb_ref.h"

#include "core/core.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Rows of the face table in bb_ref.h: u, v, inward. */
static const float bb_face_table[6][3][3] = {
    {{0, 0, -1}, {0, 1, 0}, {-1, 0, 0}},
    {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}},
    {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}},
    {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {{1, 0, 0}, {0, 1, 0}, {0, 0, -1}},
    {{-1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
};

void bb_cubemap_face_basis(int face, vec3 axis_u, vec3 axis_v, vec3 inward)
{
    assert(face >= 0 && face < 6);
    for (int k = 0; k < 3; k++) {
        axis_u[k] = bb_face_table[face][0][k];
        axis_v[k] = bb_face_table[face][1][k];
        inward[k] = bb_face_table[face][2][k];
    }
}

bool bb_cubemap_init(bb_cubemap_t *cube, int res, const vec3 centre, float half)
{
    assert(res > 0 && half > 0.0f);
    memset(cube, 0, sizeof *cube);
    cube->texels = malloc(sizeof(float) * 4u * 6u * (size_t)res * (size_t)res);
    if (!cube->texels) {
        core_log_error("%s:%d: out of memory for a %d^2 cube map", __FILE__, __LINE__, res);
        return false;
    }
    cube->res = res;
    glm_vec3_copy((float *)centre, cube->centre);
    cube->half = half;
    bb_cubemap_clear(cube);
    return true;
}

void bb_cubemap_free(bb_cubemap_t *cube)
{
    free(cube->texels);
    memset(cube, 0, sizeof *cube);
}

void bb_cubemap_clear(bb_cubemap_t *cube)
{
    int res = cube->res;
    for (int f = 0; f < 6; f++) {
        vec3 u, v, in;
        bb_cubemap_face_basis(f, u, v, in);
        for (int t = 0; t < res * res; t++) {
            float *tx = cube->texels + ((size_t)f * res * res + t) * 4;
            tx[0] = 2.0f * cube->half;
            tx[1] = -in[0];
            tx[2] = -in[1];
            tx[3] = -in[2];
        }
    }
}

void bb_cubemap_texel_origin(const bb_cubemap_t *cube, int face, int i, int j, vec3 out)
{
    vec3 u, v, in;
    bb_cubemap_face_basis(face, u, v, in);
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

static float bb_ray_sphere(const vec3 o, const vec3 d, const vec3 c, float r, bool *inside)
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

static void bb_closest_on_segment(const vec3 p, const vec3 a, const vec3 b, vec3 out)
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
static float bb_ray_capsule(const vec3 o, const vec3 d, const vec3 a, const vec3 b, float r,
                            bool *inside)
{
    vec3 cl;
    bb_closest_on_segment(o, a, b, cl);
    if (glm_vec3_distance2((float *)o, cl) <= r * r) {
        *inside = true;
        return 0.0f;
    }
    bool dummy = false;
    float best = -1.0f;
    float ts[2] = {bb_ray_sphere(o, d, a, r, &dummy), bb_ray_sphere(o, d, b, r, &dummy)};
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

static float bb_ray_box(const vec3 o, const vec3 d, const vec3 c, const vec3 he, bool *inside,
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

enum { BB_SHAPE_SPHERE, BB_SHAPE_CAPSULE, BB_SHAPE_BOX };

typedef struct bb_shape_t {
    int kind;
    vec3 a, b; /* sphere: a = centre; capsule: segment a-b; box: centre a, half extents b */
    float r;
} bb_shape_t;

static void bb_cubemap_render(bb_cubemap_t *cube, const bb_shape_t *s)
{
    int res = cube->res;
    for (int f = 0; f < 6; f++) {
        vec3 u, v, in;
        bb_cubemap_face_basis(f, u, v, in);
        for (int j = 0; j < res; j++) {
            for (int i = 0; i < res; i++) {
                vec3 o, hit, n;
                bb_cubemap_texel_origin(cube, f, i, j, o);
                bool inside = false;
                int axis = 0;
                float t = -1.0f;
                switch (s->kind) {
                case BB_SHAPE_SPHERE: t = bb_ray_sphere(o, in, s->a, s->r, &inside); break;
                case BB_SHAPE_CAPSULE: t = bb_ray_capsule(o, in, s->a, s->b, s->r, &inside); break;
                default: t = bb_ray_box(o, in, s->a, s->b, &inside, &axis); break;
                }
                if (t < 0.0f || t > 2.0f * cube->half) continue;
                float *tx = cube->texels + (((size_t)f * res + j) * res + i) * 4;
                if (t >= tx[0]) continue;
                glm_vec3_scale(in, -1.0f, n);
                if (!inside) {
                    glm_vec3_copy(o, hit);
                    glm_vec3_muladds(in, t, hit);
                    if (s->kind == BB_SHAPE_SPHERE) {
                        glm_vec3_sub(hit, (float *)s->a, n);
                    } else if (s->kind == BB_SHAPE_CAPSULE) {
                        vec3 cl;
                        bb_closest_on_segment(hit, s->a, s->b, cl);
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

void bb_cubemap_render_sphere(bb_cubemap_t *cube, const vec3 centre, float radius)
{
    bb_shape_t s = {.kind = BB_SHAPE_SPHERE, .r = radius};
    glm_vec3_copy((float *)centre, s.a);
    bb_cubemap_render(cube, &s);
}

void bb_cubemap_render_capsule(bb_cubemap_t *cube, const vec3 a, const vec3 b, float radius)
{
    bb_shape_t s = {.kind = BB_SHAPE_CAPSULE, .r = radius};
    glm_vec3_copy((float *)a, s.a);
    glm_vec3_copy((float *)b, s.b);
    bb_cubemap_render(cube, &s);
}

void bb_cubemap_render_box(bb_cubemap_t *cube, const vec3 centre, const vec3 half_extents)
{
    bb_shape_t s = {.kind = BB_SHAPE_BOX};
    glm_vec3_copy((float *)centre, s.a);
    glm_vec3_copy((float *)half_extents, s.b);
    bb_cubemap_render(cube, &s);
}

/* ---- eq. 1-5 ------------------------------------------------------------------ */

float bb_ref_lookup(const bb_cubemap_t *cube, int face, const vec3 q, vec4 texel)
{
    vec3 u, v, in, rel;
    bb_cubemap_face_basis(face, u, v, in);
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

bool bb_ref_inside(const bb_cubemap_t *cube, const vec3 q)
{
    for (int f = 0; f < 6; f++) {
        vec4 tx;
        float d = bb_ref_lookup(cube, f, q, tx);
        if (!(d > tx[0])) return false;
    }
    return true;
}

bool bb_ref_push_out(const bb_cubemap_t *cube, const vec3 q, vec3 out)
{
    float best = INFINITY;
    vec3 n = {0, 0, 0};
    for (int f = 0; f < 6; f++) {
        vec4 tx;
        float pen = bb_ref_lookup(cube, f, q, tx) - tx[0];
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

/* ---- mesh, eq. 6-8 ---------------------------------------------------------------- */

bool bb_mesh_init_quad(bb_mesh_t *mesh, const vec3 root_centre, const vec3 right,
                       const vec3 up, float width, float height, int n, int m)
{
    assert(n >= 2 && m >= 2);
    memset(mesh, 0, sizeof *mesh);
    mesh->pos = malloc(sizeof(vec3) * (size_t)n * (size_t)m);
    mesh->rest = malloc(sizeof(vec3) * (size_t)n * (size_t)m);
    if (!mesh->pos || !mesh->rest) {
        core_log_error("%s:%d: out of memory for a %dx%d billboard mesh", __FILE__, __LINE__, n, m);
        bb_mesh_free(mesh);
        return false;
    }
    mesh->n = n;
    mesh->m = m;
    vec3 r, u;
    glm_vec3_normalize_to((float *)right, r);
    glm_vec3_normalize_to((float *)up, u);
    for (int j = 0; j < m; j++) {
        for (int i = 0; i < n; i++) {
            float x = width * ((float)i / (float)(n - 1) - 0.5f);
            float y = height * (float)j / (float)(m - 1);
            float *p = mesh->rest[j * n + i];
            for (int k = 0; k < 3; k++) p[k] = root_centre[k] + x * r[k] + y * u[k];
            glm_vec3_copy(p, mesh->pos[j * n + i]);
        }
    }
    return true;
}

void bb_mesh_free(bb_mesh_t *mesh)
{
    free(mesh->pos);
    free(mesh->rest);
    memset(mesh, 0, sizeof *mesh);
}

/* One spring of eq. 6-7 between vertices a and b (indices); fixed = row 0. */
static void bb_spring(bb_mesh_t *mesh, int a, int b, float r)
{
    bool fa = a < mesh->n, fb = b < mesh->n;
    if (fa && fb) return;
    vec3 delta;
    glm_vec3_sub(mesh->pos[b], mesh->pos[a], delta);
    float l = glm_vec3_norm(delta);
    if (l < 1e-12f) return;
    float l0 = glm_vec3_distance(mesh->rest[a], mesh->rest[b]);
    vec3 c;
    glm_vec3_scale(delta, (l - l0) / l, c);
    if (fa) {
        glm_vec3_muladds(c, -r, mesh->pos[b]);
    } else if (fb) {
        glm_vec3_muladds(c, r, mesh->pos[a]);
    } else {
        glm_vec3_muladds(c, 0.5f * r, mesh->pos[a]);
        glm_vec3_muladds(c, -0.5f * r, mesh->pos[b]);
    }
}

void bb_ref_relax_springs(bb_mesh_t *mesh, float r1, float r2, int iterations)
{
    int n = mesh->n, m = mesh->m;
    for (int it = 0; it < iterations; it++) {
        for (int j = 1; j < m; j++)
            for (int i = 0; i < n - 1; i++) bb_spring(mesh, j * n + i, j * n + i + 1, r1);
        for (int i = 0; i < n; i++)
            for (int j = 0; j < m - 1; j++) bb_spring(mesh, j * n + i, (j + 1) * n + i, r1);
        for (int j = 0; j < m - 1; j++) {
            for (int i = 0; i < n - 1; i++) {
                bb_spring(mesh, j * n + i, (j + 1) * n + i + 1, r2);
                bb_spring(mesh, j * n + i + 1, (j + 1) * n + i, r2);
            }
        }
    }
}

static void bb_spring_err(const bb_mesh_t *mesh, int a, int b, double *sum, int *count)
{
    if (a < mesh->n && b < mesh->n) return;
    float l = glm_vec3_distance(mesh->pos[a], mesh->pos[b]);
    float l0 = glm_vec3_distance(mesh->rest[a], mesh->rest[b]);
    *sum += fabs((double)l - (double)l0) / (double)l0;
    (*count)++;
}

float bb_ref_spring_error(const bb_mesh_t *mesh)
{
    int n = mesh->n, m = mesh->m, count = 0;
    double sum = 0.0;
    for (int j = 1; j < m; j++)
        for (int i = 0; i < n - 1; i++) bb_spring_err(mesh, j * n + i, j * n + i + 1, &sum, &count);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < m - 1; j++) bb_spring_err(mesh, j * n + i, (j + 1) * n + i, &sum, &count);
    for (int j = 0; j < m - 1; j++) {
        for (int i = 0; i < n - 1; i++) {
            bb_spring_err(mesh, j * n + i, (j + 1) * n + i + 1, &sum, &count);
            bb_spring_err(mesh, j * n + i + 1, (j + 1) * n + i, &sum, &count);
        }
    }
    return count ? (float)(sum / count) : 0.0f;
}

bb_collide_desc_t bb_collide_desc_defaults(const bb_collide_desc_t *desc)
{
    bb_collide_desc_t d = desc ? *desc : (bb_collide_desc_t){0};
    if (d.r1 == 0.0f) d.r1 = 1.0f;
    if (d.r2 == 0.0f) d.r2 = 0.5f;
    if (d.iterations == 0) d.iterations = 4;
    return d;
}

static void bb_push_mesh(bb_mesh_t *mesh, const bb_cubemap_t *cubes, const mat4 *w2c,
                         const mat4 *c2w, int count)
{
    for (int v = mesh->n; v < mesh->n * mesh->m; v++) {
        for (int c = 0; c < count; c++) {
            vec3 q, out;
            glm_mat4_mulv3((vec4 *)w2c[c], mesh->pos[v], 1.0f, q);
            if (bb_ref_push_out(&cubes[c], q, out))
                glm_mat4_mulv3((vec4 *)c2w[c], out, 1.0f, mesh->pos[v]);
        }
    }
}

void bb_ref_collide(bb_mesh_t *mesh, const bb_cubemap_t *cubes, const mat4 *world_to_cube,
                    int count, const bb_collide_desc_t *desc)
{
    bb_collide_desc_t d = bb_collide_desc_defaults(desc);
    enum { BB_MAX_CUBES = 64 };
    assert(count >= 0 && count <= BB_MAX_CUBES);
    mat4 c2w[BB_MAX_CUBES];
    for (int c = 0; c < count; c++) glm_mat4_inv((vec4 *)world_to_cube[c], c2w[c]);
    bb_push_mesh(mesh, cubes, world_to_cube, (const mat4 *)c2w, count);
    for (int it = 0; it < d.iterations; it++) {
        bb_ref_relax_springs(mesh, d.r1, d.r2, 1);
        bb_push_mesh(mesh, cubes, world_to_cube, (const mat4 *)c2w, count);
    }
}

void bb_ref_recover(bb_mesh_t *mesh, const vec3 *wind_pose, float t)
{
    t = glm_clamp(t, 0.0f, 1.0f);
    float t3 = t * t * t;
    for (int v = 0; v < mesh->n * mesh->m; v++)
        for (int k = 0; k < 3; k++)
            mesh->pos[v][k] = (1.0f - t3) * wind_pose[v][k] + t3 * mesh->pos[v][k];
}

bb_wind_desc_t bb_wind_desc_defaults(const bb_wind_desc_t *desc)
{
    bb_wind_desc_t d = desc ? *desc : (bb_wind_desc_t){0};
    float len = sqrtf(d.dir[0] * d.dir[0] + d.dir[1] * d.dir[1]);
    if (len == 0.0f) {
        d.dir[0] = 1.0f;
        d.dir[1] = 0.0f;
    } else {
        d.dir[0] /= len;
        d.dir[1] /= len;
    }
    if (d.strength == 0.0f) d.strength = 0.1f;
    if (d.omega == 0.0f) d.omega = 1.5f;
    if (d.wavenumber == 0.0f) d.wavenumber = 0.4f;
    return d;
}

void bb_ref_wind_vertex(const bb_wind_desc_t *wind, const vec3 rest, const vec3 root,
                        float h, float time, vec3 out)
{
    float ph = wind->wavenumber * (root[0] * wind->dir[0] + root[2] * wind->dir[1]);
    float wt = wind->omega * time;
    float s = 0.6f * sinf(wt - ph) + 0.3f * sinf(2.3f * wt - 1.7f * ph + 1.3f) +
              0.1f * sinf(5.1f * wt - 2.9f * ph + 0.7f);
    float bend = wind->strength * h * h * (0.4f + 0.6f * s);
    out[0] = rest[0] + bend * wind->dir[0];
    out[1] = rest[1];
    out[2] = rest[2] + bend * wind->dir[1];
}

void bb_ref_wind_pose(const bb_mesh_t *mesh, const bb_wind_desc_t *desc, float time, vec3 *out)
{
    bb_wind_desc_t w = bb_wind_desc_defaults(desc);
    int n = mesh->n, m = mesh->m;
    vec3 root;
    glm_vec3_lerp(mesh->rest[0], mesh->rest[n - 1], 0.5f, root);
    for (int j = 0; j < m; j++) {
        float h = (float)j / (float)(m - 1);
        for (int i = 0; i < n; i++) bb_ref_wind_vertex(&w, mesh->rest[j * n + i], root, h, time, out[j * n + i]);
    }
}

/* bb_ref: CPU reference of Orthmann et al. 2009 billboard collisions: mesh
 * push-out against depth cube maps (eq. 4-5 through collide_push_out),
 * spring relaxation (eq. 6-7), recovery (eq. 8) and the procedural wind
 * pose. shaders/common/bb.glsl mirrors these functions line by line. */
#include "billboard/bb_ref.h"

#include "core/core.h"

#include <assert.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---- mesh, eq. 6-8 ---------------------------------------------------------------- */

bool bb_mesh_init_quad(bb_mesh_t *mesh, const vec3 root_centre, const vec3 right,
                       const vec3 up, float width, float height, int n, int m)
{
    assert(n >= 2 && m >= 2);
    memset(mesh, 0, sizeof *mesh);
    mesh->pos = malloc(sizeof(vec3) * (size_t)n * (size_t)m);
    mesh->rest = malloc(sizeof(vec3) * (size_t)n * (size_t)m);
    if (!mesh->pos || !mesh->rest) {
        core_log_error("out of memory for a %dx%d billboard mesh", n, m);
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

/* Bend limit (departure from the paper; issue 17): the constraint
 * C = (x_v - x_a) . t - BB_REF_BEND_COS l0 >= 0, t the unit direction of
 * the segment b -> a before joint a (for a root a, its rest column
 * direction; b < 0), l0 the rest length a-v. A violated constraint is
 * projected as in position-based dynamics, along the gradients
 * dC/dv = t, dC/da = -t + p / |a - b|, dC/db = -p / |a - b| (p the part of
 * v - a across t), roots fixed: the segment before the joint leans into
 * the bend instead of the joint creasing. */
static void bb_bend(bb_mesh_t *mesh, const float t_in[3], int b, int a, int v)
{
    int n = mesh->n;
    vec3 t, av, p, ga, gb;
    float tl = glm_vec3_norm((float *)t_in);
    if (tl < 1e-12f) return;
    glm_vec3_scale((float *)t_in, 1.0f / tl, t);
    glm_vec3_sub(mesh->pos[v], mesh->pos[a], av);
    float c = glm_vec3_dot(av, t) - BB_REF_BEND_COS * glm_vec3_distance(mesh->rest[a], mesh->rest[v]);
    if (c >= 0.0f) return;
    glm_vec3_scale(t, glm_vec3_dot(av, t), p);
    glm_vec3_sub(av, p, p);
    float inv = b >= 0 ? 1.0f / tl : 0.0f, wa = a >= n ? 1.0f : 0.0f, wb = b >= n ? 1.0f : 0.0f;
    for (int k = 0; k < 3; k++) {
        ga[k] = -t[k] + p[k] * inv;
        gb[k] = -p[k] * inv;
    }
    float lambda = -c / (1.0f + wa * glm_vec3_dot(ga, ga) + wb * glm_vec3_dot(gb, gb));
    glm_vec3_muladds(t, lambda, mesh->pos[v]);
    glm_vec3_muladds(ga, wa * lambda, mesh->pos[a]);
    if (b >= 0) glm_vec3_muladds(gb, wb * lambda, mesh->pos[b]);
}

void bb_ref_bend_limit(bb_mesh_t *mesh)
{
    int n = mesh->n, m = mesh->m;
    vec3 t;
    for (int i = 0; i < n; i++)
        for (int j = 1; j < m; j++) {
            int v = j * n + i, a = v - n;
            if (j == 1) glm_vec3_sub(mesh->rest[v], mesh->rest[a], t);
            else glm_vec3_sub(mesh->pos[a], mesh->pos[a - n], t);
            bb_bend(mesh, t, j == 1 ? -1 : a - n, a, v);
        }
    for (int j = 1; j < m; j++)
        for (int i = 2; i < n; i++) {
            int v = j * n + i, a = v - 1;
            glm_vec3_sub(mesh->pos[a], mesh->pos[a - 1], t);
            bb_bend(mesh, t, a - 1, a, v);
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

/* The translation that moves cube c back along its sweep s to the point of
 * the step's path nearest the world point p (bb_collide_desc_t.sweep). */
static void sweep_shift(const collide_cubemap_t *cube, const mat4 c2w, const float s[3], const float p[3], vec3 out)
{
    vec3 centre;
    glm_mat4_mulv3((vec4 *)c2w, (float *)cube->centre, 1.0f, centre);
    float ss = s[0] * s[0] + s[1] * s[1] + s[2] * s[2];
    float t = 0.0f;
    if (ss > 0.0f)
        t = glm_clamp(((p[0] - centre[0]) * s[0] + (p[1] - centre[1]) * s[1] + (p[2] - centre[2]) * s[2]) / ss, 0.0f,
                      1.0f);
    for (int k = 0; k < 3; k++) out[k] = s[k] * t;
}

/* Where cube c's push-out would take world point x (its swept position
 * included); false when x is outside. */
static bool push_target(const collide_cubemap_t *cube, const mat4 w2c, const mat4 c2w, const float *sweep,
                        const float x[3], vec3 out)
{
    vec3 shift = {0.0f, 0.0f, 0.0f}, p, q, o;
    if (sweep) sweep_shift(cube, c2w, sweep, x, shift);
    glm_vec3_sub((float *)x, shift, p);
    glm_mat4_mulv3((vec4 *)w2c, p, 1.0f, q);
    if (!collide_push_out(cube, q, o)) return false;
    glm_mat4_mulv3((vec4 *)c2w, o, 1.0f, p);
    glm_vec3_add(p, shift, out);
    return true;
}

/* Slide (departure from the paper): x, which a push takes to `to`, goes
 * instead to the point of the plane through `to` across the push that lies
 * at the rest distance l0 from the vertex below it, a, in the direction
 * x - a has along that plane: its column segment turns about a out of the
 * object instead of being shortened. `to` is kept where no such point
 * exists (a farther than l0 from the plane, or x straight along the push
 * from a). */
static void bb_slide(const float a[3], float l0, const float x[3], vec3 to)
{
    vec3 nrm, foot, tang, ax;
    glm_vec3_sub(to, (float *)x, nrm);
    float pen = glm_vec3_norm(nrm);
    if (pen < 1e-12f) return;
    glm_vec3_scale(nrm, 1.0f / pen, nrm);
    glm_vec3_sub((float *)a, to, foot);
    float h = glm_vec3_dot(foot, nrm);
    if (h * h >= l0 * l0) return;
    glm_vec3_sub((float *)x, (float *)a, ax);
    glm_vec3_scale(nrm, glm_vec3_dot(ax, nrm), tang);
    glm_vec3_sub(ax, tang, tang);
    float tl = glm_vec3_norm(tang);
    if (tl < 1e-6f * l0) return;
    float s = sqrtf(l0 * l0 - h * h) / tl;
    for (int k = 0; k < 3; k++) to[k] = a[k] - h * nrm[k] + s * tang[k];
}

/* Keeps x on or above the ground (bb_collide_desc_t.ground). */
static void bb_ground_vertex(float x[3], const collide_cubemap_t *cubes, const mat4 *w2c, const mat4 *c2w, int count,
                             const bb_collide_desc_t *d)
{
    float g = d->ground(d->ground_user, x[0], x[2]);
    if (x[1] >= g) return;
    x[1] = g;
    /* Raised back into an object whose push pointed down: leave it
     * sideways instead, along the push's horizontal part by the distance
     * that removes its depth across a locally flat surface (pen / |n_h|,
     * at most 4 pen), then onto the ground again. */
    for (int c = 0; c < count; c++) {
        vec3 to;
        if (!push_target(&cubes[c], w2c[c], c2w[c], d->sweep ? d->sweep[c] : NULL, x, to)) continue;
        float dx = to[0] - x[0], dy = to[1] - x[1], dz = to[2] - x[2];
        float pen = sqrtf(dx * dx + dy * dy + dz * dz), hl = sqrtf(dx * dx + dz * dz);
        if (hl < 1e-6f * fmaxf(pen, 1e-12f)) continue;
        float s = fminf(pen * pen / hl, 4.0f * pen);
        x[0] += dx / hl * s;
        x[2] += dz / hl * s;
        x[1] = fmaxf(x[1], d->ground(d->ground_user, x[0], x[2]));
    }
}

static void bb_push_mesh(bb_mesh_t *mesh, const collide_cubemap_t *cubes, const mat4 *w2c,
                         const mat4 *c2w, int count, const bb_collide_desc_t *d)
{
    for (int v = mesh->n; v < mesh->n * mesh->m; v++) {
        float *x = mesh->pos[v];
        const float *a = mesh->pos[v - mesh->n];
        float l0 = glm_vec3_distance(mesh->rest[v], mesh->rest[v - mesh->n]);
        /* Each object's push slides x at its row length (bb_slide), then
         * pushes the slid point again: the push comes last. */
        for (int c = 0; c < count; c++) {
            const float *sweep = d->sweep ? d->sweep[c] : NULL;
            vec3 to;
            if (!push_target(&cubes[c], w2c[c], c2w[c], sweep, x, to)) continue;
            if (d->paper) {
                glm_vec3_copy(to, x);
                continue;
            }
            bb_slide(a, l0, x, to);
            glm_vec3_copy(to, x);
            push_target(&cubes[c], w2c[c], c2w[c], sweep, x, x);
        }
        if (d->ground && !d->paper) bb_ground_vertex(x, cubes, w2c, c2w, count, d);
    }
}

void bb_ref_collide(bb_mesh_t *mesh, const collide_cubemap_t *cubes, const mat4 *world_to_cube,
                    int count, const bb_collide_desc_t *desc)
{
    bb_collide_desc_t d = bb_collide_desc_defaults(desc);
    enum { BB_MAX_CUBES = 64 };
    assert(count >= 0 && count <= BB_MAX_CUBES);
    mat4 c2w[BB_MAX_CUBES];
    for (int c = 0; c < count; c++) glm_mat4_inv((vec4 *)world_to_cube[c], c2w[c]);
    bb_push_mesh(mesh, cubes, world_to_cube, (const mat4 *)c2w, count, &d);
    if (d.paper) {
        bb_ref_relax_springs(mesh, d.r1, d.r2, d.iterations);
        return;
    }
    for (int it = 0; it < d.iterations; it++) {
        bb_ref_bend_limit(mesh);
        bb_ref_relax_springs(mesh, d.r1, d.r2, 1);
        bb_push_mesh(mesh, cubes, world_to_cube, (const mat4 *)c2w, count, &d);
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

bb_wind_desc_t bb_wind_from_wave(float dir_x, float dir_z, float strength, float wavelength, float speed)
{
    assert(wavelength > 0.0f);
    return (bb_wind_desc_t){.dir = {dir_x, dir_z},
                            .strength = 0.08f * strength,
                            .omega = 2.0f * GLM_PIf * speed / wavelength,
                            .wavenumber = 2.0f * GLM_PIf / wavelength};
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
    float s = 0.6f * sinf(ph - wt) + 0.3f * sinf(1.7f * ph - 2.3f * wt + 1.3f) +
              0.1f * sinf(2.9f * ph - 5.1f * wt + 0.7f);
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

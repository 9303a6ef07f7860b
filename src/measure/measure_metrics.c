/* measure_metrics: accuracy metrics of a world's state for `meadow bench`
 * and the stability suite; the definitions, formulas and sample points are
 * docs/METRICS.md's ("Penetration", "Shape error", "Texture distortion").
 *
 * Penetration is measured against the exact analytic collider
 * (collide_signed_distance at its current position), never against the
 * proxy a method collides with (blade spheres, billboard cube maps):
 *   - blades: 8 points per Bezier curve at t = k/8, k = 1..8 (the root is
 *     fixed and left out);
 *   - billboards: every non-root vertex, three points inside every mesh
 *     edge above the root row and every cell centre of each deformed mesh;
 *     a billboard without a mesh is sampled on its wind pose, so a
 *     collision the method missed counts.
 * Characters stand in as their blade proxy spheres. Only samples rooted
 * within reach of a collider count, and a collider is ignored for samples
 * anchored inside it (no method can move grass rooted there).
 *
 * Shape errors: blade length |L - h| / h; billboard spring error
 * |l - l0| / l0 over the structural springs. Texture distortion: the largest
 * structural stretch and the folded cells of each deformed billboard. */
#include "measure/measure_metrics.h"

#include "measure/measure.h"

#include "collide/collide_shape.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define SAMPLES_PER_BLADE 8
#define MAX_EXACT (SCENE_MAX_COLLIDERS + BLADE_MAX_SPHERES)

typedef struct exact_t {
    collide_shape_t shape;
    vec3 pos;
    float reach; /* bounding radius */
} exact_t;

static int gather_exact(world_t *w, exact_t *out)
{
    int n = 0;
    for (int i = 0; i < world_collider_count(w); i++) {
        world_collider_info_t c = world_collider(w, i);
        out[n].shape = scene_collider_shape(&c.desc);
        glm_vec3_copy(c.position, out[n].pos);
        out[n].reach = c.bound_radius;
        n++;
    }
    character_set_t *chars = world_info(w).characters;
    if (chars) {
        float (*s)[4] = malloc(sizeof(float[4]) * BLADE_MAX_SPHERES);
        int k = s ? character_set_spheres(chars, s, BLADE_MAX_SPHERES) : 0;
        if (k > BLADE_MAX_SPHERES) k = BLADE_MAX_SPHERES;
        for (int i = 0; i < k; i++, n++) {
            out[n] = (exact_t){.shape = {.type = COLLIDE_SHAPE_SPHERE, .radius = s[i][3]}, .reach = s[i][3]};
            glm_vec3_copy(s[i], out[n].pos);
        }
        free(s);
    }
    return n;
}

typedef struct pen_acc_t {
    long near, inside;
    double max_depth;
} pen_acc_t;

/* The sample's fixed root points: the row-0 vertices of the one or two
 * columns it lies on or between. */
typedef struct anchors_t {
    const float *a, *b;
} anchors_t;

static bool anchored_inside(const exact_t *e, const float a[3])
{
    float q[3] = {a[0] - e->pos[0], a[1] - e->pos[1], a[2] - e->pos[2]};
    return collide_signed_distance(&e->shape, q) < 0.0f;
}

/* Depth of p inside the deepest collider among those within reach of the
 * root (0 when outside all). *near is set when any collider is in reach.
 * A collider that contains one of the sample's anchors is skipped: no
 * method can move grass rooted inside a collider. */
static float depth_at(const exact_t *ex, int n, const float root[3], float reach_extra, anchors_t an,
                      const float p[3], bool *near)
{
    float depth = 0.0f;
    *near = false;
    for (int i = 0; i < n; i++) {
        float dx = root[0] - ex[i].pos[0], dz = root[2] - ex[i].pos[2];
        float r = ex[i].reach + reach_extra;
        if (dx * dx + dz * dz >= r * r) continue;
        if (anchored_inside(&ex[i], an.a) || anchored_inside(&ex[i], an.b)) continue;
        *near = true;
        float q[3] = {p[0] - ex[i].pos[0], p[1] - ex[i].pos[1], p[2] - ex[i].pos[2]};
        float d = -collide_signed_distance(&ex[i].shape, q);
        if (d > depth) depth = d;
    }
    return depth;
}

/* The colliders of ex[0..n) within reach of root (depth_at's reach test,
 * once per blade or billboard instead of once per sample: with 16 walkers'
 * 608 spheres over the worlds' 571,536 billboards a bench --perf run of
 * world_1km took 110 s on llvmpipe, 67 s now) into out, in order; returns
 * how many. */
static int near_exact(const exact_t *ex, int n, const float root[3], float reach_extra, exact_t *out)
{
    int k = 0;
    for (int i = 0; i < n; i++) {
        float dx = root[0] - ex[i].pos[0], dz = root[2] - ex[i].pos[2];
        float r = ex[i].reach + reach_extra;
        if (dx * dx + dz * dz < r * r) out[k++] = ex[i];
    }
    return k;
}

static void sample(pen_acc_t *acc, const exact_t *ex, int n, const float root[3], float reach_extra, anchors_t an,
                   const float p[3])
{
    bool near;
    float d = depth_at(ex, n, root, reach_extra, an, p, &near);
    if (!near) return;
    acc->near++;
    if (d > 0.0f) {
        acc->inside++;
        if (d > acc->max_depth) acc->max_depth = d;
    }
}

/* EDGE_SAMPLES points inside the segment a b (a mesh edge: between two
 * vertices a sphere or a box corner can poke through where no vertex is). */
#define EDGE_SAMPLES 3
static void sample_edge(pen_acc_t *acc, const exact_t *ex, int n, const float root[3], float reach_extra,
                        anchors_t an, const float a[3], const float b[3])
{
    for (int i = 1; i <= EDGE_SAMPLES; i++) {
        float t = (float)i / (float)(EDGE_SAMPLES + 1), q[3];
        for (int k = 0; k < 3; k++) q[k] = a[k] + t * (b[k] - a[k]);
        sample(acc, ex, n, root, reach_extra, an, q);
    }
}

static void bezier(const blade_t *b, float t, float out[3])
{
    float a = (1 - t) * (1 - t), c = 2 * (1 - t) * t, d = t * t;
    for (int k = 0; k < 3; k++) out[k] = a * b->v0[k] + c * b->v1[k] + d * b->v2[k];
}

static bool blade_finite(const blade_t *b)
{
    for (int k = 0; k < 3; k++)
        if (!isfinite(b->v1[k]) || !isfinite(b->v2[k])) return false;
    return true;
}

static void blade_metrics(world_t *w, const exact_t *ex, int n, pen_acc_t *acc, measure_metrics_t *m,
                          measure_metrics_ext_t *x)
{
    blade_gpu_t *g = measure_drivers(w).blades;
    const terrain_mesh_t *terrain = world_info(w).terrain;
    bool heightfield = world_info(w).scene->terrain.type == TERRAIN_HEIGHTFIELD;
    uint32_t count = blade_gpu_info(g).padded_count;
    blade_t *b = malloc(sizeof *b * count);
    exact_t *near = malloc(sizeof *near * (size_t)(n > 0 ? n : 1));
    if (!b || !near) {
        free(b);
        free(near);
        return;
    }
    blade_gpu_read_blades(g, b, NULL);
    double len_sum = 0;
    long real = 0, below = 0;
    for (uint32_t i = 0; i < count; i++) {
        float h = b[i].v1[3];
        if (h <= 0.0f) continue;
        real++;
        if (!blade_finite(&b[i])) {
            x->nonfinite++;
            continue;
        }
        len_sum += fabs(blade_ref_curve_length(&b[i], 32) - h) / h;
        float ground = terrain_height_at(terrain, b[i].v2[0], b[i].v2[2], NULL);
        if (isfinite(ground) && b[i].v2[1] < ground - 0.01f && heightfield)
            below++;
        int nn = near_exact(ex, n, b[i].v0, h, near);
        if (nn == 0) continue; /* no collider in reach: no sample counts */
        for (int k = 1; k <= SAMPLES_PER_BLADE; k++) {
            float p[3];
            bezier(&b[i], (float)k / SAMPLES_PER_BLADE, p);
            sample(acc, near, nn, b[i].v0, h, (anchors_t){b[i].v0, b[i].v0}, p);
        }
        for (int k = 0; k < 2; k++) {
            float p[3];
            bool in_reach;
            bezier(&b[i], k ? 1.0f : 0.5f, p);
            double d = depth_at(near, nn, b[i].v0, h, (anchors_t){b[i].v0, b[i].v0}, p, &in_reach);
            if (d > x->tested_max) x->tested_max = d;
        }
    }
    if (real) {
        m->blade_length_error = len_sum / (double)real;
        x->below_ground = (double)below / (double)real;
    }
    free(b);
    free(near);
}

/* The world's billboard field and what it holds (NULL without one). */
static bb_field_t *bb_of(world_t *w, bb_field_info_t *fi)
{
    bb_field_t *f = measure_drivers(w).billboards;
    if (f) bb_field_info(f, fi);
    return f;
}

/* Reads the billboard points and the deformed-mesh pool back from the GPU
 * (false, with both NULL, when out of memory or a read fails; the caller
 * frees both). */
static bool read_bb(const bb_field_t *f, const bb_field_info_t *fi, bb_point_t **pts, float (**mesh)[4])
{
    size_t slots = (size_t)fi->desc.max_deformed;
    *pts = malloc(sizeof **pts * (size_t)(fi->billboards > 0 ? fi->billboards : 1));
    *mesh = malloc(sizeof(float[4]) * slots * (size_t)fi->mesh_vertices);
    if (!*pts || !*mesh || !bb_field_read(f, BB_DATA_POINTS, 0, (size_t)fi->billboards, *pts) ||
        !bb_field_read(f, BB_DATA_MESHES, 0, slots, *mesh)) {
        free(*pts);
        free(*mesh);
        *pts = NULL;
        *mesh = NULL;
        return false;
    }
    return true;
}

/* Billboard p's wind pose at the field's time into grid (N x M). */
static void bb_wind_grid(const bb_field_info_t *fi, const bb_point_t *p, vec3 *grid)
{
    int nn = fi->desc.subdiv[0], mm = fi->desc.subdiv[1];
    vec3 right, up;
    bb_point_frame(p, right, up);
    for (int j = 0; j < mm; j++)
        for (int c = 0; c < nn; c++) {
            float xo = p->size[0] * ((float)c / (float)(nn - 1) - 0.5f);
            float yo = p->size[1] * (float)j / (float)(mm - 1);
            vec3 rest;
            for (int k = 0; k < 3; k++) rest[k] = p->position[k] + xo * right[k] + yo * up[k];
            bb_ref_wind_vertex(&fi->desc.wind, rest, (float *)p->position, (float)j / (float)(mm - 1), fi->time,
                               grid[j * nn + c]);
        }
}

/* Billboard p's pose into grid: its deformed mesh, else its wind pose. */
static void bb_grid(const bb_field_info_t *fi, const bb_point_t *p, const float (*mesh)[4], vec3 *grid)
{
    int nv = fi->desc.subdiv[0] * fi->desc.subdiv[1];
    uint32_t slot = p->pad[0];
    if (slot == BB_NO_SLOT || slot >= (uint32_t)fi->desc.max_deformed) {
        bb_wind_grid(fi, p, grid);
        return;
    }
    for (int v = 0; v < nv; v++) glm_vec3_copy((float *)mesh[(size_t)slot * nv + v], grid[v]);
}

static void bb_metrics(world_t *w, const exact_t *ex, int n, pen_acc_t *acc, measure_metrics_t *m,
                       measure_metrics_ext_t *x)
{
    bb_field_info_t fi;
    bb_field_t *f = bb_of(w, &fi);
    int nn = fi.desc.subdiv[0], mm = fi.desc.subdiv[1], nv = nn * mm;
    bb_point_t *pts;
    float (*mesh)[4];
    bool have = read_bb(f, &fi, &pts, &mesh);
    vec3 *grid = malloc(sizeof(vec3) * (size_t)nv);
    exact_t *near = malloc(sizeof *near * (size_t)(n > 0 ? n : 1));
    if (!have || !grid || !near) goto done;
    double spring_sum = 0;
    long springs = 0;
    for (int i = 0; i < fi.billboards; i++) {
        const bb_point_t *p = &pts[i];
        uint32_t slot = p->pad[0];
        bool deformed = slot != BB_NO_SLOT && slot < (uint32_t)fi.desc.max_deformed;
        float reach = fmaxf(p->size[0], p->size[1]);
        int nk = near_exact(ex, n, p->position, reach, near);
        if (!deformed && nk == 0) continue; /* no spring to measure, no sample counts */
        bb_grid(&fi, p, (const float (*)[4])mesh, grid);
        if (deformed) {
            x->deformed++;
            for (int v = 0; v < nv; v++)
                if (!isfinite(grid[v][0]) || !isfinite(grid[v][1]) || !isfinite(grid[v][2])) x->nonfinite++;
            float l0x = p->size[0] / (float)(nn - 1), l0y = p->size[1] / (float)(mm - 1);
            for (int j = 0; j < mm; j++)
                for (int c = 0; c < nn; c++) {
                    if (c + 1 < nn) {
                        spring_sum += fabsf(glm_vec3_distance(grid[j * nn + c], grid[j * nn + c + 1]) - l0x) / l0x;
                        springs++;
                    }
                    if (j + 1 < mm) {
                        spring_sum +=
                            fabsf(glm_vec3_distance(grid[j * nn + c], grid[(j + 1) * nn + c]) - l0y) / l0y;
                        springs++;
                    }
                }
        }
        for (int j = 1; j < mm && nk > 0; j++)
            for (int c = 0; c < nn; c++) {
                anchors_t col = {grid[c], grid[c]}, row = {grid[c], grid[c + 1 < nn ? c + 1 : c]};
                sample(acc, near, nk, p->position, reach, col, grid[j * nn + c]);
                sample_edge(acc, near, nk, p->position, reach, col, grid[(j - 1) * nn + c], grid[j * nn + c]);
                if (c + 1 < nn) {
                    sample_edge(acc, near, nk, p->position, reach, row, grid[j * nn + c], grid[j * nn + c + 1]);
                    vec3 q;
                    for (int k = 0; k < 3; k++)
                        q[k] = 0.25f * (grid[j * nn + c][k] + grid[j * nn + c + 1][k] + grid[(j - 1) * nn + c][k] +
                                        grid[(j - 1) * nn + c + 1][k]);
                    sample(acc, near, nk, p->position, reach, row, q);
                }
            }
    }
    m->spring_error = springs ? spring_sum / (double)springs : 0.0;
done:
    free(pts);
    free(mesh);
    free(grid);
    free(near);
}

void measure_metrics(world_t *w, measure_metrics_t *m, measure_metrics_ext_t *x)
{
    measure_metrics_ext_t dummy;
    if (!x) x = &dummy;
    memset(x, 0, sizeof *x);
    m->penetration_fraction = m->penetration_max = m->blade_length_error = m->spring_error = -1;
    exact_t *ex = malloc(sizeof *ex * MAX_EXACT);
    if (!ex) return;
    int n = gather_exact(w, ex);
    pen_acc_t acc = {0};
    scene_mode_t mode = world_info(w).mode;
    bool reference = world_info(w).reference;
    bool blades = measure_drivers(w).blades && (mode != SCENE_MODE_BILLBOARD || reference);
    bool bbs = measure_drivers(w).billboards && mode != SCENE_MODE_BLADE && !reference;
    if (blades) blade_metrics(w, ex, n, &acc, m, x);
    if (bbs) bb_metrics(w, ex, n, &acc, m, x);
    if (blades || bbs) {
        m->penetration_fraction = acc.near ? (double)acc.inside / (double)acc.near : 0.0;
        m->penetration_max = acc.max_depth;
    }
    x->near_samples = acc.near;
    x->inside_samples = acc.inside;
    free(ex);
}

static blade_t *read_blades(blade_gpu_t *g)
{
    blade_t *b = malloc(sizeof *b * blade_gpu_info(g).padded_count);
    if (b) blade_gpu_read_blades(g, b, NULL);
    return b;
}

double measure_blade_offset(world_t *w, world_t *twin, float *prev, bool *primed, double *jitter)
{
    blade_gpu_t *gw = measure_drivers(w).blades, *gt = measure_drivers(twin).blades;
    uint32_t count = gw ? blade_gpu_info(gw).padded_count : 0;
    if (!gw || !gt || count != blade_gpu_info(gt).padded_count) return 0;
    blade_t *a = read_blades(gw), *b = read_blades(gt);
    double worst = 0, jit = 0;
    bool first = prev && !*primed;
    for (uint32_t i = 0; a && b && i < count; i++) {
        if (a[i].v1[3] <= 0.0f) continue;
        float d[3];
        for (int k = 0; k < 3; k++) d[k] = a[i].v2[k] - b[i].v2[k];
        double len = sqrt((double)d[0] * d[0] + (double)d[1] * d[1] + (double)d[2] * d[2]);
        if (!isfinite(len)) worst = INFINITY;
        else if (len > worst) worst = len;
        if (prev) {
            if (!first) {
                double dj = sqrt((double)(d[0] - prev[3 * i]) * (d[0] - prev[3 * i]) +
                                 (double)(d[1] - prev[3 * i + 1]) * (d[1] - prev[3 * i + 1]) +
                                 (double)(d[2] - prev[3 * i + 2]) * (d[2] - prev[3 * i + 2]));
                if (dj > jit) jit = dj;
            }
            memcpy(&prev[3 * i], d, sizeof d);
        }
    }
    if (prev) *primed = true;
    if (jitter) *jitter = jit;
    free(a);
    free(b);
    return worst;
}

double measure_blade_coverage(world_t *w, world_t *twin, const float a[2], const float b[2],
                                    float radius, float frac, uint8_t *ever, long *corridor)
{
    *corridor = 0;
    blade_gpu_t *gw = measure_drivers(w).blades, *gt = measure_drivers(twin).blades;
    uint32_t count = gw ? blade_gpu_info(gw).padded_count : 0;
    if (!gw || !gt || count != blade_gpu_info(gt).padded_count) return 0;
    blade_t *x = read_blades(gw), *y = read_blades(gt);
    long hit = 0;
    float ab[2] = {b[0] - a[0], b[1] - a[1]};
    float ab2 = ab[0] * ab[0] + ab[1] * ab[1];
    for (uint32_t i = 0; x && y && i < count; i++) {
        float h = x[i].v1[3];
        if (h <= 0.0f) continue;
        float ap[2] = {x[i].v0[0] - a[0], x[i].v0[2] - a[1]};
        float t = (ap[0] * ab[0] + ap[1] * ab[1]) / ab2;
        if (t <= 0.0f || t >= 1.0f) continue;
        float dx = ap[0] - t * ab[0], dz = ap[1] - t * ab[1];
        if (dx * dx + dz * dz > radius * radius) continue;
        (*corridor)++;
        float dd = glm_vec3_distance(x[i].v2, y[i].v2);
        bool deflected = !isfinite(dd) || dd > frac * h;
        if (ever) deflected = (ever[i] |= deflected);
        if (deflected) hit++;
    }
    free(x);
    free(y);
    return *corridor ? (double)hit / (double)*corridor : 0.0;
}

/* Largest distance of billboard p's deformed mesh (slot) from its wind pose. */
static double bb_mesh_offset(const bb_field_info_t *fi, const bb_point_t *p, const float (*mesh)[4])
{
    int nn = fi->desc.subdiv[0], mm = fi->desc.subdiv[1], nv = nn * mm;
    uint32_t slot = p->pad[0];
    if (slot == BB_NO_SLOT || slot >= (uint32_t)fi->desc.max_deformed) return 0.0;
    vec3 right, up;
    bb_point_frame(p, right, up);
    double worst = 0.0;
    for (int j = 1; j < mm; j++)
        for (int c = 0; c < nn; c++) {
            float xo = p->size[0] * ((float)c / (float)(nn - 1) - 0.5f);
            float yo = p->size[1] * (float)j / (float)(mm - 1);
            vec3 rest, wind;
            for (int k = 0; k < 3; k++) rest[k] = p->position[k] + xo * right[k] + yo * up[k];
            bb_ref_wind_vertex(&fi->desc.wind, rest, (float *)p->position, (float)j / (float)(mm - 1), fi->time, wind);
            double d = glm_vec3_distance(wind, (float *)mesh[(size_t)slot * nv + j * nn + c]);
            if (!isfinite(d)) return INFINITY;
            if (d > worst) worst = d;
        }
    return worst;
}

double measure_bb_coverage(world_t *w, const float a[2], const float b[2], float radius, float frac,
                                 uint8_t *ever, long *corridor)
{
    *corridor = 0;
    bb_field_info_t fi;
    bb_field_t *f = bb_of(w, &fi);
    bb_point_t *pts;
    float (*mesh)[4];
    if (!f || !read_bb(f, &fi, &pts, &mesh)) return 0.0;
    float ab[2] = {b[0] - a[0], b[1] - a[1]};
    float ab2 = ab[0] * ab[0] + ab[1] * ab[1];
    long hit = 0;
    for (int i = 0; i < fi.billboards; i++) {
        const bb_point_t *p = &pts[i];
        float ap[2] = {p->position[0] - a[0], p->position[2] - a[1]};
        float t = (ap[0] * ab[0] + ap[1] * ab[1]) / ab2;
        if (t <= 0.0f || t >= 1.0f) continue;
        float dx = ap[0] - t * ab[0], dz = ap[1] - t * ab[1];
        if (dx * dx + dz * dz > radius * radius) continue;
        (*corridor)++;
        ever[i] |= bb_mesh_offset(&fi, p, (const float (*)[4])mesh) > frac * p->size[1];
        hit += ever[i];
    }
    free(pts);
    free(mesh);
    return *corridor ? (double)hit / (double)*corridor : 0.0;
}

double measure_bb_offset(world_t *w)
{
    bb_field_info_t fi;
    bb_field_t *f = bb_of(w, &fi);
    if (!f) return 0;
    bb_point_t *pts;
    float (*mesh)[4];
    double worst = 0;
    if (read_bb(f, &fi, &pts, &mesh)) {
        for (int i = 0; i < fi.billboards; i++) {
            double d = bb_mesh_offset(&fi, &pts[i], (const float (*)[4])mesh);
            if (d > worst) worst = d;
        }
    }
    free(pts);
    free(mesh);
    return worst;
}

/* Area vector (e - a) x (d - b) / 2 of the cell with lower corners a, b and
 * upper corners d, e (left to right). */
static void cell_area(const float *a, const float *b, const float *d, const float *e, vec3 out)
{
    vec3 p, q;
    glm_vec3_sub((float *)e, (float *)a, p);
    glm_vec3_sub((float *)d, (float *)b, q);
    glm_vec3_cross(p, q, out);
    glm_vec3_scale(out, 0.5f, out);
}

void measure_bb_distortion(world_t *w, measure_bb_distortion_t *out)
{
    memset(out, 0, sizeof *out);
    bb_field_info_t fi;
    bb_field_t *f = bb_of(w, &fi);
    if (!f) return;
    int nn = fi.desc.subdiv[0], mm = fi.desc.subdiv[1], nv = nn * mm;
    bb_point_t *pts;
    float (*mesh)[4];
    vec3 *unit = malloc(sizeof(vec3) * (size_t)nv); /* unit cell normals of the billboard at hand */
    if (!unit || !read_bb(f, &fi, &pts, &mesh)) {
        free(unit);
        return;
    }
    for (int i = 0; i < fi.billboards; i++) {
        const bb_point_t *p = &pts[i];
        uint32_t slot = p->pad[0];
        if (slot == BB_NO_SLOT || slot >= (uint32_t)fi.desc.max_deformed) continue;
        out->deformed++;
        float (*g)[4] = &mesh[(size_t)slot * nv];
        vec3 right, up, rest;
        bb_point_frame(p, right, up);
        glm_vec3_cross(right, up, rest);
        glm_vec3_normalize(rest);
        float l0x = p->size[0] / (float)(nn - 1), l0y = p->size[1] / (float)(mm - 1), a0 = l0x * l0y;
        for (int j = 0; j < mm; j++)
            for (int c = 0; c < nn; c++) {
                float *v = g[j * nn + c];
                if (!isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) out->nonfinite++;
                double s = 0;
                if (c + 1 < nn) s = fmax(s, fabs(glm_vec3_distance(v, g[j * nn + c + 1]) / l0x - 1.0));
                if (j + 1 < mm) s = fmax(s, fabs(glm_vec3_distance(v, g[(j + 1) * nn + c]) / l0y - 1.0));
                if (!isfinite(glm_vec3_norm(v))) s = INFINITY;
                if (s > out->max_stretch) out->max_stretch = s;
            }
        for (int j = 0; j + 1 < mm; j++)
            for (int c = 0; c + 1 < nn; c++) {
                vec3 area;
                cell_area(g[j * nn + c], g[j * nn + c + 1], g[(j + 1) * nn + c], g[(j + 1) * nn + c + 1], area);
                float below = glm_vec3_dot(area, j ? unit[(j - 1) * nn + c] : rest) / a0;
                float left = c ? glm_vec3_dot(area, unit[j * nn + c - 1]) / a0 : 1.0f;
                out->cells++;
                if (!(below > 0.0f && left > 0.0f)) out->folded++;
                glm_vec3_normalize_to(area, unit[j * nn + c]);
            }
    }
    free(pts);
    free(mesh);
    free(unit);
}

long measure_roots_in(world_t *w, const float lo[3], const float hi[3])
{
    long n = 0;
    blade_gpu_t *g = measure_drivers(w).blades;
    bb_field_info_t fi;
    bb_field_t *f = bb_of(w, &fi);
    if (world_info(w).mode == SCENE_MODE_BLADE && g) {
        blade_t *b = read_blades(g);
        uint32_t count = blade_gpu_info(g).padded_count;
        for (uint32_t i = 0; b && i < count; i++) {
            const float *p = b[i].v0;
            if (b[i].v1[3] > 0.0f && p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] &&
                p[2] >= lo[2] && p[2] <= hi[2])
                n++;
        }
        free(b);
    } else if (world_info(w).mode == SCENE_MODE_BILLBOARD && f) {
        bb_point_t *pts;
        float (*mesh)[4];
        if (!read_bb(f, &fi, &pts, &mesh)) return 0;
        for (int i = 0; i < fi.billboards; i++) {
            const float *p = pts[i].position;
            if (p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] && p[2] >= lo[2] && p[2] <= hi[2])
                n++;
        }
        free(pts);
        free(mesh);
    }
    return n;
}

/* ---- measures that grow with their failure (issue 33) ---------------------------- */

double measure_bb_crossing(world_t *w, int collider, long *near)
{
    *near = 0;
    bb_field_info_t fi;
    bb_field_t *f = bb_of(w, &fi);
    if (!f || collider < 0 || collider >= world_collider_count(w)) return 0.0;
    const world_collider_info_t wc = world_collider(w, collider);
    const float *c = wc.position, *h = wc.desc.half_extents;
    int nv = fi.desc.subdiv[0] * fi.desc.subdiv[1], nn = fi.desc.subdiv[0];
    int a = h[0] <= h[2] ? 0 : 2, b = 2 - a; /* the wall's thin axis a, its length along b */
    bb_point_t *pts;
    float (*mesh)[4];
    vec3 *grid = malloc(sizeof(vec3) * (size_t)nv);
    if (!grid || !read_bb(f, &fi, &pts, &mesh)) {
        free(grid);
        return 0.0;
    }
    long crossed = 0;
    for (int i = 0; i < fi.billboards; i++) {
        const bb_point_t *p = &pts[i];
        float side = p->position[a] - c[a], reach = fmaxf(p->size[0], p->size[1]);
        if (fabsf(side) <= h[a] || fabsf(side) > h[a] + reach || fabsf(p->position[b] - c[b]) > h[b]) continue;
        (*near)++;
        bb_grid(&fi, p, (const float (*)[4])mesh, grid);
        for (int v = nn; v < nv; v++) {
            const float *q = grid[v];
            if (q[1] <= c[1] + h[1] && fabsf(q[b] - c[b]) <= h[b] && (q[a] - c[a]) * side < 0.0f) {
                crossed++;
                break;
            }
        }
    }
    free(pts);
    free(mesh);
    free(grid);
    return *near ? (double)crossed / (double)*near : 0.0;
}

double measure_bb_jump(world_t *w, float *prev, bool *primed)
{
    bb_field_info_t fi;
    bb_field_t *f = bb_of(w, &fi);
    if (!f) return 0.0;
    int nv = fi.desc.subdiv[0] * fi.desc.subdiv[1];
    bb_point_t *pts;
    float (*mesh)[4];
    vec3 *grid = malloc(sizeof(vec3) * (size_t)nv * 2), *wind = grid + nv;
    if (!grid || !read_bb(f, &fi, &pts, &mesh)) {
        free(grid);
        return 0.0;
    }
    double jump = 0.0;
    for (int i = 0; i < fi.billboards; i++) {
        bb_grid(&fi, &pts[i], (const float (*)[4])mesh, grid);
        bb_wind_grid(&fi, &pts[i], wind);
        for (int v = 0; v < nv; v++) {
            float *o = &prev[((size_t)i * (size_t)nv + (size_t)v) * 3], d[3];
            for (int k = 0; k < 3; k++) d[k] = grid[v][k] - wind[v][k];
            double dj = sqrt((double)(d[0] - o[0]) * (d[0] - o[0]) + (double)(d[1] - o[1]) * (d[1] - o[1]) +
                             (double)(d[2] - o[2]) * (d[2] - o[2]));
            if (!isfinite(dj)) dj = INFINITY;
            if (*primed && dj > jump) jump = dj;
            memcpy(o, d, sizeof d);
        }
    }
    *primed = true;
    free(pts);
    free(mesh);
    free(grid);
    return jump;
}

/* Bilinear sample (u, v in [0, 1]) of an N x M grid of offsets. */
static void grid_sample(const vec3 *g, int nn, int mm, float u, float v, float out[3])
{
    float x = u * (float)(nn - 1), y = v * (float)(mm - 1);
    int c = x >= (float)(nn - 1) ? nn - 2 : (int)x, r = y >= (float)(mm - 1) ? mm - 2 : (int)y;
    float s = x - (float)c, t = y - (float)r;
    for (int k = 0; k < 3; k++)
        out[k] = (1 - t) * ((1 - s) * g[r * nn + c][k] + s * g[r * nn + c + 1][k]) +
                 t * ((1 - s) * g[(r + 1) * nn + c][k] + s * g[(r + 1) * nn + c + 1][k]);
}

bool measure_bb_pose(world_t *w, measure_bb_pose_t *out)
{
    memset(out, 0, sizeof *out);
    bb_field_info_t fi;
    bb_field_t *f = bb_of(w, &fi);
    if (!f) return true;
    int nn = fi.desc.subdiv[0], mm = fi.desc.subdiv[1], nv = nn * mm;
    bb_point_t *pts;
    float (*mesh)[4];
    vec3 *grid = malloc(sizeof(vec3) * (size_t)nv * 2), *wind = grid + nv;
    if (!grid || !read_bb(f, &fi, &pts, &mesh)) {
        free(grid);
        return false;
    }
    int deformed = 0;
    for (int i = 0; i < fi.billboards; i++) deformed += pts[i].pad[0] < (uint32_t)fi.desc.max_deformed;
    out->index = malloc(sizeof *out->index * (size_t)(deformed + 1));
    out->off = malloc(sizeof *out->off * (size_t)(deformed + 1));
    bool ok = out->index && out->off;
    for (int i = 0; i < fi.billboards && ok; i++) {
        if (pts[i].pad[0] >= (uint32_t)fi.desc.max_deformed) continue;
        bb_grid(&fi, &pts[i], (const float (*)[4])mesh, grid);
        bb_wind_grid(&fi, &pts[i], wind);
        for (int v = 0; v < nv; v++) glm_vec3_sub(grid[v], wind[v], grid[v]);
        for (int s = 0; s < MEASURE_POSE_SAMPLES; s++)
            grid_sample(grid, nn, mm, (float)(s % MEASURE_POSE_SIDE) / (MEASURE_POSE_SIDE - 1),
                        (float)(s / MEASURE_POSE_SIDE) / (MEASURE_POSE_SIDE - 1), out->off[out->count][s]);
        out->index[out->count++] = i;
    }
    free(pts);
    free(mesh);
    free(grid);
    if (!ok) measure_bb_pose_free(out);
    return ok;
}

void measure_bb_pose_free(measure_bb_pose_t *p)
{
    free(p->index);
    free(p->off);
    memset(p, 0, sizeof *p);
}

/* Largest sample distance between offsets a and b (either NULL: zero). */
static double pose_distance(const float (*a)[3], const float (*b)[3])
{
    static const float zero[MEASURE_POSE_SAMPLES][3];
    if (!a) a = zero;
    if (!b) b = zero;
    double worst = 0.0;
    for (int s = 0; s < MEASURE_POSE_SAMPLES; s++) {
        double d = glm_vec3_distance((float *)a[s], (float *)b[s]);
        worst = isfinite(d) ? fmax(worst, d) : INFINITY;
    }
    return worst;
}

double measure_bb_pose_deviation(const measure_bb_pose_t *a, const measure_bb_pose_t *ref)
{
    int i = 0, j = 0;
    long n = 0;
    double sum = 0.0;
    while (i < a->count || j < ref->count) {
        bool take_a = j >= ref->count || (i < a->count && a->index[i] <= ref->index[j]);
        bool take_r = i >= a->count || (j < ref->count && ref->index[j] <= a->index[i]);
        sum += pose_distance(take_a ? a->off[i] : NULL, take_r ? ref->off[j] : NULL);
        n++;
        i += take_a;
        j += take_r;
    }
    return n ? sum / (double)n : 0.0;
}

long measure_blade_overpush(world_t *w, float *eta_prev, bool primed, double *dist)
{
    blade_gpu_t *g = measure_drivers(w).blades;
    if (!g) return 0;
    uint32_t count = blade_gpu_info(g).padded_count;
    blade_t *b = malloc(sizeof *b * count);
    float *eta = malloc(sizeof *eta * count);
    exact_t *ex = malloc(sizeof *ex * MAX_EXACT);
    long n = 0;
    if (b && eta && ex) {
        blade_gpu_read_blades(g, b, eta);
        int ne = gather_exact(w, ex);
        for (uint32_t i = 0; i < count && ne > 0; i++) {
            bool pushed = primed && b[i].v1[3] > 0.0f && eta[i] > eta_prev[i];
            eta_prev[i] = eta[i];
            if (!pushed) continue;
            float nearest = INFINITY;
            for (int k = 1; k <= SAMPLES_PER_BLADE; k++) {
                float p[3];
                bezier(&b[i], (float)k / SAMPLES_PER_BLADE, p);
                for (int e = 0; e < ne; e++) {
                    float q[3] = {p[0] - ex[e].pos[0], p[1] - ex[e].pos[1], p[2] - ex[e].pos[2]};
                    nearest = fminf(nearest, collide_signed_distance(&ex[e].shape, q));
                }
            }
            dist[n++] = fmax(0.0, (double)nearest);
        }
    }
    free(b);
    free(eta);
    free(ex);
    return n;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double measure_percentile(double *v, long n, double q)
{
    if (n <= 0) return 0.0;
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    double pos = q * (double)(n - 1);
    long lo = (long)pos;
    return lo + 1 < n ? v[lo] + (pos - (double)lo) * (v[lo + 1] - v[lo]) : v[lo];
}

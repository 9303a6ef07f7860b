/* test_bb_gpu_many: more objects than one collide pass takes
 * (BB_PASS_OBJECTS) on the GPU collision of Orthmann et al. 2009 (eq. 1-7):
 * 42 spheres, 30 on a grid over the field and 12 in a cluster whose leaves
 * overlap more than BB_PASS_OBJECTS of them (split into runs of billboards).
 * Every object gets the CPU cube map of its sphere (bb_field_set_cube), so
 * each deformed mesh must equal bb_ref_collide over the spheres its bounding
 * sphere meets, in object order, to float rounding; no refined vertex may lie
 * deeper than one texel inside any sphere; no hit may be dropped.
 * B: 20 small spheres around one billboard: it keeps the nearest
 * BB_PASS_OBJECTS (equal to bb_ref_collide over those); the excess hits
 * (of it and its neighbours) are counted in bb_stats_t.objects_dropped. */
#include "test.h"
#include "test_gl.h"

#include "bb_gpu_test_util.h"

#include <string.h>

#define RES 32
#define GRID 6      /* GRID x (GRID - 1) spheres on the grid */
#define CLUSTER 12  /* spheres around one point */
#define OBJECTS (GRID * (GRID - 1) + CLUSTER)

/* The spheres: GRID x (GRID - 1) of 0.3 m on a grid over the field and
 * CLUSTER of 0.12 m around one point, sunk half their radius into the
 * terrain. */
static void place_spheres(const terrain_mesh_t *terrain, float centre[OBJECTS][3], float radius[OBJECTS])
{
    for (int k = 0; k < OBJECTS; k++) {
        if (k < GRID * (GRID - 1)) {
            centre[k][0] = -3.4f + 6.8f * (float)(k % GRID) / (GRID - 1);
            centre[k][2] = -3.2f + 6.4f * (float)(k / GRID) / (GRID - 2);
            radius[k] = 0.3f;
        } else {
            float a = 6.2831853f * (float)(k - GRID * (GRID - 1)) / CLUSTER;
            centre[k][0] = 0.7f + 0.45f * cosf(a);
            centre[k][2] = 0.6f + 0.45f * sinf(a);
            radius[k] = 0.12f;
        }
        centre[k][1] = terrain_height_at(terrain, centre[k][0], centre[k][2], NULL) + 0.5f * radius[k];
    }
}

/* A: every object with the CPU cube map of its sphere (cube[0] 0.3 m,
 * cube[1] 0.12 m). Returns the field's points (*n of them; the caller
 * frees them). */
static bb_point_t *check_many(const bb_field_desc_t *desc, const collide_cubemap_t cube[2], float time, int *n_out)
{
    float centre[OBJECTS][3], radius[OBJECTS];
    place_spheres(desc->terrain, centre, radius);
    bb_field_t *f = bb_field_make(desc);
    CHECK(f);
    bb_field_info_t fi = test_info(f);
    const bb_field_desc_t *d = &fi.desc;
    collide_object_t objs[OBJECTS];
    mat4 w2c[OBJECTS];
    for (int k = 0; k < OBJECTS; k++) {
        bb_field_set_cube(f, k, &cube[radius[k] < 0.2f]);
        objs[k] = test_object(NULL, centre[k], radius[k]);
        glm_translate_make(w2c[k], (vec3){-centre[k][0], -centre[k][1], -centre[k][2]});
    }
    gfx_timer_frame_begin();
    bb_field_update(f, test_set(objs, OBJECTS), time, 1.0f / 30.0f);
    bb_stats_t st;
    bb_field_stats(f, true, &st);

    int n = fi.billboards, nm = fi.mesh_vertices;
    bb_point_t *pts = malloc(sizeof *pts * (size_t)n);
    float *meshes = malloc(sizeof(float) * 4 * (size_t)nm * (size_t)d->max_deformed);
    CHECK(bb_field_read(f, BB_DATA_POINTS, 0, (size_t)n, pts));
    CHECK(bb_field_read(f, BB_DATA_MESHES, 0, (size_t)d->max_deformed, meshes));
    int deformed = 0, cpu_hits = 0, late_hits = 0, most = 0, borderline = 0;
    double max_err = 0, deepest = 0, worst = 0; /* worst: depth in texels of that sphere's cube */
    int below = 0;                              /* vertices under the terrain */
    for (int i = 0; i < n; i++) {
        const bb_point_t *p = &pts[i];
        vec3 right, up;
        bb_point_frame(p, right, up);
        float bc[3], br = 0.5f * sqrtf(p->size[0] * p->size[0] + p->size[1] * p->size[1]) + d->wind.strength;
        for (int a = 0; a < 3; a++) bc[a] = p->position[a] + up[a] * 0.5f * p->size[1];
        collide_cubemap_t hc[OBJECTS];
        mat4 hw[OBJECTS];
        int h = 0, late = 0;
        for (int k = 0; k < OBJECTS; k++) {
            float gap = sqrtf(glm_vec3_distance2(bc, centre[k])) - (br + radius[k]);
            borderline += fabsf(gap) < 1e-4f;
            if (gap >= 0.0f) continue;
            hc[h] = cube[radius[k] < 0.2f];
            glm_mat4_copy(w2c[k], hw[h++]);
            late += k >= BB_PASS_OBJECTS;
        }
        cpu_hits += h > 0;
        late_hits += late > 0;
        most = h > most ? h : most;
        if (p->pad[0] == BB_NO_SLOT) {
            CHECK_MSG(h == 0, "billboard %d hits %d spheres on the CPU only", i, h);
            continue;
        }
        CHECK_MSG(h > 0, "billboard %d deformed on the GPU only", i);
        deformed++;
        bb_mesh_t mesh;
        test_cpu_mesh(d, p, time, &mesh);
        bb_collide_desc_t cd = test_collide_desc(d);
        bb_ref_collide(&mesh, hc, (const mat4 *)hw, h, &cd);
        const float *g = &meshes[(size_t)p->pad[0] * (size_t)nm * 4];
        for (int v = 0; v < nm; v++) {
            for (int a = 0; a < 3; a++) max_err = fmax(max_err, fabs(g[4 * v + a] - mesh.pos[v][a]));
            /* roots are fixed; a vertex held on the ground may stay in a sunk sphere */
            if (v < d->subdiv[0] || test_on_ground(d, &g[4 * v], &below)) continue;
            for (int k = 0; k < OBJECTS; k++) {
                float rel[3] = {g[4 * v] - centre[k][0], g[4 * v + 1] - centre[k][1], g[4 * v + 2] - centre[k][2]};
                collide_shape_t sph = {.type = COLLIDE_SHAPE_SPHERE, .radius = radius[k]};
                double sd = collide_signed_distance(&sph, rel);
                deepest = fmin(deepest, sd);
                worst = fmin(worst, sd / (2.0 * radius[k] / RES));
            }
        }
        bb_mesh_free(&mesh);
    }
    printf("%d objects: %d of %d billboards deformed (CPU: %d hit, %d by an object past the %dth, up to %d "
           "objects on one), %d batches, %d hits dropped; max |dv| vs bb_ref_collide %.3g m, deepest %.3g m, "
           "%.2f texels, %d vertices under the terrain\n",
           OBJECTS, deformed, n, cpu_hits, late_hits, BB_PASS_OBJECTS, most, st.batches, st.objects_dropped,
           max_err, deepest, -worst, below);
    CHECK(below == 0);
    CHECK(borderline == 0);
    CHECK(late_hits > 50 && most >= 3);
    CHECK(deformed == cpu_hits);
    CHECK(max_err < 1e-3); /* the slide (bb_slide) amplifies float rounding: 3.8e-4 m on NVIDIA */
    CHECK(worst > -1.0);
    CHECK(st.batches > 1 && st.objects_dropped == 0 && st.pool_exhausted == 0 && st.deformed == deformed);

    free(meshes);
    bb_field_destroy(f);
    *n_out = n;
    return pts;
}

/* B: billboard n / 2 of pts (a field made from desc) inside 20 small
 * spheres' reach, on a fresh field. */
static void check_nearest(const bb_field_desc_t *desc, const bb_point_t *pts, int n, float time)
{
    bb_field_t *f = bb_field_make(desc);
    CHECK(f);
    bb_field_info_t fi = test_info(f);
    const bb_field_desc_t *d = &fi.desc;
    int nm = fi.mesh_vertices;
    bb_stats_t st;
    int i0 = n / 2;
    const bb_point_t *p0 = &pts[i0];
    vec3 right, up;
    bb_point_frame(p0, right, up);
    float c0[3], small = 0.05f;
    for (int a = 0; a < 3; a++) c0[a] = p0->position[a] + up[a] * 0.7f * p0->size[1];
    collide_cubemap_t sc;
    CHECK(collide_init_cubemap(&sc, RES, (vec3){0, 0, 0}, small));
    collide_render_sphere(&sc, (vec3){0, 0, 0}, small);
    enum { NB = BB_PASS_OBJECTS + 4 };
    collide_object_t objs[NB];
    float cb[NB][3], db[NB];
    int order[NB];
    for (int k = 0; k < NB; k++) {
        float a = 6.2831853f * (float)k / NB, rr = 0.04f + 0.01f * (float)k;
        cb[k][0] = c0[0] + rr * cosf(a), cb[k][1] = c0[1], cb[k][2] = c0[2] + rr * sinf(a);
        db[k] = rr;
        order[k] = k;
        bb_field_set_cube(f, k, &sc);
        objs[k] = test_object(NULL, cb[k], small);
    }
    gfx_timer_frame_begin();
    bb_field_update(f, test_set(objs, NB), time, 1.0f / 30.0f);
    bb_field_stats(f, true, &st);
    bb_point_t pb;
    CHECK(bb_field_read(f, BB_DATA_POINTS, (size_t)i0, 1, &pb));
    CHECK(pb.pad[0] != BB_NO_SLOT);
    /* nearest BB_PASS_OBJECTS to the billboard's sphere centre, in object order */
    float bc0[3];
    for (int a = 0; a < 3; a++) bc0[a] = p0->position[a] + up[a] * 0.5f * p0->size[1];
    for (int k = 0; k < NB; k++) db[k] = sqrtf(glm_vec3_distance2(bc0, cb[k]));
    for (int a = 1; a < NB; a++)
        for (int c = a; c > 0 && db[order[c]] < db[order[c - 1]]; c--) {
            int t = order[c];
            order[c] = order[c - 1], order[c - 1] = t;
        }
    bool keep[NB] = {false};
    for (int k = 0; k < BB_PASS_OBJECTS; k++) keep[order[k]] = true;
    collide_cubemap_t kc[NB];
    mat4 kw[NB];
    int nk = 0;
    for (int k = 0; k < NB; k++) {
        if (!keep[k]) continue;
        kc[nk] = sc;
        glm_translate_make(kw[nk++], (vec3){-cb[k][0], -cb[k][1], -cb[k][2]});
    }
    bb_mesh_t mesh;
    test_cpu_mesh(d, p0, time, &mesh);
    bb_collide_desc_t cd = test_collide_desc(d);
    bb_ref_collide(&mesh, kc, (const mat4 *)kw, nk, &cd);
    float gm[8 * 8 * 4];
    CHECK(bb_field_read(f, BB_DATA_MESHES, pb.pad[0], 1, gm));
    double berr = 0;
    for (int v = 0; v < nm; v++)
        for (int a = 0; a < 3; a++) berr = fmax(berr, fabs(gm[4 * v + a] - mesh.pos[v][a]));
    bb_mesh_free(&mesh);
    printf("B: %d spheres on billboard %d: %d hits dropped, %d batches, max |dv| vs bb_ref_collide (nearest %d) "
           "%.3g m\n", NB, i0, st.objects_dropped, st.batches, BB_PASS_OBJECTS, berr);
    CHECK(st.objects_dropped >= NB - BB_PASS_OBJECTS);
    CHECK(berr < 1e-4);
    collide_free_cubemap(&sc);

    bb_field_destroy(f);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    terrain_mesh_t terrain;
    bb_field_desc_t desc = test_field_desc(&terrain, RES, OBJECTS);
    const float time = 0.7f;
    collide_cubemap_t cube[2];
    const float radii[2] = {0.3f, 0.12f};
    for (int c = 0; c < 2; c++) {
        CHECK(collide_init_cubemap(&cube[c], RES, (vec3){0, 0, 0}, radii[c]));
        collide_render_sphere(&cube[c], (vec3){0, 0, 0}, radii[c]);
    }
    int n = 0;
    bb_point_t *pts = check_many(&desc, cube, time, &n);
    check_nearest(&desc, pts, n, time);
    free(pts);
    for (int c = 0; c < 2; c++) collide_free_cubemap(&cube[c]);
    terrain_free(&terrain);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

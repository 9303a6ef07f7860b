/* test_bb_gpu_collide: the collision pass of Orthmann et al. 2009 on the GPU
 * (bb_collide.geom, eq. 1-7) against the CPU reference bb_ref_collide.
 *  A: the CPU cube map of the sphere (collide_render_sphere) uploaded with
 *     bb_field_set_cube: GPU meshes equal bb_ref_collide to float rounding;
 *     A2 the same for the sphere swept over the last step; P the same
 *     for the paper's collision as printed (bb_field_desc_t.paper).
 *  B: the GPU cube map of the sphere mesh from shapes.h: its texels against
 *     the CPU ones, the GPU meshes against bb_ref_collide on the CPU cube,
 *     and no refined vertex deeper than one texel inside the analytic sphere. */
#include "test.h"
#include "test_gl.h"

#include "bb_gpu_test_util.h"

#include <string.h>

#define RES 48

static float sphere_y(const terrain_mesh_t *t, float x, float z) { return terrain_height_at(t, x, z, NULL) + 0.3f; }

/* Returns the number of deformed billboards; fills max/mean vertex error
 * against bb_ref_collide(cpu_cube, the terrain as ground), the deepest
 * penetration of vertices off the ground and the count of vertices under
 * the terrain (the sphere is sunk 0.2 m into it). */
static int compare(const bb_field_t *f, const collide_cubemap_t *cube, const float centre[3], const float sweep[3],
                   float radius, float time, double *max_err, double *mean_err, double *deepest, int *cpu_hits,
                   int *below)
{
    test_readback_t rb = test_readback_make(f);
    const bb_field_desc_t *d = &rb.info.desc;
    int n = rb.info.billboards, nm = rb.info.mesh_vertices;
    const bb_point_t *pts = rb.pts;
    test_readback_read(f, &rb, true);
    mat4 w2c;
    glm_translate_make(w2c, (vec3){-centre[0], -centre[1], -centre[2]});
    collide_shape_t sph = {.type = COLLIDE_SHAPE_SPHERE, .radius = radius};
    int deformed = 0, sum_n = 0;
    *max_err = 0, *mean_err = 0, *deepest = 0, *cpu_hits = 0, *below = 0;
    for (int i = 0; i < n; i++) {
        const bb_point_t *p = &pts[i];
        vec3 right, up;
        bb_point_frame(p, right, up);
        float bc[3], br = 0.5f * sqrtf(p->size[0] * p->size[0] + p->size[1] * p->size[1]) + d->wind.strength;
        for (int k = 0; k < 3; k++) bc[k] = p->position[k] + up[k] * 0.5f * p->size[1];
        /* the swept object's capsule (bb_collide.geom) */
        float ss = glm_vec3_norm2((float *)sweep), t = 0.0f, near[3];
        if (ss > 0.0f) t = glm_clamp(glm_vec3_dot((vec3){bc[0] - centre[0], bc[1] - centre[1], bc[2] - centre[2]},
                                                  (float *)sweep) / ss, 0.0f, 1.0f);
        for (int k = 0; k < 3; k++) near[k] = centre[k] + t * sweep[k];
        float dist = sqrtf(glm_vec3_distance2(bc, near));
        bool hit = dist < br + radius;
        *cpu_hits += hit;
        if (p->pad[0] == BB_NO_SLOT) {
            CHECK_MSG(!hit || fabsf(dist - (br + radius)) < 1e-4f, "billboard %d hit on the CPU only", i);
            continue;
        }
        CHECK(hit || fabsf(dist - (br + radius)) < 1e-4f);
        CHECK(p->state == BB_STATE_RECOVERING && fabsf(p->recover_time - d->recover_time) < 1e-6f);
        deformed++;
        bb_mesh_t mesh;
        test_cpu_mesh(d, p, time, &mesh);
        bb_collide_desc_t cd = test_collide_desc(d);
        const float sweeps[1][3] = {{sweep[0], sweep[1], sweep[2]}};
        cd.sweep = sweeps;
        bb_ref_collide(&mesh, cube, (const mat4 *)&w2c, 1, &cd);
        const float *g = test_readback_mesh(&rb, p->pad[0]);
        for (int v = 0; v < nm; v++) {
            double e = 0;
            for (int k = 0; k < 3; k++) e = fmax(e, fabs(g[4 * v + k] - mesh.pos[v][k]));
            *max_err = fmax(*max_err, e);
            *mean_err += e;
            sum_n++;
            float rel[3] = {g[4 * v] - centre[0], g[4 * v + 1] - centre[1], g[4 * v + 2] - centre[2]};
            /* roots are fixed, and vertices held on the ground may stay in
             * a sphere sunk into it (the push out goes under the terrain) */
            if (v >= d->subdiv[0] && !test_on_ground(d, &g[4 * v], below))
                *deepest = fmin(*deepest, collide_signed_distance(&sph, rel));
        }
        bb_mesh_free(&mesh);
    }
    if (sum_n) *mean_err /= sum_n;
    test_readback_free(&rb);
    return deformed;
}

/* What every part shares: the field's desc on its terrain, the sphere
 * (centre sunk 0.2 m into the ground), the update time and the sphere's
 * CPU cube map. */
typedef struct fixture_t {
    terrain_mesh_t terrain;
    bb_field_desc_t desc;
    float radius, time, centre[3];
    collide_cubemap_t cpu_cube;
} fixture_t;

/* A: the CPU cube map uploaded, same inputs on both sides; P: the paper's
 * collision as printed; H: the hybrid's hidden region. Returns A's
 * deformed billboards. */
static int check_cpu_cube(const fixture_t *x)
{
    const float radius = x->radius, time = x->time, *centre = x->centre;
    const collide_cubemap_t *cpu_cube = &x->cpu_cube;
    bb_field_t *fa = bb_field_make(&x->desc);
    CHECK(fa);
    bb_field_set_cube(fa, 0, cpu_cube);
    collide_object_t oa = test_object(NULL, centre, radius);
    gfx_timer_frame_begin();
    bb_field_update(fa, test_set(&oa, 1), time, 1.0f / 30.0f);
    double max_err, mean_err, deepest;
    int cpu_hits, below;
    const float still[3] = {0, 0, 0};
    int da = compare(fa, cpu_cube, centre, still, radius, time, &max_err, &mean_err, &deepest, &cpu_hits, &below);
    printf("A (CPU cube): %d of %d billboards deformed (CPU: %d hit), max |dv| %.3g m, mean %.3g m, deepest %.3g m, "
           "%d vertices under the terrain\n",
           da, test_info(fa).billboards, cpu_hits, max_err, mean_err, deepest, below);
    CHECK(da > 10 && da == cpu_hits);
    CHECK(max_err < 1e-4);
    CHECK(below == 0);
    bb_stats_t st;
    bb_field_stats(fa, true, &st);
    CHECK(st.deformed == da && st.pool_exhausted == 0);
    CHECK(st.leaves[BB_NODE_COLLIDING] > 0 && st.objects_hidden == 0);

    /* P: the paper's collision as printed (no slide, ground, bend limit or
     * push after the sweeps) equals bb_ref_collide with paper set. */
    bb_field_desc_t dp = x->desc;
    dp.paper = true;
    bb_field_t *fp = bb_field_make(&dp);
    CHECK(fp);
    bb_field_set_cube(fp, 0, cpu_cube);
    bb_field_update(fp, test_set(&oa, 1), time, 1.0f / 30.0f);
    double pmax, pmean, pdeep;
    int phits, pbelow;
    int dpp = compare(fp, cpu_cube, centre, still, radius, time, &pmax, &pmean, &pdeep, &phits, &pbelow);
    printf("P (paper's collision): %d deformed, max |dv| %.3g m, mean %.3g m, deepest %.3g m\n", dpp, pmax, pmean,
           pdeep);
    CHECK(dpp == da && pmax < 1e-4);
    bb_field_destroy(fp);

    /* H: the hybrid's hidden region (bb_field_set_hidden). A camera 2 m
     * above the sphere: with a fade start just beyond the sphere's reach
     * (2 m + radius + 3 of the largest billboard spheres) it is left out
     * (no colliding leaf, no collide batch); just short of it, it collides
     * again, and with the fade off too. */
    float cam[3] = {centre[0], centre[1] + 2.0f, centre[2]};
    float reach = 2.0f + radius + 3.0f * test_info(fa).sphere_max;
    const float fades[3] = {reach + 0.01f, reach - 0.01f, 0.0f};
    for (int i = 0; i < 3; i++) {
        bb_field_set_hidden(fa, cam, fades[i]);
        bb_field_update(fa, test_set(&oa, 1), time + 0.1f * (float)(i + 1), 1.0f / 30.0f);
        bb_field_stats(fa, true, &st);
        printf("H (fade start %.2f m, reach %.2f m): hidden %d, colliding leaves %d, batches %d\n", fades[i], reach,
               st.objects_hidden, st.leaves[BB_NODE_COLLIDING], st.batches);
        CHECK(st.objects_hidden == (i == 0));
        CHECK((st.leaves[BB_NODE_COLLIDING] > 0) == (i > 0));
        CHECK((st.batches > 0) == (i > 0));
    }
    bb_field_destroy(fa);

    return da;
}

/* A2: the sphere swept (da: billboards A deformed where it stands). */
static void check_swept(const fixture_t *x, int da)
{
    const float radius = x->radius, time = x->time, *centre = x->centre;
    const collide_cubemap_t *cpu_cube = &x->cpu_cube;
    double max_err, mean_err, deepest;
    int cpu_hits, below;
    /* A2: the same sphere swept: one step ago it was 1.0 m back along x and
     * 0.7 m along z (collide_add_object with dt > 0 gives prev_position);
     * GPU meshes equal bb_ref_collide with the same sweep, and more
     * billboards bend than where it stands. The sweep is diagonal on
     * purpose: along a cube axis every swept query lands on the plane
     * through the cube centre across the sweep, which is a texel boundary
     * at even resolutions, and the GPU and the CPU then round to texels on
     * either side (normals tilted +-half a texel: 0.019 m apart along the
     * sweep without springs, 0.056 m with them, measured). */
    bb_field_t *fs = bb_field_make(&x->desc);
    CHECK(fs);
    bb_field_set_cube(fs, 0, cpu_cube);
    const float sweep[3] = {-1.0f, 0.0f, -0.7f};
    float before[3] = {centre[0] + sweep[0], centre[1] + sweep[1], centre[2] + sweep[2]};
    collide_object_t os[2] = {test_object(NULL, before, radius), test_object(NULL, centre, radius)};
    static collide_set_t moving;
    collide_begin_set(&moving);
    collide_add_object(&moving, &os[0], 0.0f);
    collide_begin_set(&moving);
    collide_add_object(&moving, &os[1], 1.0f / 30.0f);
    gfx_timer_frame_begin();
    bb_field_update(fs, &moving, time, 1.0f / 30.0f);
    int ds = compare(fs, cpu_cube, centre, sweep, radius, time, &max_err, &mean_err, &deepest, &cpu_hits, &below);
    printf("A2 (swept 1.22 m): %d billboards deformed (CPU: %d hit; %d standing), max |dv| %.3g m, %d under the "
           "terrain\n",
           ds, cpu_hits, da, max_err, below);
    CHECK(ds == cpu_hits && ds > da + 10);
    CHECK(max_err < 1e-4);
    CHECK(below == 0);
    bb_field_destroy(fs);

}

static void check_lend(const fixture_t *x)
{
    const float radius = x->radius, *centre = x->centre;
    const collide_cubemap_t *cpu_cube = &x->cpu_cube;
    /* Lent cube proxies keep the object's index (layers 6k .. 6k+5): object
     * 0 without a map, object 1 with one. */
    bb_field_t *fl = bb_field_make(&x->desc);
    CHECK(fl);
    bb_field_set_cube(fl, 1, cpu_cube);
    float far_centre[3] = {centre[0] + 3.0f, centre[1], centre[2]};
    collide_object_t two[2] = {test_object(NULL, centre, radius), test_object(NULL, far_centre, radius)};
    collide_set_t lend = *test_set(two, 2);
    lend.cube_count = 0;
    bb_field_lend_cubes(fl, &lend);
    CHECK(lend.cube_count == 2);
    CHECK(lend.cubes[0].sphere[3] <= 0.0f);
    CHECK(lend.cubes[1].sphere[3] > 0.0f && fabsf(lend.cubes[1].sphere[0] - far_centre[0]) < 1e-4f);
    bb_field_destroy(fl);

}

/* B: the GPU cube map of the sphere mesh; returns its six layers (for B2). */
static float *check_gpu_cube(const fixture_t *x, const test_mesh_t *mesh)
{
    const float radius = x->radius, time = x->time, *centre = x->centre;
    const collide_cubemap_t *cpu_cube = &x->cpu_cube;
    double max_err, mean_err, deepest;
    int cpu_hits, below;
    const float still[3] = {0, 0, 0};
    bb_field_t *fb = bb_field_make(&x->desc);
    CHECK(fb);
    collide_object_t ob = test_object(mesh, centre, radius);
    gfx_timer_frame_begin();
    bb_field_update(fb, test_set(&ob, 1), time, 1.0f / 30.0f);
    float *tex = malloc(sizeof(float) * 4 * 6 * RES * RES);
    CHECK(bb_field_read(fb, BB_DATA_CUBES, 0, 6, tex));
    int both = 0, disagree = 0, far = 0;
    double max_dd = 0, max_dn = 0, mean_dd = 0;
    for (int t = 0; t < 6 * RES * RES; t++) {
        const float *g = &tex[4 * t], *c = &cpu_cube->texels[4 * t];
        bool gh = g[0] < 2 * radius - 1e-5f, ch = c[0] < 2 * radius - 1e-5f;
        if (gh != ch) {
            disagree++;
            continue;
        }
        if (!gh) {
            CHECK(fabsf(g[0] - c[0]) < 1e-6f && fabsf(g[1] - c[1]) + fabsf(g[2] - c[2]) + fabsf(g[3] - c[3]) < 1e-6f);
            continue;
        }
        both++;
        max_dd = fmax(max_dd, fabs(g[0] - c[0]));
        far += fabs(g[0] - c[0]) > 0.03;
        mean_dd += fabs(g[0] - c[0]);
        for (int k = 1; k < 4; k++) max_dn = fmax(max_dn, fabs(g[k] - c[k]));
    }
    printf("B cube texels: %d hit on both, %d hit/miss disagree (silhouette), mean |dD| %.3g m, max %.3g m (%d over 3 cm), "
           "max |dn| %.3g\n", both, disagree, mean_dd / both, max_dd, far, max_dn);
    CHECK(both > 6 * RES * RES / 2);
    CHECK(disagree < 6 * 4 * RES); /* only a ring of texels along each face's silhouette */
    CHECK(max_dd < 0.1);           /* 24x16 UV sphere vs the exact sphere: grazing texels differ most */
    CHECK(far < both / 20);
    CHECK(mean_dd / both < 0.01); /* the flat facets lie up to ~1.4 cm inside the sphere */
    CHECK(max_dn < 0.15);
    int db = compare(fb, cpu_cube, centre, still, radius, time, &max_err, &mean_err, &deepest, &cpu_hits, &below);
    float texel = 2 * radius / RES;
    printf("B (GPU cube): %d deformed (CPU: %d hit), max |dv| %.3g m, mean %.3g m, deepest %.3g m (texel %.3g m), "
           "%d vertices under the terrain\n",
           db, cpu_hits, max_err, mean_err, deepest, texel, below);
    CHECK(below == 0);
    CHECK(db == cpu_hits);
    CHECK(mean_err < 0.01);
    /* 0.039 m before the ground clamp: where the two cube maps push a vertex
     * one down (then raised onto the ground) and one sideways, they part
     * further (0.102 m measured on llvmpipe) */
    CHECK(max_err < 0.15);
    CHECK(deepest > -texel);
    bb_field_destroy(fb);

    return tex;
}

static void check_two_objects(const fixture_t *x, const test_mesh_t *mesh, const float *tex)
{
    const float radius = x->radius, time = x->time, *centre = x->centre;
    bb_field_t *fb = bb_field_make(&x->desc);
    /* B2: two spheres in one update, each in its own six layers (one draw
     * per object, the geometry shader picks the layer): both maps equal
     * B's texel for texel. */
    CHECK(fb);
    float other[3] = {centre[0] - 2.0f, 0.0f, centre[2] + 1.5f};
    other[1] = sphere_y(&x->terrain, other[0], other[2]);
    collide_object_t pair[2] = {test_object(mesh, other, radius), test_object(mesh, centre, radius)};
    gfx_timer_frame_begin();
    bb_field_update(fb, test_set(pair, 2), time, 1.0f / 30.0f);
    float *tex2 = malloc(sizeof(float) * 4 * 12 * RES * RES);
    CHECK(bb_field_read(fb, BB_DATA_CUBES, 0, 12, tex2));
    int differ = 0;
    for (int t = 0; t < 12 * 4 * RES * RES; t++) differ += fabsf(tex2[t] - tex[t % (6 * 4 * RES * RES)]) > 1e-6f;
    printf("B2 two objects: %d of %d cube map floats differ from B's\n", differ, 12 * 4 * RES * RES);
    CHECK(differ == 0);
    free(tex2);
    bb_field_destroy(fb);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    fixture_t x = {.radius = 0.5f, .time = 0.7f, .centre = {0.3f, 0, -0.2f}};
    x.desc = test_field_desc(&x.terrain, RES, 0);
    x.centre[1] = sphere_y(&x.terrain, x.centre[0], x.centre[2]);
    CHECK(collide_init_cubemap(&x.cpu_cube, RES, (vec3){0, 0, 0}, x.radius));
    collide_render_sphere(&x.cpu_cube, (vec3){0, 0, 0}, x.radius);

    check_swept(&x, check_cpu_cube(&x));
    check_lend(&x);
    collide_shape_t sc = {.type = COLLIDE_SHAPE_SPHERE, .radius = x.radius};
    test_mesh_t mesh;
    test_mesh_make(&mesh, &sc);
    float *tex = check_gpu_cube(&x, &mesh);
    check_two_objects(&x, &mesh, tex);
    free(tex);
    test_mesh_destroy(&mesh);
    collide_free_cubemap(&x.cpu_cube);
    terrain_free(&x.terrain);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

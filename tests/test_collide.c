/* test_collide: the collide module. Depth cube maps (collide_cube.h): the
 * face table, the CPU rasterisation of a sphere/box/capsule against analytic
 * values, the inside test (Orthmann et al. 2009 eq. 1-3) against analytic
 * inside-ness and the push-out (eq. 4-5) against the analytic surface.
 * Shapes (collide_shape.h): collider meshes lie on their analytic surfaces
 * and face outward, signed distances match hand values, sphere packing and
 * the CPU cube map of a collider. Sets (collide_set.h): cube proxies,
 * previous positions and velocities. */
#include "collide/collide_set.h"
#include "collide/collide_shape.h"
#include "core/core.h"
#include "test.h"

#include <math.h>
#include <string.h>

static void test_face_basis(void)
{
    for (int f = 0; f < 6; f++) {
        vec3 u, v, in, c;
        collide_get_face_basis(f, u, v, in);
        glm_vec3_cross(u, v, c);
        int axis = f / 2;
        float s = (f % 2 == 0) ? 1.0f : -1.0f;
        for (int k = 0; k < 3; k++) {
            CHECK_NEAR(c[k], -in[k], 1e-6);                 /* u x v = outward */
            CHECK_NEAR(in[k], k == axis ? -s : 0.0f, 1e-6); /* inward per table */
        }
        CHECK_NEAR(glm_vec3_dot(u, v), 0.0, 1e-6);
    }
}

/* Analytic depth of a sphere seen from face f at ray origin o: the ray runs
 * along axis a from the plane at coordinate P towards the cube centre. */
static bool sphere_depth(const collide_cubemap_t *cube, int f, const float *o, const float *sc, float r,
                         double *depth, double n[3])
{
    int a = f / 2, b = (a + 1) % 3, c = (a + 2) % 3;
    double s = (f % 2 == 0) ? 1.0 : -1.0;
    double P = cube->centre[a] + s * cube->half;
    double rho2 = (o[b] - sc[b]) * (double)(o[b] - sc[b]) + (o[c] - sc[c]) * (double)(o[c] - sc[c]);
    if (rho2 >= (double)r * r) return false;
    double surf = sc[a] + s * sqrt((double)r * r - rho2);
    *depth = s * (P - surf);
    double hit[3] = {o[0], o[1], o[2]};
    hit[a] = surf;
    for (int k = 0; k < 3; k++) n[k] = (hit[k] - sc[k]) / r;
    return true;
}

static void test_sphere_map(void)
{
    collide_cubemap_t cube;
    vec3 cc = {0.1f, -0.05f, 0.2f}, sc = {0.15f, 0.0f, 0.1f};
    float r = 0.7f;
    CHECK(collide_init_cubemap(&cube, 64, cc, 1.0f));
    collide_render_sphere(&cube, sc, r);
    int hits = 0, misses = 0;
    double max_err = 0.0;
    for (int f = 0; f < 6; f++) {
        for (int j = 0; j < cube.res; j++) {
            for (int i = 0; i < cube.res; i++) {
                vec3 o;
                collide_get_texel_origin(&cube, f, i, j, o);
                const float *tx = cube.texels + ((f * cube.res + j) * cube.res + i) * 4;
                double depth, n[3];
                if (sphere_depth(&cube, f, o, sc, r, &depth, n)) {
                    hits++;
                    max_err = fmax(max_err, fabs(tx[0] - depth));
                    /* Near-grazing rays: sqrt amplifies float error in depth; normals stay good. */
                    for (int k = 0; k < 3; k++) CHECK_NEAR(tx[1 + k], n[k], 2e-3);
                } else {
                    misses++;
                    CHECK_NEAR(tx[0], 2.0f * cube.half, 1e-6);
                }
            }
        }
    }
    printf("sphere map: %d hits, %d misses, max depth error %.2e m\n", hits, misses, max_err);
    CHECK(hits > 6 * 64 * 64 / 3 && misses > 1000);
    CHECK(max_err < 2e-3);

    /* Eq. 1-3 against analytic inside-ness, away from the surface. */
    float texel = 2.0f * cube.half / (float)cube.res;
    core_rng_t rng;
    core_rng_seed(&rng, 7, 1);
    int wrong = 0, near = 0, inside_count = 0;
    for (int t = 0; t < 20000; t++) {
        vec3 q = {core_rng_range(&rng, -1.2f, 1.2f) + cc[0], core_rng_range(&rng, -1.2f, 1.2f) + cc[1],
                  core_rng_range(&rng, -1.2f, 1.2f) + cc[2]};
        double d = test_dist3(q, sc) - r;
        bool in = collide_test_inside(&cube, q);
        if (fabs(d) <= texel) {
            near++;
            continue;
        }
        inside_count += in;
        if (in != (d < 0)) wrong++;
    }
    printf("inside test: %d wrong of %d (%d near-surface skipped, %d inside)\n", wrong, 20000 - near, near,
           inside_count);
    CHECK(wrong == 0);
    CHECK(inside_count > 1000);

    /* Eq. 4-5: pushed points end outside (within a texel) and move along +normal. */
    int pushed = 0;
    for (int t = 0; t < 5000; t++) {
        vec3 q = {core_rng_range(&rng, -0.7f, 0.7f) + sc[0], core_rng_range(&rng, -0.7f, 0.7f) + sc[1],
                  core_rng_range(&rng, -0.7f, 0.7f) + sc[2]};
        vec3 out;
        bool moved = collide_push_out(&cube, q, out);
        CHECK(moved == collide_test_inside(&cube, q));
        if (!moved) {
            CHECK(test_dist3(q, out) == 0.0);
            continue;
        }
        pushed++;
        CHECK_MSG(test_dist3(out, sc) >= r - texel, "pushed point %g inside", r - test_dist3(out, sc));
        CHECK(test_dist3(out, sc) > test_dist3(q, sc));
    }
    CHECK(pushed > 1000);
    collide_free_cubemap(&cube);
}

static void test_box_capsule_map(void)
{
    collide_cubemap_t cube;
    CHECK(collide_init_cubemap(&cube, 32, (vec3){0, 0, 0}, 1.0f));
    collide_render_box(&cube, (vec3){0.1f, 0.2f, -0.1f}, (vec3){0.3f, 0.4f, 0.5f});
    vec4 tx;
    /* Face +X, a point in front of the box: distance = 1 - 0.4 = 0.6, normal +X. */
    collide_lookup_texel(&cube, COLLIDE_FACE_PX, (vec3){0.9f, 0.2f, -0.1f}, tx);
    CHECK_NEAR(tx[0], 0.6, 1e-5);
    CHECK_NEAR(tx[1], 1.0, 1e-6);
    /* Face -Z: distance = 1 - (0.1 + 0.5) = 0.4, normal -Z. */
    collide_lookup_texel(&cube, COLLIDE_FACE_NZ, (vec3){0.1f, 0.2f, -0.9f}, tx);
    CHECK_NEAR(tx[0], 0.4, 1e-5);
    CHECK_NEAR(tx[3], -1.0, 1e-6);
    CHECK(collide_test_inside(&cube, (vec3){0.1f, 0.2f, -0.1f}));
    CHECK(!collide_test_inside(&cube, (vec3){0.5f, 0.2f, -0.1f}));

    collide_clear_cubemap(&cube);
    collide_render_capsule(&cube, (vec3){0, -0.3f, 0}, (vec3){0, 0.3f, 0}, 0.25f);
    collide_lookup_texel(&cube, COLLIDE_FACE_PY, (vec3){0.01f, 0.9f, 0.01f}, tx); /* top cap */
    double rho = (1.0 / 32.0) * sqrt(2.0);                            /* texel centre offset */
    CHECK_NEAR(tx[0], 1.0 - 0.3 - sqrt(0.25 * 0.25 - rho * rho), 1e-4);
    vec3 o;
    collide_get_texel_origin(&cube, COLLIDE_FACE_PX, 16, 16, o); /* side: u = -z, v = +y */
    CHECK_NEAR(o[0], 1.0, 1e-6);
    collide_lookup_texel(&cube, COLLIDE_FACE_PX, o, tx);
    CHECK_NEAR(tx[0], 1.0 - sqrt(0.25 * 0.25 - o[2] * o[2]), 1e-4);
    CHECK_NEAR(tx[2], 0.0, 1e-5); /* side normal is horizontal */
    /* Union of two shapes keeps the nearer hit. */
    collide_render_sphere(&cube, (vec3){0, 0.55f, 0}, 0.2f);
    collide_lookup_texel(&cube, COLLIDE_FACE_PY, (vec3){0.01f, 0.9f, 0.01f}, tx);
    CHECK_NEAR(tx[0], 1.0 - 0.55 - sqrt(0.2 * 0.2 - rho * rho), 1e-4);
    collide_free_cubemap(&cube);
}


static void check_mesh(const collide_shape_t *c)
{
    collide_mesh_t m;
    CHECK(collide_make_mesh(&m, c));
    CHECK(m.vertex_count > 0 && m.index_count % 3 == 0);
    float worst = 0;
    for (uint32_t i = 0; i < m.vertex_count; i++) {
        float d = fabsf(collide_signed_distance(c, m.positions + i * 3));
        if (d > worst) worst = d;
        float r2 = 0;
        for (int k = 0; k < 3; k++) r2 += m.positions[i * 3 + k] * m.positions[i * 3 + k];
        CHECK(sqrtf(r2) <= collide_bounding_radius(c) + 1e-4f);
    }
    CHECK_NEAR(worst, 0.0, 1e-4);
    /* Outward winding: each triangle's normal points away from the centre. */
    int inward = 0;
    for (uint32_t t = 0; t < m.index_count; t += 3) {
        const float *a = m.positions + m.indices[t] * 3, *b = m.positions + m.indices[t + 1] * 3,
                    *d = m.positions + m.indices[t + 2] * 3;
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        float area2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        if (area2 < 1e-12f) continue;
        float cx = (a[0] + b[0] + d[0]), cy = (a[1] + b[1] + d[1]), cz = (a[2] + b[2] + d[2]);
        if (n[0] * cx + n[1] * cy + n[2] * cz < 0) inward++;
    }
    CHECK_MSG(inward == 0, "%d inward triangles (type %d)", inward, c->type);
    collide_free_mesh(&m);
}

static void test_pack_render(void)
{
    collide_shape_t cap = {.type = COLLIDE_SHAPE_CAPSULE, .radius = 0.3f, .length = 1.0f};
    float sp[8][4], pos[3] = {1, 2, 3};
    int n = collide_pack_spheres(&cap, pos, sp, 8);
    CHECK(n == 1 + 4); /* 1 + ceil(1 / 0.3) */
    CHECK_NEAR(sp[0][1], 1.5, 1e-6);
    CHECK_NEAR(sp[n - 1][1], 2.5, 1e-6);
    CHECK(sp[2][3] == 0.3f && sp[2][0] == 1.0f && sp[2][2] == 3.0f);
    CHECK(collide_pack_spheres(&cap, pos, sp, 2) == n); /* too small: full count back */
    collide_shape_t box = {.type = COLLIDE_SHAPE_BOX, .half_extents = {0.5f, 0.25f, 1.0f}};
    CHECK(collide_pack_spheres(&box, pos, sp, 8) == 1 && sp[0][3] == collide_bounding_radius(&box));
    /* the CPU cube map of a collider is its shape's rasterisation */
    collide_cubemap_t a, b;
    CHECK(collide_init_cubemap(&a, 16, (vec3){0, 0, 0}, 1.2f) && collide_init_cubemap(&b, 16, (vec3){0, 0, 0}, 1.2f));
    collide_render_shape(&a, &box);
    collide_render_box(&b, (vec3){0, 0, 0}, (vec3){0.5f, 0.25f, 1.0f});
    CHECK(memcmp(a.texels, b.texels, sizeof(float) * 4 * 6 * 16 * 16) == 0);
    collide_free_cubemap(&a);
    collide_free_cubemap(&b);
}

static void test_set(void)
{
    mat4 m;
    glm_translate_make(m, (vec3){1, 2, 3});
    collide_cube_proxy_t p;
    collide_make_cube_proxy((const float *)m, (float[3]){0, 0.5f, 0}, 0.5f, &p);
    CHECK(p.sphere[0] == 1.0f && p.sphere[1] == 2.5f && p.sphere[2] == 3.0f);
    CHECK_NEAR(p.sphere[3], 0.5 * sqrt(3.0), 1e-6);
    CHECK_NEAR(p.w2c[12], -1.0, 1e-6);
    static collide_set_t set;
    collide_object_t o = {.centre = {0, 0.5f, 0}, .radius = 0.5f};
    memcpy(o.model, m, sizeof o.model);
    collide_begin_set(&set);
    collide_object_t *a = collide_add_object(&set, &o, 0.1f);
    CHECK(a && a->position[1] == 2.5f && a->prev_position[1] == 2.5f && a->velocity[0] == 0.0f);
    o.model[12] = 1.5f;
    collide_begin_set(&set);
    a = collide_add_object(&set, &o, 0.1f);
    CHECK(a->prev_position[0] == 1.0f && a->position[0] == 1.5f);
    CHECK_NEAR(a->velocity[0], 5.0, 1e-5);
    for (int k = 1; k < COLLIDE_MAX_OBJECTS; k++) CHECK(collide_add_object(&set, &o, 0.1f));
    CHECK(collide_add_object(&set, &o, 0.1f) == NULL);
    CHECK(set.object_count == COLLIDE_MAX_OBJECTS);
}

int main(void)
{
    test_pack_render();
    test_set();
    test_face_basis();
    test_sphere_map();
    test_box_capsule_map();
    collide_shape_t s = {.type = COLLIDE_SHAPE_SPHERE, .radius = 0.5f};
    collide_shape_t cap = {.type = COLLIDE_SHAPE_CAPSULE, .radius = 0.3f, .length = 1.0f};
    collide_shape_t box = {.type = COLLIDE_SHAPE_BOX, .half_extents = {0.5f, 0.25f, 1.0f}};
    check_mesh(&s);
    check_mesh(&cap);
    check_mesh(&box);
    CHECK_NEAR(collide_signed_distance(&s, (float[3]){1, 0, 0}), 0.5, 1e-6);
    CHECK_NEAR(collide_signed_distance(&s, (float[3]){0, 0, 0}), -0.5, 1e-6);
    CHECK_NEAR(collide_signed_distance(&cap, (float[3]){0, 0.9f, 0}), 0.1, 1e-6);
    CHECK_NEAR(collide_signed_distance(&cap, (float[3]){0.5f, 0.2f, 0}), 0.2, 1e-6);
    CHECK_NEAR(collide_signed_distance(&box, (float[3]){0, 0, 0}), -0.25, 1e-6);
    CHECK_NEAR(collide_signed_distance(&box, (float[3]){1.5f, 0, 0}), 1.0, 1e-6);
    CHECK_NEAR(collide_signed_distance(&box, (float[3]){1.5f, 1.25f, 0}), sqrt(2.0), 1e-5);
    CHECK_NEAR(collide_bounding_radius(&cap), 0.8, 1e-6);
    TEST_END();
}

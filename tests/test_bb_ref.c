/* test_bb_ref: the Orthmann et al. 2009 collision reference (bb_ref.c).
 * Checks collide (eq. 4-5, the cube maps are tests/test_collide.c) against
 * the analytic surface, the swept collision and the bend limit (departures), spring relaxation (eq. 6-7),
 * recovery (eq. 8), the wind formula, a 1000-frame stress run, and the
 * bb_point_t layout against struct bb_point in shaders/common/bb.glsl. */
#include "billboard/bb_ref.h"
#include "blade/blade_ref.h"
#include "core/core.h"
#include "test.h"

#include <ctype.h>
#include <stddef.h>
#include <string.h>

static void collide_field(bb_mesh_t *meshes, int count, const collide_cubemap_t *cube, const vec3 pos,
                          const bb_collide_desc_t *desc)
{
    mat4 w2c;
    glm_translate_make(w2c, (vec3){-pos[0], -pos[1], -pos[2]});
    for (int b = 0; b < count; b++) bb_ref_collide(&meshes[b], cube, (const mat4 *)&w2c, 1, desc);
}

/* A 64^2 cube map (half r + 0.05 m) of a sphere of radius r at its centre;
 * returns its texel size. */
static float sphere_cube(collide_cubemap_t *cube, float r)
{
    CHECK(collide_init_cubemap(cube, 64, (vec3){0, 0, 0}, r + 0.05f));
    collide_render_sphere(cube, (vec3){0, 0, 0}, r);
    return 2.0f * cube->half / (float)cube->res;
}

static void test_collide(void)
{
    collide_cubemap_t cube;
    float r = 0.3f, texel = sphere_cube(&cube, r);
    core_rng_t rng;
    core_rng_seed(&rng, 11, 2);
    int touched = 0;
    double worst = 0.0;
    for (int trial = 0; trial < 200; trial++) {
        bb_mesh_t mesh;
        float ang = core_rng_range(&rng, 0.0f, 6.283f);
        CHECK(bb_mesh_init_quad(&mesh, (vec3){0, 0, 0}, (vec3){cosf(ang), 0, sinf(ang)}, (vec3){0, 1, 0},
                                0.6f, 0.5f, 5, 6));
        vec3 sp = {core_rng_range(&rng, -0.3f, 0.3f), core_rng_range(&rng, 0.32f, 0.6f),
                   core_rng_range(&rng, -0.3f, 0.3f)};
        vec3 roots[5];
        memcpy(roots, mesh.pos, sizeof roots);
        bool any_in = false;
        for (int v = 0; v < mesh.n * mesh.m; v++) any_in |= test_dist3(mesh.pos[v], sp) < r;
        touched += any_in;
        collide_field(&mesh, 1, &cube, sp, NULL);
        for (int v = mesh.n; v < mesh.n * mesh.m; v++) {
            double depth = r - test_dist3(mesh.pos[v], sp);
            worst = fmax(worst, depth);
            CHECK_MSG(depth <= texel, "vertex %d is %g m inside (texel %g)", v, depth, texel);
        }
        CHECK(memcmp(roots, mesh.pos, sizeof roots) == 0);
        bb_mesh_free(&mesh);
    }
    printf("collide: %d of 200 meshes touched, deepest vertex %.4f m inside (texel %.4f)\n", touched, worst,
           texel);
    CHECK(touched > 100);
    collide_free_cubemap(&cube);
}

/* Swept collision: a 0.3 m sphere that moved 1.5 m along x in one step (at
 * x = 1.5 now, at 0 before) pushes a billboard standing at x = 0.75, which
 * only the path between the two positions meets, and leaves nothing of it
 * inside the path's capsule; without the sweep the billboard is untouched. */
static void test_swept(void)
{
    collide_cubemap_t cube;
    float r = 0.3f, texel = sphere_cube(&cube, r);
    vec3 now = {1.5f, 0.35f, 0.0f};
    const float sweep[1][3] = {{-1.5f, 0.0f, 0.0f}};
    for (int swept = 0; swept < 2; swept++) {
        bb_mesh_t mesh, rest;
        CHECK(bb_mesh_init_quad(&mesh, (vec3){0.75f, 0, 0.1f}, (vec3){0, 0, 1}, (vec3){0, 1, 0}, 0.6f, 0.5f, 5, 6));
        CHECK(bb_mesh_init_quad(&rest, (vec3){0.75f, 0, 0.1f}, (vec3){0, 0, 1}, (vec3){0, 1, 0}, 0.6f, 0.5f, 5, 6));
        bb_collide_desc_t d = {.sweep = swept ? sweep : NULL};
        collide_field(&mesh, 1, &cube, now, &d);
        double moved = 0.0, deepest = -1.0;
        for (int v = mesh.n; v < mesh.n * mesh.m; v++) {
            moved = fmax(moved, test_dist3(mesh.pos[v], rest.pos[v]));
            /* distance to the capsule's axis (x in [0, 1.5] at y 0.35, z 0) */
            float x = glm_clamp(mesh.pos[v][0], 0.0f, 1.5f);
            float dy = mesh.pos[v][1] - 0.35f, dz = mesh.pos[v][2], dx = mesh.pos[v][0] - x;
            deepest = fmax(deepest, r - sqrt((double)(dx * dx + dy * dy + dz * dz)));
        }
        printf("swept %d: billboard moved %.3f m, deepest in the capsule %.4f m (texel %.4f)\n", swept, moved,
               deepest, texel);
        if (swept) {
            CHECK(moved > 0.05);
            CHECK(deepest <= texel);
        } else {
            CHECK(moved == 0.0);
        }
        bb_mesh_free(&mesh);
        bb_mesh_free(&rest);
    }
    collide_free_cubemap(&cube);
}

static float flat_ground(const void *user, float x, float z)
{
    (void)user, (void)x, (void)z;
    return 0.0f;
}

/* A ball sunk 0.2 m into flat ground: a billboard rooted just outside its
 * ground circle has vertices whose push points down; raised back onto the
 * ground they leave the ball sideways, so none stays inside it. */
static void test_ground_escape(void)
{
    collide_cubemap_t cube;
    float r = 0.3f, texel = sphere_cube(&cube, r);
    vec3 centre = {0.0f, 0.1f, 0.0f};
    double deepest = -1.0;
    int below = 0;
    for (int k = 0; k < 12; k++) {
        float ang = 6.2831853f * (float)k / 12.0f;
        /* rooted 0.3 m out (the ground circle is 0.283 m), facing the
         * centre, 0.58 m wide and 0.14 m tall: its innermost column stands
         * 1 cm from the ball's axis, where the push points straight down */
        vec3 root = {0.3f * cosf(ang), 0.0f, 0.3f * sinf(ang)};
        bb_mesh_t mesh;
        CHECK(bb_mesh_init_quad(&mesh, root, (vec3){cosf(ang), 0, sinf(ang)}, (vec3){0, 1, 0}, 0.58f, 0.14f, 5, 8));
        bb_collide_desc_t d = {.ground = flat_ground, .iterations = 1};
        collide_field(&mesh, 1, &cube, centre, &d);
        for (int v = mesh.n; v < mesh.n * mesh.m; v++) {
            deepest = fmax(deepest, r - test_dist3(mesh.pos[v], centre));
            below += mesh.pos[v][1] < -1e-6f;
        }
        bb_mesh_free(&mesh);
    }
    printf("ground escape: deepest vertex %.4f m inside the sunk ball (texel %.4f), %d under the ground\n", deepest,
           texel, below);
    CHECK(deepest <= texel);
    CHECK(below == 0);
    collide_free_cubemap(&cube);
}

/* Texture distortion of a 4 x 4 mesh as measure_bb_distortion
 * measures it: the largest structural stretch |l / l0 - 1| and the folded
 * cells (signed area <= 0 against the rest normal for the root row, against
 * the cell below and the cell to the left above it). */
static int border_distortion(const bb_mesh_t *mesh, const vec3 rest_normal, double *stretch)
{
    enum { N = 4 };
    int folded = 0;
    vec3 unit[N * N];
    for (int v = 0; v < N * N; v++) {
        if (v % N + 1 < N) {
            double l0 = test_dist3(mesh->rest[v], mesh->rest[v + 1]);
            *stretch = fmax(*stretch, fabs(test_dist3(mesh->pos[v], mesh->pos[v + 1]) / l0 - 1.0));
        }
        if (v + N < N * N) {
            double l0 = test_dist3(mesh->rest[v], mesh->rest[v + N]);
            *stretch = fmax(*stretch, fabs(test_dist3(mesh->pos[v], mesh->pos[v + N]) / l0 - 1.0));
        }
    }
    for (int j = 0; j + 1 < N; j++)
        for (int i = 0; i + 1 < N; i++) {
            const float *a = mesh->pos[j * N + i], *b = mesh->pos[j * N + i + 1];
            const float *d = mesh->pos[(j + 1) * N + i], *e = mesh->pos[(j + 1) * N + i + 1];
            vec3 p, q, area;
            glm_vec3_sub((float *)e, (float *)a, p);
            glm_vec3_sub((float *)d, (float *)b, q);
            glm_vec3_cross(p, q, area);
            float below = glm_vec3_dot(area, j ? unit[(j - 1) * N + i] : (float *)rest_normal);
            float left = i ? glm_vec3_dot(area, unit[j * N + i - 1]) : 1.0f;
            folded += !(below > 0.0f && left > 0.0f);
            glm_vec3_normalize_to(area, unit[j * N + i]);
        }
    return folded;
}

/* A 0.8 m ball rolling on flat ground over 0.6 x 0.4 m billboards that face
 * its path within 22.5 degrees, its centre passing -0.75 to 0.75 m beside
 * their roots (mesh 4 x 4, 2 spring sweeps, swept, 1.6 m/s at 60 Hz, cube
 * texel 2.7 cm: the stability case bb_border's): the ball is wider than the
 * billboards are tall and presses their upper rows down; no spring may
 * stretch or shrink by more than 25 %, no cell fold, no vertex stay inside
 * the ball or under the ground. Without the slide (bb_push_mesh) the worst
 * spring was 33 % off and 10 cell-frames folded. */
static void test_border_ball(void)
{
    collide_cubemap_t cube;
    float r = 0.8f, texel = sphere_cube(&cube, r), step = 1.6f / 60.0f;
    const float sweep[1][3] = {{-step, 0.0f, 0.0f}};
    double stretch = 0.0, deepest = -1.0;
    int folded = 0, below = 0;
    for (int k = 3; k <= 5; k++) {
        float ang = 3.1415927f * (float)k / 8.0f;
        vec3 right = {cosf(ang), 0, sinf(ang)}, up = {0, 1, 0}, rest_normal;
        glm_vec3_cross(right, up, rest_normal);
        for (int o = -3; o <= 3; o++) {
            float z = 0.25f * (float)o;
            bb_mesh_t mesh;
            CHECK(bb_mesh_init_quad(&mesh, (vec3){0, 0, 0}, right, up, 0.6f, 0.4f, 4, 4));
            bb_collide_desc_t d = {.ground = flat_ground, .iterations = 2, .sweep = sweep};
            for (float x = -1.5f; x <= 1.5f; x += step) {
                vec3 centre = {x, r, z};
                if (sqrtf(x * x + (r - 0.2f) * (r - 0.2f) + z * z) >= r + 0.36f) continue;
                collide_field(&mesh, 1, &cube, centre, &d);
                folded += border_distortion(&mesh, rest_normal, &stretch);
                for (int v = mesh.n; v < mesh.n * mesh.m; v++) {
                    deepest = fmax(deepest, r - test_dist3(mesh.pos[v], centre));
                    below += mesh.pos[v][1] < -1e-6f;
                }
            }
            bb_mesh_free(&mesh);
        }
    }
    printf("border ball: max stretch %.3f, %d folded cell-frames, deepest vertex %.4f m inside (texel %.4f), "
           "%d under the ground\n", stretch, folded, deepest, texel, below);
    CHECK(stretch <= 0.25);
    CHECK(folded == 0);
    CHECK(deepest <= texel);
    CHECK(below == 0);
    collide_free_cubemap(&cube);
}

/* A ball rolling to a stop over billboards facing its path (issue 17,
 * stability case bb_border): a billboard crushed under the resting ball
 * lies on the ground with its upper rows in the wedge between ball and
 * ground, where the push-out turned a column up the ball's back: a joint
 * past 90 degrees, a cell folded against the one below. The bend limit
 * (bb_ref_bend_limit) leans the segments below into the bend instead.
 * Without it: 12 folded billboards of 72 here (cube maps of 2 cm texels,
 * as the bench case; checked by disabling the call in bb_ref_collide). */
static void test_resting_wedge(void)
{
    const float radii[] = {0.2f, 0.5f, 0.8f};
    int folded_bb = 0, placements = 0;
    double stretch = 0.0, deepest = -1.0, worst_texel = 0.0;
    for (int ri = 0; ri < 3; ri++) {
        float r = radii[ri], step = 1.6f / 60.0f;
        collide_cubemap_t cube;
        CHECK(collide_init_cubemap(&cube, (int)ceilf(2.0f * r / 0.02f), (vec3){0, 0, 0}, r + 0.01f));
        collide_render_sphere(&cube, (vec3){0, 0, 0}, r);
        worst_texel = fmax(worst_texel, 2.0 * cube.half / cube.res);
        for (int k = -1; k <= 1; k++) {
            float ang = 1.5707963f + 0.3926991f * (float)k;
            vec3 right = {cosf(ang), 0, sinf(ang)}, up = {0, 1, 0}, rest_normal;
            glm_vec3_cross(right, up, rest_normal);
            for (int o = 0; o < 8; o++) {
                float ox = -(r + 0.35f) * (float)o / 7.0f, oz = o % 2 ? 0.0123f : -0.1f;
                bb_mesh_t mesh;
                CHECK(bb_mesh_init_quad(&mesh, (vec3){ox, 0, oz}, right, up, 0.6f, 0.4f, 4, 4));
                float sweep[1][3] = {{0, 0, 0}};
                bb_collide_desc_t d = {.ground = flat_ground, .iterations = 2, .sweep = (const float (*)[3])sweep};
                int folded = 0;
                float prev = -2.0f;
                for (int f = 0; f < 150; f++) {
                    float x = fminf(-2.0f + step * (float)f, 0.0f);
                    sweep[0][0] = f ? prev - x : 0.0f;
                    prev = x;
                    vec3 centre = {x, r, 0};
                    if (sqrtf((x - ox) * (x - ox) + oz * oz) >= r + 0.45f) continue;
                    collide_field(&mesh, 1, &cube, centre, &d);
                    folded += border_distortion(&mesh, rest_normal, &stretch);
                    for (int v = mesh.n; v < mesh.n * mesh.m; v++)
                        deepest = fmax(deepest, r - test_dist3(mesh.pos[v], centre));
                }
                folded_bb += folded > 0;
                placements++;
                bb_mesh_free(&mesh);
            }
        }
        collide_free_cubemap(&cube);
    }
    printf("resting wedge: %d of %d billboards folded, max stretch %.3f, deepest vertex %.4f m inside (texel %.4f)\n",
           folded_bb, placements, stretch, deepest, worst_texel);
    CHECK(folded_bb == 0);
    CHECK(deepest <= worst_texel);
}

static void test_springs(void)
{
    bb_mesh_t mesh;
    CHECK(bb_mesh_init_quad(&mesh, (vec3){1, 2, 3}, (vec3){1, 0, 0}, (vec3){0, 1, 0}, 0.5f, 0.4f, 4, 5));
    /* Hand-checked geometry: vertex (3,4) sits at root + (0.25, 0.4, 0). */
    CHECK_NEAR(mesh.rest[4 * 4 + 3][0], 1.25, 1e-6);
    CHECK_NEAR(mesh.rest[4 * 4 + 3][1], 2.4, 1e-6);
    CHECK_NEAR(bb_ref_spring_error(&mesh), 0.0, 1e-7);
    bb_mesh_t tiny;
    core_rng_t rng;
    core_rng_seed(&rng, 3, 3);
    for (int v = mesh.n; v < mesh.n * mesh.m; v++)
        for (int k = 0; k < 3; k++) mesh.pos[v][k] += core_rng_range(&rng, -0.08f, 0.08f);
    vec3 roots[4];
    memcpy(roots, mesh.pos, sizeof roots);
    float prev = bb_ref_spring_error(&mesh);
    printf("spring error:");
    for (int it = 0; it < 10; it++) {
        printf(" %.4f", prev);
        bb_ref_relax_springs(&mesh, 0.9f, 0.5f, 1);
        float e = bb_ref_spring_error(&mesh);
        CHECK_MSG(e < prev, "iteration %d: %g -> %g", it, prev, e);
        prev = e;
    }
    printf(" %.4f\n", prev);
    CHECK(memcmp(roots, mesh.pos, sizeof roots) == 0);
    bb_mesh_free(&mesh);

    /* Hand value of eq. 6 with a fixed end: 2x2 mesh, top vertices
     * lifted to y = 1.5 above their roots: vertical spring 1.5 vs rest 1, r1 = 0.5
     * moves it back by 0.5 * 0.5 = 0.25. Both top vertices are lifted
     * equally so the horizontal spring stays at rest; r2 = 0 disables shear. */
    CHECK(bb_mesh_init_quad(&tiny, (vec3){0, 0, 0}, (vec3){1, 0, 0}, (vec3){0, 1, 0}, 1.0f, 1.0f, 2, 2));
    tiny.pos[2][1] = 1.5f;
    tiny.pos[3][1] = 1.5f;
    bb_ref_relax_springs(&tiny, 0.5f, 0.0f, 1);
    CHECK_NEAR(tiny.pos[2][1], 1.25, 1e-6);
    CHECK_NEAR(tiny.pos[3][1], 1.25, 1e-6);
    CHECK_NEAR(tiny.pos[2][0], -0.5, 1e-6);
    bb_mesh_free(&tiny);
}

/* Billboards and blades sway in phase under one wave (bb_wind_from_wave):
 * over places and times, the billboard top's bend along the wind and the
 * blades' wind strength correlate (s's main term is the wave itself: about
 * 0.6 / sqrt(0.6^2 + 0.3^2 + 0.1^2) = 0.88; in antiphase it would be -0.88). */
static void test_wind_phase(void)
{
    const float dir[2] = {1.0f, 0.3f}, strength = 1.0f, wavelength = 10.0f, speed = 2.0f;
    bb_wind_desc_t bw = bb_wind_from_wave(dir[0], dir[1], strength, wavelength, speed);
    bw = bb_wind_desc_defaults(&bw);
    blade_wind_t blw = blade_wind_wave(dir[0], dir[1], strength, wavelength, speed);
    core_rng_t rng;
    core_rng_seed(&rng, 11u, 0u);
    double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    const int n = 2000;
    for (int i = 0; i < n; i++) {
        vec3 root = {core_rng_range(&rng, -20.0f, 20.0f), 0.0f, core_rng_range(&rng, -20.0f, 20.0f)};
        float t = core_rng_range(&rng, 0.0f, 30.0f);
        vec3 top = {root[0], 1.0f, root[2]}, out;
        bb_ref_wind_vertex(&bw, top, root, 1.0f, t, out);
        float bend = (out[0] - top[0]) * bw.dir[0] + (out[2] - top[2]) * bw.dir[1];
        float w[3];
        blade_ref_wind_field(&blw, root, t, w);
        float f = sqrtf(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        sx += bend;
        sy += f;
        sxx += (double)bend * bend;
        syy += (double)f * f;
        sxy += (double)bend * f;
    }
    double cov = sxy / n - (sx / n) * (sy / n);
    double r = cov / sqrt((sxx / n - (sx / n) * (sx / n)) * (syy / n - (sy / n) * (sy / n)));
    printf("wind phase: billboard bend vs blade wind correlation %.3f\n", r);
    CHECK_MSG(r > 0.8, "billboard bend vs blade wind correlation %.3f (in phase: > 0.8)", r);
    CHECK_NEAR(bw.strength, 0.08f * strength, 1e-6f);
}

static void test_wind_recover(void)
{
    bb_mesh_t mesh;
    CHECK(bb_mesh_init_quad(&mesh, (vec3){0, 0, 0}, (vec3){0, 0, 1}, (vec3){0, 1, 0}, 0.5f, 0.4f, 3, 4));
    vec3 w[12];
    bb_wind_desc_t wd = {.dir = {2.0f, 0.0f}, .strength = 0.1f, .omega = 1.5f, .wavenumber = 0.4f};
    bb_ref_wind_pose(&mesh, &wd, 0.0f, w);
    /* Hand value at t = 0, root at the origin (ph = 0): s = 0.3 sin 1.3 + 0.1 sin 0.7. */
    double s = 0.3 * sin(1.3) + 0.1 * sin(0.7);
    double bend = 0.1 * (0.4 + 0.6 * s);
    CHECK_NEAR(w[3 * 3 + 1][0] - mesh.rest[3 * 3 + 1][0], bend, 1e-6);
    CHECK_NEAR(w[2 * 3 + 1][0] - mesh.rest[2 * 3 + 1][0], bend * 4.0 / 9.0, 1e-6);
    for (int i = 0; i < 3; i++) CHECK(test_dist3(w[i], mesh.rest[i]) == 0.0);
    for (int v = 0; v < 12; v++) CHECK(w[v][1] == mesh.rest[v][1] && w[v][2] == mesh.rest[v][2]);

    /* Eq. 8 by hand at t = 0.5: v' = 0.875 w + 0.125 v. */
    for (int v = 3; v < 12; v++) mesh.pos[v][2] += 0.2f;
    float before = mesh.pos[11][2];
    bb_ref_recover(&mesh, (const vec3 *)w, 0.5f);
    CHECK_NEAR(mesh.pos[11][2], 0.875 * w[11][2] + 0.125 * before, 1e-6);
    /* A recovery sequence over 0.5 s with a moving wind pose ends on it. */
    float dur = 0.5f, left = dur, time = 0.0f;
    while (left > 0.0f) {
        time += 1.0f / 60.0f;
        left = fmaxf(0.0f, left - 1.0f / 60.0f);
        bb_ref_wind_pose(&mesh, &wd, time, w);
        bb_ref_recover(&mesh, (const vec3 *)w, left / dur);
    }
    double maxd = 0.0;
    for (int v = 0; v < 12; v++) maxd = fmax(maxd, test_dist3(mesh.pos[v], w[v]));
    printf("recovery: max distance to wind pose at t=0: %.2e m\n", maxd);
    CHECK(maxd < 1e-3);
    bb_mesh_free(&mesh);
}

/* 1000 frames of a sphere moving through a small field at 0.1-20 m/s. */
static void test_stress(void)
{
    enum { NB = 16 };
    bb_mesh_t meshes[NB];
    float left[NB] = {0};
    for (int b = 0; b < NB; b++)
        CHECK(bb_mesh_init_quad(&meshes[b], (vec3){(float)(b % 4) * 0.4f, 0, (float)(b / 4) * 0.4f},
                                (vec3){1, 0, (float)b * 0.1f}, (vec3){0, 1, 0}, 0.5f, 0.5f, 5, 5));
    collide_cubemap_t cube;
    float r = 0.35f;
    CHECK(collide_init_cubemap(&cube, 32, (vec3){0, 0, 0}, 0.4f));
    collide_render_sphere(&cube, (vec3){0, 0, 0}, r);
    core_rng_t rng;
    core_rng_seed(&rng, 5, 5);
    vec3 p = {0.6f, 0.3f, 0.6f}, vel = {1, 0, 0};
    float time = 0.0f, recover = 0.8f;
    int collided = 0, bad = 0;
    double maxdev = 0.0;
    for (int frame = 0; frame < 1000; frame++) {
        float dt = core_rng_range(&rng, 1.0f / 240.0f, 1.0f / 10.0f);
        if (frame % 50 == 0) {
            float speed = frame < 500 ? 0.1f + 19.9f * (float)frame / 500.0f : core_rng_range(&rng, 0.1f, 20.0f);
            float a = core_rng_range(&rng, 0.0f, 6.283f);
            vel[0] = speed * cosf(a);
            vel[2] = speed * sinf(a);
            vel[1] = core_rng_range(&rng, -0.2f, 0.2f) * speed;
        }
        glm_vec3_muladds(vel, dt, p);
        for (int k = 0; k < 3; k += 2) { /* bounce inside the field */
            if (p[k] < -0.2f) { p[k] = -0.2f; vel[k] = fabsf(vel[k]); }
            if (p[k] > 1.4f) { p[k] = 1.4f; vel[k] = -fabsf(vel[k]); }
        }
        if (p[1] < 0.1f) { p[1] = 0.1f; vel[1] = fabsf(vel[1]); }
        if (p[1] > 0.6f) { p[1] = 0.6f; vel[1] = -fabsf(vel[1]); }
        time += dt;
        mat4 w2c;
        glm_translate_make(w2c, (vec3){-p[0], -p[1], -p[2]});
        for (int b = 0; b < NB; b++) {
            bb_mesh_t *m = &meshes[b];
            vec3 w[25];
            bb_ref_wind_pose(m, NULL, time, w);
            bool near = test_dist3(m->rest[2], p) < r + 0.8;
            if (near) {
                left[b] = recover;
                collided++;
                bb_ref_recover(m, (const vec3 *)w, 0.9f);
                bb_ref_collide(m, &cube, (const mat4 *)&w2c, 1, NULL);
            } else {
                left[b] = fmaxf(0.0f, left[b] - dt);
                bb_ref_recover(m, (const vec3 *)w, left[b] / recover);
            }
            for (int v = 0; v < 25; v++) {
                for (int k = 0; k < 3; k++) bad += !isfinite(m->pos[v][k]);
                maxdev = fmax(maxdev, test_dist3(m->pos[v], m->rest[v]));
            }
        }
    }
    printf("stress: %d colliding billboard-frames, max deviation from rest %.3f m, %d non-finite\n", collided,
           maxdev, bad);
    CHECK(bad == 0);
    CHECK(collided > 1000);
    CHECK(maxdev < 2.0);
    for (int b = 0; b < NB; b++) bb_mesh_free(&meshes[b]);
    collide_free_cubemap(&cube);
}

/* std430 layout of `struct bb_point` parsed from the GLSL, compared with the
 * C mirror. Only scalar / vector members are allowed there. */
static void test_point_layout(void)
{
    char path[1024], err[256];
    CHECK(core_fs_resolve("shaders/common/bb.glsl", path, sizeof path));
    char *src = core_fs_read(path, NULL, err, sizeof err);
    CHECK(src != NULL);
    if (!src) return;
    char *p = strstr(src, "struct bb_point");
    CHECK(p != NULL);
    if (!p) {
        free(src);
        return;
    }
    p = strchr(p, '{') + 1;
    char *end = strstr(p, "};");
    static const struct { const char *name; size_t off; } c_members[] = {
        {"position", offsetof(bb_point_t, position)}, {"angle", offsetof(bb_point_t, angle)},
        {"growth", offsetof(bb_point_t, growth)},     {"messiness", offsetof(bb_point_t, messiness)},
        {"size", offsetof(bb_point_t, size)},         {"layer", offsetof(bb_point_t, layer)},
        {"state", offsetof(bb_point_t, state)},       {"recover_time", offsetof(bb_point_t, recover_time)},
        {"seed", offsetof(bb_point_t, seed)},         {"pad0", offsetof(bb_point_t, pad[0])},
        {"pad1", offsetof(bb_point_t, pad[1])},
    };
    size_t off = 0, max_align = 4;
    int idx = 0;
    while (p < end) {
        char type[32], name[64];
        while (p < end && isspace((unsigned char)*p)) p++;
        if (p >= end) break;
        if (sscanf(p, "%31s %63[a-z_0-9]", type, name) != 2) break;
        size_t size = 4, align = 4;
        if (!strcmp(type, "vec2") || !strcmp(type, "uvec2") || !strcmp(type, "ivec2")) size = align = 8;
        else if (!strcmp(type, "vec3") || !strcmp(type, "uvec3") || !strcmp(type, "ivec3")) size = 12, align = 16;
        else if (!strcmp(type, "vec4") || !strcmp(type, "uvec4") || !strcmp(type, "ivec4")) size = align = 16;
        else CHECK_MSG(!strcmp(type, "float") || !strcmp(type, "uint") || !strcmp(type, "int"), "type %s", type);
        off = (off + align - 1) / align * align;
        max_align = align > max_align ? align : max_align;
        CHECK_MSG(idx < (int)(sizeof c_members / sizeof c_members[0]), "extra GLSL member %s", name);
        if (idx < (int)(sizeof c_members / sizeof c_members[0])) {
            CHECK_MSG(!strcmp(name, c_members[idx].name), "member %d: %s vs %s", idx, name, c_members[idx].name);
            CHECK_MSG(off == c_members[idx].off, "%s at %zu vs C %zu", name, off, c_members[idx].off);
        }
        off += size;
        idx++;
        p = strchr(p, ';') + 1;
    }
    off = (off + max_align - 1) / max_align * max_align;
    CHECK(idx == (int)(sizeof c_members / sizeof c_members[0]));
    CHECK_MSG(off == sizeof(bb_point_t), "std430 size %zu vs C %zu", off, sizeof(bb_point_t));
    free(src);
}

int main(void)
{
    core_log_set_quiet(true);
    test_collide();
    test_swept();
    test_ground_escape();
    test_border_ball();
    test_resting_wedge();
    test_springs();
    test_wind_recover();
    test_wind_phase();
    test_stress();
    test_point_layout();
    TEST_END();
}

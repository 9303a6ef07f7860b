/* test_canopy_gpu: the ground canopy's colour in GLSL (canopy_color of
 * common/canopy.glsl, which the terrain shades the far ground with) against
 * its C twin blade_canopy_color, the table of the default blades uploaded
 * as the terrain uploads it (blade_canopy_pack, a texture): 512 ground
 * points, a quarter flat, the rest on slopes up to 50 degrees facing any
 * way, each seen from a camera and lit by a sun at random elevations over
 * its ground (the sun from 80 degrees below to 80 above it) and azimuths,
 * three in four of the columns cut at a random height (up to 1.2 times the
 * table's top), and the overhang of the whole column over the cut one
 * (canopy_overhang against blade_canopy_overhang) with random blades kept.
 * A shader that ignored the cut fails on the cut columns' cover.
 * The table has wind poses (blade_canopy_desc_t.wind 1): each point has a
 * wind force (three in four; up to 1.3 times the table's largest, any
 * azimuth, with a part along the ground normal that the twin leaves out),
 * so a shader that ignored the wind, its azimuth or the sun's side of it
 * fails; on a slope the blades' gravity along the ground adds to it
 * (blade_canopy_slope_lean, the twin's wind summed here in the ground's
 * frame), so a shader without the lean fails too.
 * The twin's inputs are the angles the camera and sun were built from in
 * the ground's frame (t towards the viewer, the normal g, s = g x t) and
 * world up in that frame, so a shader that took the sun's elevation over
 * flat ground or the ambient's world up in the wrong frame fails. Colour
 * and cover within 1e-3 (a quarter of an 8-bit step; the shader's angles
 * come from float dot products, ill-conditioned near 0 and pi); the
 * overhang (canopy_overhang against blade_canopy_overhang) of the
 * shader's own columns within 1e-4: it divides the whole column's gap by
 * the cut's, which turns the columns' last bits into 1e-3 where the cut
 * is opaque. */
#include "common/bindings_ground.glsl"
#include "common/bindings_tests.glsl"
#include "blade/blade_canopy.h"
#include "gfx/gfx.h"
#include "test.h"
#include "test_gl.h"

#include <string.h>

enum { N = 512 };

typedef struct item_t {
    float pos[4], normal[4], camera[4], wind[4];
} item_t;

static void cross3(const float a[3], const float b[3], float out[3])
{
    out[0] = a[1] * b[2] - a[2] * b[1];
    out[1] = a[2] * b[0] - a[0] * b[2];
    out[2] = a[0] * b[1] - a[1] * b[0];
}

static void normalize3(float v[3])
{
    float l = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (int k = 0; k < 3; k++) v[k] /= l;
}

int main(void)
{
    test_gl_init();
    static blade_canopy_t c;
    CHECK(blade_canopy_make(&c, &(blade_canopy_desc_t){.seed = 9, .rays = 1024, .sun = {0.45f, 0.8f, 0.35f},
                                                       .wind = 1.0f}));
    CHECK(c.poses == BLADE_CANOPY_POSES);
    CHECK(c.top > 0.3f && c.top < 0.7f);
    static blade_canopy_texture_t tex;
    blade_canopy_pack(&c, &tex);
    static const float root[3] = {0.10f, 0.25f, 0.05f}, tip[3] = {0.45f, 0.65f, 0.20f};
    static item_t items[N];
    static float suns[N][4], want[N][4], got[N][3][4], whole[N][4];
    double wind_spread = 0.0, lean_spread = 0.0; /* the most the wind, the lean moves a colour channel */
    core_rng_t rng;
    core_rng_seed(&rng, 11, 2);
    for (int i = 0; i < N; i++) {
        item_t *it = &items[i];
        float tilt = i < N / 4 ? 0.0f : core_rng_range(&rng, 0.05f, 0.87f), ta = core_rng_range(&rng, -3.14f, 3.14f);
        float g[3] = {sinf(tilt) * cosf(ta), cosf(tilt), sinf(tilt) * sinf(ta)};
        /* t: a random direction across the ground, s = g x t */
        float a = core_rng_range(&rng, -3.14f, 3.14f), s[3];
        float t[3] = {cosf(a), core_rng_range(&rng, -1.0f, 1.0f), sinf(a)};
        float td = t[0] * g[0] + t[1] * g[1] + t[2] * g[2];
        for (int k = 0; k < 3; k++) t[k] -= td * g[k];
        normalize3(t);
        cross3(g, t, s);
        float e = core_rng_range(&rng, 0.01f, 1.56f), se = core_rng_range(&rng, -1.4f, 1.4f);
        float phi = core_rng_range(&rng, 0.0f, 3.14f), side = core_rng_float(&rng) < 0.5f ? -1.0f : 1.0f;
        float dist = core_rng_range(&rng, 5.0f, 200.0f);
        float wm = core_rng_float(&rng) < 0.25f ? 0.0f : core_rng_range(&rng, 0.0f, 1.3f);
        float psi = core_rng_range(&rng, -3.14f, 3.14f), wg = core_rng_range(&rng, -0.5f, 0.5f);
        for (int k = 0; k < 3; k++) {
            it->pos[k] = core_rng_range(&rng, -50.0f, 50.0f);
            it->normal[k] = g[k];
            it->camera[k] = it->pos[k] + dist * (cosf(e) * t[k] + sinf(e) * g[k]);
            suns[i][k] = cosf(se) * (cosf(phi) * t[k] + side * sinf(phi) * s[k]) + sinf(se) * g[k];
            it->wind[k] = wm * (cosf(psi) * t[k] + sinf(psi) * s[k]) + wg * g[k];
        }
        it->wind[3] = 0.0f;
        float cut = core_rng_float(&rng) < 0.25f ? 0.0f : core_rng_range(&rng, 0.0f, 1.2f * c.top);
        it->pos[3] = it->normal[3] = 0.0f;
        it->camera[3] = cut;
        suns[i][3] = core_rng_float(&rng); /* blades kept */
        /* the wind and the lean along t and along the sun's side of s */
        float lean[3];
        blade_canopy_slope_lean(&c, g, lean);
        float lt = lean[0] * t[0] + lean[1] * t[1] + lean[2] * t[2];
        float ls = lean[0] * s[0] + lean[1] * s[1] + lean[2] * s[2];
        float wt = wm * cosf(psi) + lt, ws = side * (wm * sinf(psi) + ls);
        blade_canopy_view_t v = {.elevation = e, .sun_elevation = se, .azimuth = phi, .up = {t[1], g[1], s[1]},
                                 .wind = sqrtf(wt * wt + ws * ws), .wind_azimuth = atan2f(ws, wt)};
        blade_canopy_color(&c, &v, root, tip, whole[i], &whole[i][3]);
        blade_canopy_view_t calm = v, unlean = v;
        calm.wind = 0.0f;
        unlean.wind = wm;
        unlean.wind_azimuth = side * psi;
        float still[4], upright[4];
        blade_canopy_color(&c, &calm, root, tip, still, &still[3]);
        blade_canopy_color(&c, &unlean, root, tip, upright, &upright[3]);
        for (int k = 0; k < 3; k++) {
            wind_spread = fmax(wind_spread, fabs(still[k] - whole[i][k]));
            lean_spread = fmax(lean_spread, fabs(upright[k] - whole[i][k]));
        }
        v.cut = cut;
        blade_canopy_color(&c, &v, root, tip, want[i], &want[i][3]);
    }
    gfx_program_t prog = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/canopy_eval.comp", .label = "canopy"});
    CHECK(prog.id != 0);
    gfx_texture_t table = gfx_texture_make(&(gfx_texture_desc_t){.w = BLADE_CANOPY_TEXELS,
                                                                 .h = tex.rows * BLADE_CANOPY_LEVELS * tex.poses,
                                                                 .format = GL_RGBA32F, .filter = GL_NEAREST,
                                                                 .data = tex.texel, .upload_type = GL_FLOAT,
                                                                 .label = "canopy.table"});
    CHECK(table.id != 0);
    gfx_buffer_t bi =
        gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof items, .data = items, .label = "canopy.items"});
    gfx_buffer_t bs = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof suns, .data = suns, .label = "canopy.suns"});
    gfx_buffer_t bo = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof got, .label = "canopy.out"});
    glUseProgram(prog.id);
    glUniform1ui(gfx_uniform(prog, "u_count"), N);
    glUniform1i(gfx_uniform(prog, "u_canopy_rows"), tex.rows);
    glUniform1f(gfx_uniform(prog, "u_canopy_sun0"), tex.sun0);
    glUniform1f(gfx_uniform(prog, "u_canopy_top"), tex.top);
    glUniform1i(gfx_uniform(prog, "u_canopy_poses"), tex.poses);
    glUniform1f(gfx_uniform(prog, "u_canopy_wind"), tex.wind);
    glUniform1f(gfx_uniform(prog, "u_canopy_gravity"), tex.gravity);
    glUniform3fv(gfx_uniform(prog, "u_canopy_albedo_root"), 1, root);
    glUniform3fv(gfx_uniform(prog, "u_canopy_albedo_tip"), 1, tip);
    glBindTextureUnit(GROUND_TEX_CANOPY, table.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN, bi.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN2, bs.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_OUT, bo.id);
    glDispatchCompute((N + 63) / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    memset(got, 0, sizeof got);
    CHECK(gfx_buffer_read(bo, 0, sizeof got, got));
    double worst = 0.0, worst_flat = 0.0, worst_cut = 0.0, worst_overhang = 0.0, spread = 0.0, cut_spread = 0.0;
    int cuts = 0;
    for (int i = 0; i < N; i++) {
        bool cut = items[i].camera[3] > 0.0f && items[i].camera[3] < c.top;
        cuts += cut;
        for (int k = 0; k < 4; k++) {
            double err = fabs(got[i][0][k] - want[i][k]);
            worst = fmax(worst, err);
            if (i < N / 4) worst_flat = fmax(worst_flat, err);
            if (cut) worst_cut = fmax(worst_cut, err);
            worst = fmax(worst, fabs(got[i][1][k] - whole[i][k]));
            spread = fmax(spread, fabs(want[i][k] - want[0][k]));
        }
        /* the overhang of the shader's own columns: its division of the
         * whole column's gap by the cut's turns the columns' last bits
         * into 1e-3 where the cut is opaque */
        float o[4];
        blade_canopy_overhang(got[i][1], got[i][0], suns[i][3], o);
        for (int k = 0; k < 4; k++) worst_overhang = fmax(worst_overhang, fabs(got[i][2][k] - o[k]));
        /* the cut's cover against the whole column's */
        if (cut) cut_spread = fmax(cut_spread, whole[i][3] - want[i][3]);
    }
    printf("canopy colour and cover, GLSL vs C twin (%d views, %d flat, %d cut below the top): worst %.2g, flat "
           "%.2g, cut %.2g, overhang of the shader's columns %.2g (values spread %.3f; the wind moves a colour by "
           "up to %.3f, the slope's lean by up to %.3f)\n",
           N, N / 4, cuts, worst, worst_flat, worst_cut, worst_overhang, spread, wind_spread, lean_spread);
    CHECK(worst < 1e-3); /* a quarter of an 8-bit step: acos / asin of float dots near +-1 */
    CHECK(worst_overhang < 1e-4);
    CHECK(spread > 0.1); /* the views differ: the comparison compares something */
    CHECK(wind_spread > 0.01); /* so does the wind */
    CHECK(lean_spread > 0.01); /* and the lean */
    CHECK(cuts > N / 2 && cut_spread > 0.1); /* some cuts take much of the column's cover away */
    blade_canopy_free(&c);
    gfx_texture_destroy(&table);
    gfx_buffer_destroy(&bi);
    gfx_buffer_destroy(&bs);
    gfx_buffer_destroy(&bo);
    gfx_program_destroy(&prog);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

/* test_bb_gpu_view: the view-dependent clump cards' blend on the GPU
 * (shaders/billboard/bb_view.glsl, through shaders/tests/bb_view.comp)
 * against its CPU twins bb_view_weights and bb_view_pick: for view
 * directions all round the wind and from the horizon to straight down,
 * under several winds and view sets, the weight each view gets, the view a
 * pixel's draw picks, the albedo, alpha and light layer read from a clump
 * array whose every layer holds its own constant colour (so a wrong layer
 * or a light layer read at the wrong offset shows in the colour), and the
 * pixel draw itself (bb_view_xi); over many draws each view is picked in
 * proportion to its weight. */
#include "common/bindings_tests.glsl"
#include "billboard/bb_view.h"
#include "gfx/gfx.h"
#include "test.h"
#include "test_gl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define QUERIES 2000
#define LAYERS 3

static void layer_rgba(int j, float out[4])
{
    out[0] = (float)(2 * j + 1) / 255.0f;
    out[1] = (float)(255 - 2 * j) / 255.0f;
    out[2] = (float)((5 * j) % 256) / 255.0f;
    out[3] = (float)(128 + j) / 255.0f;
}

int main(void)
{
    test_gl_init();
    gfx_program_t p = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/bb_view.comp", .label = "test.bb_view"});
    CHECK(p.id != 0);
    const bb_view_desc_t sets[3] = {{.on = true},
                                    {.on = true, .elevations = 2, .azimuths = 3, .elevation_max = 0.5f},
                                    {.on = true, .elevations = 3, .azimuths = 5}};
    const float winds[3][2] = {{1.0f, 0.0f}, {0.9578263f, 0.2873479f}, {-0.6f, 0.8f}};
    float *q = malloc(sizeof(float) * 8 * QUERIES), *res = malloc(sizeof(float) * 20 * QUERIES);
    CHECK(q && res);
    double worst_w = 0.0, worst_c = 0.0, worst_xi = 0.0;
    int picks_differ = 0, picks = 0;
    double share[BB_VIEW_MAX] = {0}, want_share[BB_VIEW_MAX] = {0};
    for (int s = 0; s < 3; s++) {
        bb_view_desc_t vd = bb_view_desc_defaults(&sets[s]);
        int views = vd.elevations * vd.azimuths, images = views * LAYERS;
        uint8_t *px = malloc((size_t)2 * images * 4 * 4 * 4);
        CHECK(px != NULL);
        for (int j = 0; j < 2 * images; j++) {
            float c[4];
            layer_rgba(j, c);
            for (int t = 0; t < 16; t++)
                for (int k = 0; k < 4; k++)
                    px[((size_t)j * 16 + (size_t)t) * 4 + (size_t)k] = (uint8_t)lrintf(c[k] * 255.0f);
        }
        gfx_texture_t tex = gfx_texture_make(&(gfx_texture_desc_t){.target = GL_TEXTURE_2D_ARRAY, .w = 4, .h = 4,
                                                                   .layers = 2 * images, .filter = GL_NEAREST,
                                                                   .data = px, .label = "test.bb_view.clumps"});
        free(px);
        for (int wi = 0; wi < 3; wi++) {
            core_rng_t rng;
            core_rng_seed(&rng, 31u, (uint64_t)(s * 3 + wi));
            for (int i = 0; i < QUERIES; i++) {
                float el = i == 0 ? 1.5707963f : core_rng_range(&rng, -0.2f, 1.5707963f);
                float az = i == 1 ? atan2f(winds[wi][1], winds[wi][0]) : core_rng_range(&rng, -3.2f, 3.2f);
                float len = core_rng_range(&rng, 0.5f, 40.0f);
                q[8 * i] = len * cosf(el) * cosf(az);
                q[8 * i + 1] = len * sinf(el);
                q[8 * i + 2] = len * cosf(el) * sinf(az);
                q[8 * i + 3] = (float)(i % LAYERS);
                q[8 * i + 4] = core_rng_float(&rng);
            }
            gfx_buffer_t qb = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof(float) * 8 * QUERIES, .data = q,
                                                                   .label = "test.bb_view.queries"});
            gfx_buffer_t ob = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof(float) * 20 * QUERIES,
                                                                   .label = "test.bb_view.out"});
            glUseProgram(p.id);
            glUniform2i(gfx_uniform(p, "u_views"), vd.elevations, vd.azimuths);
            glUniform1f(gfx_uniform(p, "u_view_elevation_max"), vd.elevation_max);
            glUniform1i(gfx_uniform(p, "u_view_layers"), LAYERS);
            glUniform1i(gfx_uniform(p, "u_view_lit"), 1);
            glUniform2f(gfx_uniform(p, "u_view_wind"), winds[wi][0], winds[wi][1]);
            glUniform1ui(gfx_uniform(p, "u_count"), QUERIES);
            glBindTextureUnit(TEST_TEX_IN, tex.id);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN, qb.id);
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_OUT, ob.id);
            glDispatchCompute((QUERIES + 63) / 64, 1, 1);
            glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
            CHECK(gfx_buffer_read(ob, 0, sizeof(float) * 20 * QUERIES, res));
            for (int i = 0; i < QUERIES; i++) {
                const float *r = res + 20 * i;
                int view[4];
                float w[4], gw[BB_VIEW_MAX] = {0}, cw[BB_VIEW_MAX] = {0};
                bb_view_weights(&vd, q + 8 * i, winds[wi], view, w);
                for (int k = 0; k < 4; k++) {
                    CHECK(view[k] >= 0 && view[k] < views && r[k] >= 0.0f && r[k] < (float)views);
                    cw[view[k]] += w[k];
                    gw[(int)r[k]] += r[4 + k];
                    want_share[view[k]] += w[k];
                }
                for (int v = 0; v < views; v++) worst_w = fmax(worst_w, fabs(gw[v] - cw[v]));
                /* The pick: the GPU's own view; the CPU's from the same draw
                 * may differ only where the draw lies within the weights'
                 * rounding of a boundary. */
                int pick = (int)r[16], want = bb_view_pick(view, w, q[8 * i + 4]);
                CHECK(pick >= 0 && pick < views);
                picks_differ += pick != want;
                picks++;
                share[pick] += 1.0;
                float c[4], l[4];
                layer_rgba(pick * LAYERS + i % LAYERS, c);
                layer_rgba(images + pick * LAYERS + i % LAYERS, l);
                for (int m = 0; m < 4; m++) worst_c = fmax(worst_c, fabs(r[8 + m] - c[m]));
                for (int m = 0; m < 3; m++) worst_c = fmax(worst_c, fabs(r[12 + m] - l[m]));
                uint32_t pixel[2] = {(uint32_t)i, 3u * (uint32_t)i};
                worst_xi = fmax(worst_xi,
                                fabs(r[17] - core_hash_float((pixel[0] * 7919u + pixel[1] * 104729u) ^ 0x9e3779b9u)));
            }
            gfx_buffer_destroy(&qb);
            gfx_buffer_destroy(&ob);
        }
        gfx_texture_destroy(&tex);
    }
    double worst_share = 0.0;
    for (int v = 0; v < BB_VIEW_MAX; v++) worst_share = fmax(worst_share, fabs(share[v] - want_share[v]) / picks);
    printf("GPU vs CPU over %d view directions x 3 winds x 3 view sets: weight per view %.2e, picks differing %d "
           "of %d, texel of the pick %.2e, pixel draw %.2e; views' share of the picks against their weights %.4f\n",
           QUERIES, worst_w, picks_differ, picks, worst_c, worst_xi, worst_share);
    /* Directions within rounding of a view's angle may split the weight
     * between its neighbours differently; 2e-3 of weight is far below a
     * wrong pick (a whole view's weight). */
    CHECK(worst_w < 2e-3);
    CHECK(picks_differ <= picks / 500);
    CHECK(worst_c < 4e-3);
    CHECK(worst_xi == 0.0);
    CHECK(worst_share < 0.01);
    free(q);
    free(res);
    gfx_program_destroy(&p);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

/* test_bb_gpu_lod: the billboard cards thinned with distance, the kept
 * ones widened (coverage-preserving thinning, billboard/bb_lod.h), on a
 * 64 m field of 0.5 x 0.4 m cards, the WIDTH rule at a focal length of
 * 300 px and 15 px (thinning from about 10 m on), the camera 1.7 m up at
 * its -z edge looking along +z:
 *   a) bb_lod_card of bb_lod.glsl on the GPU over the field's cards read
 *      back equals its C twin within 1e-4 (weight and widening), for the
 *      width rule with and without the shrink window and compensation and
 *      for the levels rule and off;
 *   b) at three camera positions of a dolly the cards' drawn area (width
 *      times weight times widening, times height) over the 20-30 m band
 *      stays within 5 % of the full field's there, while the cards kept
 *      there are fewer than 60 % of its cards;
 *   c) backing away 5 cm a frame for 60 frames, no card whose weight is
 *      above 0.15 in a frame is gone in the next; with lod.no_shrink the
 *      same check finds such pops (it can fail);
 *   d) both paths draw it: a small field seen from 6 m, thinned hard,
 *      differs from the unthinned drawing, and the compute rasterizer's
 *      image agrees with the hardware path's (test_bb_gpu_render's
 *      bounds). */
#include "test.h"
#include "test_gl.h"

#include "bb_gpu_test_util.h"
#include "billboard/bb_lod.h"
#include "blade/blade.h"
#include "common/bindings_tests.glsl"

#define FOCAL 300.0f
#define BAND_LO 20.0f
#define BAND_HI 30.0f

typedef struct cards_t {
    test_readback_t rb;
    gfx_program_t prog;
    gfx_buffer_t in, out;
    float (*got)[2];
} cards_t;

static float eye_z(float back) { return -32.0f - back; }

/* The cards' weight and widening on the GPU (bb_lod_eval.comp) from eye;
 * counts GPU-vs-CPU differences over 1e-4 into *differ, the worst in *worst. */
static void eval(cards_t *c, const blade_lod_t *rule, const float eye[3], int *differ, double *worst)
{
    int n = c->rb.info.billboards;
    glUseProgram(c->prog.id);
    glUniform1ui(gfx_uniform(c->prog, "u_count"), (GLuint)n);
    glUniform3fv(gfx_uniform(c->prog, "u_eye"), 1, eye);
    blade_lod_uniforms(c->prog, rule, FOCAL, BB_LOD_CULL);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_IN, c->in.id);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, TEST_BIND_OUT, c->out.id);
    glDispatchCompute(((GLuint)n + 63u) / 64u, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    CHECK(gfx_buffer_read(c->out, 0, sizeof *c->got * (size_t)n, c->got));
    for (int i = 0; i < n; i++) {
        blade_lod_draw_t l = bb_lod_card(rule, &c->rb.pts[i], eye, FOCAL);
        double e = fmax(fabs(c->got[i][0] - l.weight), fabs(c->got[i][1] - l.scale));
        *worst = fmax(*worst, e);
        *differ += !(e <= 1e-4);
    }
}

static float dist(const bb_point_t *p, const float eye[3])
{
    float dx = p->position[0] - eye[0], dy = p->position[1] - eye[1], dz = p->position[2] - eye[2];
    return sqrtf(dx * dx + dy * dy + dz * dz);
}

/* d) the small field of the render tests drawn by either path into tgt. */
static void draw(bb_field_t *f, const gfx_target_t *tgt, raster_t *r, const blade_lod_t *lod)
{
    mat4 vp;
    vec3 eye = {0.0f, 4.5f, 4.0f};
    test_view(eye, vp);
    bb_draw_desc_t d = test_draw_desc(vp, eye, 0.5f);
    d.lod = lod;
    d.focal_px = blade_lod_focal(d.view.viewproj, 128);
    test_draw_path(f, tgt, r, &d);
}

static void paths(void)
{
    terrain_mesh_t terrain;
    bb_field_desc_t desc;
    CHECK(test_small_field(&terrain, &desc));
    bb_field_t *f = bb_field_make(&desc);
    CHECK(f);
    gfx_target_t tgt = gfx_target_make(&(gfx_target_desc_t){.w = 192, .h = 128, .samples = 4, .label = "bb.lod"});
    raster_t r;
    CHECK(raster_make(&r, &(raster_desc_t){.w = 192, .h = 128}));
    blade_lod_t hard = {.start = 1.0f, .width_px = 40.0f};
    core_image_t full, hw, cs;
    draw(f, &tgt, NULL, NULL);
    CHECK(gfx_target_read(&tgt, &full));
    draw(f, &tgt, NULL, &hard);
    CHECK(gfx_target_read(&tgt, &hw));
    draw(f, &tgt, &r, &hard);
    CHECK(gfx_target_read(&tgt, &cs));
    test_image_result_t thinned = test_image_diff(&full, &hw, &(test_image_cmp_t){.mean_threshold = 1e9}, NULL);
    test_image_cmp_t bound = {.mean_threshold = 2.3, .fail_budget = 0.025};
    test_image_result_t both = test_image_diff(&hw, &cs, &bound, NULL);
    double rgb[3];
    double grass_full = test_grass_pixels(&full, rgb), grass_hw = test_grass_pixels(&hw, rgb);
    printf("d) thinned hard from 6 m: hardware path vs unthinned mean difference %.2f, grass pixels %.3f -> %.3f; "
           "compute vs hardware path %.2f, %.1f %% of pixels over 24\n",
           thinned.mean_diff, grass_full, grass_hw, both.mean_diff, 100.0 * both.fail_fraction);
    CHECK(thinned.mean_diff > 3.0);
    CHECK(both.pass);
    core_image_free(&full);
    core_image_free(&hw);
    core_image_free(&cs);
    raster_destroy(&r);
    gfx_target_destroy(&tgt);
    bb_field_destroy(f);
    terrain_free(&terrain);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    terrain_mesh_t terrain;
    CHECK(terrain_make_heightfield(&terrain, &(terrain_desc_t){.size = 64, .resolution = 16, .height = 0.05f}, 5));
    bb_field_t *f = bb_field_make(&(bb_field_desc_t){.terrain = &terrain, .seed = 7, .density = 12,
                                                     .size = {0.5f, 0.4f}, .layout = {.size = 32, .clump_size = 32}});
    CHECK(f);
    cards_t c = {.rb = test_readback_make(f)};
    test_readback_read(f, &c.rb, false);
    int n = c.rb.info.billboards;
    printf("field: %d cards\n", n);
    CHECK(n > 10000);
    c.prog = gfx_program_make(&(gfx_program_desc_t){.cs = "tests/bb_lod_eval.comp", .label = "bb_lod"});
    CHECK(c.prog.id != 0);
    c.in = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof *c.rb.pts * (size_t)n, .data = c.rb.pts,
                                                .label = "bb_lod.in"});
    c.out = gfx_buffer_make(&(gfx_buffer_desc_t){.size = sizeof *c.got * (size_t)n, .label = "bb_lod.out"});
    c.got = malloc(sizeof *c.got * (size_t)n);
    float(*prev)[2] = malloc(sizeof *prev * (size_t)n);
    CHECK(c.got && prev);
    int differ = 0;
    double worst = 0.0;

    /* a) the other rules; b) and c) below run the default's twin too */
    static const blade_lod_t rules[] = {
        {.width_px = 15.0f, .no_compensation = true},
        {.width_px = 15.0f, .no_shrink = true, .max_scale = 2.0f},
        {.rule = BLADE_LOD_LEVELS, .levels = 4, .level_distance = 50.0f},
        {.rule = BLADE_LOD_OFF},
    };
    for (size_t k = 0; k < sizeof rules / sizeof rules[0]; k++) {
        blade_lod_t rule = bb_lod_rule(&rules[k]);
        eval(&c, &rule, (float[3]){0.0f, 1.7f, eye_z(0.0f)}, &differ, &worst);
    }

    /* b) coverage across a dolly */
    blade_lod_t rule = bb_lod_rule(&(blade_lod_t){.width_px = 15.0f});
    static const float dolly[] = {0.0f, 4.0f, 8.0f};
    for (int k = 0; k < 3; k++) {
        float eye[3] = {0.0f, 1.7f, eye_z(dolly[k])};
        eval(&c, &rule, eye, &differ, &worst);
        double full = 0.0, drawn = 0.0;
        int cards = 0, kept = 0;
        for (int i = 0; i < n; i++) {
            const bb_point_t *p = &c.rb.pts[i];
            float d = dist(p, eye);
            if (d < BAND_LO || d >= BAND_HI) continue;
            full += p->size[0] * p->size[1];
            drawn += p->size[0] * p->size[1] * c.got[i][0] * c.got[i][1];
            cards++;
            kept += c.got[i][0] > 0.0f;
        }
        printf("b) camera %4.1f m back: %d-%d m, %d cards, %d kept (%.2f); drawn area / full %.4f\n",
               (double)dolly[k], (int)BAND_LO, (int)BAND_HI, cards, kept, (double)kept / cards, drawn / full);
        CHECK(cards > 2000 && (double)kept < 0.6 * cards);
        CHECK(fabs(drawn / full - 1.0) <= 0.05);
    }

    /* c) no pops while backing away: with the shrink window, then without */
    for (int no_shrink = 0; no_shrink < 2; no_shrink++) {
        blade_lod_t r = bb_lod_rule(&(blade_lod_t){.width_px = 15.0f, .no_shrink = no_shrink});
        int pops = 0, vanished = 0;
        eval(&c, &r, (float[3]){0.0f, 1.7f, eye_z(0.0f)}, &differ, &worst);
        memcpy(prev, c.got, sizeof *prev * (size_t)n);
        for (int frame = 1; frame <= 60; frame++) {
            eval(&c, &r, (float[3]){0.0f, 1.7f, eye_z(0.05f * (float)frame)}, &differ, &worst);
            for (int i = 0; i < n; i++) {
                if (prev[i][0] <= 0.0f || c.got[i][0] > 0.0f) continue;
                vanished++;
                pops += prev[i][0] > 0.15f;
            }
            memcpy(prev, c.got, sizeof *prev * (size_t)n);
        }
        printf("c) %s: 60 frames backing 5 cm each, %d cards gone, %d of them at weight > 0.15\n",
               no_shrink ? "no shrink window" : "shrink window", vanished, pops);
        CHECK(vanished > 100);
        if (no_shrink) CHECK(pops > 100);
        else CHECK(pops == 0);
    }
    printf("a) GPU vs CPU over every evaluation: %d cards differ, worst %.2g\n", differ, worst);
    CHECK(differ == 0 && worst < 1e-4);

    free(prev);
    free(c.got);
    gfx_buffer_destroy(&c.in);
    gfx_buffer_destroy(&c.out);
    gfx_program_destroy(&c.prog);
    test_readback_free(&c.rb);
    bb_field_destroy(f);
    terrain_free(&terrain);
    paths();
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

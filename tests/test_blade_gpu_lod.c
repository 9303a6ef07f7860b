/* test_blade_gpu_lod: blade mode's thinning with distance on the GPU
 * (blade_cull.comp with common/lod.glsl; coverage-preserving thinning,
 * blade_lod.h) over a 12 x 60 m strip of grass, the distance test alone
 * on (orientation, frustum and occlusion off), the WIDTH rule thinning
 * from 10 m on (a focal length of 300 px), cut at 40 m:
 *   a) each frame's GPU survivors and width factors equal the CPU twin's
 *      (blade_ref_cull; factors within 1e-4);
 *   b) at three camera positions of a dolly the survivors' summed drawn
 *      width (width times factor) over the 20-30 m band stays within 5 %
 *      of the full field's there, while the survivors there are fewer
 *      than 60 % of its blades;
 *   c) dollying back 5 cm a frame for 60 frames, no survivor of a frame
 *      whose weight (blade_lod_blade) is above 0.15 is gone in the next;
 *      with lod.no_shrink the same check finds such pops (it can fail). */
#include "blade/blade.h"
#include "test.h"
#include "test_gl.h"

#include <cglm/cglm.h>
#include <stdlib.h>
#include <string.h>

#define FOCAL 300.0f
#define CUT 40.0f
#define BAND_LO 20.0f
#define BAND_HI 30.0f

static bool seed_strip(blade_field_t *f)
{
    static const float pos[] = {-6, 0, 0, 6, 0, 0, 6, 0, 60, -6, 0, 60};
    static const uint32_t idx[] = {0, 2, 1, 0, 3, 2};
    blade_mesh_t mesh = {pos, NULL, 4, idx, 6};
    return blade_seed_mesh(&mesh, &(blade_seed_desc_t){.seed = 9, .population = {.density = 24.0f}}, f);
}

/* The cull desc of a camera 1.7 m up at z, looking along +z. */
static blade_cull_desc_t camera_at(float z, bool no_shrink)
{
    blade_cull_desc_t c = {.max_distance = CUT,
                           .focal_px = FOCAL,
                           .disable = BLADE_CULL_ORIENTATION | BLADE_CULL_FRUSTUM | BLADE_CULL_OCCLUSION,
                           .lod = {.no_shrink = no_shrink}};
    mat4 view, proj, vp;
    vec3 eye = {0.0f, 1.7f, z}, at = {0.0f, 0.0f, z + 20.0f}, up = {0, 1, 0};
    glm_lookat(eye, at, up, view);
    glm_perspective(glm_rad(60.0f), 1.5f, 0.1f, 200.0f, proj);
    glm_mat4_mul(proj, view, vp);
    memcpy(c.view.viewproj, vp, sizeof vp);
    memcpy(c.view.camera, eye, sizeof eye);
    return blade_cull_desc_defaults(&c);
}

/* One frame: the GPU survivors as a per-blade factor (0: not a survivor);
 * counts GPU-vs-CPU mismatches (set or factor) into *differ. */
static void cull_frame(blade_gpu_t *g, const blade_field_t *f, const blade_cull_desc_t *c, float *factor,
                       uint32_t *ids, float *got, int *differ)
{
    blade_gpu_cull(g, c, 0);
    uint32_t n = blade_gpu_read_survivors(g, ids, got);
    memset(factor, 0, f->padded_count * sizeof *factor);
    for (uint32_t i = 0; i < n; i++) factor[ids[i]] = got[i];
    size_t nref = blade_ref_cull(f->blades, f->padded_count, c, ids, got, NULL);
    *differ += (int)n != (int)nref;
    for (size_t i = 0; i < nref; i++) *differ += !(fabsf(factor[ids[i]] - got[i]) <= 1e-4f);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    blade_field_t f;
    CHECK(seed_strip(&f));
    printf("field: %zu blades, %zu patches\n", f.blade_count, f.patch_count);
    blade_gpu_t *g = blade_gpu_make(&(blade_gpu_desc_t){.field = &f, .path = BLADE_PATH_PULLING, .label = "lod_test"});
    CHECK(g);
    float *factor = malloc(f.padded_count * sizeof *factor), *prev = malloc(f.padded_count * sizeof *prev);
    float *got = malloc(f.padded_count * sizeof *got);
    uint32_t *ids = malloc(f.padded_count * sizeof *ids);
    int differ = 0;

    /* b) coverage across a dolly */
    static const float dolly[] = {0.0f, -4.0f, -8.0f};
    for (int k = 0; k < 3; k++) {
        blade_cull_desc_t c = camera_at(dolly[k], false);
        cull_frame(g, &f, &c, factor, ids, got, &differ);
        double full = 0.0, drawn = 0.0;
        int blades = 0, kept = 0;
        for (size_t i = 0; i < f.padded_count; i++) {
            const blade_t *b = &f.blades[i];
            float d = blade_ref_cull_distance(b, &c);
            if (b->v1[3] <= 0.0f || d < BAND_LO || d >= BAND_HI) continue;
            full += b->v2[3];
            drawn += b->v2[3] * factor[i];
            blades++;
            kept += factor[i] > 0.0f;
        }
        printf("b) camera z %5.1f: %d-%d m, %d blades, %d survivors (%.2f); drawn width / full %.4f\n",
               (double)dolly[k], (int)BAND_LO, (int)BAND_HI, blades, kept, (double)kept / blades, drawn / full);
        CHECK(blades > 1000 && (double)kept < 0.6 * blades);
        CHECK(fabs(drawn / full - 1.0) <= 0.05);
    }

    /* c) no pops while backing away: with the shrink window, then without */
    for (int no_shrink = 0; no_shrink < 2; no_shrink++) {
        int pops = 0, vanished = 0;
        blade_cull_desc_t c = camera_at(0.0f, no_shrink);
        cull_frame(g, &f, &c, prev, ids, got, &differ);
        for (int frame = 1; frame <= 60; frame++) {
            blade_cull_desc_t next = camera_at(-0.05f * (float)frame, no_shrink);
            cull_frame(g, &f, &next, factor, ids, got, &differ);
            for (size_t i = 0; i < f.padded_count; i++) {
                if (prev[i] <= 0.0f || factor[i] > 0.0f) continue;
                const blade_t *b = &f.blades[i];
                blade_lod_draw_t l = blade_lod_blade(&c.lod, (uint32_t)i, blade_ref_cull_distance(b, &c), b->v2[3],
                                                     c.focal_px, c.max_distance);
                vanished++;
                pops += l.weight > 0.15f;
            }
            memcpy(prev, factor, f.padded_count * sizeof *prev);
            c = next;
        }
        printf("c) %s: 60 frames backing 5 cm each, %d survivors gone, %d of them at weight > 0.15\n",
               no_shrink ? "no shrink window" : "shrink window", vanished, pops);
        CHECK(vanished > 100);
        if (no_shrink) CHECK(pops > 100);
        else CHECK(pops == 0);
    }
    printf("a) GPU vs CPU over every frame: %d survivors or factors differ\n", differ);
    CHECK(differ == 0);

    free(factor);
    free(prev);
    free(got);
    free(ids);
    blade_gpu_destroy(g);
    blade_field_free(&f);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

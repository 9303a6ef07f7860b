/* test_blade_gpu_cull: blade_cull.comp (Jahrmann & Wimmer 2017 eq. 17-20,
 * with the thinning of blade_lod.h) through blade_gpu_cull against the CPU
 * reference blade_ref_cull for a fixed camera: per-test culled counts equal
 * (patch culling off), survivor sets equal (patch culling on and off), with
 * and without a depth texture, every survivor's width factor equal to the
 * CPU's within 1e-4, and the draw count in the indirect command equals the
 * survivors for both render paths. With patch culling (on the GPU) every patch the CPU rule
 * (blade_ref_box_outside) keeps is listed, once, in nondecreasing distance
 * bucket (blade_ref_patch_bucket: the order the draw appends them in). Also: the non-blocking statistics
 * become valid a few frames late without a wait. The LEVELS rule (eq. 19-20
 * as the text states them) over 20 m cut beyond or before the levels' end
 * (lod.level_distance != max_distance) matches the reference too. */
#include "blade/blade.h"
#include "test.h"
#include "test_gl.h"

#include <cglm/cglm.h>
#include <stdlib.h>
#include <string.h>

enum { DW = 192, DH = 128 };

static bool seed_plane(blade_field_t *f)
{
    static const float pos[] = {-14, 0, -14, 14, 0, -14, 14, 0, 14, -14, 0, 14};
    static const uint32_t idx[] = {0, 2, 1, 0, 3, 2};
    blade_mesh_t mesh = {pos, NULL, 4, idx, 6};
    return blade_seed_mesh(&mesh, &(blade_seed_desc_t){.seed = 21, .population = {.density = 6.0f}, .patch_size = 64},
                           f);
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

static void camera(blade_cull_desc_t *c)
{
    mat4 view, proj, vp;
    vec3 eye = {1.0f, 1.7f, -12.0f}, at = {-2.0f, 0.0f, 4.0f}, up = {0, 1, 0};
    glm_lookat(eye, at, up, view);
    glm_perspective(glm_rad(60.0f), (float)DW / DH, 0.1f, 200.0f, proj);
    glm_mat4_mul(proj, view, vp);
    memcpy(c->view.viewproj, vp, sizeof vp);
    memcpy(c->view.camera, eye, sizeof eye);
    c->max_distance = 20.0f;
    c->focal_px = 300.0f; /* the WIDTH rule thins from its start, 10 m, on: the widest blade is 5 px there */
}

/* Runs one configuration and compares with the reference; cut > 0 culls
 * at cut metres with the LEVELS rule over 20 m, else the default thinning
 * (WIDTH, from 10 m) to 20 m. */
static void compare(const blade_field_t *f, blade_render_path_t path, bool patch_cull, const float *depth,
                    GLuint depth_tex, float cut, const char *name)
{
    blade_cull_desc_t cd = {0};
    camera(&cd);
    if (cut > 0.0f) {
        cd.lod = (blade_lod_t){.rule = BLADE_LOD_LEVELS, .level_distance = cd.max_distance};
        cd.max_distance = cut;
    }
    blade_gpu_t *g = blade_gpu_make(&(blade_gpu_desc_t){.field = f, .path = path, .no_patch_cull = !patch_cull,
                                                         .label = "cull_test"});
    CHECK(g);
    blade_gpu_cull(g, &cd, depth_tex);
    blade_gpu_stats_t st = blade_gpu_stats(g, true);

    blade_cull_desc_t rd = cd;
    rd.depth = depth;
    rd.depth_w = DW;
    rd.depth_h = DH;
    uint32_t *ref = malloc(f->padded_count * sizeof *ref), *got = malloc(f->padded_count * sizeof *got);
    float *ref_factor = malloc(f->padded_count * sizeof *ref_factor);
    float *got_factor = malloc(f->padded_count * sizeof *got_factor);
    blade_cull_stats_t rs;
    size_t nref = blade_ref_cull(f->blades, f->padded_count, &rd, ref, ref_factor, &rs);
    uint32_t ngot = blade_gpu_read_survivors(g, got, got_factor);
    uint32_t cmd[4];
    blade_gpu_read_command(g, cmd);
    /* the GPU's (id, factor) pairs in id order */
    uint64_t *pairs = malloc((ngot ? ngot : 1) * sizeof *pairs);
    for (uint32_t i = 0; i < ngot; i++) {
        uint32_t bits;
        memcpy(&bits, &got_factor[i], sizeof bits);
        pairs[i] = (uint64_t)got[i] << 32 | bits;
    }
    qsort(pairs, ngot, sizeof *pairs, cmp_u64);
    float worst = 0.0f, widest = 0.0f, least = 1.0f;
    for (uint32_t i = 0; i < ngot; i++) {
        uint32_t bits = (uint32_t)pairs[i];
        got[i] = (uint32_t)(pairs[i] >> 32);
        memcpy(&got_factor[i], &bits, sizeof bits);
        if (i < nref && got[i] == ref[i]) worst = fmaxf(worst, fabsf(got_factor[i] - ref_factor[i]));
        widest = fmaxf(widest, got_factor[i]);
        least = fminf(least, got_factor[i]);
    }
    free(pairs);
    printf("%-34s ref: orient %u frustum %u dist %u occl %u visible %zu | gpu: %u %u %u %u visible %u "
           "patch-culled %u (%u patches drawn of %zu)\n",
           name, rs.culled[0], rs.culled[1], rs.culled[2], rs.culled[3], nref, st.culled[0], st.culled[1],
           st.culled[2], st.culled[3], st.survivors, st.patch_culled, st.patches_drawn, f->patch_count);
    printf("%-34s width factors %.3f to %.3f, worst |gpu - cpu| %.2g\n", name, least, widest, worst);
    CHECK(st.valid);
    CHECK(ngot == nref);
    CHECK(ngot == nref && memcmp(got, ref, nref * sizeof *ref) == 0);
    CHECK(worst <= 1e-4f);
    if (cut <= 0.0f) CHECK(widest > 1.5f && least < 0.5f); /* the thinning widens and shrinks here */
    CHECK(st.survivors == nref);
    if (path == BLADE_PATH_PULLING) {
        CHECK(cmd[1] == nref);
        CHECK(cmd[0] == 2u * (8u + 1u));
    } else {
        CHECK(cmd[0] == nref);
        CHECK(cmd[1] == 1u);
    }
    uint32_t sum = st.survivors + st.patch_culled;
    for (int i = 0; i < 4; i++) sum += st.culled[i];
    CHECK(sum == f->blade_count);
    if (!patch_cull) {
        for (int i = 0; i < 4; i++) CHECK(st.culled[i] == rs.culled[i]);
        CHECK(st.patch_culled == 0);
    } else {
        /* a blade of a culled patch fails the frustum test, so the reference
         * counts it as orientation or frustum; the later tests agree exactly */
        CHECK(st.patch_culled > 0);
        int unordered = 0, missing = 0, twice = 0, extra = 0;
        uint32_t *listed = malloc(f->patch_count * sizeof *listed);
        char *seen = calloc(f->patch_count, 1);
        CHECK(blade_gpu_read_patches(g, listed) == st.patches_drawn);
        uint32_t prev_bucket = 0;
        for (uint32_t k = 0; k < st.patches_drawn; k++) {
            const blade_aabb_t *box = &f->patch_aabbs[listed[k]];
            uint32_t bucket =
                blade_ref_patch_bucket(cd.view.camera, box->min, box->max, cd.max_distance, BLADE_PATCH_BUCKETS);
            unordered += k > 0 && bucket < prev_bucket;
            prev_bucket = bucket;
            twice += seen[listed[k]]++ > 0;
        }
        for (size_t p = 0; p < f->patch_count; p++) {
            const blade_aabb_t *box = &f->patch_aabbs[p];
            bool kept = !blade_ref_box_outside(box->min, box->max, cd.view.viewproj, 0.1f);
            missing += kept && !seen[p];
            extra += !kept && seen[p];
        }
        free(listed);
        free(seen);
        printf("%-34s %u visible patches: %d out of bucket order, %d kept by the CPU rule not listed, %d listed twice, "
               "%d listed the CPU rule culls\n",
               name, st.patches_drawn, unordered, missing, twice, extra);
        CHECK(st.patches_drawn > 2 && unordered == 0 && missing == 0 && twice == 0);
        CHECK(st.culled[0] + st.culled[1] + st.patch_culled == rs.culled[0] + rs.culled[1]);
        CHECK(st.culled[2] == rs.culled[2] && st.culled[3] == rs.culled[3]);
    }
    if (depth) CHECK(rs.culled[3] > 100);
    free(ref);
    free(got);
    free(ref_factor);
    free(got_factor);
    blade_gpu_destroy(g);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    blade_field_t f;
    CHECK(seed_plane(&f));
    printf("field: %zu blades, %zu patches\n", f.blade_count, f.patch_count);

    /* synthetic depth of an opaque wall: window depth 0.9 on the left half
     * of the screen (NDC 0.8; the far grass behind it is occluded), 1.0
     * elsewhere. Row 0 is the bottom, as the texture and the reference use. */
    float *depth = malloc(DW * DH * sizeof *depth), *ndc = malloc(DW * DH * sizeof *ndc);
    for (int y = 0; y < DH; y++)
        for (int x = 0; x < DW; x++) {
            depth[y * DW + x] = x < DW / 2 && y < DH * 3 / 4 ? 0.9f : 1.0f;
            ndc[y * DW + x] = 2.0f * depth[y * DW + x] - 1.0f;
        }
    gfx_texture_t tex = gfx_texture_make(&(gfx_texture_desc_t){.w = DW, .h = DH, .format = GL_DEPTH_COMPONENT32F,
                                                               .filter = GL_NEAREST, .data = depth,
                                                               .upload_format = GL_DEPTH_COMPONENT,
                                                               .upload_type = GL_FLOAT, .label = "cull_test.depth"});
    CHECK(tex.id != 0);

    compare(&f, BLADE_PATH_TESSELLATION, false, NULL, 0, 0.0f, "tess, no patch cull, no depth");
    compare(&f, BLADE_PATH_TESSELLATION, false, ndc, tex.id, 0.0f, "tess, no patch cull, depth");
    compare(&f, BLADE_PATH_TESSELLATION, true, NULL, 0, 0.0f, "tess, patch cull, no depth");
    compare(&f, BLADE_PATH_PULLING, true, ndc, tex.id, 0.0f, "pull, patch cull, depth");
    compare(&f, BLADE_PATH_PULLING, false, ndc, tex.id, 0.0f, "pull, no patch cull, depth");
    compare(&f, BLADE_PATH_PULLING, false, NULL, 0, 30.0f, "pull, no patch cull, cut 30 m");
    compare(&f, BLADE_PATH_PULLING, false, NULL, 0, 9.0f, "pull, no patch cull, cut 9 m");

    /* non-blocking statistics: invalid before any cull, valid after a few
     * frames of culling without ever waiting */
    blade_gpu_t *g = blade_gpu_make(&(blade_gpu_desc_t){.field = &f, .label = "cull_async"});
    CHECK(g);
    CHECK(!blade_gpu_stats(g, false).valid);
    blade_cull_desc_t cd = {0};
    camera(&cd);
    bool valid = false;
    int frames = 0;
    for (; frames < 50 && !valid; frames++) {
        blade_gpu_cull(g, &cd, 0);
        glFlush();
        valid = blade_gpu_stats(g, false).valid;
    }
    printf("non-blocking stats valid after %d cull(s)\n", frames);
    CHECK(valid);
    blade_gpu_destroy(g);

    gfx_texture_destroy(&tex);
    free(depth);
    free(ndc);
    blade_field_free(&f);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

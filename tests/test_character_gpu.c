/* test_character_gpu: GPU skinning (skin.comp) read back and compared with
 * character_skin_cpu for the humanoid and the quadruped at several
 * animation times; the billboard object's bounding sphere holds every
 * skinned vertex; 8 characters share 2 models and update without GL errors;
 * bad model files, unknown clips and ranges off the timeline fail with
 * exactly one error line; named ranges play as clips; a clip without
 * duration gives way to the next; morph targets reach the GPU skinning
 * (the clips fixture, also compared with the CPU above); a
 * 128x128 golden image of the humanoid mid-stride (character_walk.png);
 * the animation level of detail (character_set_view): a character is
 * posed every character_pose_step-th update, its skinned vertices then
 * equal those of a set without it, between poses they stay, and its
 * bounding sphere follows the walk and holds them as drawn; the distance
 * is horizontal. */
#include "test.h"
#include "test_gl.h"

#include "character/character.h"

#include <string.h>

static scene_character_t walker(const char *model, float x0, float z0, float x1, float z1)
{
    scene_character_t c = {.speed = 1.2f, .scale = 1.0f, .waypoint_count = 2, .loop = true};
    snprintf(c.model, sizeof c.model, "%s", model);
    c.waypoints[0][0] = x0, c.waypoints[0][1] = z0, c.waypoints[1][0] = x1, c.waypoints[1][1] = z1;
    return c;
}

/* GPU vs CPU skinning at several times; also checks the bounding sphere. */
static void check_skinning(const char *model)
{
    scene_character_t c = walker(model, -3, 1, 4, -2);
    character_set_t set;
    CHECK(character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1}));
    if (!set.count) return;
    const character_instance_t *inst = &set.items[0];
    const character_model_t *m = &set.assets[0].model;
    int n = m->vertex_count;
    float *pos = malloc((size_t)n * 3 * sizeof(float)), *nrm = malloc((size_t)n * 3 * sizeof(float));
    character_skinned_vertex_t *gpu = malloc((size_t)n * sizeof *gpu);
    const float times[] = {0.0f, 0.13f, 0.41f, 0.77f, 1.9f, 3.3f};
    double max_pos = 0.0, max_nrm = 0.0, max_out = -1e9;
    for (size_t ti = 0; ti < sizeof times / sizeof times[0]; ti++) {
        character_set_update(&set, times[ti], 1.0f / 60.0f);
        gfx_buffer_read(inst->skinned, 0, (size_t)n * sizeof *gpu, gpu);
        character_skin_cpu(m, &inst->pose, pos, nrm);
        for (int v = 0; v < n; v++) {
            float w[3];
            for (int k = 0; k < 3; k++) {
                max_pos = fmax(max_pos, fabs(gpu[v].pos[k] - pos[3 * v + k]));
                max_nrm = fmax(max_nrm, fabs(gpu[v].normal[k] - nrm[3 * v + k]));
            }
            CHECK(gpu[v].pos[3] == 1.0f && gpu[v].normal[3] == 0.0f);
            character_mat4_point(inst->model, &gpu[v].pos[0], w);
            double d = sqrt((w[0] - inst->centre[0]) * (w[0] - inst->centre[0]) +
                            (w[1] - inst->centre[1]) * (w[1] - inst->centre[1]) +
                            (w[2] - inst->centre[2]) * (w[2] - inst->centre[2]));
            max_out = fmax(max_out, d - inst->radius);
        }
    }
    printf("%s: GPU vs CPU skinning max |dpos| %.3g m, max |dnormal| %.3g; bounding sphere r %.3f m, "
           "max (dist - r) %.3g m; %d capsules, %d spheres\n",
           model, max_pos, max_nrm, inst->radius, max_out, inst->capsule_count, inst->sphere_count);
    CHECK(max_pos < 1e-4);
    CHECK(max_nrm < 1e-3);
    CHECK(max_out <= 1e-4);
    /* not absurdly loose: models are < 1.8 m; the 1 x 1 quad's bone sphere
     * (0.71 m) grows by how far its targets reach (0.5 + 0.5 m) */
    CHECK(inst->radius < (m->morph_count ? 1.75f : 1.5f));
    character_object_t obj;
    character_bb_object(inst, &obj);
    CHECK(obj.vao == inst->vao && obj.index_count == m->index_count && obj.index_type == GL_UNSIGNED_INT);
    CHECK(obj.radius == inst->radius && memcmp(obj.model, inst->model, sizeof obj.model) == 0);
    free(pos), free(nrm), free(gpu);
    character_set_destroy(&set);
}

static void check_errors(void)
{
    const char *bad = "/tmp/meadow_character_bad.gltf";
    FILE *f = fopen(bad, "w");
    if (f) {
        fputs("{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ { \"primitives\": [ {", f);
        fclose(f);
    }
    scene_character_t c = walker(bad, 0, 0, 1, 0);
    character_set_t set;
    int before = core_log_error_count();
    CHECK(!character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1}));
    CHECK_NEAR(core_log_error_count() - before, 1, 0);
    CHECK(gfx_live_objects() == 0);

    c = walker("models/no_such_model.gltf", 0, 0, 1, 0);
    before = core_log_error_count();
    CHECK(!character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1}));
    CHECK_NEAR(core_log_error_count() - before, 1, 0);

    c = walker("models/humanoid.gltf", 0, 0, 1, 0);
    before = core_log_error_count();
    CHECK(!character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1, .clip_override = "run"}));
    CHECK_NEAR(core_log_error_count() - before, 1, 0);
    CHECK(gfx_live_objects() == 0);

    /* --character/--clip overrides with an empty scene: one character. */
    CHECK(character_set_make(&set, &(character_set_desc_t){.model_override = "models/quadruped.gltf",
                                                           .clip_override = "walk"}));
    CHECK(set.count == 1 && set.items[0].clip == 0 && strstr(set.assets[0].path, "quadruped.gltf"));
    character_set_destroy(&set);
    CHECK(character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1, .clip_override = "idle"}));
    CHECK(set.count == 1 && set.items[0].clip == 1);
    character_set_destroy(&set);
}

/* Named ranges ("clips") and the fallback from a clip without duration:
 * the range plays as its own clip; a range past the timeline is one error
 * line and nothing left; the clips fixture's clip 0 has no duration (one
 * warning naming it and "grow"), and "grow"'s morph targets reach the GPU
 * skinning (the quad's box grows as the weights say). */
static void check_clip_ranges_and_morphs(void)
{
    scene_character_t c = walker("models/humanoid.gltf", 0, 0, 1, 0);
    snprintf(c.clip_name, sizeof c.clip_name, "stride");
    c.clip_index = -1;
    c.clip_range_count = 1;
    c.clip_ranges[0] = (scene_clip_range_t){.name = "stride", .range = {250, 750}};
    character_set_t set;
    CHECK(character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1}));
    if (set.count) {
        const character_clip_t *clip = &set.assets[0].model.clips[set.items[0].clip];
        CHECK(!strcmp(clip->name, "stride") && clip->cut[0] == 250 && clip->cut[1] == 750);
        CHECK_NEAR(clip->duration, 0.5, 1e-6);
        character_set_destroy(&set);
    }
    c.clip_ranges[0].range[1] = 5000; /* the walk has 1000 ticks */
    int before = core_log_error_count();
    CHECK(!character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1}));
    CHECK_NEAR(core_log_error_count() - before, 1, 0);
    CHECK(gfx_live_objects() == 0);

    scene_character_t q = {.speed = 1.2f, .scale = 1.0f}; /* stands: clip time = time */
    snprintf(q.model, sizeof q.model, "tests/data/models/clips.gltf");
    int warns = core_log_warn_count();
    CHECK(character_set_make(&set, &(character_set_desc_t){.characters = &q, .count = 1}));
    CHECK(core_log_warn_count() > warns);
    if (!set.count) return;
    const character_instance_t *inst = &set.items[0];
    const character_model_t *m = &set.assets[0].model;
    CHECK(inst->clip == 1 && !strcmp(m->clips[1].name, "grow") && inst->morphed != NULL);
    character_skinned_vertex_t gpu[4];
    const float want[3][3] = {{0.5f, 1, 1.25f}, {1, 1, 1.5f}, {1.5f, 1.25f, 1.25f}}; /* t, width, height */
    for (int i = 0; i < 3 && m->vertex_count == 4; i++) {
        character_set_update(&set, want[i][0], 1.0f / 60.0f);
        gfx_buffer_read(inst->skinned, 0, sizeof gpu, gpu);
        float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
        for (int v = 0; v < 4; v++)
            for (int k = 0; k < 2; k++) lo[k] = fminf(lo[k], gpu[v].pos[k]), hi[k] = fmaxf(hi[k], gpu[v].pos[k]);
        printf("clips.gltf at %.1f s: morph weights %.3f %.3f, GPU box %.4f x %.4f m\n", (double)want[i][0],
               (double)inst->pose.morph[0], (double)inst->pose.morph[1], (double)(hi[0] - lo[0]),
               (double)(hi[1] - lo[1]));
        CHECK_NEAR(hi[0] - lo[0], want[i][1], 1e-5);
        CHECK_NEAR(hi[1] - lo[1], want[i][2], 1e-5);
    }
    character_set_destroy(&set);
    CHECK(gfx_live_objects() == 0);
}

static void check_eight(void)
{
    scene_character_t cs[9];
    for (int i = 0; i < 9; i++)
        cs[i] = walker(i % 2 ? "models/quadruped.gltf" : "models/humanoid.gltf", (float)i - 4, -3, (float)i - 4, 3);
    cs[2].clip_index = 1, cs[2].clip_name[0] = 0; /* humanoid idle by index */
    cs[5].scale = 2.0f;
    character_set_t set;
    CHECK(character_set_make(&set, &(character_set_desc_t){.characters = cs, .count = 9, .capsules = 6}));
    CHECK(set.count == 9 && set.asset_count == 2);
    for (int f = 1; f <= 10; f++) character_set_update(&set, (float)f / 60.0f, 1.0f / 60.0f);
    CHECK(gfx_check_errors("eight characters") == 0);
    float spheres[512][4];
    int need = character_set_spheres(&set, spheres, 512), sum = 0;
    for (int i = 0; i < set.count; i++) {
        CHECK(set.items[i].capsule_count <= 6);
        sum += set.items[i].sphere_count;
    }
    CHECK(need == sum && need <= 512);
    int warns = core_log_warn_count();
    CHECK(character_set_spheres(&set, spheres, 3) == need); /* too small: full count back, one warning */
    CHECK(core_log_warn_count() == warns + 1);
    character_object_t objs[9];
    CHECK(character_set_objects(&set, objs, 9) == 9);
    CHECK(objs[5].radius > 1.9f * objs[3].radius); /* scale 2 vs 1, same quadruped */
    printf("9 characters: %d proxy spheres with 6 capsules each\n", need);
    character_set_destroy(&set);
}

static void check_golden(void)
{
    /* The humanoid walks along +Z through the origin; seen from its left. */
    scene_character_t c = walker("models/humanoid.gltf", 0, -10, 0, 10);
    c.loop = false;
    character_set_t set;
    CHECK(character_set_make(&set, &(character_set_desc_t){.characters = &c, .count = 1}));
    if (!set.count) return;
    float t = 10.0f / 1.2f + 0.25f / fabsf(set.items[0].rate); /* a quarter cycle past the origin */
    character_set_update(&set, t, 0.0f);
    gfx_target_t tgt = gfx_target_make(&(gfx_target_desc_t){.w = 128, .h = 128, .samples = 4, .label = "golden"});
    mat4 view, proj, vp;
    glm_lookat((vec3){3.2f, 1.2f, set.items[0].position[2]}, (vec3){0, 0.85f, set.items[0].position[2]},
               (vec3){0, 1, 0}, view);
    glm_perspective(glm_rad(40.0f), 1.0f, 0.1f, 50.0f, proj);
    glm_mat4_mul(proj, view, vp);
    gfx_target_bind(&tgt);
    glClearColor(0.6f, 0.7f, 0.8f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    vec3 sun;
    glm_vec3_normalize_to((vec3){0.4f, 0.8f, 0.3f}, sun);
    character_set_draw(&set, (const float *)vp, (vec3){3.2f, 1.2f, 0}, sun);
    glDisable(GL_DEPTH_TEST);
    core_image_t img;
    CHECK(gfx_target_read(&tgt, &img));
    int body = 0;
    for (int i = 0; i < 128 * 128; i++) body += img.px[4 * i] > img.px[4 * i + 2] + 20; /* brownish, not sky */
    printf("golden: %d character pixels of %d\n", body, 128 * 128);
    CHECK(body > 600 && body < 6000);
    CHECK(test_image_check(&img, "character_walk", NULL));
    core_image_free(&img);
    gfx_target_destroy(&tgt);
    character_set_destroy(&set);
}

static void read_skinned(const character_instance_t *inst, int n, character_skinned_vertex_t *out)
{
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gfx_buffer_read(inst->skinned, 0, (size_t)n * sizeof *out, out);
}

/* Walkers 0, 15, 25 ... 95 m from a camera at the origin with lod_distance
 * 10 m (steps 1, 2, 3 ... 8) against the same set without it. */
static void check_lod(void)
{
    enum { N = 9, UPDATES = 48 };
    scene_character_t cs[N];
    for (int i = 0; i < N; i++) {
        float x = i ? 5.0f + 10.0f * (float)i : 0.0f;
        cs[i] = walker("models/humanoid.gltf", x, -2, x, 2);
    }
    character_set_t full, lod;
    CHECK(character_set_make(&full, &(character_set_desc_t){.characters = cs, .count = N}));
    CHECK(character_set_make(&lod, &(character_set_desc_t){.characters = cs, .count = N}));
    const float camera[3] = {0.0f, 0.0f, 0.0f};
    character_set_view(&lod, camera, 10.0f);
    int nv = full.assets[0].model.vertex_count;
    character_skinned_vertex_t *a = malloc((size_t)nv * sizeof *a), *b = malloc((size_t)nv * sizeof *b);
    character_skinned_vertex_t *last = malloc((size_t)N * (size_t)nv * sizeof *last);
    for (int i = 0; i < N; i++) read_skinned(&lod.items[i], nv, last + (size_t)i * (size_t)nv); /* make's pose */
    int poses[N] = {0}, differ = 0, moved = 0, posed_sum = 0;
    double outside = -1e9;
    for (int u = 0; u < UPDATES; u++) {
        float t = (float)u / 60.0f;
        character_set_update(&full, t, 1.0f / 60.0f);
        character_set_update(&lod, t, 1.0f / 60.0f);
        for (int i = 0; i < N; i++) {
            CHECK(full.items[i].posed);
            posed_sum += lod.items[i].posed;
            const character_instance_t *fi = &full.items[i], *li = &lod.items[i];
            CHECK(memcmp(fi->model, li->model, sizeof fi->model) == 0); /* the walk at every update */
            read_skinned(li, nv, b);
            if (li->posed) {
                poses[i]++;
                read_skinned(fi, nv, a);
                differ += memcmp(a, b, (size_t)nv * sizeof *a) != 0;
                memcpy(last + (size_t)i * (size_t)nv, b, (size_t)nv * sizeof *b);
            } else {
                moved += memcmp(last + (size_t)i * (size_t)nv, b, (size_t)nv * sizeof *b) != 0;
            }
            for (int v = 0; v < nv; v++) { /* drawn: this skin, this model matrix */
                float w[3];
                character_mat4_point(li->model, &b[v].pos[0], w);
                double d = sqrt((w[0] - li->centre[0]) * (w[0] - li->centre[0]) +
                                (w[1] - li->centre[1]) * (w[1] - li->centre[1]) +
                                (w[2] - li->centre[2]) * (w[2] - li->centre[2]));
                outside = fmax(outside, d - li->radius);
            }
        }
    }
    int bad_count = 0;
    for (int i = 0; i < N; i++) {
        int step = i ? i + 1 : 1;
        bad_count += poses[i] < UPDATES / step || poses[i] > UPDATES / step + 1;
    }
    printf("animation LOD: %d poses over %d updates of %d characters (%d without it); posed skins differing "
           "%d, skipped skins changed %d, drawn vertices outside the bounding sphere by %.3g m\n",
           posed_sum, UPDATES, N, UPDATES * N, differ, moved, outside);
    CHECK(bad_count == 0);
    CHECK(differ == 0 && moved == 0);
    CHECK(outside <= 1e-4);
    CHECK(posed_sum < UPDATES * N / 3);
    /* The distance is horizontal: the walker under a camera 500 m up is
     * posed at every update. */
    const float high[3] = {0.0f, 500.0f, 0.0f};
    character_set_view(&lod, high, 10.0f);
    int under = 0;
    for (int u = 0; u < 8; u++) {
        character_set_update(&lod, (float)(UPDATES + u) / 60.0f, 1.0f / 60.0f);
        under += lod.items[0].posed;
    }
    CHECK(under == 8);
    free(a), free(b), free(last);
    character_set_destroy(&full);
    character_set_destroy(&lod);
}

int main(void)
{
    core_log_set_quiet(true);
    test_gl_init();
    check_lod();
    check_skinning("models/humanoid.gltf");
    check_skinning("models/quadruped.gltf");
    check_skinning("tests/data/models/clips.gltf");
    check_errors();
    check_clip_ranges_and_morphs();
    check_eight();
    check_golden();
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

/* test_bb_octree: the billboard octree of Orthmann et al. 2009 (sec. 4).
 * Assign must give contiguous leaf ranges covering every billboard once;
 * the hierarchical collision/recovery state machine must match a flat
 * brute-force computation frame by frame over a scripted path; collect must
 * list exactly the non-empty leaves in the requested states and frustum;
 * sort_near_first must order them by their parent cell's distance; boxes
 * grown by the cards' widening (bb_lod_reach) keep the leaves the widened
 * cards reach. */
#include "billboard/bb_lod.h"
#include "billboard/bb_octree.h"
#include "core/core.h"
#include "test.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

static const bb_octree_desc_t desc = {
    .min = {-50.0f, -2.0f, -50.0f}, .max = {50.0f, 8.0f, 50.0f}, .max_depth = 4, .margin = 1.0f};

/* The non-empty leaves whose boxes grown by margin are not outside any
 * plane, in leaf order, checked against got[0..n); returns their count and
 * sets *all to the non-empty leaves. */
static int frustum_brute(const bb_octree_t *t, const vec4 planes[6], float margin, const bb_range_t *got, int n,
                         int *all)
{
    int want = 0;
    *all = 0;
    for (int k = 0; k < t->leaf_count; k++) {
        int node = bb_octree_leaf_node(t, (uint32_t)k);
        if (!t->count[node]) continue;
        (*all)++;
        bool culled = false;
        for (int p = 0; p < 6 && !culled; p++) {
            bool all_out = true;
            for (int c = 0; c < 8; c++) {
                float x = (c & 1) ? t->hi[node][0] + margin : t->lo[node][0] - margin;
                float y = (c & 2) ? t->hi[node][1] + margin : t->lo[node][1] - margin;
                float z = (c & 4) ? t->hi[node][2] + margin : t->lo[node][2] - margin;
                if (planes[p][0] * x + planes[p][1] * y + planes[p][2] * z + planes[p][3] >= 0.0f) all_out = false;
            }
            culled = all_out;
        }
        if (culled) continue;
        if (want < n) CHECK(got[want].leaf == (uint32_t)k);
        want++;
    }
    return want;
}

static void leaf_coords(uint32_t leaf, int depth, int c[3])
{
    c[0] = c[1] = c[2] = 0;
    for (int b = 0; b < depth; b++)
        for (int a = 0; a < 3; a++) c[a] |= (int)((leaf >> (3 * b + a)) & 1u) << b;
}

static void test_build(void)
{
    bb_octree_t t;
    CHECK(bb_octree_build(&t, &desc));
    CHECK(t.depth == 4 && t.side == 16 && t.leaf_count == 4096);
    CHECK(t.node_count == 1 + 8 + 64 + 512 + 4096);
    /* Leaf 1 = (x=1, y=0, z=0): x in [-43.75, -37.5]. */
    int node = bb_octree_leaf_node(&t, 1);
    CHECK_NEAR(t.lo[node][0], -43.75, 1e-5);
    CHECK_NEAR(t.hi[node][0], -37.5, 1e-5);
    CHECK_NEAR(t.hi[node][1], -2.0 + 10.0 / 16.0, 1e-5);
    bb_octree_free(&t);
    /* min_size stops the split: 10 m / 2 = 5 >= 3 but 10 / 4 < 3 -> depth 1. */
    bb_octree_desc_t d2 = {.min = {0, 0, 0}, .max = {10, 1, 10}, .max_depth = 6, .min_size = 3.0f};
    CHECK(bb_octree_build(&t, &d2));
    CHECK(t.depth == 1);
    CHECK_NEAR(t.desc.margin, 1.0, 0.0);
    bb_octree_free(&t);
    bb_octree_desc_t bad = {.min = {0, 0, 0}, .max = {10, 0, 10}};
    CHECK(!bb_octree_build(&t, &bad));
}

static void test_assign(void)
{
    enum { N = 20000 };
    bb_octree_t t;
    CHECK(bb_octree_build(&t, &desc));
    static float pos[N][3];
    static uint32_t order[N];
    static int seen[N];
    core_rng_t rng;
    core_rng_seed(&rng, 9, 9);
    for (int i = 0; i < N; i++) {
        pos[i][0] = core_rng_range(&rng, -52.0f, 52.0f); /* a few outside: clamped */
        pos[i][1] = core_rng_range(&rng, -1.0f, 3.0f);
        pos[i][2] = core_rng_range(&rng, -50.0f, 40.0f);
    }
    int warns = core_log_warn_count();
    bb_octree_assign(&t, (const float (*)[3])pos, N, order);
    CHECK(core_log_warn_count() == warns + 1);
    memset(seen, 0, sizeof seen);
    for (int s = 0; s < N; s++) {
        CHECK(order[s] < N);
        if (order[s] < N) seen[order[s]]++;
    }
    int once = 0;
    for (int i = 0; i < N; i++) once += seen[i] == 1;
    CHECK(once == N);
    uint32_t expect_first = 0;
    int inside_checked = 0, empty = 0;
    for (uint32_t k = 0; k < (uint32_t)t.leaf_count; k++) {
        int node = bb_octree_leaf_node(&t, k);
        CHECK(t.first[node] == expect_first);
        expect_first += t.count[node];
        empty += t.count[node] == 0;
        int c[3];
        leaf_coords(k, t.depth, c);
        for (uint32_t s = t.first[node]; s < t.first[node] + t.count[node]; s++) {
            const float *p = pos[order[s]];
            CHECK(bb_octree_leaf_of(&t, p) == k);
            /* Independent check: the position lies in the leaf's cell (or is clamped). */
            for (int a = 0; a < 3; a++) {
                double ext = (double)(desc.max[a] - desc.min[a]) / t.side;
                double lo = desc.min[a] + ext * c[a], hi = lo + ext;
                bool ok = (p[a] >= lo - 1e-4 && p[a] <= hi + 1e-4) || (c[a] == 0 && p[a] < lo) ||
                          (c[a] == t.side - 1 && p[a] > hi);
                CHECK_MSG(ok, "billboard %u axis %d at %g not in leaf [%g,%g]", order[s], a, p[a], lo, hi);
                inside_checked++;
            }
        }
    }
    CHECK(expect_first == N);
    CHECK(inside_checked == 3 * N);
    CHECK(empty > 0); /* y above 3 m holds nothing */
    /* Internal nodes: counts add up and ranges are contiguous. */
    for (int l = 0; l < t.depth; l++) {
        for (int k = 0; k < (1 << (3 * l)); k++) {
            int node = t.level_start[l] + k, child = t.level_start[l + 1] + 8 * k;
            uint32_t sum = 0;
            for (int c = 0; c < 8; c++) {
                CHECK(t.first[child + c] == t.first[node] + sum);
                sum += t.count[child + c];
            }
            CHECK(t.count[node] == sum);
        }
    }
    CHECK(t.count[0] == N);
    bb_octree_free(&t);
}

static void scripted_objects(float time, bb_bound_t obj[3])
{
    obj[0] = (bb_bound_t){.kind = BB_BOUND_SPHERE, .radius = 1.2f,
                          .centre = {30.0f * sinf(0.7f * time), 0.5f, 25.0f * sinf(1.1f * time)}};
    obj[1] = (bb_bound_t){.kind = BB_BOUND_SPHERE, .radius = 0.6f,
                          .centre = {-40.0f + 9.0f * time, 0.2f + 2.0f * sinf(time), 10.0f}};
    obj[2] = (bb_bound_t){.kind = BB_BOUND_AABB, .half = {0.4f, 0.9f, 0.3f},
                          .centre = {10.0f * cosf(0.3f * time), 0.9f, -30.0f + 5.0f * time}};
}

static void test_states(void)
{
    bb_octree_t t;
    CHECK(bb_octree_build(&t, &desc));
    /* Billboards everywhere on the ground so that collect has ranges. */
    enum { N = 8000 };
    static float pos[N][3];
    static uint32_t order[N];
    core_rng_t rng;
    core_rng_seed(&rng, 4, 4);
    for (int i = 0; i < N; i++) {
        pos[i][0] = core_rng_range(&rng, -50.0f, 50.0f);
        pos[i][1] = core_rng_range(&rng, -0.5f, 0.5f);
        pos[i][2] = core_rng_range(&rng, -50.0f, 50.0f);
    }
    bb_octree_assign(&t, (const float (*)[3])pos, N, order);
    uint8_t *bs = calloc((size_t)t.leaf_count, 1);
    float *bt = calloc((size_t)t.leaf_count, sizeof(float));
    bb_range_t *ranges = malloc(sizeof(bb_range_t) * (size_t)t.leaf_count);
    float time = 0.0f, recover = 0.7f;
    int mismatches = 0, collide_frames = 0, recover_frames = 0, range_checks = 0;
    for (int frame = 0; frame < 600; frame++) {
        float dt = core_rng_range(&rng, 1.0f / 240.0f, 1.0f / 10.0f);
        time += dt;
        bb_bound_t obj[3];
        scripted_objects(time, obj);
        int nobj = (frame % 97 < 80) ? 3 : 1; /* objects vanish for a while */
        if (frame % 53 < 12) obj[0].kind = BB_BOUND_NONE; /* or are left out (bb_field_set_hidden) */
        bb_octree_update(&t, obj, nobj, dt, recover);
        bb_octree_state_brute(&t, obj, nobj, dt, recover, bs, bt);
        int nc = 0, nr = 0;
        for (int k = 0; k < t.leaf_count; k++) {
            int node = bb_octree_leaf_node(&t, (uint32_t)k);
            if (t.state[node] != bs[k] || t.timer[node] != bt[k]) mismatches++;
            nc += bs[k] == BB_NODE_COLLIDING;
            nr += bs[k] == BB_NODE_RECOVERING;
        }
        collide_frames += nc > 0;
        recover_frames += nr > 0;
        /* collect == brute list of non-empty leaves in the mask, in Morton order. */
        uint32_t mask = BB_NODE_MASK(BB_NODE_COLLIDING) | BB_NODE_MASK(BB_NODE_RECOVERING);
        int got = bb_octree_collect(&t, mask, NULL, 0.0f, ranges, t.leaf_count);
        int want = 0;
        for (int k = 0; k < t.leaf_count; k++) {
            int node = bb_octree_leaf_node(&t, (uint32_t)k);
            if (!t.count[node] || !(mask & BB_NODE_MASK(bs[k]))) continue;
            if (want < got) {
                CHECK(ranges[want].leaf == (uint32_t)k && ranges[want].first == t.first[node] &&
                      ranges[want].count == t.count[node] && ranges[want].state == bs[k] &&
                      ranges[want].recover_left == bt[k]);
            }
            want++;
        }
        CHECK_MSG(got == want, "frame %d: collect %d vs brute %d", frame, got, want);
        range_checks += got;
    }
    printf("octree states: %d mismatches over 600 frames; frames with colliding %d, recovering %d; "
           "%d ranges checked\n", mismatches, collide_frames, recover_frames, range_checks);
    CHECK(mismatches == 0);
    CHECK(collide_frames > 400 && recover_frames > 400 && range_checks > 1000);
    /* After the objects leave for longer than recover_time everything is IDLE. */
    for (int frame = 0; frame < 20; frame++) bb_octree_update(&t, NULL, 0, 0.1f, recover);
    int idle = 0;
    for (int k = 0; k < t.leaf_count; k++) idle += t.state[bb_octree_leaf_node(&t, (uint32_t)k)] == BB_NODE_IDLE;
    CHECK(idle == t.leaf_count);
    CHECK(t.mask[0] == BB_NODE_MASK(BB_NODE_IDLE));

    /* Frustum culling against brute force: a perspective camera on the field. */
    mat4 proj, view, vp;
    glm_perspective(glm_rad(50.0f), 1.5f, 0.5f, 60.0f, proj);
    glm_lookat((vec3){-45.0f, 6.0f, -40.0f}, (vec3){0.0f, 0.0f, 0.0f}, (vec3){0, 1, 0}, view);
    glm_mat4_mul(proj, view, vp);
    vec4 planes[6];
    glm_frustum_planes(vp, planes);
    int got = bb_octree_collect(&t, BB_NODE_MASK(BB_NODE_IDLE), (const float (*)[4])planes, 0.0f, ranges,
                                t.leaf_count);
    int all = 0, want = frustum_brute(&t, planes, 1.0f, ranges, got, &all);
    printf("frustum: %d of %d non-empty leaves visible (brute %d)\n", got, all, want);
    CHECK(got == want);
    CHECK(got > 10 && got < all / 2);
    /* Cards widened by the thinning: collect grown by bb_lod_reach keeps
     * the leaves whose boxes grown by the margin plus the reach are in the
     * frustum (cards up to 1.2 m wide drawn up to 8 times as wide:
     * 4.8 m from the root, the margin's 0.6 m plus 4.2 m). */
    blade_lod_t rule = bb_lod_rule(&(blade_lod_t){.rule = BLADE_LOD_WIDTH, .max_scale = 8.0f});
    float reach = bb_lod_reach(&rule, 1.0f);
    CHECK(fabsf(reach - 4.2f) < 1e-5f);
    CHECK(bb_lod_reach(&(blade_lod_t){.rule = BLADE_LOD_OFF}, 1.0f) == 0.0f);
    CHECK(bb_lod_reach(&(blade_lod_t){.rule = BLADE_LOD_WIDTH, .max_scale = 8.0f, .no_compensation = true}, 1.0f) == 0.0f);
    int wide = bb_octree_collect(&t, BB_NODE_MASK(BB_NODE_IDLE), (const float (*)[4])planes, reach, ranges,
                                 t.leaf_count);
    int wide_want = frustum_brute(&t, planes, 1.0f + reach, ranges, wide, &all);
    printf("frustum, cards widened: %d leaves visible (brute %d)\n", wide, wide_want);
    CHECK(wide == wide_want && wide > got);
    CHECK(bb_octree_collect(&t, BB_NODE_MASK(BB_NODE_IDLE), (const float (*)[4])planes, 0.0f, ranges,
                            t.leaf_count) == got);

    /* Nearest first: the same leaves, by the distance from the eye to their
     * parent's box (computed here from the leaf coordinates), ties in leaf
     * order, so each parent's leaves stay adjacent in the buffer. */
    const float eye[3] = {-45.0f, 6.0f, -40.0f};
    uint8_t *seen = calloc((size_t)t.leaf_count, 1);
    for (int i = 0; i < got; i++) seen[ranges[i].leaf] = 1;
    bb_range_key_t *keys = malloc((size_t)got * sizeof *keys);
    bb_octree_sort_near_first(&t, eye, ranges, got, keys);
    free(keys);
    int sorted_bad = 0, merged = 0;
    float prev = -1.0f;
    for (int i = 0; i < got; i++) {
        sorted_bad += seen[ranges[i].leaf] != 1;
        seen[ranges[i].leaf] = 2;
        int c[3];
        leaf_coords(ranges[i].leaf, t.depth, c);
        float d2 = 0.0f;
        for (int a = 0; a < 3; a++) {
            float cell = (desc.max[a] - desc.min[a]) / (float)(t.side / 2);
            float lo = desc.min[a] + cell * (float)(c[a] / 2), hi = lo + cell;
            float d = eye[a] < lo ? lo - eye[a] : (eye[a] > hi ? eye[a] - hi : 0.0f);
            d2 += d * d;
        }
        sorted_bad += d2 < prev - 1e-3f || (i > 0 && fabsf(d2 - prev) <= 1e-3f && ranges[i].leaf < ranges[i - 1].leaf);
        prev = d2;
        merged += i == 0 || ranges[i - 1].first + ranges[i - 1].count != ranges[i].first;
    }
    printf("near first: %d leaves in %d draw ranges, %d out of order\n", got, merged, sorted_bad);
    CHECK(sorted_bad == 0);
    CHECK(merged * 3 < got);
    free(seen);

    /* Near only (the canopy's end): the leaves whose margin-grown box, from
     * the leaf coordinates, comes within 30 m of the eye, order kept. */
    bb_range_t *near = malloc((size_t)got * sizeof *near);
    memcpy(near, ranges, (size_t)got * sizeof *near);
    int kept = bb_octree_keep_near(&t, eye, 30.0f, near, got), expect = 0, near_bad = 0;
    for (int i = 0; i < got; i++) {
        int c[3];
        leaf_coords(ranges[i].leaf, t.depth, c);
        float d2 = 0.0f;
        for (int a = 0; a < 3; a++) {
            float cell = (desc.max[a] - desc.min[a]) / (float)t.side;
            float lo = desc.min[a] + cell * (float)c[a], hi = lo + cell;
            float d = eye[a] < lo ? lo - eye[a] : (eye[a] > hi ? eye[a] - hi : 0.0f);
            d2 += d * d;
        }
        if (sqrtf(d2) > 30.0f + t.desc.margin) continue;
        near_bad += expect >= kept || near[expect].leaf != ranges[i].leaf;
        expect++;
    }
    printf("near only: %d of %d leaves within 30 m (brute %d), %d differ\n", kept, got, expect, near_bad);
    CHECK(kept == expect && near_bad == 0);
    CHECK(kept > 0 && kept < got);
    free(near);
    /* No silent cap: a short output array logs and reports the full count. */
    int warns = core_log_warn_count();
    CHECK(bb_octree_collect(&t, BB_NODE_MASK(BB_NODE_IDLE), NULL, 0.0f, ranges, 5) == all);
    CHECK(core_log_warn_count() == warns + 1);
    free(bs);
    free(bt);
    free(ranges);
    bb_octree_free(&t);
}

/* A left-out object (BB_BOUND_NONE) overlaps no box, however large, while
 * the same centre as a sphere does. */
static void test_bound_none(void)
{
    const float lo[3] = {-1e6f, -1e6f, -1e6f}, hi[3] = {1e6f, 1e6f, 1e6f};
    bb_bound_t b = {.kind = BB_BOUND_SPHERE, .radius = 1.0f};
    CHECK(bb_bound_overlaps_box(&b, lo, hi, 1.0f));
    b.kind = BB_BOUND_NONE;
    CHECK(!bb_bound_overlaps_box(&b, lo, hi, 1.0f));
}

int main(void)
{
    core_log_set_quiet(true);
    test_bound_none();
    test_build();
    test_assign();
    test_states();
    TEST_END();
}

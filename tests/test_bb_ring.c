/* test_bb_ring: the billboard ring of world terrains (bb_ring.h,
 * bb_ring.c, shaders/billboard/bb_ring_gen.comp; docs/WORLD.md).
 *   a) the window (GL-free): its size, a follow generates exactly the
 *      cells that entered, every held cell is in its slot;
 *   b) the generation kernel against the CPU rule: every slot's K^2
 *      points are bb_layout_sample of their candidate with the root on
 *      terrain_world_height (tolerance), or a dead point where the rule
 *      rejects or the candidate lies outside the world square;
 *   c) a camera walk across cell borders (negative coordinates too) and
 *      back: the ring is bit-identical to its first generation, GPU memory
 *      is flat over the walk;
 *   d) the same area of the whole-field generation (bb_generate.geom on a
 *      heightfield of the same square, seed and layout): the same
 *      billboards with every field bit for bit but the root's height
 *      (the heightfield's instead of the world function's);
 *   e) collision: a ball rolled 0.9 m where the ground lies well below 0
 *      deforms billboards within its reach only, every mesh vertex above
 *      the root row on or above terrain_world_height (the collide pass's
 *      world ground; a flat ground at 0 would lift them) and within a
 *      billboard's height of its root; when the cell leaves the window its meshes
 *      go back to the pool (bb_ring_release.comp: the pool is full again,
 *      no point holds a mesh), and the cell generated again is its first
 *      generation (the state dropped). */
#include "test.h"
#include "test_gl.h"

#include "bb_gpu_test_util.h"
#include "billboard/bb.h"
#include "billboard/bb_ring.h"

#include <string.h>

static void test_window(void)
{
    CHECK(bb_ring_side(64.0f, 8.0f) == 21);
    CHECK(bb_ring_cand(8.0f, 0.40824829f, 2) == 20);
    CHECK(bb_ring_cand(0.1f, 0.4f, 2) == 2);
    bb_ring_window_t w;
    CHECK(bb_ring_window_make(&w, 5, 4, 0.5f, (const float[2]){-10.0f, -10.0f}));
    int slots[25];
    int32_t coords[25][2];
    bool dropped[25];
    CHECK(bb_ring_window_plan(&w, (const float[3]){0.1f, 0.0f, 0.1f}, slots, coords, dropped) == 25);
    CHECK(bb_ring_window_plan(&w, (const float[3]){0.1f, 0.0f, 0.1f}, slots, coords, dropped) == 0);
    /* an object on cell (5, 5) (x, z in [0, 2)): that slot collides, then recovers for 1 s */
    w.y[0] = -1.0f, w.y[1] = 1.0f, w.margin = 0.5f;
    bb_bound_t ball = {.kind = BB_BOUND_SPHERE, .centre = {1.0f, 0.0f, 1.0f}, .radius = 0.2f};
    int hit = bb_ring_slot(5, (const int32_t[2]){5, 5});
    bb_ring_window_touch(&w, &ball, 1, 0.1f, 1.0f);
    int colliding = 0;
    for (int k = 0; k < 25; k++) colliding += w.state[k] == BB_NODE_COLLIDING;
    CHECK(colliding == 1 && w.state[hit] == BB_NODE_COLLIDING);
    bb_ring_window_touch(&w, NULL, 0, 0.1f, 1.0f);
    CHECK(w.state[hit] == BB_NODE_RECOVERING);
    /* one cell (2 m) along +x: a column of 5 enters; then one along -z, x back */
    CHECK(bb_ring_window_plan(&w, (const float[3]){2.1f, 0.0f, 0.1f}, slots, coords, dropped) == 5);
    for (int k = 0; k < 5; k++) CHECK(coords[k][0] == 5 + 3 && slots[k] == bb_ring_slot(5, coords[k]) && !dropped[k]);
    CHECK(bb_ring_window_plan(&w, (const float[3]){0.1f, 0.0f, -1.9f}, slots, coords, dropped) == 9);
    int32_t centre[2];
    bb_ring_cell_of(&w, 0.1f, -1.9f, centre);
    CHECK(centre[0] == 5 && centre[1] == 4);
    int held = 0;
    for (int j = -2; j <= 2; j++)
        for (int i = -2; i <= 2; i++) held += bb_ring_window_find(&w, (const int32_t[2]){centre[0] + i, centre[1] + j}) >= 0;
    CHECK(held == 25);
    CHECK(bb_ring_window_find(&w, (const int32_t[2]){centre[0] + 3, centre[1]}) == -1);
    bb_ring_window_free(&w);
}

static bb_field_desc_t ring_desc(const terrain_mesh_t *t)
{
    return (bb_field_desc_t){.terrain = t, .seed = 77, .density = 6.0f, .ring_reach = 6.0f, .ring_cell = 2.0f,
                             .layout = {.size = 32, .clump_size = 16, .clump_layers = 2}};
}

/* b) every slot against the CPU rule; returns the live billboards. */
static int check_kernel(const bb_field_info_t *fi, const terrain_mesh_t *t, const bb_point_t *gpu)
{
    bb_layout_t lay;
    CHECK(bb_layout_generate(&lay, &fi->desc.layout));
    int k = fi->ring_cand, tile = 2, per_row = k / tile, live = 0, bad = 0, cells[2];
    for (int a = 0; a < 2; a++) cells[a] = (int)ceilf((t->aabb_max[2 * a] - t->aabb_min[2 * a]) / fi->gen.spacing);
    double worst_xz = 0, worst_y = 0, worst_f = 0;
    for (int s = 0; s < fi->ring_side * fi->ring_side; s++) {
        const bb_point_t *cell = &gpu[(size_t)s * (size_t)(k * k)];
        /* the slot's cell from its first candidate's dead or live root */
        int32_t c[2] = {(int32_t)floorf((cell[0].position[0] - fi->gen.origin[0]) / (fi->gen.spacing * (float)k)),
                        (int32_t)floorf((cell[0].position[2] - fi->gen.origin[1]) / (fi->gen.spacing * (float)k))};
        for (int q = 0; q < k * k; q++) {
            int tl = q / (tile * tile), in = q % (tile * tile);
            int ix = c[0] * k + (tl % per_row) * tile + in % tile, iz = c[1] * k + (tl / per_row) * tile + in / tile;
            bb_point_t p;
            bool want = ix >= 0 && iz >= 0 && ix < cells[0] && iz < cells[1] &&
                        bb_layout_sample(&lay, &fi->gen, ix, iz, &p) && p.position[0] <= t->aabb_max[0] &&
                        p.position[2] <= t->aabb_max[2];
            const bb_point_t *g = &cell[q];
            if (!want) {
                bad += g->size[0] != 0.0f || g->position[1] != -1e6f || g->pad[0] != BB_NO_SLOT;
                continue;
            }
            live++;
            p.position[1] = terrain_height_at(t, p.position[0], p.position[2], NULL);
            bad += g->seed != p.seed || g->layer != p.layer || g->state != BB_STATE_IDLE || g->pad[0] != BB_NO_SLOT;
            worst_xz = fmax(worst_xz, fmax(fabs(g->position[0] - p.position[0]), fabs(g->position[2] - p.position[2])));
            worst_y = fmax(worst_y, fabs(g->position[1] - p.position[1]));
            worst_f = fmax(worst_f, fmax(fabs(g->size[0] - p.size[0]), fabs(g->size[1] - p.size[1])));
            worst_f = fmax(worst_f, fmax(fabs(g->angle - p.angle), fabs(g->messiness - p.messiness)));
            for (int a = 0; a < 3; a++) worst_f = fmax(worst_f, fabs(g->growth[a] - p.growth[a]));
        }
    }
    printf("b) kernel: %d live of %d points, wrong %d; worst |dxz| %.3g m, |dy| %.3g m, other fields %.3g\n", live,
           fi->capacity, bad, worst_xz, worst_y, worst_f);
    CHECK(bad == 0 && live > fi->capacity / 4);
    CHECK(worst_xz < 1e-5 && worst_y < 1e-3 && worst_f < 1e-5);
    bb_layout_free(&lay);
    return live;
}

/* d) the whole-field generation of the same square: every live ring point
 * is one of its billboards, every field equal but the height. */
static void check_whole_field(const bb_field_info_t *fi, const bb_point_t *gpu)
{
    terrain_mesh_t hf;
    CHECK(terrain_make_heightfield(&hf, &(terrain_desc_t){.size = 64, .resolution = 32, .height = 0.5f}, 5));
    bb_field_desc_t d = fi->desc;
    d.terrain = &hf;
    bb_field_t *whole = bb_field_make(&d);
    CHECK(whole);
    if (!whole) return;
    bb_field_info_t wi;
    bb_field_info(whole, &wi);
    bb_point_t *all = malloc(sizeof *all * (size_t)wi.billboards);
    CHECK(bb_field_read(whole, BB_DATA_POINTS, 0, (size_t)wi.billboards, all));
    int live = 0, found = 0, differ = 0;
    for (int i = 0; i < fi->capacity; i++) {
        if (gpu[i].size[0] == 0.0f) continue;
        live++;
        for (int j = 0; j < wi.billboards; j++) {
            if (all[j].seed != gpu[i].seed) continue;
            bb_point_t a = all[j], b = gpu[i];
            a.position[1] = b.position[1] = 0.0f;
            found++;
            differ += memcmp(&a, &b, sizeof a) != 0;
            break;
        }
    }
    printf("d) whole field: %d billboards; the ring's %d live ones found %d, differing beyond the height %d\n",
           wi.billboards, live, found, differ);
    CHECK(found == live && differ == 0);
    free(all);
    bb_field_destroy(whole);
    terrain_free(&hf);
}

/* e) The lowest ground on a 1 m grid of the square's inner part. */
static void lowest(const terrain_mesh_t *t, float at[2])
{
    float best = INFINITY;
    for (int j = -24; j <= 24; j++)
        for (int i = -24; i <= 24; i++) {
            float h = terrain_height_at(t, (float)i, (float)j, NULL);
            if (h < best) best = h, at[0] = (float)i, at[1] = (float)j;
        }
}

static void check_collision(bb_field_t *f, const terrain_mesh_t *t)
{
    float at[2] = {0.0f, 0.0f};
    lowest(t, at);
    float ground = terrain_height_at(t, at[0], at[1], NULL);
    float cam[3] = {at[0], ground + 1.7f, at[1]};
    bb_field_follow(f, cam);
    bb_field_info_t fi = test_info(f);
    size_t n = (size_t)fi.capacity;
    bb_point_t *before = malloc(sizeof *before * n), *pts = malloc(sizeof *pts * n);
    CHECK(bb_field_read(f, BB_DATA_POINTS, 0, n, before));
    test_mesh_t ball;
    test_mesh_make(&ball, &(collide_shape_t){.type = COLLIDE_SHAPE_SPHERE, .radius = 0.5f});
    for (int k = 0; k < 10; k++) {
        float c[3] = {at[0] + 0.1f * (float)k, ground + 0.35f, at[1]};
        collide_object_t o = test_object(&ball, c, 0.5f);
        bb_field_update(f, test_set(&o, 1), 0.1f * (float)k, 0.1f);
    }
    bb_stats_t st;
    bb_field_stats(f, true, &st);
    CHECK(bb_field_read(f, BB_DATA_POINTS, 0, n, pts));
    int32_t cell[2] = {(int32_t)floorf((at[0] - fi.gen.origin[0]) / (fi.gen.spacing * (float)fi.ring_cand)),
                       (int32_t)floorf((at[1] - fi.gen.origin[1]) / (fi.gen.spacing * (float)fi.ring_cand))};
    int slot = bb_field_ring_slot(f, cell), deformed = 0, outside = 0;
    /* a billboard the ball's path cannot reach: root (xz) farther from it
     * than the ball's radius, the billboard's half diagonal and the wind */
    float reach_xz = 0.5f + 0.5f * sqrtf(1.44f * fi.desc.size[0] * fi.desc.size[0] +
                                         1.96f * fi.desc.size[1] * fi.desc.size[1]) + fi.desc.wind.strength;
    float *mesh = malloc(sizeof *mesh * 4 * (size_t)fi.mesh_vertices);
    double below = 0.0, reach = 0.0;
    for (size_t i = 0; i < n; i++) {
        if (pts[i].pad[0] == BB_NO_SLOT) continue;
        deformed++;
        float dx = fmaxf(fmaxf(at[0] - pts[i].position[0], pts[i].position[0] - at[0] - 0.9f), 0.0f);
        float dz = pts[i].position[2] - at[1];
        outside += sqrtf(dx * dx + dz * dz) > reach_xz + 0.1f;
        CHECK(bb_field_read(f, BB_DATA_MESHES, pts[i].pad[0], 1, mesh));
        for (int v = fi.desc.subdiv[0]; v < fi.mesh_vertices; v++) { /* the root row stays at the root */
            const float *p = &mesh[4 * v];
            outside += !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2]);
            below = fmax(below, terrain_height_at(t, p[0], p[2], NULL) - p[1]);
            reach = fmax(reach, p[1] - pts[i].position[1]);
        }
    }
    printf("e) collision: ground %.2f m at (%g, %g); %d deformed billboards (pool says %d), %d out of the ball's "
           "reach or not finite; mesh vertices below the world's ground by at most %.2g m, above their root by at most %.2f m "
           "(billboard height at most %.2f m); leaves colliding %d, recovering %d\n", (double)ground,
           (double)at[0], (double)at[1], deformed, st.deformed, outside, below, reach,
           (double)(1.4f * fi.desc.size[1]), st.leaves[BB_NODE_COLLIDING], st.leaves[BB_NODE_RECOVERING]);
    CHECK(ground < -1.0f && slot >= 0);
    CHECK(deformed > 5 && deformed == st.deformed && outside == 0);
    CHECK(below < 1e-3 && reach < 1.5 * 1.4 * fi.desc.size[1]);
    CHECK(st.leaves[BB_NODE_COLLIDING] + st.leaves[BB_NODE_RECOVERING] >= 1);

    /* the cell leaves (40 m away), then comes back */
    float away[3] = {cam[0] + 40.0f, cam[1], cam[2]};
    bb_field_follow(f, away);
    CHECK(bb_field_ring_slot(f, cell) == -1);
    uint32_t hdr[4];
    CHECK(bb_field_read(f, BB_DATA_POOL, 0, 4, hdr));
    CHECK(bb_field_read(f, BB_DATA_POINTS, 0, n, pts));
    int holding = 0;
    for (size_t i = 0; i < n; i++) holding += pts[i].pad[0] != BB_NO_SLOT;
    bb_field_follow(f, cam);
    CHECK(bb_field_read(f, BB_DATA_POINTS, 0, n, pts));
    bb_field_stats(f, true, &st);
    bool same = memcmp(before, pts, sizeof *pts * n) == 0;
    printf("e) the cell left: pool free %d of %d, points holding a mesh %d; back: ring %s its first generation, "
           "leaves colliding %d, recovering %d\n", (int)hdr[0], fi.desc.max_deformed, holding,
           same ? "equals" : "DIFFERS from", st.leaves[BB_NODE_COLLIDING], st.leaves[BB_NODE_RECOVERING]);
    CHECK((int)hdr[0] == fi.desc.max_deformed && holding == 0 && same && st.deformed == 0);
    CHECK(st.leaves[BB_NODE_COLLIDING] + st.leaves[BB_NODE_RECOVERING] == 0);
    free(mesh);
    free(before);
    free(pts);
    test_mesh_destroy(&ball);
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    test_window();

    terrain_mesh_t t;
    CHECK(terrain_make_world(&t, &(terrain_desc_t){.type = TERRAIN_WORLD, .size = 64.0f, .height = 30.0f}, 1));
    bb_field_desc_t desc = ring_desc(&t);
    bb_field_t *f = bb_field_make(&desc);
    CHECK(f);
    if (!f) return 1;
    /* start near the square's corner: cells outside it hold dead points */
    float cam[3] = {-27.0f, 0.0f, -25.0f};
    bb_field_follow(f, cam);
    bb_field_info_t fi;
    bb_field_info(f, &fi);
    printf("ring: %d x %d cells of %d x %d candidates, %d points\n", fi.ring_side, fi.ring_side, fi.ring_cand,
           fi.ring_cand, fi.capacity);
    CHECK(fi.ring_side == 9 && fi.ring_cand == 6 && fi.ring_generated == 81);
    size_t n = (size_t)fi.capacity;
    bb_point_t *first = malloc(sizeof *first * n), *again = malloc(sizeof *again * n);
    CHECK(bb_field_read(f, BB_DATA_POINTS, 0, n, first));
    check_kernel(&fi, &t, first);

    /* c) walk 12 m along +x and 5 m along +z in 0.25 m steps, then back */
    size_t bytes0 = gfx_memory_bytes();
    int32_t corner[2] = {0, 0};
    for (int step = 0; step <= 96; step++) {
        float s = (float)(step <= 48 ? step : 96 - step) / 48.0f;
        float at[3] = {cam[0] + 12.0f * s, 0.0f, cam[2] + 5.0f * s};
        bb_field_follow(f, at);
        if (step == 48) corner[0] = bb_field_ring_slot(f, (const int32_t[2]){0, 0});
    }
    bb_field_info(f, &fi);
    CHECK(bb_field_read(f, BB_DATA_POINTS, 0, n, again));
    size_t bytes1 = gfx_memory_bytes();
    int same = memcmp(first, again, sizeof *first * n) == 0;
    printf("c) walk: %ld cells generated (81 at the start), cell (0, 0) %s at the far end; ring after the walk "
           "back %s; GPU memory %zu -> %zu bytes\n", fi.ring_generated, corner[0] < 0 ? "left" : "held",
           same ? "bit-identical" : "DIFFERS", bytes0, bytes1);
    CHECK(fi.ring_generated > 81 + 2 * 9 * 4 && corner[0] < 0 && same && bytes0 == bytes1);
    CHECK(bb_field_ring_slot(f, (const int32_t[2]){0, 0}) >= 0);
    check_whole_field(&fi, first);
    check_collision(f, &t);

    free(first);
    free(again);
    bb_field_destroy(f);
    terrain_free(&t);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

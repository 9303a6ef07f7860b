/* test_bb_ring: the billboard ring of world terrains (bb_ring.h,
 * bb_ring.c, shaders/billboard/bb_ring.geom; docs/WORLD.md).
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
 *      (the heightfield's instead of the world function's). */
#include "test.h"
#include "test_gl.h"

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
    CHECK(bb_ring_window_plan(&w, (const float[3]){0.1f, 0.0f, 0.1f}, slots, coords) == 25);
    CHECK(bb_ring_window_plan(&w, (const float[3]){0.1f, 0.0f, 0.1f}, slots, coords) == 0);
    /* one cell (2 m) along +x: a column of 5 enters; then one along -z, x back */
    CHECK(bb_ring_window_plan(&w, (const float[3]){2.1f, 0.0f, 0.1f}, slots, coords) == 5);
    for (int k = 0; k < 5; k++) CHECK(coords[k][0] == 5 + 3 && slots[k] == bb_ring_slot(5, coords[k]));
    CHECK(bb_ring_window_plan(&w, (const float[3]){0.1f, 0.0f, -1.9f}, slots, coords) == 9);
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

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    test_window();

    terrain_mesh_t t;
    CHECK(terrain_make_world(&t, &(terrain_desc_t){.type = TERRAIN_WORLD, .size = 64.0f, .height = 5.0f}, 3));
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

    free(first);
    free(again);
    bb_field_destroy(f);
    terrain_free(&t);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

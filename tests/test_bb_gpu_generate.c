/* test_bb_gpu_generate: the billboard generation geometry shader of
 * Orthmann et al. 2009 (bb_generate.geom) read back from its transform
 * feedback buffer equals the CPU rule bb_layout_sample + terrain_height_at on
 * every candidate cell (same accepted set, fields within tolerance), and the
 * buffer is ordered by octree leaf with the ranges bb_octree holds. */
#include "test.h"
#include "test_gl.h"

#include "billboard/bb.h"

#include <string.h>
#include <time.h>

static int find_seed(const bb_point_t *pts, int n, uint32_t seed)
{
    for (int i = 0; i < n; i++)
        if (pts[i].seed == seed) return i;
    return -1;
}

int main(void)
{
    test_gl_init();
    core_log_set_quiet(true);
    terrain_mesh_t terrain;
    CHECK(terrain_make_heightfield(&terrain, &(terrain_desc_t){.size = 16, .resolution = 16, .height = 0.8f}, 7));

    bb_field_t f;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    bool ok = bb_field_make(&f, &(bb_field_desc_t){.terrain = &terrain, .seed = 1234, .octree_depth = 3, .density = 25,
                                                   .layout = {.size = 64, .clump_size = 32}});
    clock_gettime(CLOCK_MONOTONIC, &t1);
    CHECK(ok);
    if (!ok) return 1;
    printf("make: %.1f ms, %d billboards of %d candidates\n",
           (double)(t1.tv_sec - t0.tv_sec) * 1e3 + (double)(t1.tv_nsec - t0.tv_nsec) * 1e-6, f.billboards,
           f.capacity);

    /* CPU reference over every candidate cell. */
    bb_layout_t lay;
    CHECK(bb_layout_generate(&lay, &f.desc.layout));
    bb_point_t *cpu = malloc(sizeof *cpu * (size_t)f.capacity);
    int ncpu = 0;
    for (int iz = 0; iz < f.cells[1]; iz++) {
        for (int ix = 0; ix < f.cells[0]; ix++) {
            bb_point_t p;
            if (!bb_layout_sample(&lay, &f.gen, ix, iz, &p)) continue;
            if (p.position[0] > f.tree.desc.max[0] || p.position[2] > f.tree.desc.max[2]) continue;
            p.position[1] = terrain_height_at(&terrain, p.position[0], p.position[2], NULL);
            cpu[ncpu++] = p;
        }
    }
    bb_point_t *gpu = malloc(sizeof *gpu * (size_t)(f.billboards + 1));
    gfx_buffer_read(f.points, 0, sizeof *gpu * (size_t)f.billboards, gpu);
    printf("gpu %d, cpu %d billboards\n", f.billboards, ncpu);
    CHECK(f.billboards == ncpu);
    CHECK(ncpu > 1000);

    double max_xz = 0, max_y = 0, max_size = 0, max_growth = 0;
    int unmatched = 0, bad_int = 0;
    for (int i = 0; i < f.billboards; i++) {
        const bb_point_t *g = &gpu[i];
        int j = find_seed(cpu, ncpu, g->seed);
        if (j < 0) {
            unmatched++;
            continue;
        }
        const bb_point_t *c = &cpu[j];
        max_xz = fmax(max_xz, fmax(fabs(g->position[0] - c->position[0]), fabs(g->position[2] - c->position[2])));
        max_y = fmax(max_y, fabs(g->position[1] - c->position[1]));
        max_size = fmax(max_size, fmax(fabs(g->size[0] - c->size[0]), fabs(g->size[1] - c->size[1])));
        max_size = fmax(max_size, fabs(g->angle - c->angle));
        for (int k = 0; k < 3; k++) max_growth = fmax(max_growth, fabs(g->growth[k] - c->growth[k]));
        bad_int += g->layer != c->layer || g->state != BB_STATE_IDLE || g->pad[0] != BB_NO_SLOT ||
                   g->messiness != c->messiness;
    }
    printf("max |dxz| %.3g, |dy| %.3g, |dsize/angle| %.3g, |dgrowth| %.3g, unmatched %d, bad ints %d\n", max_xz,
           max_y, max_size, max_growth, unmatched, bad_int);
    CHECK(unmatched == 0);
    CHECK(bad_int == 0);
    CHECK(max_xz < 1e-5);
    CHECK(max_y < 1e-4);
    CHECK(max_size < 1e-5);
    CHECK(max_growth < 1e-5);

    /* Leaf order: every leaf's range holds exactly its billboards. */
    int wrong_leaf = 0;
    uint32_t covered = 0;
    for (int k = 0; k < f.tree.leaf_count; k++) {
        int node = bb_octree_leaf_node(&f.tree, (uint32_t)k);
        covered += f.tree.count[node];
        for (uint32_t s = f.tree.first[node]; s < f.tree.first[node] + f.tree.count[node]; s++)
            wrong_leaf += bb_octree_leaf_of(&f.tree, gpu[s].position) != (uint32_t)k;
    }
    printf("billboards in the wrong leaf range: %d\n", wrong_leaf);
    CHECK(wrong_leaf == 0);
    CHECK(covered == (uint32_t)f.billboards);
    CHECK(f.tree.count[0] == (uint32_t)f.billboards);

    bb_stats_t st;
    bb_field_stats(&f, true, &st);
    CHECK(st.billboards == f.billboards && st.deformed == 0 && st.pool_capacity == 4096);
    CHECK(st.leaves[BB_NODE_IDLE] > 1 && st.leaves[BB_NODE_COLLIDING] == 0);
    /* Generation timing: GPU timestamps inside the CPU wall time of make. */
    printf("generation pass %.2f ms (GPU timestamps), make %.2f ms (wall)\n", st.generate_ms, st.make_ms);
    CHECK(st.make_ms > 0 && st.make_ms < 60000);
    CHECK(st.generate_ms == -1.0f || (st.generate_ms >= 0 && st.generate_ms <= st.make_ms));

    free(cpu);
    free(gpu);
    bb_layout_free(&lay);
    bb_field_destroy(&f);
    terrain_free(&terrain);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}

/* test_terrain_clipmap: the world terrain's clipmap (terrain_clipmap.h).
 * Triangles and bytes are the same for 1, 2, 4 and 8 km worlds (the desc
 * has no world size; the coarsest level reaches 2 km by default). Each
 * level's unmorphed triangles cover its square less the finer level's,
 * exactly. With the morph applied for a camera (terrain_clipmap_vertex,
 * the vertex shader's twin), the whole clipmap is watertight: every
 * directed edge of a triangle not collapsed by the morph has its reverse
 * except on the outermost square, no triangle folds over, and the signed area is the
 * outer square's (no holes, no overlaps), for cameras at snap boundaries
 * and at negative coordinates. No popping: moving the camera in 1 cm steps
 * across snap lines of every level changes the drawn surface's height under
 * fixed probes by at most a few millimetres. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "terrain/terrain.h"
#include "terrain/terrain_clipmap.h"
#include "test.h"

typedef struct edge_t {
    uint64_t a, b;
} edge_t;

static uint64_t key_of(const float p[2])
{
    uint32_t x, z;
    memcpy(&x, &p[0], 4);
    memcpy(&z, &p[1], 4);
    return (uint64_t)x << 32 | z;
}

static int edge_cmp(const void *pa, const void *pb)
{
    const edge_t *a = pa, *b = pb;
    if (a->a != b->a) return a->a < b->a ? -1 : 1;
    return a->b < b->b ? -1 : a->b > b->b;
}

/* Morphed xz of the three corners of triangle t of a placed level. */
static void tri_xz(const terrain_clipmap_t *c, const terrain_clipmap_level_t *l, uint32_t t, float cam[2],
                   float p[3][2])
{
    for (int k = 0; k < 3; k++) {
        uint32_t v = c->indices[t + (uint32_t)k];
        terrain_clipmap_vertex(l, c->grid[2 * v], c->grid[2 * v + 1], cam[0], cam[1], p[k]);
    }
}

static double area2(float p[3][2])
{
    return ((double)p[1][0] - p[0][0]) * ((double)p[2][1] - p[0][1]) -
           ((double)p[2][0] - p[0][0]) * ((double)p[1][1] - p[0][1]);
}

/* Two corners at one point: the morph folded the triangle away. (Three
 * distinct corners in a line in xz are a vertical sliver that still closes
 * the surface in 3D: kept.) */
static bool collapsed(float p[3][2])
{
    for (int k = 0; k < 3; k++)
        if (key_of(p[k]) == key_of(p[(k + 1) % 3])) return true;
    return false;
}

static bool on_outer(const float p[2], float lo[2], float hi[2])
{
    return p[0] == lo[0] || p[0] == hi[0] || p[1] == lo[1] || p[1] == hi[1];
}

/* Watertightness of the whole morphed clipmap around cam. Note: the
 * triangle winding is clockwise in (x, z) seen this way (ccw from +y). */
static void check_watertight(const terrain_clipmap_t *c, float cx, float cz)
{
    float cam[2] = {cx, cz};
    size_t cap = 0;
    for (int lv = 0; lv < c->desc.levels; lv++) cap += c->count[lv == 0 ? 0 : 1];
    edge_t *edges = malloc(sizeof(edge_t) * cap);
    size_t ne = 0;
    double area = 0.0;
    int folded = 0;
    terrain_clipmap_level_t outer = terrain_clipmap_place(c, c->desc.levels - 1, cx, cz);
    float side = (float)c->desc.ring_cells * outer.cell;
    float lo[2] = {outer.origin[0], outer.origin[1]}, hi[2] = {outer.origin[0] + side, outer.origin[1] + side};
    for (int lv = 0; lv < c->desc.levels; lv++) {
        terrain_clipmap_level_t l = terrain_clipmap_place(c, lv, cx, cz);
        CHECK(lv == 0 ? l.range == 0 : l.range >= 1 && l.range <= 4);
        for (uint32_t t = c->first[l.range]; t < c->first[l.range] + c->count[l.range]; t += 3) {
            float p[3][2];
            tri_xz(c, &l, t, cam, p);
            if (collapsed(p)) continue;
            double a = area2(p);
            folded += a > 0.0;
            area -= a * 0.5;
            for (int k = 0; k < 3; k++) edges[ne++] = (edge_t){key_of(p[k]), key_of(p[(k + 1) % 3])};
        }
    }
    qsort(edges, ne, sizeof *edges, edge_cmp);
    int dup = 0, open = 0;
    for (size_t e = 0; e < ne; e++) {
        if (e > 0 && !edge_cmp(&edges[e], &edges[e - 1])) dup++;
        edge_t rev = {edges[e].b, edges[e].a};
        if (bsearch(&rev, edges, ne, sizeof *edges, edge_cmp)) continue;
        float pa[2], pb[2];
        uint32_t bits[4] = {(uint32_t)(edges[e].a >> 32), (uint32_t)edges[e].a, (uint32_t)(edges[e].b >> 32),
                            (uint32_t)edges[e].b};
        memcpy(&pa[0], &bits[0], 4);
        memcpy(&pa[1], &bits[1], 4);
        memcpy(&pb[0], &bits[2], 4);
        memcpy(&pb[1], &bits[3], 4);
        bool border = on_outer(pa, lo, hi) && on_outer(pb, lo, hi) && (pa[0] == pb[0] || pa[1] == pb[1]);
        open += !border;
    }
    double want = (double)side * side;
    printf("camera (%g, %g): %zu edges, %d open inside, %d duplicated, %d folded, area %.6g of %.6g m^2\n",
           (double)cx, (double)cz, ne, open, dup, folded, area, want);
    CHECK(open == 0 && dup == 0 && folded == 0);
    CHECK(fabs(area - want) <= want * 1e-9);
    free(edges);
}

/* Unmorphed area per level: its square less the finer level's. */
static void check_level_areas(const terrain_clipmap_t *c)
{
    int n = c->desc.ring_cells;
    for (int r = 0; r < TERRAIN_CLIPMAP_RANGES; r++) {
        double area = 0.0;
        for (uint32_t t = c->first[r]; t < c->first[r] + c->count[r]; t += 3) {
            float p[3][2];
            for (int k = 0; k < 3; k++) {
                uint32_t v = c->indices[t + (uint32_t)k];
                p[k][0] = c->grid[2 * v];
                p[k][1] = c->grid[2 * v + 1];
            }
            area -= area2(p) * 0.5;
        }
        double want = r == 0 ? (double)n * n : (double)n * n - (double)(n / 2) * (n / 2);
        CHECK_NEAR(area, want, 0.0);
    }
}

/* Height of the drawn surface under (x, z): the morphed triangle holding it. */
static float surface_height(const terrain_clipmap_t *c, const terrain_world_t *w, float cam[2], float x, float z)
{
    for (int lv = 0; lv < c->desc.levels; lv++) {
        terrain_clipmap_level_t l = terrain_clipmap_place(c, lv, cam[0], cam[1]);
        for (uint32_t t = c->first[l.range]; t < c->first[l.range] + c->count[l.range]; t += 3) {
            float p[3][2];
            tri_xz(c, &l, t, cam, p);
            double a = area2(p);
            if (a == 0.0) continue;
            float q0[3][2] = {{x, z}, {p[1][0], p[1][1]}, {p[2][0], p[2][1]}};
            float q1[3][2] = {{p[0][0], p[0][1]}, {x, z}, {p[2][0], p[2][1]}};
            float q2[3][2] = {{p[0][0], p[0][1]}, {p[1][0], p[1][1]}, {x, z}};
            double w0 = area2(q0) / a, w1 = area2(q1) / a, w2 = area2(q2) / a;
            if (w0 < -1e-9 || w1 < -1e-9 || w2 < -1e-9) continue;
            return (float)(w0 * terrain_world_height(w, p[0][0], p[0][1], NULL) +
                           w1 * terrain_world_height(w, p[1][0], p[1][1], NULL) +
                           w2 * terrain_world_height(w, p[2][0], p[2][1], NULL));
        }
    }
    return NAN;
}

static void check_no_popping(void)
{
    terrain_clipmap_t c;
    CHECK(terrain_clipmap_make(&c, &(terrain_clipmap_desc_t){.ring_cells = 32, .levels = 4}));
    terrain_world_t w = terrain_world_make(&(terrain_desc_t){.type = TERRAIN_WORLD, .size = 2048, .height = 30}, 5);
    static const float probes[][2] = {{-10.3f, 2.1f}, {6.7f, -9.9f}, {-3.4f, -4.6f}, {13.2f, 14.6f}};
    double worst = 0.0;
    float prev[4];
    /* 8 m in 1 cm steps: crosses the snap lines of every level (2 cells of 4 m). */
    for (int s = 0; s <= 800; s++) {
        float cam[2] = {-4.005f + 0.01f * (float)s, -2.0f + 0.005f * (float)s};
        for (int k = 0; k < 4; k++) {
            float h = surface_height(&c, &w, cam, probes[k][0], probes[k][1]);
            CHECK(isfinite(h));
            if (s > 0) worst = fmax(worst, fabs(h - prev[k]));
            prev[k] = h;
        }
    }
    printf("no popping: worst change of the drawn height under 4 probes per 1 cm camera step: %.3g m\n", worst);
    CHECK(worst < 5e-3);
    terrain_clipmap_free(&c);
}

int main(void)
{
    terrain_clipmap_t c;
    CHECK(terrain_clipmap_make(&c, &(terrain_clipmap_desc_t){0}));
    CHECK(c.desc.cell == 0.5f && c.desc.ring_cells == 128 && c.desc.levels == 7 && c.desc.morph_cells == 16);
    uint32_t tris = c.count[0] / 3 + (uint32_t)(c.desc.levels - 1) * c.count[1] / 3;
    float reach = (float)(c.desc.ring_cells / 2) * ldexpf(c.desc.cell, c.desc.levels - 1);
    printf("default clipmap: %d levels, %u triangles drawn, %zu bytes held, reaches %g m\n", c.desc.levels, tris,
           terrain_clipmap_bytes(&c), (double)reach);
    CHECK(reach >= 2048.0f);
    CHECK(terrain_clipmap_estimate_bytes(&(terrain_clipmap_desc_t){0}) == terrain_clipmap_bytes(&c));
    for (float size = 1024.0f; size <= 8192.0f; size *= 2.0f) {
        /* a world's size changes nothing the clipmap holds or draws */
        terrain_mesh_t m;
        CHECK(terrain_make_world(&m, &(terrain_desc_t){.type = TERRAIN_WORLD, .size = size, .height = 30}, 1));
        CHECK(m.vertex_count == 0 && m.index_count == 0);
        terrain_clipmap_t again;
        CHECK(terrain_clipmap_make(&again, &(terrain_clipmap_desc_t){0}));
        CHECK(terrain_clipmap_bytes(&again) == terrain_clipmap_bytes(&c));
        terrain_clipmap_free(&again);
    }
    for (int r = 1; r < TERRAIN_CLIPMAP_RANGES; r++) CHECK(c.count[r] == c.count[1]);
    check_level_areas(&c);
    check_watertight(&c, 0.3f, -0.7f);
    check_watertight(&c, 1000.0f, -1024.0f); /* on the snap lines of every level */
    check_watertight(&c, -1536.49f, 777.77f);
    terrain_clipmap_t small;
    CHECK(terrain_clipmap_make(&small, &(terrain_clipmap_desc_t){.cell = 1.0f, .ring_cells = 32, .levels = 5}));
    for (int k = 0; k < 16; k++) check_watertight(&small, -40.0f + 5.37f * (float)k, 31.9f - 4.11f * (float)k);
    terrain_clipmap_free(&small);
    terrain_clipmap_desc_t bad;
    CHECK(!terrain_clipmap_resolve(&(terrain_clipmap_desc_t){.cell = 0.3f}, &bad));
    CHECK(!terrain_clipmap_resolve(&(terrain_clipmap_desc_t){.ring_cells = 36}, &bad));
    CHECK(!terrain_clipmap_resolve(&(terrain_clipmap_desc_t){.ring_cells = 32, .morph_cells = 5}, &bad));
    check_no_popping();
    terrain_clipmap_free(&c);
    TEST_END();
}

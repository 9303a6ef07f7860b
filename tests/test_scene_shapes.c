/* test_scene_shapes: collider meshes lie on their analytic surfaces, face
 * outward, and signed distances match hand values. */
#include "scene/shapes.h"
#include "test.h"

static void check_mesh(const scene_collider_t *c)
{
    shape_mesh_t m;
    CHECK(shape_mesh_make(&m, c));
    CHECK(m.vertex_count > 0 && m.index_count % 3 == 0);
    float worst = 0;
    for (uint32_t i = 0; i < m.vertex_count; i++) {
        float d = fabsf(shape_signed_distance(c, m.positions + i * 3));
        if (d > worst) worst = d;
        float r2 = 0;
        for (int k = 0; k < 3; k++) r2 += m.positions[i * 3 + k] * m.positions[i * 3 + k];
        CHECK(sqrtf(r2) <= shape_bounding_radius(c) + 1e-4f);
    }
    CHECK_NEAR(worst, 0.0, 1e-4);
    /* Outward winding: each triangle's normal points away from the centre. */
    int inward = 0;
    for (uint32_t t = 0; t < m.index_count; t += 3) {
        const float *a = m.positions + m.indices[t] * 3, *b = m.positions + m.indices[t + 1] * 3,
                    *d = m.positions + m.indices[t + 2] * 3;
        float e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        float n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
        float area2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        if (area2 < 1e-12f) continue;
        float cx = (a[0] + b[0] + d[0]), cy = (a[1] + b[1] + d[1]), cz = (a[2] + b[2] + d[2]);
        if (n[0] * cx + n[1] * cy + n[2] * cz < 0) inward++;
    }
    CHECK_MSG(inward == 0, "%d inward triangles (type %d)", inward, c->type);
    shape_mesh_free(&m);
}

int main(void)
{
    scene_collider_t s = {.type = SCENE_COLLIDER_SPHERE, .radius = 0.5f};
    scene_collider_t cap = {.type = SCENE_COLLIDER_CAPSULE, .radius = 0.3f, .length = 1.0f};
    scene_collider_t box = {.type = SCENE_COLLIDER_BOX, .half_extents = {0.5f, 0.25f, 1.0f}};
    check_mesh(&s);
    check_mesh(&cap);
    check_mesh(&box);
    CHECK_NEAR(shape_signed_distance(&s, (float[3]){1, 0, 0}), 0.5, 1e-6);
    CHECK_NEAR(shape_signed_distance(&s, (float[3]){0, 0, 0}), -0.5, 1e-6);
    CHECK_NEAR(shape_signed_distance(&cap, (float[3]){0, 0.9f, 0}), 0.1, 1e-6);
    CHECK_NEAR(shape_signed_distance(&cap, (float[3]){0.5f, 0.2f, 0}), 0.2, 1e-6);
    CHECK_NEAR(shape_signed_distance(&box, (float[3]){0, 0, 0}), -0.25, 1e-6);
    CHECK_NEAR(shape_signed_distance(&box, (float[3]){1.5f, 0, 0}), 1.0, 1e-6);
    CHECK_NEAR(shape_signed_distance(&box, (float[3]){1.5f, 1.25f, 0}), sqrt(2.0), 1e-5);
    CHECK_NEAR(shape_bounding_radius(&cap), 0.8, 1e-6);
    TEST_END();
}

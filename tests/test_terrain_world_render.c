/* test_terrain_world_render: a 4 km world terrain drawn by app_terrain as a
 * clipmap (terrain_world.vert + terrain.frag) on llvmpipe, read back: seen
 * straight down from 250 m (over a point on the snap lines of every level)
 * and from 1500 m (all 7 levels in view), every pixel has terrain depth (no
 * hole at any level border); the depth under the centre pixel unprojects to
 * terrain_world_height there within 5 cm; a walker's view 1.7 m above the
 * ground covers the lower half of the image. The walker's view is written
 * to $MEADOW_TEST_OUT/world_walk.png. */
#include "app/app_world.h"
#include "platform/plat.h"
#include "scene/terrain.h"
#include "test.h"
#include "test_gl.h"

#include <stdlib.h>
#include <string.h>

enum { W = 160, H = 120 };

static void view_at(app_view_t *v, const float eye[3], const float target[3], const float up[3])
{
    memset(v, 0, sizeof *v);
    glm_lookat((float *)eye, (float *)target, (float *)up, v->view);
    glm_perspective(glm_rad(90.0f), (float)W / (float)H, 1.0f, 6000.0f, v->proj);
    glm_mat4_mul(v->proj, v->view, v->viewproj);
    glm_mat4_inv(v->viewproj, v->inv_viewproj);
    glm_vec3_copy((float *)eye, v->camera);
    glm_vec3_copy((vec3){0.4f, 0.8f, 0.3f}, v->sun_dir);
    glm_vec3_normalize(v->sun_dir);
    v->far = 6000.0f;
    v->width = W;
    v->height = H;
}

/* Draws and reads depth; returns the pixels without terrain in rows [row0, H). */
static int draw_holes(const app_terrain_t *t, const gfx_target_t *tg, const app_view_t *v, int row0, float *depth)
{
    gfx_target_bind(tg);
    glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    app_terrain_draw(t, v);
    gfx_target_resolve(tg);
    CHECK(gfx_target_read_depth(tg, depth));
    int holes = 0;
    for (int y = row0; y < H; y++)
        for (int x = 0; x < W; x++) holes += !(depth[y * W + x] < 1.0f);
    return holes;
}

int main(void)
{
    test_gl_init();
    terrain_mesh_t mesh;
    CHECK(terrain_make_world(&mesh, &(terrain_desc_t){.type = TERRAIN_WORLD, .size = 4096, .height = 30}, 3));
    app_terrain_t t;
    CHECK(app_terrain_make(&t, &mesh));
    gfx_target_t tg = gfx_target_make(&(gfx_target_desc_t){.w = W, .h = H, .samples = 1, .label = "world.target"});
    float *depth = malloc(sizeof(float) * W * H);
    app_view_t v;
    static const float north[3] = {0.0f, 0.0f, -1.0f}, up[3] = {0.0f, 1.0f, 0.0f};

    float x = 1024.0f, z = -512.0f, g = terrain_world_height(&mesh.world, x, z, NULL);
    view_at(&v, (float[3]){x, g + 250.0f, z}, (float[3]){x, g, z}, north);
    int holes = draw_holes(&t, &tg, &v, 0, depth);
    /* depth of the centre (between the 4 middle pixels: read one, W/2, H/2) */
    float d = depth[(H / 2) * W + W / 2];
    vec4 ndc = {((float)(W / 2) + 0.5f) / W * 2.0f - 1.0f, 1.0f - ((float)(H / 2) + 0.5f) / H * 2.0f, d * 2.0f - 1.0f,
                1.0f},
         p;
    glm_mat4_mulv(v.inv_viewproj, ndc, p);
    float px = p[0] / p[3], py = p[1] / p[3], pz = p[2] / p[3];
    float want = terrain_world_height(&mesh.world, px, pz, NULL);
    printf("top-down from 250 m: %d pixels without terrain; centre at (%.2f, %.2f): drawn %.3f m, function %.3f m\n",
           holes, (double)px, (double)pz, (double)py, (double)want);
    CHECK(holes == 0);
    CHECK_NEAR(py, want, 0.05);

    view_at(&v, (float[3]){-700.0f, 1500.0f, 300.0f}, (float[3]){-700.0f, 0.0f, 300.0f}, north);
    holes = draw_holes(&t, &tg, &v, 0, depth);
    printf("top-down from 1500 m: %d pixels without terrain\n", holes);
    CHECK(holes == 0);

    g = terrain_world_height(&mesh.world, -300.0f, 200.0f, NULL);
    view_at(&v, (float[3]){-300.0f, g + 1.7f, 200.0f}, (float[3]){-280.0f, g - 3.0f, 180.0f}, up);
    holes = draw_holes(&t, &tg, &v, H / 2, depth);
    printf("walker's view: %d pixels of the lower half without terrain\n", holes);
    CHECK(holes == 0);
    glFinish();
    double t0 = plat_time();
    for (int k = 0; k < 10; k++) draw_holes(&t, &tg, &v, H, depth);
    printf("walker's view, %dx%d, 7 levels: %.1f ms per draw and readback (timing only)\n", W, H,
           (plat_time() - t0) * 100.0);
    const char *out = getenv("MEADOW_TEST_OUT");
    if (out) {
        char path[1024];
        core_fs_mkdirs(out);
        snprintf(path, sizeof path, "%s/world_walk.png", out);
        CHECK(gfx_target_screenshot(&tg, path));
    }
    free(depth);
    gfx_target_destroy(&tg);
    app_terrain_destroy(&t);
    terrain_free(&mesh);
    CHECK(test_gl_shutdown() == 0);
    TEST_END();
}
